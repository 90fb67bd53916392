// DiscreteMotionValidator: OMPL's states of a motion, checked in the discrete motion check's
// order (see the header).
#include "dss/planning/discrete_motion_validator.h"

#include <ompl/base/SpaceInformation.h>

#include <stdexcept>
#include <vector>

#include "dss/planning/validity_checker.h"

namespace dss {

namespace ob = ompl::base;

namespace {
// A per-thread state of `space` for interpolated states: kept until the thread ends or asks for
// another space's (no allocation per motion once warm).
ob::State* scratchState(const ob::StateSpacePtr& space, int which = 0) {
  struct Slot {
    ob::StateSpacePtr space;
    ob::State* state = nullptr;
    ~Slot() {
      if (state) space->freeState(state);
    }
  };
  thread_local Slot slots[3];
  Slot& slot = slots[which];
  if (slot.space != space) {
    if (slot.state) slot.space->freeState(slot.state);
    slot.space = space;
    slot.state = space->allocState();
  }
  return slot.state;
}
// The joint values of the ends of the motion this thread checks (usableEnds reads them, the
// direct path interpolates between them).
struct Ends {
  std::vector<double> q0, q1;
};
Ends& endValues() {
  thread_local Ends ends;
  return ends;
}
}  // namespace

DiscreteMotionValidator::DiscreteMotionValidator(
    const ob::SpaceInformationPtr& si, std::shared_ptr<const DiscreteMotionChecker> motion,
    std::shared_ptr<const GroupStateMap> map)
    : ob::MotionValidator(si), motion_(std::move(motion)), map_(std::move(map)) {}

bool DiscreteMotionValidator::directPath(const ValidityChecker* vc) const {
  // The same model (every checker of one Problem shares it): the joint values map_ gives are
  // the ones vc's checker takes.
  return map_->plain() && vc && &vc->checker().model() == &motion_->checker().model();
}

bool DiscreteMotionValidator::usableEnds(const ob::State*& s1, const ob::State*& s2) const {
  Ends& ends = endValues();
  const std::size_t nq = map_->robot().numActiveJoints();
  if (ends.q0.size() < nq) ends.q0.resize(nq), ends.q1.resize(nq);
  if (map_->toJoints(s1, ends.q0.data()) && map_->toJoints(s2, ends.q1.data())) {
    const ob::StateSpacePtr& space = si_->getStateSpace();
    // A plain space's bounds are the ones toJoints held the values to.
    if (map_->plain() || (space->satisfiesBounds(s1) && space->satisfiesBounds(s2))) return true;
    // Valid input outside the space's own bounds: an angle beyond [-pi, pi] (OMPL's SO(2)
    // distance asserts on it), a quaternion off unit norm. Wrapped copies take their place,
    // the same joint positions.
    ob::State* w1 = scratchState(space, 1);
    ob::State* w2 = scratchState(space, 2);
    space->copyState(w1, s1);
    space->copyState(w2, s2);
    space->enforceBounds(w1);
    space->enforceBounds(w2);
    s1 = w1, s2 = w2;
    return true;
  }
  count(MotionOrder::kEndFirst, true, 0, 0);
  return false;
}

bool DiscreteMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  // An end that is not valid input (NaN, an infinity, a bounded value beyond its limits) makes
  // the motion colliding before the space measures it: its segment count would be undefined or
  // absurd.
  if (!usableEnds(s1, s2)) return false;
  return check(s1, s2, segmentCount(s1, s2), nullptr);
}

bool DiscreteMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                          std::pair<ob::State*, double>& lastValid) const {
  const ob::State* start = s1;
  if (!usableEnds(s1, s2)) {
    lastValid.second = 0.0;
    if (lastValid.first) si_->getStateSpace()->copyState(lastValid.first, start);
    return false;
  }
  const int n = segmentCount(s1, s2);
  int first = 0;
  if (check(s1, s2, n, &first)) return true;
  lastValid.second = n > 0 ? double(first - 1) / double(n) : 0.0;
  if (lastValid.first) si_->getStateSpace()->interpolate(s1, s2, lastValid.second, lastValid.first);
  return false;
}

