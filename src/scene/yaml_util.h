// YAML access with messages that name the file, the line and the element (internal to the
// scene readers). yaml-cpp counts lines from 0; messages count from 1.
//
// Keys: checkKeys() compares the keys of a mapping with the fields of the ROS message read
// there (plus our documented extensions). A key the message lacks is what makes a ROS message
// fail to deserialize (rostopic pub, ros2 topic pub, rosidl's set_message_fields), so it is an
// error by default, or a warning naming the key and the line when the caller allows it. A key
// given twice is always an error: YAML requires unique keys, and yaml-cpp would silently keep
// only one of the values.
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <initializer_list>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "dss/scene/scene_error.h"
#include "scene_util.h"

namespace dss {
namespace scene_detail {

/// At most `max` characters of `s` (then "..."), for quoting file content in messages.
inline std::string clip(const std::string& s, std::size_t max = 64) {
  return s.size() <= max ? s : s.substr(0, max) + "...";
}

/// The edit distance of two short strings, capped at 3 (for "did you mean" hints).
inline int editDistance(const std::string& a, const std::string& b) {
  if (a.size() > b.size() + 3 || b.size() > a.size() + 3) return 3;
  std::vector<int> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = static_cast<int>(j);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    int diagonal = row[0];
    row[0] = static_cast<int>(i);
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const int up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = up;
    }
  }
  return std::min(row[b.size()], 3);
}

class YamlReader {
 public:
  explicit YamlReader(std::string file) : file_(std::move(file)) {}

  /// Unknown keys become lines in `*warnings` instead of errors; `option` names the setting
  /// that chose this (for the error message's hint).
  void setUnknownKeyPolicy(bool as_warnings, std::vector<std::string>* warnings,
                           std::string option) {
    unknown_as_warnings_ = as_warnings;
    warnings_ = warnings;
    option_ = std::move(option);
  }

  /// Checks the keys of `map` (nothing to do for a non-mapping): each must be one of `known`,
  /// the fields of `message` (e.g. "moveit_msgs/CollisionObject") and our extensions, and
  /// appear once.
  void checkKeys(const YAML::Node& map, const std::string& element, const char* message,
                 std::initializer_list<const char*> known) const {
    if (!map.IsMap()) return;
    std::map<std::string, std::string> seen;  // key -> where
    for (auto it = map.begin(); it != map.end(); ++it) {
      const YAML::Node key = it->first;
      if (!key.IsScalar()) fail(key, element + ": expected a plain key");
      const std::string k = key.Scalar();
      const auto [first, inserted] = seen.emplace(k, at(key));
      if (!inserted)
        fail(key, element + ": duplicate key '" + clip(k) + "' (first at " + first->second +
                      "; YAML keys must be unique)");
      if (std::any_of(known.begin(), known.end(), [&](const char* f) { return k == f; })) continue;
      // The closest field (case ignored) as a hint, when it is close for the key's length.
      std::string fields, hint;
      int best = 3;
      for (const char* f : known) {
        fields += (fields.empty() ? "" : ", ") + std::string(f);
        std::string lk = k, lf = f;
        for (auto* s : {&lk, &lf})
          std::transform(s->begin(), s->end(), s->begin(),
                         [](unsigned char c) { return std::tolower(c); });
        const int d = editDistance(lk, lf);
        if (d < best && (d == 0 || d < static_cast<int>(k.size()))) {
          best = d;
          hint = "; did you mean '" + std::string(f) + "'?";
        }
      }
      const std::string what = at(key) + ": " + element + ": unknown key '" + clip(k) + "' (" +
                               message + " has " + fields + hint + ")";
      if (!unknown_as_warnings_ || !warnings_)
        throw SceneError(what + "; " + option_ + " = true reads it as a warning");
      warnings_->push_back(what + ": ignored");
    }
  }

  const std::string& file() const { return file_; }

