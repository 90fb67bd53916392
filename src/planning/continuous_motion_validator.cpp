// ContinuousMotionValidator: padded swept hulls per link, halving until every pair is cleared.
#include "dss/planning/continuous_motion_validator.h"

#include <cmath>
#include <limits>

#include <ompl/base/SpaceInformation.h>

#include "dss/core/padded.h"
#include "dss/core/swept.h"

namespace dss {

namespace {

struct Scratch {
  std::vector<Eigen::Isometry3d> XA, XB;
  std::vector<double> pad;
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
}

bool ContinuousMotionValidator::clear(const double* qa, const double* qb) const {
  sub_motions_.fetch_add(1, std::memory_order_relaxed);
  const CollisionModel& m = checker_->model();
  const auto& set = checker_->settings();
  Scratch& sc = scratch();
  const std::size_t nl = m.robot().links.size();
  if (sc.XA.size() < nl) sc.XA.resize(nl), sc.XB.resize(nl);
  if (sc.pad.size() < m.slots().size()) sc.pad.resize(m.slots().size());
  m.kinematics().computeLinkPoses(qa, sc.XA.data());
  m.kinematics().computeLinkPoses(qb, sc.XB.data());
  for (std::size_t k = 0; k < m.slots().size(); ++k) {
    double len = 0.0;
    for (const auto& t : chains_[k]) {
      const double dq = std::abs(t.multiplier * (qb[t.active] - qa[t.active]));
      len += t.radius < 0 ? dq : dq * t.radius;
    }
    sc.pad[k] = 0.5 * len * (1.0 + 1e-9) + (len > 0 ? 1e-12 : 0.0);
  }
  const auto& el = m.elements();
  const auto& obstacles = m.scene().obstacles;
  // Robot vs scene.
  for (std::size_t k = 0; k < m.slots().size(); ++k) {
    const auto& s = m.slots()[k];
    if (s.obstacles.empty()) continue;
    for (int e = s.first_element; e < s.first_element + s.num_elements; ++e) {
      const Eigen::Isometry3d A0 = sc.XA[s.link] * el[e].source->X_LS;
      const Eigen::Isometry3d A1 = sc.XB[s.link] * el[e].source->X_LS;
      const Eigen::Vector3d c0 = sc.XA[s.link] * el[e].center_L, c1 = sc.XB[s.link] * el[e].center_L;
      const double pad = sc.pad[k] + set.scene_padding;
      const double r = 0.5 * (c1 - c0).norm() + el[e].radius + pad;
      for (int o : s.obstacles) {
        if (detail::sqDistPointAabb(0.5 * (c0 + c1), m.obstacleBoxes()[o]) > r * r) continue;
        if (sweptVsPosed(el[e].source->shape, A0, A1, pad, obstacles[o].shape, obstacles[o].X_WO, set.options))
          return false;
      }
    }
  }
  // Self pairs (both swept).
  for (const auto& p : m.selfPairs()) {
    const auto& sa = m.slots()[p.a];
    const auto& sb = m.slots()[p.b];
    const double pad = sc.pad[p.a] + sc.pad[p.b] + set.self_padding;
    for (int ea = sa.first_element; ea < sa.first_element + sa.num_elements; ++ea) {
      const Eigen::Vector3d a0 = sc.XA[sa.link] * el[ea].center_L, a1 = sc.XB[sa.link] * el[ea].center_L;
      for (int eb = sb.first_element; eb < sb.first_element + sb.num_elements; ++eb) {
        const Eigen::Vector3d b0 = sc.XA[sb.link] * el[eb].center_L, b1 = sc.XB[sb.link] * el[eb].center_L;
        const double r = 0.5 * (a1 - a0).norm() + 0.5 * (b1 - b0).norm() + el[ea].radius + el[eb].radius + pad;
        if ((0.5 * (a0 + a1) - 0.5 * (b0 + b1)).squaredNorm() > r * r) continue;
        if (sweptVsSwept(el[ea].source->shape, sc.XA[sa.link] * el[ea].source->X_LS,
                         sc.XB[sa.link] * el[ea].source->X_LS, pad, el[eb].source->shape,
                         sc.XA[sb.link] * el[eb].source->X_LS, sc.XB[sb.link] * el[eb].source->X_LS,
                         set.options))
          return false;
      }
    }
  }
  return true;
}

bool ContinuousMotionValidator::check(const double* q0, const double* q1, double* last) const {
  // Depth-first halving, left half first, with an explicit stack of [ta, tb] intervals.
  const std::size_t n = checker_->model().robot().numActiveJoints();
  std::vector<double> qa(n), qb(n);  // small; motions are far rarer than states
  std::vector<std::pair<double, double>> stack{{0.0, 1.0}};
  while (!stack.empty()) {
    const auto [ta, tb] = stack.back();
    stack.pop_back();
    for (std::size_t i = 0; i < n; ++i) {
      qa[i] = q0[i] + ta * (q1[i] - q0[i]);
      qb[i] = q0[i] + tb * (q1[i] - q0[i]);
    }
    if (clear(qa.data(), qb.data())) continue;
    if (tb - ta <= min_fraction_) {
      *last = ta;
      return false;
    }
    const double tm = 0.5 * (ta + tb);
    stack.push_back({tm, tb});
    stack.push_back({ta, tm});
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
  std::vector<double> q0(n), q1(n);
  double last = 0.0;
  bool ok = map.toJoints(s1, q0.data()) && map.toJoints(s2, q1.data());
  if (ok) {
    // Continuous joints: move the short way, as OMPL's SO2 interpolation does.
    for (std::size_t i = 0; i < map.dimension(); ++i) {
      const int a = map.groupActive()[i];
      const auto& j = checker_->model().robot().joints[checker_->model().robot().active_joints[a]];
      if (j.type == JointType::kContinuous || !j.limits.has_position_limits)
        q1[a] = q0[a] + std::remainder(q1[a] - q0[a], 2.0 * M_PI);
    }
    ok = check(q0.data(), q1.data(), &last);
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
