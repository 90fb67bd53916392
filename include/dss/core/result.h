// Options, status and result of a pairwise intersection decision (DSS, GJK and Hybrid
// share them, so that benchmarks and failure accounting treat all three alike).
#pragma once

#include <cstdint>

#include "dss/core/types.h"

namespace dss {

/// Arithmetic of the decision.
///  - kExact: double arithmetic with filtered signs and an exact fallback. Never wrong for
///    shapes whose support returns input points (two ConvexHulls in world coordinates, or at
///    the exact identity pose on the model-shape dispatch of any_shape_query.h); for other
///    shapes -- every posed shape, so every robot link -- a "disjoint" answer is certified and
///    an "intersect" answer is exact up to the rounding of the support points (about 1e-16 of
///    their size). A checker built on it never answers "free" for a colliding pair.
///  - kDouble: plain double signs; may be wrong within rounding of contact.
///  - kFloat: the search in float (supports of double shapes are rounded to float); may be
///    wrong within float rounding of contact.
enum class Mode : std::uint8_t { kExact, kDouble, kFloat };

enum class Status : std::uint8_t {
  kDecided,         ///< the answer was proved (within the mode's guarantee)
  kIterationLimit,  ///< the cap was reached: answered "intersect", conservatively
  kInvalidInput,    ///< NaN or Inf met: answered "intersect", conservatively
};

struct Options {
  Mode mode = Mode::kExact;
  /// Cap on support evaluations (plane tests). Near-tangent curved shapes need more than the
  /// paper's 20; hitting the cap answers "intersect" and is reported in the status.
  int max_iterations = 64;
};

struct Result {
  bool intersect = true;  ///< touching counts as intersecting
  Status status = Status::kDecided;
  int iterations = 0;  ///< support evaluations of the Minkowski difference
  /// For a disjoint answer: a direction n with h_A(n) < -h_B(-n), i.e. the plane with normal
  /// n separates A (behind) from B (in front). Zero otherwise.
  Vec3d separating_direction = Vec3d::Zero();
};

inline const char* toString(Status s) {
  switch (s) {
    case Status::kDecided:
      return "decided";
    case Status::kIterationLimit:
      return "iteration_limit";
    case Status::kInvalidInput:
      return "invalid_input";
  }
  return "unknown";
}

inline const char* toString(Mode m) {
  switch (m) {
    case Mode::kExact:
      return "exact";
    case Mode::kDouble:
      return "double";
    case Mode::kFloat:
      return "float";
  }
  return "unknown";
}

}  // namespace dss
