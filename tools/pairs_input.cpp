// Validation of `dss_pairs` input lines: each field is checked where it enters, and the
// message names the side (a or b), the field and what is wrong with it.
#include "pairs_input.h"

#include <cmath>
#include <nlohmann/json.hpp>

namespace dss {
namespace pairs {
namespace {

using Json = nlohmann::json;

struct FieldError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

const Json& field(const Json& obj, const char* key, const std::string& where) {
  auto it = obj.find(key);
  if (it == obj.end()) throw FieldError(where + ": missing field \"" + key + "\"");
  return *it;
}

double number(const Json& v, const std::string& what) {
  if (!v.is_number()) throw FieldError(what + ": expected a number, got " + v.dump());
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
                     v.dump());
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
  if (!j.is_object()) throw FieldError(where + ": expected a shape object, got " + j.dump());
  const Json& type = field(j, "type", where);
  if (!type.is_string()) throw FieldError(where + ".type: expected a string, got " + type.dump());
  const std::string t = type.get<std::string>();
  ShapeSpec s;
  if (t == "sphere") {
    s.kind = ShapeKind::kSphere;
    s.radius = size(j, "radius", where);
  } else if (t == "box") {
    s.kind = ShapeKind::kBox;
    s.dims = sizes(j, "size", where);
  } else if (t == "cylinder" || t == "capsule" || t == "cone") {
    s.kind = t == "cylinder"  ? ShapeKind::kCylinder
             : t == "capsule" ? ShapeKind::kCapsule
                              : ShapeKind::kCone;
    s.radius = size(j, "radius", where);
    s.length = size(j, "length", where);
  } else if (t == "ellipsoid") {
    s.kind = ShapeKind::kEllipsoid;
    s.dims = sizes(j, "radii", where);
  } else if (t == "convex") {
    s.kind = ShapeKind::kConvex;
    const Json& v = field(j, "vertices", where);
    if (!v.is_array()) throw FieldError(where + ".vertices: expected an array of [x,y,z]");
    if (v.empty()) throw FieldError(where + ".vertices: empty vertex list");
    s.vertices.reserve(v.size());
    for (std::size_t i = 0; i < v.size(); ++i)
      s.vertices.push_back(numbers<3>(v[i], where + ".vertices[" + std::to_string(i) + "]"));
  } else {
    throw FieldError(where + ".type: unknown shape type \"" + t + "\"");
  }
  auto pose = j.find("pose");
  if (pose != j.end()) {
    const std::string pw = where + ".pose";
    if (!pose->is_object()) throw FieldError(pw + ": expected an object, got " + pose->dump());
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
  Json j;
  try {
    j = Json::parse(text);
  } catch (const Json::exception& e) {
    throw PairsInputError(line, std::string("bad JSON: ") + e.what());
  }
  try {
    if (!j.is_object()) throw FieldError("expected a JSON object {\"id\",\"a\",\"b\"}");
    PairSpec p;
    p.line = line;
    const Json& id = field(j, "id", "pair");
    if (!id.is_string() && !id.is_number())
      throw FieldError("id: expected a string or a number, got " + id.dump());
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

std::vector<PairSpec> readPairs(std::istream& in) {
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
    out.push_back(parsePairLine(text, line));
  }
  if (in.bad()) throw PairsInputError(line + 1, "read error");
  return out;
}

}  // namespace pairs
}  // namespace dss