  YAML::Node load(const std::string& text) const {
    try {
      return YAML::Load(text);
    } catch (const YAML::Exception& e) {
      throw SceneError(file_ + ":" + std::to_string(e.mark.line + 1) + ":" +
                       std::to_string(e.mark.column + 1) + ": malformed YAML: " + e.msg);
    }
  }

  /// "file:line" for a node read from the file, "file" otherwise.
  std::string at(const YAML::Node& n) const {
    if (!n.IsDefined()) return file_;
    const YAML::Mark m = n.Mark();
    if (m.is_null() || m.line < 0) return file_;
    return file_ + ":" + std::to_string(m.line + 1);
  }

  [[noreturn]] void fail(const YAML::Node& n, const std::string& msg) const {
    throw SceneError(at(n) + ": " + msg);
  }

  /// map[key], which must exist; `element` names what is being read (e.g. "object 'Can1'").
  YAML::Node require(const YAML::Node& map, const char* key, const std::string& element) const {
    if (!map.IsMap()) fail(map, element + ": expected a mapping");
    const YAML::Node v = map[key];
    if (!v.IsDefined() || v.IsNull())
      fail(map, element + ": missing field '" + std::string(key) + "'");
    return v;
  }

  static YAML::Node optional(const YAML::Node& map, const char* key) {
    if (!map.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
    const YAML::Node v = map[key];
    return v;  // check IsDefined() / IsNull()
  }
  static bool has(const YAML::Node& map, const char* key) {
    const YAML::Node v = optional(map, key);
    return v.IsDefined() && !v.IsNull();
  }

  double number(const YAML::Node& n, const std::string& element) const {
    if (!n.IsScalar()) fail(n, element + ": expected a number");
    double v = 0;
    try {
      v = n.as<double>();
    } catch (const YAML::Exception&) {
      fail(n, element + ": expected a number, got '" + n.Scalar() + "'");
    }
    if (!std::isfinite(v)) fail(n, element + ": non-finite number '" + n.Scalar() + "'");
    return v;
  }

  int integer(const YAML::Node& n, const std::string& element) const {
    if (!n.IsScalar()) fail(n, element + ": expected an integer");
    try {
      return n.as<int>();
    } catch (const YAML::Exception&) {
      fail(n, element + ": expected an integer, got '" + n.Scalar() + "'");
    }
  }

  std::string string(const YAML::Node& n, const std::string& element) const {
    if (n.IsNull()) return std::string();
    if (!n.IsScalar()) fail(n, element + ": expected a string");
    return n.Scalar();
  }

  YAML::Node sequence(const YAML::Node& n, const std::string& element) const {
    if (!n.IsSequence()) fail(n, element + ": expected a list");
    return n;
  }

  /// [x, y, z] or {x:, y:, z:}.
  Eigen::Vector3d vector3(const YAML::Node& n, const std::string& element) const {
    if (n.IsSequence()) {
      if (n.size() != 3) fail(n, element + ": expected 3 numbers, got " + std::to_string(n.size()));
      return {number(n[0], element), number(n[1], element), number(n[2], element)};
    }
    if (n.IsMap()) {
      checkKeys(n, element, "geometry_msgs/Point", {"x", "y", "z"});
      return {number(require(n, "x", element), element + ".x"),
              number(require(n, "y", element), element + ".y"),
              number(require(n, "z", element), element + ".z")};
    }
    fail(n, element + ": expected [x, y, z] or {x, y, z}");
  }

  /// [x, y, z, w] or {x:, y:, z:, w:}; normalised; NaN and zero refused.
  Eigen::Quaterniond quaternion(const YAML::Node& n, const std::string& element) const {
    double q[4];
    if (n.IsSequence()) {
      if (n.size() != 4)
        fail(n, element + ": expected 4 numbers [x, y, z, w], got " + std::to_string(n.size()));
      for (int i = 0; i < 4; ++i) q[i] = rawNumber(n[i], element);
    } else if (n.IsMap()) {
      checkKeys(n, element, "geometry_msgs/Quaternion", {"x", "y", "z", "w"});
      const char* keys[] = {"x", "y", "z", "w"};
      for (int i = 0; i < 4; ++i) q[i] = rawNumber(require(n, keys[i], element), element);
    } else {
      fail(n, element + ": expected [x, y, z, w] or {x, y, z, w}");
    }
    return checkedQuaternion(q[0], q[1], q[2], q[3], at(n) + ": " + element);
  }

  /// {position, orientation} (both required).
  Eigen::Isometry3d pose(const YAML::Node& n, const std::string& element) const {
    if (!n.IsMap()) fail(n, element + ": expected a pose {position, orientation}");
    checkKeys(n, element, "geometry_msgs/Pose", {"position", "orientation"});
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() =
        quaternion(require(n, "orientation", element), element + " orientation").toRotationMatrix();
    X.translation() = vector3(require(n, "position", element), element + " position");
    return X;
  }

  /// geometry_msgs/Transform: {translation, rotation}.
  Eigen::Isometry3d transform(const YAML::Node& n, const std::string& element) const {
    if (!n.IsMap()) fail(n, element + ": expected a transform {translation, rotation}");
    checkKeys(n, element, "geometry_msgs/Transform", {"translation", "rotation"});
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() =
        quaternion(require(n, "rotation", element), element + " rotation").toRotationMatrix();
    X.translation() = vector3(require(n, "translation", element), element + " translation");
    return X;
  }

  /// sensor_msgs/MultiDOFJointState `n` at `element`: one transform per joint name, names
  /// distinct, in file order. `max_joints` bounds the count (counted after alias expansion);
  /// `over_limit(count)` gives the error message beyond it.
  template <class OverLimit>
  std::vector<std::pair<std::string, Eigen::Isometry3d>> multiDofJointState(
      const YAML::Node& n, const std::string& element, std::size_t max_joints,
      OverLimit&& over_limit) const {
    checkKeys(n, element, "sensor_msgs/MultiDOFJointState",
              {"header", "joint_names", "transforms", "twist", "wrench"});
    const YAML::Node names = has(n, "joint_names")
                                 ? sequence(n["joint_names"], element + ".joint_names")
                                 : YAML::Node(YAML::NodeType::Sequence);
    const YAML::Node tr = has(n, "transforms") ? sequence(n["transforms"], element + ".transforms")
                                               : YAML::Node(YAML::NodeType::Sequence);
    if (names.size() != tr.size())
      fail(n, element + ": " + std::to_string(names.size()) + " joint names but " +
                  std::to_string(tr.size()) + " transforms");
    if (names.size() > max_joints) fail(names, over_limit(names.size()));
    std::vector<std::pair<std::string, Eigen::Isometry3d>> out;
    std::set<std::string> seen;
    for (std::size_t i = 0; i < names.size(); ++i) {
      const std::string name = string(names[i], element + ".joint_names");
      if (!seen.insert(name).second)
        fail(names[i], element + ": multi-DOF joint '" + name + "' given twice");
      out.emplace_back(name, transform(tr[i], element + " transform of '" + name + "'"));
    }
    return out;
  }

 private:
  // Numbers of a quaternion: NaN must reach checkedQuaternion's message, so not refused here.
  double rawNumber(const YAML::Node& n, const std::string& element) const {
    if (!n.IsScalar()) fail(n, element + ": expected a number");
    try {
      return n.as<double>();
    } catch (const YAML::Exception&) {
      fail(n, element + ": expected a number, got '" + n.Scalar() + "'");
    }
  }

  std::string file_;
  bool unknown_as_warnings_ = false;
  std::vector<std::string>* warnings_ = nullptr;
  std::string option_ = "unknown_keys_are_warnings";
};

}  // namespace scene_detail
}  // namespace dss
