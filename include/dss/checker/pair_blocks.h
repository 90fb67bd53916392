// Pair blocks: runs of self pairs that share their first slot, tested behind one ball.
//
// Self pairs [begin, end) share slot a (consecutive in the model's self pairs). With anchor
// >= 0, the spheres of all their b slots lie, in every state with the held joints at their
// held values, inside the ball of `radius` about the origin of link `anchor` (an ancestor of
// them all, and a pose link, so the folded sweep has its pose): when a's sphere misses that
// ball, no pair of the block can pass its own sphere test, and the sweep skips the block in
// one test. The radius is the motion bound from each b slot's sphere up to the anchor
// (motion_bounds.h). A ball is kept only where it pays on random states of the group (it
// must save at least CollisionModelOptions::pair_block_min_saving per-pair sphere tests per
// state); consecutive blocks without a ball are merged. (The Panda: link0, link1 and link2
// against link5 .. the fingers, 17 of its 21 self pairs, behind balls about link5.)
#pragma once

#include <vector>

namespace dss {

class CollisionModel;

struct PairBlock {
  int a = -1;
  int begin = 0, end = 0;
  int anchor = -1;
  double radius = 0.0;
};

/// The blocks of a model's self pairs (its slots, self pairs, tables and pose links set).
std::vector<PairBlock> buildPairBlocks(const CollisionModel& model, double min_saving);

}  // namespace dss
