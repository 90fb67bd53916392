// A conservative continuous motion validator: no collision between two states along the
// straight joint-space motion can be missed.
//
// Over a sub-motion [t0, t1], every point of link L travels a path no longer than
//   len_L = sum over moving joints j above L of |dq_j| * R_jL   (R_jL: a bound on the
//           distance of L's geometry from joint j's origin; prismatic joints add |dq_j|),
// so each point at time t lies within len_L / 2 of its position at t0 or at t1. Hence every
// intermediate pose of an element lies inside conv(X_t0(S) U X_t1(S)) grown by len_L / 2
// (a padded SweptHull, decided by DSS). A pair is cleared for the whole sub-motion when those
// bounds are disjoint (for self pairs both links are swept, ignoring the time correlation,
// which is conservative). Otherwise the sub-motion is halved, left half first, down to a
// minimum fraction; a pair still not cleared there makes the motion invalid. OMPL's
// lastValid contract: the last state known valid (start of the first failing leaf) and its
// fraction of the motion.
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

  std::uint64_t subMotions() const { return sub_motions_.load(); }

 private:
  bool check(const double* q0, const double* q1, double* last_valid_fraction) const;
  bool clear(const double* qa, const double* qb) const;

  std::shared_ptr<const DssValidityChecker> checker_;
  double min_fraction_;
  // For each slot: the moving joints above it (active index or mimic) and R_jL.
  struct ChainTerm {
    int active;          // active joint index read
    double multiplier;   // mimic multiplier (1 for active joints)
    double radius;       // R_jL (revolute) or 1 (prismatic)
  };
  std::vector<std::vector<ChainTerm>> chains_;
  mutable std::atomic<std::uint64_t> sub_motions_{0};
};

}  // namespace dss
