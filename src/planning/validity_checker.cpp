// ValidityChecker: OMPL states to joint values, then the state checker (see the header).
#include "dss/planning/validity_checker.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <atomic>
#include <cstring>
#include <vector>

namespace dss {

namespace {
double* jointScratch(std::size_t n) {
  thread_local std::vector<double> q;
  if (q.size() < n) q.resize(n);
  return q.data();
}

// The last state an adapter (by id; 0: none) found free on this thread, by its values.
struct LastFree {
  static constexpr std::size_t kMaxValues = 16;
  std::uint64_t owner = 0;
  double v[kMaxValues];
};
LastFree& lastFree() {
  thread_local LastFree last;
  return last;
}
std::atomic<std::uint64_t> next_id{1};

// The values of a plain real vector state of n values, or null (another space, or too many).
const double* plainValues(const GroupStateMap& map, const ompl::base::State* s) {
  if (!map.plain() || map.dimension() > LastFree::kMaxValues) return nullptr;
  return s->as<ompl::base::RealVectorStateSpace::StateType>()->values;
}
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
  if (const double* v = plainValues(*map_, state)) {
    LastFree& last = lastFree();
    last.owner = id_;
    std::memcpy(last.v, v, map_->dimension() * sizeof(double));
  }
  return true;
}

bool ValidityChecker::lastFoundFree(const ompl::base::State* state) const {
  const double* v = plainValues(*map_, state);
  const LastFree& last = lastFree();
  return v && last.owner == id_ && std::memcmp(last.v, v, map_->dimension() * sizeof(double)) == 0;
}

double ValidityChecker::clearance(const ompl::base::State* state) const {
  if (!dss_) return ompl::base::StateValidityChecker::clearance(state);
  double* q = jointScratch(checker_->model().robot().numActiveJoints());
  if (!map_->toJoints(state, q)) return 0.0;
  return dss_->clearance(q);
}

CheckerCounters ValidityChecker::counters() const {
  CheckerCounters c = checker_->counters();
  const std::uint64_t n = out_of_bounds_.load(std::memory_order_relaxed);
  c.checks += n;
  c.invalid_input += n;
  return c;
}

}  // namespace dss
