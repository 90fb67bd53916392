// YAML access with messages that name the file, the line and the element (internal to the
// scene readers). yaml-cpp counts lines from 0; messages count from 1.
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "dss/scene/scene_error.h"
#include "scene_util.h"

namespace dss {
namespace scene_detail {

class YamlReader {
 public:
  explicit YamlReader(std::string file) : file_(std::move(file)) {}

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
    if (n.IsMap())
      return {number(require(n, "x", element), element + ".x"),
              number(require(n, "y", element), element + ".y"),
              number(require(n, "z", element), element + ".z")};
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
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() =
        quaternion(require(n, "orientation", element), element + " orientation").toRotationMatrix();
    X.translation() = vector3(require(n, "position", element), element + " position");
    return X;
  }

  /// geometry_msgs/Transform: {translation, rotation}.
  Eigen::Isometry3d transform(const YAML::Node& n, const std::string& element) const {
    if (!n.IsMap()) fail(n, element + ": expected a transform {translation, rotation}");
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() =
        quaternion(require(n, "rotation", element), element + " rotation").toRotationMatrix();
    X.translation() = vector3(require(n, "translation", element), element + " translation");
    return X;
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
};

}  // namespace scene_detail
}  // namespace dss
