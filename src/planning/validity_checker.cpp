// ValidityChecker: OMPL states to joint values, then the state checker (see the header).
#include "dss/planning/validity_checker.h"

#include <atomic>
#include <cstring>
#include <typeinfo>
#include <vector>

namespace dss {

namespace {
double* jointScratch(std::size_t n) {
  thread_local std::vector<double> q;
  if (q.size() < n) q.resize(n);
  return q.data();
}

// The last state an adapter (by id; 0: none) found free on this thread, by its group values.
struct LastFree {
  static constexpr std::size_t kMaxValues = 32;
  std::uint64_t owner = 0;
  double v[kMaxValues];
};
LastFree& lastFree() {
  thread_local LastFree last;
  return last;
}
std::atomic<std::uint64_t> next_id{1};
}  // namespace

ValidityChecker::ValidityChecker(const ompl::base::SpaceInformationPtr& si,
                                 std::shared_ptr<const StateChecker> checker,
                                 std::shared_ptr<const GroupStateMap> map)
    : ompl::base::StateValidityChecker(si),
      checker_(std::move(checker)),
      dss_(dynamic_cast<const DssChecker*>(checker_.get())),
      map_(std::move(map)),
      id_(next_id.fetch_add(1, std::memory_order_relaxed)) {
  specs_.clearanceComputationType = dss_
                                        ? ompl::base::StateValidityCheckerSpecs::BOUNDED_APPROXIMATE
                                        : ompl::base::StateValidityCheckerSpecs::NONE;
  specs_.hasValidDirectionComputation = false;
}

bool ValidityChecker::isValid(const ompl::base::State* state) const {
  double* q = jointScratch(checker_->model().robot().numActiveJoints());
  if (!map_->toJoints(state, q)) {
    out_of_bounds_.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  if (checker_->check(q) != StateVerdict::kFree) return false;
  if (map_->dimension() <= LastFree::kMaxValues) {
    LastFree& last = lastFree();
    last.owner = id_;
    map_->toGroupValues(state, last.v);
  }
  return true;
}

bool ValidityChecker::lastFoundFree(const ompl::base::State* state) const {
  const std::size_t n = map_->dimension();
  const LastFree& last = lastFree();
  if (n > LastFree::kMaxValues || last.owner != id_) return false;
  double g[LastFree::kMaxValues];
  map_->toGroupValues(state, g);
  return std::memcmp(last.v, g, n * sizeof(double)) == 0;
}

const ValidityChecker* decidingChecker(const ompl::base::StateValidityChecker* checker) {
  // Asked once per motion: the usual answer, a ValidityChecker itself, by its type alone (a
  // comparison of two type_info pointers) before the dynamic casts' walk of the hierarchy.
  if (checker && typeid(*checker) == typeid(ValidityChecker))
    return static_cast<const ValidityChecker*>(checker);
  if (const auto* ours = dynamic_cast<const ValidityChecker*>(checker)) return ours;
  if (const auto* f = dynamic_cast<const ForwardingValidityChecker*>(checker)) return f->target();
  return nullptr;
}

MotionOrder motionOrderFrom(const ValidityChecker* checker, const ompl::base::State* s1) {
  return checker && checker->lastFoundFree(s1) ? MotionOrder::kEndLast : MotionOrder::kEndFirst;
}

double ValidityChecker::clearance(const ompl::base::State* state) const {
  if (!dss_) return ompl::base::StateValidityChecker::clearance(state);
  double* q = jointScratch(checker_->model().robot().numActiveJoints());
  if (!map_->toJoints(state, q)) return 0.0;
  return dss_->clearance(q);
}

std::optional<std::vector<Contact>> ValidityChecker::contacts(
    const ompl::base::State* state) const {
  if (!dss_) return std::nullopt;
  std::vector<double> q(checker_->model().robot().numActiveJoints());
  if (!map_->toJoints(state, q.data())) return std::nullopt;
  return contactsAt(*dss_, q.data());
}

CheckerCounters ValidityChecker::counters() const {
  CheckerCounters c = checker_->counters();
  const std::uint64_t n = out_of_bounds_.load(std::memory_order_relaxed);
  c.checks += n;
  c.invalid_input += n;
  return c;
}

}  // namespace dss
