// ModelValidityChecker (mapping, scratch, counters) and DssValidityChecker.
#include "dss/planning/validity_checker.h"

#include <algorithm>

#include <ompl/base/SpaceInformation.h>

namespace dss {

namespace {
// Per-thread scratch, shared by every checker a thread uses; it grows to the largest model
// and then never allocates again.
struct Scratch {
  std::vector<double> q;
  std::vector<Eigen::Isometry3d> X_WL;
  std::vector<unsigned char> table_skip;  // CollisionModel::readTables
  void reserve(std::size_t joints, std::size_t links) {
    if (q.size() < joints) q.resize(joints);
    if (X_WL.size() < links) X_WL.resize(links, Eigen::Isometry3d::Identity());
  }
};
Scratch& scratch() {
  thread_local Scratch s;
  return s;
}
}  // namespace

ModelValidityChecker::ModelValidityChecker(const ompl::base::SpaceInformationPtr& si,
                                           std::shared_ptr<const CollisionModel> model,
                                           std::shared_ptr<const GroupStateMap> map,
                                           double scene_padding, double self_padding)
    : ompl::base::StateValidityChecker(si), model_(std::move(model)), map_(std::move(map)),
      scene_padding_(scene_padding), self_padding_(self_padding) {
  specs_.clearanceComputationType = ompl::base::StateValidityCheckerSpecs::NONE;
  specs_.hasValidDirectionComputation = false;
}

bool ModelValidityChecker::isValid(const ompl::base::State* state) const {
  slot().checks.fetch_add(1, std::memory_order_relaxed);
  Scratch& s = scratch();
  s.reserve(model_->robot().numActiveJoints(), model_->robot().links.size());
  if (!map_->toJoints(state, s.q.data())) {
    slot().invalid_input.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  return checkJoints(s.q.data(), s.X_WL.data());
}

bool ModelValidityChecker::isValidJoints(const double* q) const {
  slot().checks.fetch_add(1, std::memory_order_relaxed);
  Scratch& s = scratch();
  s.reserve(model_->robot().numActiveJoints(), model_->robot().links.size());
  return checkJoints(q, s.X_WL.data());
}

bool ModelValidityChecker::checkJoints(const double* q, Eigen::Isometry3d* X_WL) const {
  const unsigned char* table_skip = nullptr;
  if (sweep_poses_ && model_->heldMatch(q)) {
    // A pair certified colliding by its table needs no pose; the tables are read once (the
    // sweep takes the flags of the pairs certified free); the sweep needs only the pose links
    // (CollisionModel::sweepKinematics).
    std::vector<unsigned char>& skip = scratch().table_skip;
    if (skip.size() < model_->selfTables().size()) skip.resize(model_->selfTables().size());
    if (model_->readTables(q, self_padding_, skip.data())) {
      slot().collisions.fetch_add(1, std::memory_order_relaxed);
      return false;
    }
    table_skip = skip.data();
    model_->sweepKinematics().computeLinkPoses(q, X_WL);
  } else {
    model_->kinematics().computeLinkPoses(q, X_WL);
  }
  if (collides(q, X_WL, table_skip)) {
    slot().collisions.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  return true;
}

ModelValidityChecker::CounterSlot& ModelValidityChecker::slot() const {
  static std::atomic<int> next{0};
  thread_local const int index = next.fetch_add(1, std::memory_order_relaxed) % kCounterSlots;
  return slots_[index];
}

CheckerCounters ModelValidityChecker::counters() const {
  CheckerCounters c;
  for (const auto& s : slots_) {
    c.checks += s.checks.load();
    c.invalid_input += s.invalid_input.load();
    c.collisions += s.collisions.load();
    c.pair_tests += s.pair_tests.load();
    c.cap_hits += s.cap_hits.load();
  }
  return c;
}

void ModelValidityChecker::resetCounters() {
  for (auto& s : slots_) {
    s.checks = 0;
    s.invalid_input = 0;
    s.collisions = 0;
    s.pair_tests = 0;
    s.cap_hits = 0;
  }
}

DssValidityChecker::DssValidityChecker(const ompl::base::SpaceInformationPtr& si,
                                       std::shared_ptr<const CollisionModel> model,
                                       std::shared_ptr<const GroupStateMap> map, const Settings& settings)
    : ModelValidityChecker(si, std::move(model), std::move(map), settings.scene_padding,
                           settings.self_padding),
      settings_(settings) {
  obb_stage_ = settings.obb_stage;
  sweep_poses_ = true;
  specs_.clearanceComputationType = ompl::base::StateValidityCheckerSpecs::BOUNDED_APPROXIMATE;
}

bool DssValidityChecker::collides(const double* q, const Eigen::Isometry3d* X_WL,
                                  const unsigned char* table_skip) const {
  return collidesPadded(q, X_WL, scene_padding_, self_padding_, table_skip);
}

double DssValidityChecker::clearance(const ompl::base::State* state) const {
  Scratch& s = scratch();
  s.reserve(model_->robot().numActiveJoints(), model_->robot().links.size());
  if (!map_->toJoints(state, s.q.data())) return 0.0;
  model_->kinematics().computeLinkPoses(s.q.data(), s.X_WL.data());
  const double* q = s.q.data();
  const Eigen::Isometry3d* X = s.X_WL.data();
  auto apart = [&](double r) { return !collidesPadded(q, X, scene_padding_ + r, self_padding_ + r); };
  if (!apart(0.0)) return 0.0;
  const double tol = settings_.clearance_tolerance > 0 ? settings_.clearance_tolerance : 1e-3;
  // Obstacles pruned from the model are at least prunedClearance() away: cap there.
  const double cap = std::max(0.0, std::min(settings_.clearance_max, model_->prunedClearance() - scene_padding_));
  // Invariant: apart(lo) proven, apart(hi) not (or hi is the cap).
  double lo = 0.0, hi = std::min(tol, cap);
  while (apart(hi)) {
    lo = hi;
    if (hi >= cap) return cap;
    hi = std::min(2.0 * hi, cap);
  }
  while (hi - lo > tol) {
    const double mid = 0.5 * (lo + hi);
    (apart(mid) ? lo : hi) = mid;
  }
  return lo;
}

bool DssValidityChecker::collidesPadded(const double* q, const Eigen::Isometry3d* X_WL, double scene_padding,
                                        double self_padding, const unsigned char* table_skip) const {
  const CollisionModel& m = *model_;
  const auto& elements = m.elements();
  const auto& obstacles = m.scene().obstacles;
  std::uint64_t tests = 0;
  bool cap = false;
  auto decideResult = [&](const Result& r) {
    ++tests;
    if (r.status == Status::kIterationLimit) cap = true;
    return r.intersect;
  };
  const bool hit = m.anyCollision(
      q, X_WL, scene_padding, self_padding,
      [&](int e, const Eigen::Isometry3d& X_WS, int o) {
        const Obstacle& ob = obstacles[o];
        return decideResult(intersect(elements[e].source->shape, X_WS, ob.shape, ob.X_WO,
                                      settings_.options, scene_padding, settings_.algorithm));
      },
      [&](int a, const Eigen::Isometry3d& X_WA, int b, const Eigen::Isometry3d& X_WB) {
        return decideResult(intersect(elements[a].source->shape, X_WA, elements[b].source->shape, X_WB,
                                      settings_.options, self_padding, settings_.algorithm));
      },
      obb_stage_, /*inner_stage=*/obb_stage_, table_skip);
  if (tests) slot().pair_tests.fetch_add(tests, std::memory_order_relaxed);
  if (cap) slot().cap_hits.fetch_add(1, std::memory_order_relaxed);
  return hit;
}

}  // namespace dss
