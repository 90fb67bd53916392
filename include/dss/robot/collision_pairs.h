// Which pairs of robot links ever need a self-collision check, and the MoveIt Setup
// Assistant style computation of pairs that never (or always) collide.
//
// The candidate pairs are all pairs of links with geometry, minus:
//  - adjacent links: joined by a joint, also across links without geometry (a link without
//    geometry joins all the geometry links around it, as the Setup Assistant does);
//  - links rigidly attached to each other (no moving joint between them: their relative pose
//    never changes, so a check can never change its answer) — optional, on by default;
//  - SRDF <disable_collisions>;
//  - an extra allowed list (e.g. a scene's allowed collision matrix).
// Link pairs are (a, b) with a < b, link indices of the model.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "dss/robot/robot_model.h"
#include "dss/robot/srdf.h"

namespace dss {

using LinkPair = std::pair<int, int>;

/// Adjacent pairs among links with geometry (see above), each once, sorted.
std::vector<LinkPair> adjacentLinkPairs(const RobotModel& model);

struct SelfCollisionPairs {
  std::vector<LinkPair> pairs;  ///< to check, sorted
  std::size_t geometry_links = 0;
  std::size_t all_pairs = 0;    ///< pairs of links with geometry
  std::size_t adjacent = 0;     ///< removed as adjacent
  std::size_t rigid = 0;        ///< removed as rigidly attached (and not adjacent)
  std::size_t disabled = 0;     ///< removed by the SRDF (and not already removed)
  std::size_t allowed = 0;      ///< removed by the extra allowed list (and not already removed)
  std::string summary() const;  ///< e.g. "check 23 of 55 link pairs (adjacent 10, ...)"
};

/// `srdf` may be nullptr. Names in the SRDF or in `allowed` that the model lacks throw
/// std::runtime_error naming the source and the link.
SelfCollisionPairs selfCollisionPairs(
    const RobotModel& model, const Srdf* srdf,
    const std::vector<std::pair<std::string, std::string>>& allowed = {},
    bool exclude_rigid = true);

/// Do links a and b (with all their collision elements at the given link poses) intersect?
/// Exact-mode DSS; touching counts as intersecting.
bool linksIntersect(const RobotModel& model, const Eigen::Isometry3d* X_WL, int a, int b);

struct DisabledPairsOptions {
  int samples = 10000;
  std::uint64_t seed = 1;
  /// Also report pairs in collision at the default state ("Default"), as the Setup Assistant does.
  bool include_default = true;
};

struct DisabledPairsResult {
  std::vector<SrdfDisabledPair> pairs;  ///< reasons: Adjacent, Default, Always, Never
  int samples = 0;
  std::size_t checked_pairs = 0;  ///< pairs sampled (not adjacent, not default)
  /// The SRDF lines, one <disable_collisions .../> per pair.
  std::string toSrdf() const;
};

/// Samples `samples` uniform random states within the joint limits (continuous joints in
/// [-pi, pi]) and reports every pair of links with geometry that is adjacent, in collision at
/// the default state, in collision in every sample, or in none.
DisabledPairsResult computeDisabledPairs(const RobotModel& model,
                                         const DisabledPairsOptions& options = {});

}  // namespace dss
