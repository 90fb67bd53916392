// ContinuousMotionValidator: padded swept hulls per element, halving each sub-motion and
// re-testing only the units its parent could not clear.
#include "dss/planning/continuous_motion_validator.h"

#include <cmath>
#include <limits>

#include <ompl/base/SpaceInformation.h>

#include "dss/core/padded.h"
#include "dss/core/swept.h"

namespace dss {

namespace {

struct Interval {
  double ta, tb;
  std::size_t begin, end;  // its units: Scratch::work[begin, end)
};
struct Scratch {
  std::vector<Eigen::Isometry3d> XA, XB;
  std::vector<double> pad, q0, q1, qa, qb;
  std::vector<int> work;  // unit indices, a stack of lists (see check())
  std::vector<Interval> stack;
  std::uint64_t unit_tests = 0;  // this motion's swept tests (added to the shared counter once)
};
Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

// Decides padded swept element vs posed shape (or vs another swept element).
template <class S>
SweptHull<detail::Ref<S>> sweep(const S& s, const Eigen::Isometry3d& X0, const Eigen::Isometry3d& X1) {
  SweptHull<detail::Ref<S>> h{detail::Ref<S>{s}};
  h.R0 = X0.linear();
  h.R1 = X1.linear();
  h.p0 = X0.translation();
  h.p1 = X1.translation();
  return h;
}

bool sweptVsPosed(const AnyShape& a, const Eigen::Isometry3d& A0, const Eigen::Isometry3d& A1, double pad,
                  const AnyShape& b, const Eigen::Isometry3d& XB, const Options& opt) {
  return std::visit(
      [&](const auto& sa, const auto& sb) {
        using SB = std::decay_t<decltype(sb)>;
        const Posed<detail::Ref<SB>> pb(detail::Ref<SB>{sb}, XB.linear(), XB.translation());
        return intersect(padded(sweep(sa, A0, A1), pad), pb, opt).intersect;
      },
      a, b);
}

bool sweptVsSwept(const AnyShape& a, const Eigen::Isometry3d& A0, const Eigen::Isometry3d& A1, double pad,
                  const AnyShape& b, const Eigen::Isometry3d& B0, const Eigen::Isometry3d& B1,
                  const Options& opt) {
  return std::visit(
      [&](const auto& sa, const auto& sb) {
        return intersect(padded(sweep(sa, A0, A1), pad), sweep(sb, B0, B1), opt).intersect;
      },
      a, b);
}

}  // namespace

ContinuousMotionValidator::ContinuousMotionValidator(const ompl::base::SpaceInformationPtr& si,
                                                     std::shared_ptr<const DssValidityChecker> checker,
                                                     double min_fraction)
    : ompl::base::MotionValidator(si), checker_(std::move(checker)), min_fraction_(min_fraction) {
  const CollisionModel& m = checker_->model();
  const RobotModel& r = m.robot();
  const double inf = std::numeric_limits<double>::infinity();
  chains_.resize(m.slots().size());
  for (std::size_t k = 0; k < m.slots().size(); ++k) {
    const auto& s = m.slots()[k];
    if (!s.moves) continue;
    double below = s.center_L.norm() + s.radius;  // bound on |p| in the current frame
    for (int l = s.link; r.links[l].parent_joint >= 0; l = r.links[l].parent_link) {
      const RobotJoint& j = r.joints[r.links[l].parent_joint];
      int active = j.active_index;
      double mult = 1.0;
      if (active < 0 && j.mimic_active >= 0) {
        active = j.mimic_active;
        mult = j.mimic_multiplier;
      }
      // Largest |displacement| of a prismatic joint: its range and its held value (a held
      // value may lie outside the limits), through the leader for a mimic joint.
      double travel = 0.0;
      if (j.type == JointType::kPrismatic) {
        const RobotJoint& src = active >= 0 ? r.joints[r.active_joints[active]] : j;
        const double held = active >= 0 ? std::abs(mult * m.held()[active] + (active == j.active_index ? 0.0 : j.mimic_offset)) : 0.0;
        const double range = src.limits.has_position_limits
                                 ? std::abs(mult) * std::max(std::abs(src.limits.lower), std::abs(src.limits.upper)) +
                                       (active == j.active_index ? 0.0 : std::abs(j.mimic_offset))
                                 : inf;
        travel = std::max(held, range);
      }
      if (active >= 0 && j.type != JointType::kFixed)
        chains_[k].push_back({active, mult, j.type == JointType::kPrismatic ? -1.0 : below});
      below += travel + j.X_PJ.translation().norm();
    }
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
      for (int eb = sb.first_element; eb < sb.first_element + sb.num_elements; ++eb) units_.push_back({ea, eb, true});
  }
}

void ContinuousMotionValidator::paddings(const double* qa, const double* qb, double* pad) const {
  for (std::size_t k = 0; k < chains_.size(); ++k) {
    double len = 0.0, turn = 0.0;  // V_L and W_L of the header
    for (const auto& t : chains_[k]) {
      const double dq = std::abs(t.multiplier * (qb[t.active] - qa[t.active]));
      if (t.radius < 0) {
        len += dq;
      } else {
        len += dq * t.radius;
        turn += dq;
      }
    }
    pad[k] = 0.5 * len * std::min(1.0, turn) * (1.0 + 1e-9) + (len > 0 ? 1e-12 : 0.0);
  }
}

bool ContinuousMotionValidator::unitClear(const Unit& u, const double* pad) const {
  const CollisionModel& m = checker_->model();
  const auto& set = checker_->settings();
  Scratch& sc = scratch();
  const auto& el = m.elements();
  const auto& ea = el[u.a];
  const Eigen::Isometry3d& XA0 = sc.XA[ea.link];
  const Eigen::Isometry3d& XA1 = sc.XB[ea.link];
  const Eigen::Vector3d a0 = XA0 * ea.center_L, a1 = XA1 * ea.center_L;
  if (!u.self) {
    const double p = pad[ea.slot] + set.scene_padding;
    const double r = 0.5 * (a1 - a0).norm() + ea.radius + p;
    if (detail::sqDistPointAabb(0.5 * (a0 + a1), m.obstacleBoxes()[u.b]) > r * r) return true;
    ++sc.unit_tests;
    const Obstacle& o = m.scene().obstacles[u.b];
    return !sweptVsPosed(ea.source->shape, XA0 * ea.source->X_LS, XA1 * ea.source->X_LS, p, o.shape, o.X_WO,
                         set.options);
  }
  const auto& eb = el[u.b];
  const Eigen::Isometry3d& XB0 = sc.XA[eb.link];
  const Eigen::Isometry3d& XB1 = sc.XB[eb.link];
  const Eigen::Vector3d b0 = XB0 * eb.center_L, b1 = XB1 * eb.center_L;
  const double p = pad[ea.slot] + pad[eb.slot] + set.self_padding;
  const double r = 0.5 * (a1 - a0).norm() + 0.5 * (b1 - b0).norm() + ea.radius + eb.radius + p;
  if ((0.5 * (a0 + a1) - 0.5 * (b0 + b1)).squaredNorm() > r * r) return true;
  ++sc.unit_tests;
  return !sweptVsSwept(ea.source->shape, XA0 * ea.source->X_LS, XA1 * ea.source->X_LS, p, eb.source->shape,
                       XB0 * eb.source->X_LS, XB1 * eb.source->X_LS, set.options);
}

bool ContinuousMotionValidator::check(const double* q0, const double* q1, double* last) const {
  // Depth-first halving, left half first. `work` is a stack of unit lists: an interval owns
  // work[begin, end), written by its parent; the units it leaves for its halves (the first
  // one it fails to clear and those after it) are appended after `end` and shared by both. When an interval is popped, everything after its
  // own list belongs to intervals already finished, so the list is cut back to `end` first.
  const CollisionModel& m = checker_->model();
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
  // The shared counters are updated once per motion, not per test: threads checking motions
  // concurrently would otherwise fight over their cache line.
  std::uint64_t intervals = 0;
  sc.unit_tests = 0;
  struct Flush {
    const ContinuousMotionValidator* v;
    const std::uint64_t& intervals;
    const std::uint64_t& tests;
    ~Flush() {
      v->sub_motions_.fetch_add(intervals, std::memory_order_relaxed);
      v->unit_tests_.fetch_add(tests, std::memory_order_relaxed);
    }
  } flush{this, intervals, sc.unit_tests};
  while (!sc.stack.empty()) {
    const Interval iv = sc.stack.back();
    sc.stack.pop_back();
    sc.work.resize(iv.end);
    ++intervals;
    for (std::size_t i = 0; i < n; ++i) {
      qa[i] = q0[i] + iv.ta * (q1[i] - q0[i]);
      qb[i] = q0[i] + iv.tb * (q1[i] - q0[i]);
    }
    m.kinematics().computeLinkPoses(qa, sc.XA.data());
    m.kinematics().computeLinkPoses(qb, sc.XB.data());
    paddings(qa, qb, sc.pad.data());
    for (std::size_t w = iv.begin; w < iv.end; ++w) {
      const int u = sc.work[w];
      if (unitClear(units_[u], sc.pad.data())) continue;  // cleared for all of [ta, tb]
      // The first unit not cleared decides that [ta, tb] is split: it goes first in the
      // halves' list (near a contact it fails again at once), followed by the units not yet
      // tested here. Testing those here too would clear some for both halves with one test,
      // but on long motions most fail at the upper levels and the tests are wasted (measured:
      // 2-4x slower per motion on the Panda and the iiwa).
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
    if (!checker_->isValidJoints(qa)) {  // a colliding state on the motion: done
      *last = iv.ta;
      return false;
    }
    sc.stack.push_back({tm, iv.tb, iv.end, sc.work.size()});
    sc.stack.push_back({iv.ta, tm, iv.end, sc.work.size()});
  }
  return true;
}

bool ContinuousMotionValidator::checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const {
  std::pair<ompl::base::State*, double> lv{nullptr, 0.0};
  return checkMotion(s1, s2, lv);
}

bool ContinuousMotionValidator::checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                                            std::pair<ompl::base::State*, double>& lastValid) const {
  const GroupStateMap& map = checker_->stateMap();
  const std::size_t n = checker_->model().robot().numActiveJoints();
  Scratch& sc = scratch();
  if (sc.q0.size() < n) sc.q0.resize(n), sc.q1.resize(n);
  double* q0 = sc.q0.data();
  double* q1 = sc.q1.data();
  double last = 0.0;
  bool ok = map.toJoints(s1, q0) && map.toJoints(s2, q1);
  if (ok) {
    // Continuous joints: move the short way, as OMPL's SO2 interpolation does.
    for (std::size_t i = 0; i < map.dimension(); ++i) {
      const int a = map.groupActive()[i];
      const auto& j = checker_->model().robot().joints[checker_->model().robot().active_joints[a]];
      if (j.type == JointType::kContinuous || !j.limits.has_position_limits)
        q1[a] = q0[a] + std::remainder(q1[a] - q0[a], 2.0 * M_PI);
    }
    ok = check(q0, q1, &last);
  }
  if (ok) {
    ++valid_;
    return true;
  }
  ++invalid_;
  if (lastValid.first) si_->getStateSpace()->interpolate(s1, s2, last, lastValid.first);
  lastValid.second = last;
  return false;
}

}  // namespace dss
