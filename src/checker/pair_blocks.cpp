// Pair blocks (see pair_blocks.h).
#include "dss/checker/pair_blocks.h"

#include <limits>
#include <random>

#include "dss/checker/collision_model.h"
#include "dss/checker/motion_bounds.h"
#include "group_sample.h"

namespace dss {

std::vector<PairBlock> buildPairBlocks(const CollisionModel& model, double min_saving) {
  // Runs of consecutive pairs with the same slot a; a run with at least kMinBlock pairs outside
  // the tables (the tables skip most of theirs already) gets an anchor when one exists.
  constexpr int kMinBlock = 3;
  const RobotModel& m = model.robot();
  const auto& slots = model.slots();
  const auto& pairs = model.selfPairs();
  auto isAncestorOrSelf = [&](int anc, int link) {
    for (int l = link; l >= 0; l = m.links[l].parent_link)
      if (l == anc) return true;
    return false;
  };
  // A bound on the distance from the anchor's origin to any point of slot s's sphere.
  auto reach = [&](int anchor, int s) {
    double r = 0.0;
    chainAbove(m, slots[s].link, anchor, slots[s].center_L.norm() + slots[s].radius, model.held(),
               &r);
    return r;
  };
  std::vector<PairBlock> blocks;
  for (std::size_t i = 0; i < pairs.size();) {
    std::size_t j = i;
    int untabled = 0;
    while (j < pairs.size() && pairs[j].a == pairs[i].a) untabled += pairs[j++].table < 0;
    PairBlock blk;
    blk.a = pairs[i].a;
    blk.begin = static_cast<int>(i);
    blk.end = static_cast<int>(j);
    if (untabled >= kMinBlock) {
      // Of the pose links that are ancestors of every b slot, the one with the smallest ball.
      double best = std::numeric_limits<double>::infinity();
      for (const CollisionModel::Slot& cand : slots) {
        const int anchor = cand.pose_link;
        double radius = 0.0;
        for (std::size_t k = i; k < j && radius >= 0.0; ++k) {
          const int b = pairs[k].b;
          radius =
              isAncestorOrSelf(anchor, slots[b].link) ? std::max(radius, reach(anchor, b)) : -1.0;
        }
        if (radius >= 0.0 && radius < best) best = radius, blk.anchor = anchor;
      }
      if (blk.anchor >= 0 && std::isfinite(best))
        blk.radius = best + 1e-9 * (1.0 + best);
      else
        blk.anchor = -1;
    }
    blocks.push_back(blk);
    i = j;
  }
  // A ball is kept only where it pays: on random states of the group (a fixed seed, the held
  // joints at their values) it must rule its block out often enough to save more per-pair
  // sphere tests than the one test it costs (a ball about a gripper whose links always overlap
  // the shared link's sphere would only add work).
  constexpr int kSamples = 256;
  std::mt19937_64 rng(1);
  std::vector<double> q = model.held();
  std::vector<Eigen::Isometry3d> X(m.links.size(), Eigen::Isometry3d::Identity());
  std::vector<int> ruled_out(blocks.size(), 0);
  for (int k = 0; k < kSamples; ++k) {
    detail::drawGroupState(model, rng, q);
    model.sweepKinematics().computeLinkPoses(q.data(), X.data());
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      const PairBlock& blk = blocks[b];
      if (blk.anchor < 0) continue;
      const CollisionModel::Slot& sa = slots[blk.a];
      const double r = blk.radius + sa.radius;
      ruled_out[b] +=
          (X[sa.pose_link] * sa.center_P - X[blk.anchor].translation()).squaredNorm() > r * r;
    }
  }
  std::vector<PairBlock> kept;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    PairBlock blk = blocks[b];
    const double saved = static_cast<double>(ruled_out[b]) / kSamples * (blk.end - blk.begin);
    if (blk.anchor >= 0 && saved < min_saving) blk.anchor = -1;
    if (blk.anchor < 0 && !kept.empty() && kept.back().anchor < 0 && kept.back().end == blk.begin)
      kept.back().end = blk.end;  // one run of pairs without a ball
    else
      kept.push_back(blk);
  }
  return kept;
}

}  // namespace dss
