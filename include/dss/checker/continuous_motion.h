// A conservative continuous motion check: no collision between two states along the straight
// joint-space motion can be missed. The quaternion of a ball joint (a floating joint's
// rotation) moves by slerp along the shorter arc, as OMPL's SO(3) and SE(3) spaces
// interpolate: a turn about a fixed axis at a constant rate, bounded like a revolute joint's.
//
// Over a sub-motion [t0, t1], every point p of a slot moves along a path p(t) with
//   |p'|  <= V = sum over moving joints j above it of |dq_j| reach_j + sum of prismatic |dq_j|
//   |p''| <= B = sum over revolute j of |dq_j| reach_j (2 W_<j + |dq_j|)
//                + 2 sum over prismatic j of |dq_j| W_<j   (at most 2 W V)
// where W_<j is the revolute |dq| above joint j and W the total (dq over the sub-motion, t in
// [0, 1]; motion_bounds.h). So p(t) lies within
//   pad = min(V / 2, B / 8)
// of the chord (1 - t) p(t0) + t p(t1) (the linear-interpolation error bound |p''| / 8 for the
// quadratic term; the nearer end point for the linear one), and every intermediate pose of an
// element lies inside conv(X_t0(S) U X_t1(S)) grown by pad: a padded swept hull, decided by
// DSS (dss/core/any_shape_sweep.h). The quadratic term makes the bound shrink four-fold per
// halving.
//
// Work is kept per unit (element vs obstacle, element vs element of a self pair): a
// sub-motion tests its units in order until one is not cleared; that unit and the ones not yet
// tested are left to its two halves (the failing one first), while the units it cleared are
// never tested again inside it. A unit goes through cheap stages before its swept test:
//  - robot vs scene: the ball around the element's swept sphere against the clearance grid
//    (one lookup clears the element against every obstacle) and the obstacle's box; then the
//    element's local box at both ends, bounded in the obstacle box's frame and grown by the
//    padding, against that box;
//  - self pairs: a pair with a self-pair table is cleared when every table cell its joint
//    values cross over the sub-motion is certified free. Otherwise both links are swept in the
//    frame of their lowest common ancestor: the joints above it move both links together and
//    add nothing to their relative motion, so only the joints in between enter the paddings
//    (the time correlation of the two links is ignored, which is conservative); their swept
//    spheres, then their local boxes bounded in the first element's frame.
// A unit whose padding still exceeds half its element's radius skips the swept test while the
// sub-motion can be halved (such tests mostly fail, and cost more than the halving). A
// sub-motion with units left is halved, left half first, after checking its midpoint state
// with the poses computed for the halves' ends: a colliding midpoint ends the search at once
// (the motion is invalid). A unit still not cleared at the minimum fraction makes the motion
// invalid.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "dss/checker/discrete_motion.h"
#include "dss/checker/dss_checker.h"
#include "dss/checker/motion_bounds.h"

namespace dss {

/// The continuous check's smallest sub-motion unless told otherwise: a fraction of the motion.
constexpr double kDefaultMinFraction = 1.0 / 1024.0;

class ContinuousMotionChecker {
 public:
  /// `checker` supplies the model, the paddings and the mode (and checks midpoint states).
  /// `min_fraction` in (0, 1]: the smallest sub-motion before giving up. Throws
  /// std::invalid_argument otherwise.
  explicit ContinuousMotionChecker(std::shared_ptr<const DssChecker> checker,
                                   double min_fraction = kDefaultMinFraction);

  /// True when the straight motion from q0 to q1 (active joint values) is free of collisions.
  /// Otherwise `last_valid_fraction` (optional) receives the start of the first sub-motion that
  /// could not be cleared: every state before it is free. States outside the model's bounds
  /// make the motion invalid (last valid fraction 0). Without `last_valid_fraction`, when the
  /// whole motion is not cleared at once, two states are checked before the first midpoint, as
  /// the discrete check's `kind` order begins (discrete_motion.h): the end state q1 and the
  /// state three quarters of the way (kEndFirst), or the states three quarters and nine tenths
  /// of the way (kEndLast: a motion towards a state the caller holds). A colliding one answers
  /// at once (the same answer).
  bool clear(const double* q0, const double* q1, double* last_valid_fraction = nullptr,
             MotionOrder kind = MotionOrder::kEndFirst) const;

  /// The padding of each model slot over the straight motion qa -> qb (all active joints):
  /// every point of the slot's geometry stays within pad[k] of the chord between its positions
  /// at qa and qb. Zero for fixed slots.
  void paddings(const double* qa, const double* qb, double* pad) const;

  const DssChecker& checker() const { return *checker_; }
  /// Sub-motions examined (each motion counts one at least) and swept tests run.
  std::uint64_t subMotions() const { return sub_motions_.load(std::memory_order_relaxed); }
  std::uint64_t unitTests() const { return unit_tests_.load(std::memory_order_relaxed); }

 private:
  // A unit: element `a` (model element index) against obstacle `b` (self == false) or
  // against element `b` (self == true).
  struct Unit {
    int a = -1, b = -1;
    bool self = false;
    int table = -1;             ///< self: the pair's self-pair table, or -1
    int pair = -1;              ///< self: index into pairs_
    std::uint8_t base_bit = 0;  ///< scene: the element's slot's bit in the base-scene table
  };
  // A self pair of slots, seen from the lowest link above both whose pose the kinematics
  // compute (`frame`; -1: the world, when that link never moves): only the joints between it
  // and each slot move the slot there (`chain_a`, `chain_b`: indices into rel_chains_, shared
  // by the pairs of a slot with the same common ancestor).
  struct PairFrame {
    int frame = -1;
    int chain_a = -1, chain_b = -1;
    bool still_a = false, still_b = false;  ///< no joint moves the slot in the frame
  };
  /// `may_defer`: the sub-motion can still be halved (see kDeferRatio in the source).
  bool unitClear(const Unit& u, const Eigen::Isometry3d* XA, const Eigen::Isometry3d* XB,
                 bool may_defer, std::uint64_t* tests) const;

  std::shared_ptr<const DssChecker> checker_;
  double min_fraction_;
  std::vector<std::vector<ChainTerm>> chains_;      ///< per slot: the joints that move it
  std::vector<Unit> units_;                         ///< every unit of the model, in sweep order
  std::vector<PairFrame> pairs_;                    ///< per self pair of the model
  std::vector<std::vector<ChainTerm>> rel_chains_;  ///< a slot's joints below an ancestor
  std::vector<int> balls_;                          ///< the first state value of each ball joint
  mutable std::atomic<std::uint64_t> sub_motions_{0}, unit_tests_{0};
};

}  // namespace dss
