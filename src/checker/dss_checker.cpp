// DssChecker: the sweep with exact DSS as its narrow phase (see dss_checker.h).
#include "dss/checker/dss_checker.h"

#include <algorithm>
#include <vector>

#include "dss/checker/sweep.h"
#include "dss/core/any_shape_query.h"

namespace dss {

namespace {
// Per-thread scratch, shared by every checker a thread uses; it grows to the largest model and
// then never allocates again.
struct Scratch {
  std::vector<Eigen::Isometry3d> X_WL;
  std::vector<unsigned char> skip;
  void reserve(const CollisionModel& m) {
    if (X_WL.size() < m.robot().links.size())
      X_WL.resize(m.robot().links.size(), Eigen::Isometry3d::Identity());
    if (skip.size() < m.selfTables().size()) skip.resize(m.selfTables().size());
  }
};
Scratch& scratch() {
  thread_local Scratch s;
  return s;
}
}  // namespace

DssChecker::DssChecker(std::shared_ptr<const CollisionModel> model, const Settings& settings)
    : StateChecker(std::move(model)),
      settings_(settings),
      batch_(this->model(), settings.scene_padding, settings.self_padding) {}

unsigned DssChecker::provenFree(const double* lanes, int n) const {
  return batch_.freeLanes(lanes, n, batch_path_);
}

bool DssChecker::collidesWithinBounds(const double* q, CounterSlots::Slot&) const {
  const CollisionModel& m = model();
  Scratch& s = scratch();
  s.reserve(m);
  // A planar base's table: a colliding cell answers before any kinematics; links certified
  // free there skip their robot-scene stages.
  const std::uint8_t base_free = m.baseTable().read(q, settings_.scene_padding);
  if (base_free == BaseSceneTable::kColliding) return true;
  const bool held = m.heldMatch(q);
  if (m.selfTables().read(q, held, settings_.self_padding, s.skip.data())) return true;
  // With the held joints at their values the sweep needs only the pose links.
  (held ? m.sweepKinematics() : m.kinematics()).computeLinkPoses(q, s.X_WL.data());
  return collidesAt(s.X_WL.data(), held, s.skip.data(), settings_.scene_padding,
                    settings_.self_padding, base_free);
}

bool DssChecker::collidesAt(const Eigen::Isometry3d* X_WL, bool pose_links,
                            const unsigned char* skip, double scene_padding, double self_padding,
                            std::uint8_t base_free) const {
  const CollisionModel& m = model();
  const auto& elements = m.elements();
  const auto& obstacles = m.scene().obstacles;
  std::uint64_t tests = 0;
  bool cap = false;
  auto decide = [&](const Result& r) {
    ++tests;
    cap |= r.status == Status::kIterationLimit;
    return r.intersect;
  };
  auto scene = [&](int e, const Eigen::Isometry3d& X_WS, int o) {
    const Obstacle& ob = obstacles[o];
    return decide(intersect(elements[e].source->shape, X_WS, ob.shape, ob.X_WO, settings_.options,
                            scene_padding));
  };
  auto self = [&](int a, const Eigen::Isometry3d& X_WA, int b, const Eigen::Isometry3d& X_WB) {
    return decide(intersect(elements[a].source->shape, X_WA, elements[b].source->shape, X_WB,
                            settings_.options, self_padding));
  };
  SweepOptions opt;
  opt.scene_padding = scene_padding;
  opt.self_padding = self_padding;
  opt.obb_stage = settings_.obb_stage;
  opt.inner_shapes = settings_.obb_stage;
  opt.base_free = base_free;
  const bool hit = pose_links ? sweep<SweepPoses::kPoseLinks>(m, X_WL, skip, opt, scene, self)
                              : sweep<SweepPoses::kOwnLinks>(m, X_WL, skip, opt, scene, self);
  CounterSlots::Slot& c = counterSlot();
  if (tests) c.add(c.pair_tests, tests);
  if (cap) c.add(c.cap_hits);
  return hit;
}

bool DssChecker::collidesWithPoses(const double* q, const Eigen::Isometry3d* X_WL) const {
  CounterSlots::Slot& c = counterSlot();
  c.add(c.checks);
  const CollisionModel& m = model();
  if (!m.withinBounds(q)) {
    c.add(c.invalid_input);
    return true;
  }
  Scratch& s = scratch();
  s.reserve(m);
  const std::uint8_t base_free = m.baseTable().read(q, settings_.scene_padding);
  if (base_free == BaseSceneTable::kColliding ||
      m.selfTables().read(q, m.heldMatch(q), settings_.self_padding, s.skip.data()) ||
      collidesAt(X_WL, false, s.skip.data(), settings_.scene_padding, settings_.self_padding,
                 base_free)) {
    c.add(c.collisions);
    return true;
  }
  return false;
}

double DssChecker::clearance(const double* q) const {
  const CollisionModel& m = model();
  if (!m.withinBounds(q)) return 0.0;
  Scratch& s = scratch();
  s.reserve(m);
  m.kinematics().computeLinkPoses(q, s.X_WL.data());
  const bool held = m.heldMatch(q);
  auto apart = [&](double r) {
    const double scene_padding = settings_.scene_padding + r,
                 self_padding = settings_.self_padding + r;
    if (m.selfTables().read(q, held, self_padding, s.skip.data())) return false;
    return !collidesAt(s.X_WL.data(), false, s.skip.data(), scene_padding, self_padding);
  };
  if (!apart(0.0)) return 0.0;
  const double tol = settings_.clearance_tolerance > 0 ? settings_.clearance_tolerance : 1e-3;
  // Obstacles pruned from the model are at least prunedClearance() away: cap there.
  const double cap = std::max(
      0.0, std::min(settings_.clearance_max, m.prunedClearance() - settings_.scene_padding));
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

}  // namespace dss
