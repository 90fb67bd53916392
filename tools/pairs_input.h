// Reading `dss_pairs` input: JSON Lines, one pair of posed convex shapes per line.
//
// A line is `{"id": ..., "a": SHAPE, "b": SHAPE}` with SHAPE one of sphere, box, cylinder,
// capsule, cone, ellipsoid (primitives, local frame, URDF dimensions, cone apex at +z as in
// fcl::Cone) or convex (a point set), each with an optional
// `"pose":{"position":[x,y,z],"orientation":[qx,qy,qz,qw]}` (ROS order; identity when
// absent). Every input error is reported as `PairsInputError` carrying the 1-based line
// number; the caller prefixes the file name. A key that the object at its place does not have
// (e.g. "radius" on a box, "Pose") and a key given twice in one object are errors: JSON
// parsers disagree on duplicates (nlohmann keeps the last), so the file is ambiguous. Nesting
// deeper than PairsInputLimits::max_depth is refused on the raw text, before parsing; values
// quoted in messages are cut short. Numbers go through nlohmann::json, whose
// floating-point reader is strtod (correctly rounded), so every decimal in the file becomes
// exactly the double it denotes.
#pragma once

#include <cstddef>
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

#include "dss/core/types.h"

namespace dss {
namespace pairs {

enum class ShapeKind { kSphere, kBox, kCylinder, kCapsule, kCone, kEllipsoid, kConvex };

const char* kindName(ShapeKind k);

/// One shape exactly as given in the file (validated), plus its rotation matrix.
struct ShapeSpec {
  ShapeKind kind = ShapeKind::kSphere;
  double radius = 0;            // sphere, cylinder, capsule, cone
  double length = 0;            // cylinder, capsule, cone (full length along z)
  Vec3d dims = Vec3d::Zero();   // box: full edge lengths; ellipsoid: radii
  std::vector<Vec3d> vertices;  // convex, in the shape's frame (or world without pose)
  bool has_pose = false;
  Vec3d p_WS = Vec3d::Zero();
  Mat3d R_WS = Mat3d::Identity();  // from the normalised quaternion
  /// Convex only: fl(R v + p) for each vertex when posed, the vertices as given otherwise.
  std::vector<Vec3d> worldVertices() const;
};

struct PairSpec {
  std::string id_json;  // the id, serialised as JSON (string or number)
  ShapeSpec a, b;
  int line = 0;  // 1-based line in the input
};

class PairsInputError : public std::runtime_error {
 public:
  PairsInputError(int line, const std::string& what) : std::runtime_error(what), line_(line) {}
  int line() const { return line_; }

 private:
  int line_;
};

/// Parses one line (no trailing newline). Throws PairsInputError.
/// Input budgets of a pairs file.
struct PairsInputLimits {
  /// Array and object nesting of one line, a line's object being 1 (largest in the shared
  /// samples: 4, vertices of a convex shape).
  static constexpr std::size_t kDefaultMaxDepth = 64;
  std::size_t max_depth = kDefaultMaxDepth;
};

PairSpec parsePairLine(const std::string& text, int line);
PairSpec parsePairLine(const std::string& text, int line, const PairsInputLimits& limits);

/// Reads every line of `in`. A final newline is allowed; any other empty or blank line is an
/// error. An empty input gives no pairs. Throws PairsInputError.
std::vector<PairSpec> readPairs(std::istream& in);
std::vector<PairSpec> readPairs(std::istream& in, const PairsInputLimits& limits);

/// The rotation of a quaternion in ROS order (x y z w), normalised. A zero or non-finite
/// quaternion throws std::invalid_argument. Exactly unit quaternions are used unchanged.
Mat3d rotationFromQuaternion(double qx, double qy, double qz, double qw);

}  // namespace pairs
}  // namespace dss
