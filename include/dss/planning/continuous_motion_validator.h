// The OMPL motion validator on the conservative continuous motion check
// (dss/checker/continuous_motion.h): a thin adapter that maps the two states to joint values
// (continuous joints move the short way, as OMPL's SO2 interpolation does) and honours OMPL's
// lastValid contract (the last state known valid -- the start of the first sub-motion that
// could not be cleared -- and its fraction). Its valid/invalid motion counts are atomic (OMPL's
// own counters are left untouched: they are not safe to increment from several threads).
#pragma once

#include <ompl/base/MotionValidator.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <utility>

#include "dss/checker/continuous_motion.h"
#include "dss/planning/group_state_space.h"

namespace dss {

class ContinuousMotionValidator : public ompl::base::MotionValidator {
 public:
  ContinuousMotionValidator(const ompl::base::SpaceInformationPtr& si,
                            std::shared_ptr<const ContinuousMotionChecker> motion,
                            std::shared_ptr<const GroupStateMap> map);

  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

  const ContinuousMotionChecker& motionChecker() const { return *motion_; }
  std::uint64_t validMotions() const { return valid_motions_.load(std::memory_order_relaxed); }
  std::uint64_t invalidMotions() const { return invalid_motions_.load(std::memory_order_relaxed); }

 private:
  /// `last` (nullptr: not wanted, two states are then checked first): the last valid fraction.
  bool check(const ompl::base::State* s1, const ompl::base::State* s2, double* last) const;

  std::shared_ptr<const ContinuousMotionChecker> motion_;
  std::shared_ptr<const GroupStateMap> map_;
  mutable std::atomic<std::uint64_t> valid_motions_{0}, invalid_motions_{0};
};

/// Motions checked so far by a motion validator: ours count atomically, OMPL's own count in
/// getValidMotionCount() and getInvalidMotionCount().
std::uint64_t motionChecks(const ompl::base::MotionValidator& validator);

}  // namespace dss