int DiscreteMotionValidator::segmentCount(const ob::State* s1, const ob::State* s2) const {
  const ob::StateSpace& space = *si_->getStateSpace();
  if (!(space.getLongestValidSegmentLength() > 0.0))
    throw std::logic_error("dss::DiscreteMotionValidator: state space '" + space.getName() +
                           "' is not set up (no resolution yet): call setup() on the space "
                           "information (SimpleSetup::setup and solve do) before checking motions");
  return static_cast<int>(space.validSegmentCount(s1, s2));
}

bool DiscreteMotionValidator::check(const ob::State* s1, const ob::State* s2, int n,
                                    int* first_colliding) const {
  const ob::SpaceInformation& si = *si_;
  const int segments = n < 1 ? 1 : n;
  const ValidityChecker* vc = decidingChecker(si.getStateValidityChecker().get());
  const MotionOrder kind = motionOrderFrom(vc, s1);
  std::uint64_t exact = 0, proven = 0;  // this motion's states, one by one and by batches
  bool ok;
  if (directPath(vc)) {
    const StateChecker& checker = vc->checker();
    const std::size_t nq = checker.model().robot().numActiveJoints();
    thread_local std::vector<double> q;
    if (q.size() < nq) q.resize(nq);
    // The ends' joint values, as usableEnds() has just read them.
    const Ends& ends = endValues();
    const double *a = ends.q0.data(), *b = ends.q1.data();
    double* const qs = q.data();
    auto free = [&](int j) {
      ++exact;
      if (j == segments) return si.isValid(s2);
      const double t = double(j) / double(n);
      for (std::size_t k = 0; k < nq; ++k) qs[k] = a[k] + (b[k] - a[k]) * t;
      return !checker.collides(qs);
    };
    if (motion_->batched()) {
      auto batch = [&](const int* js, int m) {
        const unsigned lanes = freeInterpolated(checker, a, b, n, js, m);
        proven += static_cast<std::uint64_t>(__builtin_popcount(lanes));
        return lanes;
      };
      ok = motionStatesFreeBatched(segments, free, batch, first_colliding, kind);
    } else {
      ok = motionStatesFree(segments, free, first_colliding, kind);
    }
  } else {
    const ob::StateSpacePtr& space = si.getStateSpace();
    ob::State* test = scratchState(space);
    auto free = [&](int j) {
      ++exact;
      if (j == segments) return si.isValid(s2);
      space->interpolate(s1, s2, double(j) / double(n), test);
      return si.isValid(test);
    };
    ok = motionStatesFree(segments, free, first_colliding, kind);
  }
  count(kind, !ok, exact, proven);
  return ok;
}

void DiscreteMotionValidator::count(MotionOrder kind, bool colliding, std::uint64_t exact,
                                    std::uint64_t proven) const {
  const int slot = threadSlotIndex();
  KindCounts& c = count_slots_[slot].kind[kind == MotionOrder::kEndLast];
  addToSlot(c.motions, 1, slot);
  if (colliding) addToSlot(c.colliding, 1, slot);
  addToSlot(c.exact_states, exact, slot);
  if (proven) addToSlot(c.batch_free_states, proven, slot);
}

std::uint64_t DiscreteMotionValidator::validMotions() const {
  const MotionCounts a = counts(MotionOrder::kEndFirst), b = counts(MotionOrder::kEndLast);
  return (a.motions - a.colliding) + (b.motions - b.colliding);
}

std::uint64_t DiscreteMotionValidator::invalidMotions() const {
  return counts(MotionOrder::kEndFirst).colliding + counts(MotionOrder::kEndLast).colliding;
}

MotionCounts DiscreteMotionValidator::counts(MotionOrder kind) const {
  MotionCounts out;
  for (const CountSlot& slot : count_slots_) {
    const KindCounts& c = slot.kind[kind == MotionOrder::kEndLast];
    out.motions += c.motions.load(std::memory_order_relaxed);
    out.colliding += c.colliding.load(std::memory_order_relaxed);
    out.exact_states += c.exact_states.load(std::memory_order_relaxed);
    out.batch_free_states += c.batch_free_states.load(std::memory_order_relaxed);
  }
  return out;
}

}  // namespace dss
