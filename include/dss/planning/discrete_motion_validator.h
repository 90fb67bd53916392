// The OMPL motion validator on the discrete motion check (dss/checker/discrete_motion.h): the
// same states as OMPL's DiscreteMotionValidator (the space's validSegmentCount segments, the
// interior states interpolated by the space, the end state itself) and the same verdicts and
// lastValid, with the states checked in an order that finds collisions sooner when lastValid is
// not wanted: OMPL's (the end first) for a motion towards a new state, and the end last for a
// motion from the state the space information's validity checker (a dss::ValidityChecker) has
// just found free, as a planner moves from a state it has just validated towards one it holds
// (MotionOrder in discrete_motion.h).
//
// When the space is a plain real vector (the group has no continuous or multi-DOF joints) and
// the space information's validity checker is a dss::ValidityChecker on the same collision
// model (any checker of the same Problem; or a checker forwarding to one: decidingChecker in
// validity_checker.h), the interior states are interpolated in joint values (OMPL's formula,
// value by value) and checked by that checker's state checker without an OMPL state or a
// virtual call; otherwise the space interpolates them and the space information's validity
// checker decides them. The end state always goes through the space information's validity
// checker, as in OMPL. A motion with NaN, an infinity or a bounded value beyond its limits at
// either end is colliding (OMPL assumes the start valid; such a start is not); an angle beyond
// [-pi, pi] is taken as the same angle within it. A motion checked before the space is set up
// (SpaceInformation::setup, which SimpleSetup's setup and solve call) throws: the space has
// no resolution yet. Motion counts are atomic (OMPL's own counters are
// not safe to increment from several threads), also per kind of motion (towards a new state, or
// from a state just found free towards a held one: MotionOrder), with the states each kind had
// checked one by one and those batches proved free: where a plan's checking goes.
#pragma once

#include <ompl/base/MotionValidator.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <utility>

#include "dss/checker/checker_counters.h"
#include "dss/checker/discrete_motion.h"
#include "dss/planning/group_state_space.h"

namespace dss {

class ValidityChecker;

/// One kind of motion's counts (DiscreteMotionValidator::counts).
struct MotionCounts {
  std::uint64_t motions = 0;    ///< checked
  std::uint64_t colliding = 0;  ///< of them found colliding
  /// States decided one by one (each state checker call, the end state's included), and states
  /// proven free by batches (StateChecker::freeLanes) and so never checked one by one.
  std::uint64_t exact_states = 0;
  std::uint64_t batch_free_states = 0;
};

class DiscreteMotionValidator : public ompl::base::MotionValidator {
 public:
  DiscreteMotionValidator(const ompl::base::SpaceInformationPtr& si,
                          std::shared_ptr<const DiscreteMotionChecker> motion,
                          std::shared_ptr<const GroupStateMap> map);

  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

  const DiscreteMotionChecker& motionChecker() const { return *motion_; }
  std::uint64_t validMotions() const;
  std::uint64_t invalidMotions() const;
  /// The counts of the motions checked in `kind` order so far: kEndLast, motions from the state
  /// the validity checker has just found free (in order from the start when lastValid is
  /// wanted); kEndFirst, every other one.
  MotionCounts counts(MotionOrder kind) const;

 private:
  /// False (the motion counted as colliding) when s1 or s2 is not valid input (NaN, an
  /// infinity, a bounded value beyond its limits). Otherwise true, with s1 and s2 replaced by
  /// per-thread copies brought within the space's bounds where they lie outside them (an angle
  /// beyond [-pi, pi]: the same joint positions).
  bool usableEnds(const ompl::base::State*& s1, const ompl::base::State*& s2) const;
  /// The space's validSegmentCount(s1, s2). Throws std::logic_error, naming the space, when
  /// the space is not set up: its longest valid segment is then 0 and OMPL's count undefined
  /// (in practice 0, which would check the end state alone).
  int segmentCount(const ompl::base::State* s1, const ompl::base::State* s2) const;
  /// `first_colliding` (nullptr: not wanted): the first colliding state, in 1 .. n.
  bool check(const ompl::base::State* s1, const ompl::base::State* s2, int n,
             int* first_colliding) const;
  /// Whether interior states can be checked in joint values (see the header); `vc`: the checker
  /// deciding the space information's states, when it is ours.
  bool directPath(const ValidityChecker* vc) const;

  std::shared_ptr<const DiscreteMotionChecker> motion_;
  std::shared_ptr<const GroupStateMap> map_;
  /// MotionCounts' fields per kind (kEndFirst, kEndLast), in per-thread slots as the checkers'
  /// counters (checker_counters.h).
  struct KindCounts {
    std::atomic<std::uint64_t> motions{0}, colliding{0}, exact_states{0}, batch_free_states{0};
  };
  struct alignas(64) CountSlot {
    KindCounts kind[2];
  };
  /// One motion of `kind` counted in this thread's slot.
  void count(MotionOrder kind, bool colliding, std::uint64_t exact, std::uint64_t proven) const;
  mutable CountSlot count_slots_[kOwnedSlots + 1];
};

}  // namespace dss
