// Validation of `dss_pairs` input lines: each field is checked where it enters, and the
// message names the side (a or b), the field and what is wrong with it.
#include "pairs_input.h"

#include <cmath>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <set>

#include "../src/common/nesting_scan.h"

namespace dss {
namespace pairs {
namespace {

using Json = nlohmann::json;

struct FieldError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

constexpr std::size_t kShownChars = 60;

// A short rendering of a value for messages: at most about kShownChars characters and three
// levels of nesting, whatever the value's size (a message never holds a whole input value).
void brief(const Json& v, int depth, std::string& out) {
  if (out.size() > kShownChars) return;
  if (v.is_array() || v.is_object()) {
    if (depth >= 3 || v.empty()) {
      out += v.is_array() ? (v.empty() ? "[]" : "[...]") : (v.empty() ? "{}" : "{...}");
      return;
    }
    out += v.is_array() ? '[' : '{';
    bool first = true;
    for (auto it = v.begin(); it != v.end(); ++it) {
      if (out.size() > kShownChars) break;
      if (!first) out += ',';
      first = false;
      if (v.is_object()) out += Json(it.key()).dump() + ':';
      brief(*it, depth + 1, out);
    }
    out += v.is_array() ? ']' : '}';
    return;
  }
  out += v.dump();
}

std::string brief(const Json& v) {
  std::string out;
  brief(v, 0, out);
  if (out.size() > kShownChars) out = out.substr(0, kShownChars) + "...";
  return out;
}

// Every key of `obj` must be one of `known` (duplicates are caught while parsing).
void checkKeys(const Json& obj, const std::string& where, const std::string& what,
               std::initializer_list<const char*> known) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool ok = false;
    for (const char* k : known) ok = ok || it.key() == k;
    if (ok) continue;
    std::string list;
    for (const char* k : known) list += std::string(list.empty() ? "" : ", ") + "\"" + k + "\"";
    throw FieldError(where + ": unknown field " + brief(Json(it.key())) + " (" + what + " has " +
                     list + ")");
  }
}

const Json& field(const Json& obj, const char* key, const std::string& where) {
  auto it = obj.find(key);
  if (it == obj.end()) throw FieldError(where + ": missing field \"" + key + "\"");
  return *it;
}

double number(const Json& v, const std::string& what) {
  if (!v.is_number()) throw FieldError(what + ": expected a number, got " + brief(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw FieldError(what + ": non-finite number");
  return x;
}

double size(const Json& obj, const char* key, const std::string& where) {
  const std::string what = where + "." + key;
  const double x = number(field(obj, key, where), what);
  if (x < 0) throw FieldError(what + ": negative size " + Json(x).dump());
  return x;
}

template <int N>
Eigen::Matrix<double, N, 1> numbers(const Json& v, const std::string& what) {
  if (!v.is_array() || v.size() != N)
    throw FieldError(what + ": expected an array of " + std::to_string(N) + " numbers, got " +
                     brief(v));
  Eigen::Matrix<double, N, 1> out;
  for (int i = 0; i < N; ++i) out[i] = number(v[i], what + "[" + std::to_string(i) + "]");
  return out;
}

Vec3d sizes(const Json& obj, const char* key, const std::string& where) {
  const std::string what = where + "." + key;
  const Vec3d x = numbers<3>(field(obj, key, where), what);
  for (int i = 0; i < 3; ++i)
    if (x[i] < 0) throw FieldError(what + ": negative size " + Json(x[i]).dump());
  return x;
}

ShapeSpec parseShape(const Json& j, const std::string& where) {
  if (!j.is_object()) throw FieldError(where + ": expected a shape object, got " + brief(j));
  const Json& type = field(j, "type", where);
  if (!type.is_string()) throw FieldError(where + ".type: expected a string, got " + brief(type));
  const std::string t = type.get<std::string>();
  ShapeSpec s;
  if (t == "sphere") {
    checkKeys(j, where, "a sphere", {"type", "radius", "pose"});
    s.kind = ShapeKind::kSphere;
    s.radius = size(j, "radius", where);
  } else if (t == "box") {
    checkKeys(j, where, "a box", {"type", "size", "pose"});
    s.kind = ShapeKind::kBox;
    s.dims = sizes(j, "size", where);
  } else if (t == "cylinder" || t == "capsule" || t == "cone") {
    checkKeys(j, where, "a " + t, {"type", "radius", "length", "pose"});
    s.kind = t == "cylinder"  ? ShapeKind::kCylinder
             : t == "capsule" ? ShapeKind::kCapsule
                              : ShapeKind::kCone;
    s.radius = size(j, "radius", where);
    s.length = size(j, "length", where);
  } else if (t == "ellipsoid") {
    checkKeys(j, where, "an ellipsoid", {"type", "radii", "pose"});
    s.kind = ShapeKind::kEllipsoid;
    s.dims = sizes(j, "radii", where);
  } else if (t == "convex") {
    checkKeys(j, where, "a convex shape", {"type", "vertices", "pose"});
    s.kind = ShapeKind::kConvex;
    const Json& v = field(j, "vertices", where);
    if (!v.is_array()) throw FieldError(where + ".vertices: expected an array of [x,y,z]");
    if (v.empty()) throw FieldError(where + ".vertices: empty vertex list");
    s.vertices.reserve(v.size());
    for (std::size_t i = 0; i < v.size(); ++i)
      s.vertices.push_back(numbers<3>(v[i], where + ".vertices[" + std::to_string(i) + "]"));
  } else {
    throw FieldError(where + ".type: unknown shape type " + brief(type));
  }
  auto pose = j.find("pose");
  if (pose != j.end()) {
    const std::string pw = where + ".pose";
    if (!pose->is_object()) throw FieldError(pw + ": expected an object, got " + brief(*pose));
    checkKeys(*pose, pw, "a pose", {"position", "orientation"});
    s.has_pose = true;
    s.p_WS = numbers<3>(field(*pose, "position", pw), pw + ".position");
    const Eigen::Vector4d q = numbers<4>(field(*pose, "orientation", pw), pw + ".orientation");
    try {
      s.R_WS = rotationFromQuaternion(q[0], q[1], q[2], q[3]);
    } catch (const std::invalid_argument& e) {
      throw FieldError(pw + ".orientation: " + e.what());
    }
  }
  if (s.kind == ShapeKind::kConvex) {
    // Posing can overflow; the hull would refuse the point later, say so here instead.
    for (const Vec3d& w : s.worldVertices())
      if (!w.allFinite()) throw FieldError(where + ".vertices: a posed vertex is not finite");
  }
  return s;
}

}  // namespace

const char* kindName(ShapeKind k) {
  switch (k) {
    case ShapeKind::kSphere:
      return "sphere";
    case ShapeKind::kBox:
      return "box";
    case ShapeKind::kCylinder:
      return "cylinder";
    case ShapeKind::kCapsule:
      return "capsule";
    case ShapeKind::kCone:
      return "cone";
    case ShapeKind::kEllipsoid:
      return "ellipsoid";
    case ShapeKind::kConvex:
      return "convex";
  }
  return "unknown";
}

std::vector<Vec3d> ShapeSpec::worldVertices() const {
  if (!has_pose) return vertices;
  std::vector<Vec3d> out;
  out.reserve(vertices.size());
  // fl(R v + p), once: these doubles are the shape that the exact mode decides on.
  for (const Vec3d& v : vertices) out.push_back(Vec3d(R_WS * v) + p_WS);
  return out;
}

Mat3d rotationFromQuaternion(double qx, double qy, double qz, double qw) {
  Eigen::Quaterniond q(qw, qx, qy, qz);
  if (!q.coeffs().allFinite()) throw std::invalid_argument("non-finite quaternion");
  if (q.coeffs().isZero(0)) throw std::invalid_argument("zero quaternion");
  double n = q.norm();
  if (!(n > 0) || !std::isfinite(n)) {
    // Under- or overflow of the squared norm: rescale by the largest component first.
    q.coeffs() /= q.coeffs().cwiseAbs().maxCoeff();
    n = q.norm();
  }
  // A quaternion that is unit in floating point is kept bit for bit (exact rotations such as
  // components in {0, +-0.5, +-1} then give exact matrices).
  if (n != 1.0) q.coeffs() /= n;
  return q.toRotationMatrix();
}

PairSpec parsePairLine(const std::string& text, int line) {
  return parsePairLine(text, line, PairsInputLimits{});
}

PairSpec parsePairLine(const std::string& text, int line, const PairsInputLimits& limits) {
  // nlohmann::json's dump and our messages recurse per level: bound the nesting on the raw
  // text first.
  const input_scan::NestingExcess deep = input_scan::jsonNesting(text, limits.max_depth);
  if (deep.exceeded)
    throw PairsInputError(line, "column " + std::to_string(deep.column) +
                                    ": arrays and objects nest deeper than the limit of " +
                                    std::to_string(limits.max_depth) +
                                    " (PairsInputLimits::max_depth in tools/pairs_input.h)");
  // Duplicate keys: nlohmann keeps the last value silently; the parser callback sees every
  // key of every object as it is read.
  std::vector<std::set<std::string>> keys;  // one set per open object
  std::string duplicate;
  const Json::parser_callback_t callback = [&](int, Json::parse_event_t event, Json& parsed) {
    if (event == Json::parse_event_t::object_start) {
      keys.emplace_back();
    } else if (event == Json::parse_event_t::object_end) {
      if (!keys.empty()) keys.pop_back();
    } else if (event == Json::parse_event_t::key && !keys.empty() && duplicate.empty()) {
      const std::string k = parsed.get<std::string>();
      if (!keys.back().insert(k).second) duplicate = k;
    }
    return true;
  };
  Json j;
  try {
    j = Json::parse(text, callback);
  } catch (const Json::exception& e) {
    std::string what = e.what();
    if (what.size() > 200) what = what.substr(0, 200) + "...";
    throw PairsInputError(line, "bad JSON: " + what);
  }
  if (!duplicate.empty())
    throw PairsInputError(line, "duplicate key " + brief(Json(duplicate)) +
                                    " in an object (each key may appear once)");
  try {
    if (!j.is_object()) throw FieldError("expected a JSON object {\"id\",\"a\",\"b\"}");
    checkKeys(j, "pair", "a pair", {"id", "a", "b"});
    PairSpec p;
    p.line = line;
    const Json& id = field(j, "id", "pair");
    if (!id.is_string() && !id.is_number())
      throw FieldError("id: expected a string or a number, got " + brief(id));
    p.id_json = id.dump();
    p.a = parseShape(field(j, "a", "pair"), "a");
    p.b = parseShape(field(j, "b", "pair"), "b");
    return p;
  } catch (const FieldError& e) {
    throw PairsInputError(line, e.what());
  } catch (const Json::exception& e) {
    throw PairsInputError(line, std::string("bad value: ") + e.what());
  }
}

std::vector<PairSpec> readPairs(std::istream& in) { return readPairs(in, PairsInputLimits{}); }

std::vector<PairSpec> readPairs(std::istream& in, const PairsInputLimits& limits) {
  std::vector<PairSpec> out;
  std::string text;
  int line = 0;
  // std::getline does not return an empty piece after a final newline, so a trailing newline
  // is accepted and every other empty line is reported.
  while (std::getline(in, text)) {
    ++line;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.find_first_not_of(" \t") == std::string::npos)
      throw PairsInputError(line, "empty line");
    out.push_back(parsePairLine(text, line, limits));
  }
  if (in.bad()) throw PairsInputError(line + 1, "read error");
  return out;
}

}  // namespace pairs
}  // namespace dss
