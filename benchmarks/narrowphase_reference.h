// Reference answers for the narrow-phase benchmark, independent of the algorithms measured.
//
//  - Polytope pairs whose vertices are doubles (tetrahedra, random polytopes): an exact
//    separating-axis test over face normals and edge-edge cross products. Every sign is a
//    3x3 determinant of differences of input doubles, evaluated in double with an error
//    filter and, when the filter cannot decide, exactly in rational arithmetic
//    (boost::multiprecision::cpp_rational). No ties: the answer is exact for the inputs.
//  - Posed boxes, frustum-box and frustum-sphere: a separating-axis test (boxes) or the
//    point-to-polytope distance (spheres) in long double, giving a signed gap; pairs within
//    a relative tolerance of contact are reported as ties and not scored.
#pragma once

#include <cstdint>

#include "narrowphase_workloads.h"

namespace dss {
namespace bench {

enum class RefAnswer : std::uint8_t { kDisjoint = 0, kIntersect = 1, kTie = 2 };

/// Exact: do the closed hulls intersect? (touching counts as intersecting)
bool polytopesIntersectExact(const Polytope& a, const Polytope& b);

/// Signed separation (> 0 disjoint, < 0 penetrating) in long double.
long double boxBoxGap(const OrientedBox& a, const OrientedBox& b);
long double polytopeBoxGap(const Polytope& a, const OrientedBox& b);
long double polytopeBallGap(const Polytope& a, const Ball& b);

/// Relative tolerance of the long double references: |gap| <= kTieTolerance * scale is a tie.
inline constexpr long double kTieTolerance = 1e-12L;

/// Reference answers for every pair of the workload.
std::vector<RefAnswer> referenceAnswers(const WorkloadSet& w);

/// How many determinant signs needed the exact (rational) fallback so far.
std::uint64_t exactFallbackCount();

}  // namespace bench
}  // namespace dss
