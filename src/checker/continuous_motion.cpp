// ContinuousMotionChecker: padded swept hulls per element, halving each sub-motion and
// re-testing only the units its parent could not clear (see continuous_motion.h).
#include "dss/checker/continuous_motion.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "dss/core/any_shape_sweep.h"

namespace dss {

namespace {

struct Interval {
  double ta, tb;
  std::size_t begin, end;  // its units: Scratch::work[begin, end)
};
struct Scratch {
  std::vector<Eigen::Isometry3d> XA, XB;
  std::vector<double> pad, qa, qb;
  std::vector<int> work;  // unit indices, a stack of lists (see clear())
  std::vector<Interval> stack;
};
Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

// The unit quaternion at t of the slerp from a to b (x, y, z, w) along the shorter arc.
void slerpInto(const double* a, const double* b, double t, double* out) {
  const Eigen::Quaterniond qa = Eigen::Quaterniond(a[3], a[0], a[1], a[2]).normalized();
  const Eigen::Quaterniond qb = Eigen::Quaterniond(b[3], b[0], b[1], b[2]).normalized();
  const Eigen::Quaterniond r = qa.slerp(t, qb);  // Eigen's slerp takes the shorter arc
  out[0] = r.x(), out[1] = r.y(), out[2] = r.z(), out[3] = r.w();
}

}  // namespace

ContinuousMotionChecker::ContinuousMotionChecker(std::shared_ptr<const DssChecker> checker,
                                                 double min_fraction)
    : checker_(std::move(checker)), min_fraction_(min_fraction) {
  if (!(min_fraction_ > 0.0 && min_fraction_ <= 1.0))
    throw std::invalid_argument("ContinuousMotionChecker: min_fraction " +
                                std::to_string(min_fraction_) + " is not in (0, 1]");
  const CollisionModel& m = checker_->model();
  chains_.resize(m.slots().size());
  for (std::size_t k = 0; k < m.slots().size(); ++k) {
    const auto& s = m.slots()[k];
    if (s.moves)
      chains_[k] = chainAbove(m.robot(), s.link, -1, s.center_L.norm() + s.radius, m.held());
  }
  for (std::size_t a = 0; a < m.robot().numActiveJoints(); ++a) {
    const RobotJoint& j = m.robot().joints[m.robot().active_joints[a]];
    if (j.type == JointType::kBall && j.active_index == int(a)) balls_.push_back(int(a));
  }
  // Units in the order of the state sweep: robot vs scene, then self pairs.
  for (const auto& s : m.slots()) {
    if (!s.moves) continue;
    for (int e = s.first_element; e < s.first_element + s.num_elements; ++e)
      for (int o : s.obstacles) units_.push_back({e, o, false});
  }
  for (const auto& p : m.selfPairs()) {
    const auto& sa = m.slots()[p.a];
    const auto& sb = m.slots()[p.b];
    for (int ea = sa.first_element; ea < sa.first_element + sa.num_elements; ++ea)
      for (int eb = sb.first_element; eb < sb.first_element + sb.num_elements; ++eb)
        units_.push_back({ea, eb, true});
  }
}

void ContinuousMotionChecker::paddings(const double* qa, const double* qb, double* pad) const {
  for (std::size_t k = 0; k < chains_.size(); ++k) {
    const MotionBound b = motionBound(chains_[k], qa, qb);
    pad[k] = 0.5 * b.length * std::min(1.0, b.turn) * (1.0 + 1e-9) + (b.length > 0 ? 1e-12 : 0.0);
  }
}

bool ContinuousMotionChecker::unitClear(const Unit& u, const Eigen::Isometry3d* XA,
                                        const Eigen::Isometry3d* XB, const double* pad,
                                        std::uint64_t* tests) const {
  const CollisionModel& m = checker_->model();
  const DssCheckerSettings& set = checker_->settings();
  const auto& el = m.elements();
  const auto& ea = el[u.a];
  const Eigen::Isometry3d& XA0 = XA[ea.link];
  const Eigen::Isometry3d& XA1 = XB[ea.link];
  const Eigen::Vector3d a0 = XA0 * ea.center_L, a1 = XA1 * ea.center_L;
  if (!u.self) {
    const double p = pad[ea.slot] + set.scene_padding;
    const double r = 0.5 * (a1 - a0).norm() + ea.radius + p;
    if (detail::sqDistPointAabb(0.5 * (a0 + a1), m.obstacleBoxes()[u.b]) > r * r) return true;
    ++*tests;
    const Obstacle& o = m.scene().obstacles[u.b];
    return !intersectSwept(ea.source->shape, XA0 * ea.source->X_LS, XA1 * ea.source->X_LS, p,
                           o.shape, o.X_WO, set.options)
                .intersect;
  }
  const auto& eb = el[u.b];
  const Eigen::Isometry3d& XB0 = XA[eb.link];
  const Eigen::Isometry3d& XB1 = XB[eb.link];
  const Eigen::Vector3d b0 = XB0 * eb.center_L, b1 = XB1 * eb.center_L;
  const double p = pad[ea.slot] + pad[eb.slot] + set.self_padding;
  const double r = 0.5 * (a1 - a0).norm() + 0.5 * (b1 - b0).norm() + ea.radius + eb.radius + p;
  if ((0.5 * (a0 + a1) - 0.5 * (b0 + b1)).squaredNorm() > r * r) return true;
  ++*tests;
  return !intersectSwept(ea.source->shape, XA0 * ea.source->X_LS, XA1 * ea.source->X_LS, p,
                         eb.source->shape, XB0 * eb.source->X_LS, XB1 * eb.source->X_LS,
                         set.options)
              .intersect;
}

bool ContinuousMotionChecker::clear(const double* q0, const double* q1, double* last) const {
  double last_storage = 0.0;
  if (!last) last = &last_storage;
  *last = 0.0;
  const CollisionModel& m = checker_->model();
  // The shared counters are updated once per motion, not per test: threads checking motions
  // concurrently would otherwise fight over their cache line.
  std::uint64_t intervals = 1, tests = 0;
  struct Flush {
    const ContinuousMotionChecker* c;
    const std::uint64_t& intervals;
    const std::uint64_t& tests;
    ~Flush() {
      c->sub_motions_.fetch_add(intervals, std::memory_order_relaxed);
      c->unit_tests_.fetch_add(tests, std::memory_order_relaxed);
    }
  } flush{this, intervals, tests};
  // The bounds hold for states within the model's bounds; the set of such states is convex
  // (a box), so the whole motion is within them when both ends are.
  if (!m.withinBounds(q0) || !m.withinBounds(q1)) return false;
  // Depth-first halving, left half first. `work` is a stack of unit lists: an interval owns
  // work[begin, end), written by its parent; the units it leaves for its halves (the first one
  // it fails to clear and those after it) are appended after `end` and shared by both. When an
  // interval is popped, everything after its own list belongs to intervals already finished, so
  // the list is cut back to `end` first.
  const std::size_t n = m.robot().numActiveJoints();
  Scratch& sc = scratch();
  const std::size_t nl = m.robot().links.size();
  if (sc.XA.size() < nl) sc.XA.resize(nl), sc.XB.resize(nl);
  if (sc.pad.size() < m.slots().size()) sc.pad.resize(m.slots().size());
  if (sc.qa.size() < n) sc.qa.resize(n), sc.qb.resize(n);
  sc.work.resize(units_.size());
  for (std::size_t u = 0; u < units_.size(); ++u) sc.work[u] = static_cast<int>(u);
  sc.stack.clear();
  sc.stack.push_back({0.0, 1.0, 0, units_.size()});
  double* qa = sc.qa.data();
  double* qb = sc.qb.data();
  bool first = true;
  while (!sc.stack.empty()) {
    const Interval iv = sc.stack.back();
    sc.stack.pop_back();
    sc.work.resize(iv.end);
    intervals += !first;
    first = false;
    for (std::size_t i = 0; i < n; ++i) {
      qa[i] = q0[i] + iv.ta * (q1[i] - q0[i]);
      qb[i] = q0[i] + iv.tb * (q1[i] - q0[i]);
    }
    for (int a : balls_) {  // quaternions: slerp along the shorter arc, as OMPL's SO(3)
      slerpInto(q0 + a, q1 + a, iv.ta, qa + a);
      slerpInto(q0 + a, q1 + a, iv.tb, qb + a);
    }
    m.kinematics().computeLinkPoses(qa, sc.XA.data());
    m.kinematics().computeLinkPoses(qb, sc.XB.data());
    paddings(qa, qb, sc.pad.data());
    for (std::size_t w = iv.begin; w < iv.end; ++w) {
      const int u = sc.work[w];
      if (unitClear(units_[u], sc.XA.data(), sc.XB.data(), sc.pad.data(), &tests))
        continue;  // cleared for [ta, tb]
      // The first unit not cleared decides that [ta, tb] is split: it goes first in the
      // halves' list (near a contact it fails again at once), followed by the units not yet
      // tested here. Testing those here too would clear some for both halves with one test,
      // but on long motions most fail at the upper levels and the tests would be wasted.
      sc.work.push_back(u);
      for (std::size_t x = w + 1; x < iv.end; ++x) {
        const int rest = sc.work[x];
        sc.work.push_back(rest);
      }
      break;
    }
    if (sc.work.size() == iv.end) continue;  // every unit cleared over [ta, tb]
    if (iv.tb - iv.ta <= min_fraction_) {
      *last = iv.ta;
      return false;
    }
    const double tm = 0.5 * (iv.ta + iv.tb);
    for (std::size_t i = 0; i < n; ++i) qa[i] = q0[i] + tm * (q1[i] - q0[i]);
    for (int a : balls_) slerpInto(q0 + a, q1 + a, tm, qa + a);
    if (checker_->collides(qa)) {  // a colliding state on the motion: done
      *last = iv.ta;
      return false;
    }
    sc.stack.push_back({tm, iv.tb, iv.end, sc.work.size()});
    sc.stack.push_back({iv.ta, tm, iv.end, sc.work.size()});
  }
  return true;
}

}  // namespace dss
