// A conservative continuous motion validator: no collision between two states along the
// straight joint-space motion can be missed.
//
// Over a sub-motion [t0, t1], every point p of link L moves along a path p(t) with
//   |p'|  <= V_L = sum over moving joints j above L of |dq_j| * R_jL + sum of prismatic |dq_j|
//   |p''| <= 4 W_L V_L,   W_L = sum of revolute |dq_j| above L   (dq over the sub-motion, t in [0, 1])
// (R_jL: a bound on the distance of L's geometry from joint j's origin). So p(t) lies within
//   pad_L = min(V_L / 2, W_L V_L / 2)
// of the chord (1 - t) p(t0) + t p(t1) (the linear-interpolation error bound |p''| / 8 for the
// quadratic term; the nearer end point for the linear one), and every intermediate pose of an
// element lies inside conv(X_t0(S) U X_t1(S)) grown by pad_L: a padded SweptHull, decided by
// DSS. The quadratic term makes the bound shrink four-fold per halving once W_L < 1 rad.
//
// Work is kept per unit (element vs obstacle, element vs element of a self pair): a
// sub-motion tests its units in order until one is not cleared; that unit and the ones not yet
// tested are left to its two halves (the failing one first), while the units it cleared are
// never tested again inside it. A sub-motion with units left is halved, left half first, after
// checking its midpoint state: a colliding midpoint ends the search at once (the motion is
// invalid). A unit still not
// cleared at the minimum fraction makes the motion invalid. For self pairs both links are
// swept, ignoring the time correlation, which is conservative. OMPL's lastValid contract: the
// last state known valid (start of the first failing sub-motion) and its fraction.
#pragma once

#include <atomic>
#include <memory>
#include <utility>

#include <ompl/base/MotionValidator.h>

#include "dss/planning/validity_checker.h"

namespace dss {

class ContinuousMotionValidator : public ompl::base::MotionValidator {
 public:
  /// `checker` supplies the model, the state map and the paddings (and validates end states).
  /// `min_fraction`: the smallest sub-motion before giving up (default 1/1024).
  ContinuousMotionValidator(const ompl::base::SpaceInformationPtr& si,
                            std::shared_ptr<const DssValidityChecker> checker,
                            double min_fraction = 1.0 / 1024.0);

  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

  /// Sub-motions examined (the whole motion counts as one).
  std::uint64_t subMotions() const { return sub_motions_.load(); }
  /// Swept narrow-phase tests run.
  std::uint64_t unitTests() const { return unit_tests_.load(); }

  /// The padding of each model slot (CollisionModel::slots()) over the straight motion from
  /// joint vector qa to qb (all active joints): every point of the slot's geometry stays
  /// within pad[k] of the chord between its positions at qa and qb. Zero for fixed slots.
  void paddings(const double* qa, const double* qb, double* pad) const;

 private:
  bool check(const double* q0, const double* q1, double* last_valid_fraction) const;
  // A unit: element `a` (model element index) against obstacle `b` (self == false) or
  // against element `b` (self == true).
  struct Unit {
    int a = -1, b = -1;
    bool self = false;
  };
  bool unitClear(const Unit& u, const double* pad) const;

  std::shared_ptr<const DssValidityChecker> checker_;
  double min_fraction_;
  // For each slot: the moving joints above it (active index or mimic) and R_jL.
  struct ChainTerm {
    int active;          // active joint index read
    double multiplier;   // mimic multiplier (1 for active joints)
    double radius;       // R_jL (revolute) or -1 (prismatic)
  };
  std::vector<std::vector<ChainTerm>> chains_;
  std::vector<Unit> units_;  // every unit of the model, in sweep order
  mutable std::atomic<std::uint64_t> sub_motions_{0}, unit_tests_{0};
};

}  // namespace dss
