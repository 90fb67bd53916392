// Eight states at once (the states of one motion, as a motion validator interpolates them):
// which of them the cheap stages prove free, in float lanes, so that only the others need the
// exact check.
//
// In double as the checkers do: the model's bounds and the held joints at their held values
// (CollisionModel::boundedHeldLanes), then per lane the self-pair tables (none certifies a
// collision; their free flags skip pairs). Then in float lanes, one state per lane: the pose
// links' poses (kinematics_batch.h), every slot sphere's centre, the clearance grid's lower bound
// at each sphere checked against the scene, then where the grid does not clear it its distance
// to each of its obstacles' oriented boxes (slots with at most 16 obstacles), and where the
// sphere alone is not cleared the same two tests for each ball of the slot's cover (its
// elements' chains of balls, sphere_chain.h); and for every self pair the tables leave, the two
// slot spheres (then each ball of one cover against the other slot's sphere or its cover's
// balls), and for the lanes those leave, every pair of the two slots' elements' local boxes
// (element_bounds.h) by the separating-axis test.
// A lane is proven free when every such test proves its link clear of the obstacles' boxes and
// every such pair apart, each test grown by margin(), which bounds the float poses' error (and
// the box distances by the roundings of the boxes' float coordinates, and the local boxes by
// their own bound on the float poses' error at their corners).
//
// Each test proves the pair it covers apart by more than the padding. Every stage of the exact
// sweep (sweep.h) is conservative (it reports a collision only where one is proven) and its
// narrow phase is exact, so the exact check of a state proven free here answers "free" (only a
// narrow phase at its iteration cap could answer otherwise, and pairs this far apart do not
// reach it). States not proven free are left to the exact check: a batch changes no answer.
//
// Arms only (kinematics_batch.h): a model with a prismatic, planar or floating group joint, or
// with a base-scene table, proves no lane free (enabled() is false).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "dss/checker/collision_model.h"
#include "dss/core/simd_path.h"
#include "dss/robot/kinematics_batch.h"

namespace dss {

class StateBatch {
 public:
  static constexpr int kLanes = KinematicsBatch::kLanes;

  StateBatch() = default;
  /// For checks of `model` (which must outlive the batch) at these paddings.
  StateBatch(const CollisionModel& model, double scene_padding, double self_padding);

  bool enabled() const { return enabled_; }
  /// How far (metres) a float centre may lie from the exact one: every test is grown by it.
  double margin() const { return margin_; }

  /// Bit l set when state l (l < n <= kLanes) is proven free, the states given value by value:
  /// active joint value j of state l at lanes[kLanes j + l] (all kLanes lanes readable; those
  /// past n are ignored). kScalar proves none (every state to the exact check); kSse2 and
  /// kAvx2 run the lanes.
  unsigned freeLanes(const double* lanes, int n, SimdPath path) const;

 private:
  struct SceneSlot {
    int slot;       ///< index into the slots
    int threshold;  ///< its sphere is cleared when the grid's bound (quanta) exceeds this
    float reach2;   ///< its sphere is clear of an oriented box beyond this squared distance
    int first_box = 0, num_boxes = 0;  ///< its obstacles' oriented boxes, into boxes_
  };
  /// An obstacle's oriented box in float (obb.h): a point p is at distance
  /// |max(|R^T (p - c)| - h, 0)| from it.
  struct Box {
    float r[9];  ///< R column by column
    float c[3], h[3];
  };
  /// A ball of a slot's cover (its elements' chains of balls, sphere_chain.h).
  struct Ball {
    float c[3];     ///< in the pose link's frame
    float grown;    ///< radius + margin + half the self padding, rounded up
    int threshold;  ///< cleared of the scene when the grid's bound exceeds this
    float reach2;   ///< clear of an oriented box beyond this squared distance
  };
  struct Cover {
    int first = 0, count = 0;  ///< into balls_ (none: the sphere alone)
  };
  struct SelfPair {
    int a, b;   ///< slots
    int table;  ///< -1: none
  };
  /// An element's local box in its slot's pose link frame: axes (R column by column), centre
  /// and half extents, and how far its float world placement may lie from the exact one.
  struct ElementBox {
    float r[9];
    float c[3], h[3];
    float error;
  };
  struct SlotBoxes {
    int first = 0, count = 0;  ///< into element_boxes_ (none: the slot has too many elements)
  };
  /// The lanes' work after the per-lane tests: `valid` lanes, the tables' flags (per table, bit
  /// l for lane l).
  unsigned provenFree(const double* qs, unsigned valid, const unsigned* skip, SimdPath path) const;
  unsigned runGeneric(const double* qs, unsigned valid, const unsigned* skip) const;
  unsigned runAvx2(const double* qs, unsigned valid, const unsigned* skip) const;
  unsigned run(const double* qs, unsigned valid, const unsigned* skip, SimdPath path) const;

  const CollisionModel* model_ = nullptr;
  bool enabled_ = false;
  double margin_ = 0.0;
  double self_padding_ = 0.0;
  KinematicsBatch kin_;
  std::vector<int> slot_link_;      ///< per slot: its pose link
  std::vector<float> slot_center_;  ///< per slot: its centre in the pose link's frame (3)
  std::vector<float> slot_grown_;   ///< per slot: its radius grown as Ball::grown
  std::vector<Cover> cover_;        ///< per slot
  std::vector<Ball> balls_;
  std::vector<SceneSlot> scene_;
  std::vector<Box> boxes_;
  std::vector<SelfPair> pairs_;
  std::vector<SlotBoxes> slot_boxes_;  ///< per slot
  std::vector<ElementBox> element_boxes_;
  std::size_t num_links_ = 0;
};

}  // namespace dss
