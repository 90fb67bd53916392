// The OMPL state validity checker: a thin adapter that maps an OMPL state of the group's space
// to the robot's joint values (GroupStateMap) and asks a state checker (dss/checker): DSS, or
// FCL on the same model.
//
// isValid(state): a value outside the space's bounds, NaN or Inf makes the state invalid
// (counted as invalid input); otherwise the checker's verdict. Each thread records the group
// values of the last state it found free (groups of up to 32 values), for lastFoundFree().
// clearance(state): with a DSS checker, a guaranteed lower bound within the checker's tolerance
// (StateValidityCheckerSpecs::BOUNDED_APPROXIMATE); with FCL, none (NONE). contacts(state):
// with a DSS checker, the pairs colliding there. Const and thread-safe, as the checker it holds.
#pragma once

#include <ompl/base/StateValidityChecker.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "dss/checker/contacts.h"
#include "dss/checker/discrete_motion.h"
#include "dss/checker/dss_checker.h"
#include "dss/checker/state_checker.h"
#include "dss/planning/group_state_space.h"

namespace dss {

class ValidityChecker : public ompl::base::StateValidityChecker {
 public:
  ValidityChecker(const ompl::base::SpaceInformationPtr& si,
                  std::shared_ptr<const StateChecker> checker,
                  std::shared_ptr<const GroupStateMap> map);

  bool isValid(const ompl::base::State* state) const override;
  /// 0 for an invalid state; see the header for what is computed.
  double clearance(const ompl::base::State* state) const override;
  /// With a DSS checker, the pairs that collide at `state` (dss/checker/contacts.h: empty for
  /// a free state; name them with describeContact(checker().model(), c)); nullopt for a state
  /// outside the bounds, or with another checker. A diagnostic: it allocates.
  std::optional<std::vector<Contact>> contacts(const ompl::base::State* state) const;

  const StateChecker& checker() const { return *checker_; }
  const std::shared_ptr<const StateChecker>& checkerPtr() const { return checker_; }
  /// True when `state` has exactly the group values of the last state this adapter found free
  /// on this thread (a planner moving on from the state it has just validated; see
  /// DiscreteMotionValidator). False for groups of more than 32 values.
  bool lastFoundFree(const ompl::base::State* state) const;
  /// The checker's counters, with the states this adapter refused before asking it.
  CheckerCounters counters() const;

 private:
  std::shared_ptr<const StateChecker> checker_;
  const DssChecker* dss_ = nullptr;  ///< the checker, when it computes clearance
  std::shared_ptr<const GroupStateMap> map_;
  std::uint64_t id_;  ///< this adapter's key in the per-thread record of the last free state
  mutable std::atomic<std::uint64_t> out_of_bounds_{0};
};

/// A validity checker that passes every state on to one of ours unchanged (a switch between
/// the checkers of a benchmark, a wrapper that logs): the motion validators look through it
/// (decidingChecker) and check a motion's states as they would under that checker itself, in
/// the same order and on the same joint-value path.
class ForwardingValidityChecker : public ompl::base::StateValidityChecker {
 public:
  using ompl::base::StateValidityChecker::StateValidityChecker;
  /// The checker isValid passes states to now; null when there is none.
  virtual const ValidityChecker* target() const = 0;
};

/// The dss::ValidityChecker that decides the states `checker` is asked about: `checker` itself
/// when it is one, the target of a ForwardingValidityChecker, null for any other.
const ValidityChecker* decidingChecker(const ompl::base::StateValidityChecker* checker);

/// The discrete check's order (discrete_motion.h) for a motion from s1 checked under `checker`
/// (null: a validity checker that is not ours): kEndLast when it has just found s1 free on this
/// thread (a planner moving from the state it has just validated towards one it holds),
/// kEndFirst otherwise. Both motion validators take their order from here.
MotionOrder motionOrderFrom(const ValidityChecker* checker, const ompl::base::State* s1);

}  // namespace dss
