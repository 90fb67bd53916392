// DiscreteMotionValidator: OMPL's states of a motion, checked in the discrete motion check's
// order (see the header).
#include "dss/planning/discrete_motion_validator.h"

#include <ompl/base/SpaceInformation.h>

#include <vector>

#include "dss/planning/validity_checker.h"

namespace dss {

namespace ob = ompl::base;

namespace {
// A per-thread state of `space` for interpolated states: kept until the thread ends or asks for
// another space's (no allocation per motion once warm).
ob::State* scratchState(const ob::StateSpacePtr& space) {
  struct Slot {
    ob::StateSpacePtr space;
    ob::State* state = nullptr;
    ~Slot() {
      if (state) space->freeState(state);
    }
  };
  thread_local Slot slot;
  if (slot.space != space) {
    if (slot.state) slot.space->freeState(slot.state);
    slot.space = space;
    slot.state = space->allocState();
  }
  return slot.state;
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

bool DiscreteMotionValidator::nonFinite(const ob::State* s1, const ob::State* s2) const {
  if (map_->finiteValues(s1) && map_->finiteValues(s2)) return false;
  KindCounts& c = kind_counts_[0];
  c.motions.fetch_add(1, std::memory_order_relaxed);
  c.colliding.fetch_add(1, std::memory_order_relaxed);
  return true;
}

bool DiscreteMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  // NaN or infinity at an end: colliding, before the space measures the motion (its segment
  // count would be undefined, and an SO(2) part asserts on such a state).
  if (nonFinite(s1, s2)) return false;
  const int n = static_cast<int>(si_->getStateSpace()->validSegmentCount(s1, s2));
  return check(s1, s2, n, nullptr);
}

bool DiscreteMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                          std::pair<ob::State*, double>& lastValid) const {
  if (nonFinite(s1, s2)) {
    lastValid.second = 0.0;
    if (lastValid.first) si_->getStateSpace()->copyState(lastValid.first, s1);
    return false;
  }
  const int n = static_cast<int>(si_->getStateSpace()->validSegmentCount(s1, s2));
  int first = 0;
  if (check(s1, s2, n, &first)) return true;
  lastValid.second = n > 0 ? double(first - 1) / double(n) : 0.0;
  if (lastValid.first) si_->getStateSpace()->interpolate(s1, s2, lastValid.second, lastValid.first);
  return false;
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
    thread_local std::vector<double> q0, q1, q;
    if (q.size() < nq) q0.resize(nq), q1.resize(nq), q.resize(nq);
    // The raw values (toJoints' bounds verdict does not matter here: the end state goes through
    // the validity checker, interior states through the checker's own bounds).
    map_->toJoints(s1, q0.data());
    map_->toJoints(s2, q1.data());
    const double *a = q0.data(), *b = q1.data();
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
  KindCounts& c = kind_counts_[kind == MotionOrder::kEndLast];
  c.motions.fetch_add(1, std::memory_order_relaxed);
  if (!ok) c.colliding.fetch_add(1, std::memory_order_relaxed);
  c.exact_states.fetch_add(exact, std::memory_order_relaxed);
  if (proven) c.batch_free_states.fetch_add(proven, std::memory_order_relaxed);
  return ok;
}

std::uint64_t DiscreteMotionValidator::validMotions() const {
  const MotionCounts a = counts(MotionOrder::kEndFirst), b = counts(MotionOrder::kEndLast);
  return (a.motions - a.colliding) + (b.motions - b.colliding);
}

std::uint64_t DiscreteMotionValidator::invalidMotions() const {
  return counts(MotionOrder::kEndFirst).colliding + counts(MotionOrder::kEndLast).colliding;
}

MotionCounts DiscreteMotionValidator::counts(MotionOrder kind) const {
  const KindCounts& c = kind_counts_[kind == MotionOrder::kEndLast];
  MotionCounts out;
  out.motions = c.motions.load(std::memory_order_relaxed);
  out.colliding = c.colliding.load(std::memory_order_relaxed);
  out.exact_states = c.exact_states.load(std::memory_order_relaxed);
  out.batch_free_states = c.batch_free_states.load(std::memory_order_relaxed);
  return out;
}

}  // namespace dss
