// Kinematic motion bounds (see motion_bounds.h).
#include "dss/checker/motion_bounds.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace dss {

namespace {
// Largest |value| over a joint's limits and its held value (infinity without limits).
double valueRange(const RobotJoint& j, double held) {
  if (!j.limits.has_position_limits) return std::numeric_limits<double>::infinity();
  return std::max({std::abs(j.limits.lower), std::abs(j.limits.upper), std::abs(held)});
}
}  // namespace

double prismaticTravel(const RobotModel& robot, const RobotJoint& j,
                       const std::vector<double>& held) {
  if (j.type != JointType::kPrismatic) return 0.0;
  if (j.active_index >= 0) return valueRange(j, held[j.active_index]);
  if (j.mimic_active >= 0) {
    const int lead = j.mimic_active;
    const RobotJoint& leader = robot.joints[robot.active_joints[lead]];
    // |m v + o| <= |m| |v| + |o| for every value v of the leader (its held value included).
    return std::abs(j.mimic_multiplier) * valueRange(leader, held[lead]) + std::abs(j.mimic_offset);
  }
  return 0.0;
}

double originOffsetBound(const RobotModel& robot, int link, int stop,
                         const std::vector<double>& held) {
  double d = 0.0;
  for (int l = link; l != stop && robot.links[l].parent_joint >= 0;
       l = robot.links[l].parent_link) {
    const RobotJoint& j = robot.joints[robot.links[l].parent_joint];
    d += j.X_PJ.translation().norm() + prismaticTravel(robot, j, held);
  }
  return d;
}

std::vector<ChainTerm> chainAbove(const RobotModel& robot, int link, int stop, double radius,
                                  const std::vector<double>& held, double* reach_at_stop) {
  std::vector<ChainTerm> out;
  double reach = radius;
  for (int l = link; l != stop && robot.links[l].parent_joint >= 0;
       l = robot.links[l].parent_link) {
    const RobotJoint& j = robot.joints[robot.links[l].parent_joint];
    if (j.isMoving()) {
      ChainTerm t;
      t.joint = robot.links[l].parent_joint;
      t.active = j.active_index;
      if (t.active < 0 && j.mimic_active >= 0) {
        t.active = j.mimic_active;
        t.multiplier = j.mimic_multiplier;
      }
      t.prismatic = j.type == JointType::kPrismatic;
      t.ball = j.type == JointType::kBall;
      t.reach = reach;
      out.push_back(t);
    }
    reach += j.X_PJ.translation().norm() + prismaticTravel(robot, j, held);
  }
  if (reach_at_stop) *reach_at_stop = reach;
  return out;
}

void slerpQuaternion(const double* a, const double* b, double t, double* out) {
  const Eigen::Quaterniond qa = Eigen::Quaterniond(a[3], a[0], a[1], a[2]).normalized();
  const Eigen::Quaterniond qb = Eigen::Quaterniond(b[3], b[0], b[1], b[2]).normalized();
  const Eigen::Quaterniond r = qa.slerp(t, qb);  // Eigen's slerp takes the shorter arc
  out[0] = r.x(), out[1] = r.y(), out[2] = r.z(), out[3] = r.w();
}

int lowestCommonAncestor(const RobotModel& robot, int a, int b) {
  for (int x = a; x >= 0; x = robot.links[std::size_t(x)].parent_link)
    for (int y = b; y >= 0; y = robot.links[std::size_t(y)].parent_link)
      if (x == y) return x;
  return -1;
}

double quaternionAngle(const double* a, const double* b) {
  const double na = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3]);
  const double nb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2] + b[3] * b[3]);
  if (!(na > 0.0 && nb > 0.0 && std::isfinite(na) && std::isfinite(nb)))
    return std::numeric_limits<double>::infinity();
  double dot = 0.0;
  for (int k = 0; k < 4; ++k) dot += a[k] * b[k];
  const double s = dot < 0.0 ? -1.0 : 1.0;  // the shorter arc
  double chord2 = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double d = a[k] / na - s * b[k] / nb;
    chord2 += d * d;
  }
  // The unit quaternions are alpha = 2 asin(chord / 2) apart on the 3-sphere; the rotation
  // turns by twice that. Rounding: a relative margin and an absolute one.
  const double half_chord = std::min(1.0, 0.5 * std::sqrt(chord2));
  return 4.0 * std::asin(half_chord) * (1.0 + 1e-12) + 1e-14;
}

namespace {
// The bounds of motion_bounds.h from each term's travel dq (>= 0; NaN for a NaN state).
template <class Travel>
MotionBound accumulate(const std::vector<ChainTerm>& chain, Travel travel) {
  MotionBound b;
  // From the root down (the chain is nearest first): `above` is the revolute angle of the
  // joints above the current one, W_<j in motion_bounds.h.
  double above = 0.0;
  for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
    const ChainTerm& t = *it;
    if (t.active < 0) continue;
    const double dq = travel(t);
    if (dq == 0.0) continue;  // a joint the motion holds adds nothing (even an unbounded reach)
    if (t.prismatic) {
      b.length += dq;
      b.bend += 2.0 * dq * above;
    } else {
      b.length += dq * t.reach;
      b.bend += dq * t.reach * (2.0 * above + dq);
      b.turn += dq;
      above += dq;
    }
  }
  return b;
}
}  // namespace

MotionBound motionBound(const std::vector<ChainTerm>& chain, const double* q0, const double* q1) {
  return accumulate(chain, [&](const ChainTerm& t) {
    if (!t.ball) return std::abs(t.multiplier * (q1[t.active] - q0[t.active]));
    const double* a = q0 + t.active;
    const double* c = q1 + t.active;
    // The same quaternion at both ends does not turn (a multi-DOF joint the motion holds).
    return sameQuaternion(a, c) ? 0.0 : quaternionAngle(a, c);
  });
}

void jointTravel(const double* q0, const double* q1, std::size_t n, const std::vector<int>& balls,
                 double* travel) {
  for (std::size_t i = 0; i < n; ++i) travel[i] = std::abs(q1[i] - q0[i]);
  for (int a : balls)
    travel[a] = sameQuaternion(q0 + a, q1 + a) ? 0.0 : quaternionAngle(q0 + a, q1 + a);
}

MotionBound motionBound(const std::vector<ChainTerm>& chain, const double* travel) {
  // |m (q1 - q0)| = |m| |q1 - q0| exactly: the same bounds as from the two states.
  return accumulate(chain, [&](const ChainTerm& t) {
    return t.ball ? travel[t.active] : std::abs(t.multiplier) * travel[t.active];
  });
}

}  // namespace dss
