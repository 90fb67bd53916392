// Kinematic motion bounds: how far the points of a link can move when the joints above it
// move. The collision model's reach balls, self-pair tables and pair blocks, the continuous
// motion check and the benchmarks all take their bounds from here.
//
// Every bound comes from one walk up the kinematic tree. For a point set rigid to link L and
// within r of L's origin, reach(j) bounds the set's distance from the origin of joint j (the
// origin of j's child link) for every joint j above L: it starts at r and grows, joint by
// joint, by the joint's origin offset |X_PJ.t| and, for a prismatic joint, its travel.
// Turning joint j by dq moves every point of the set by at most |dq| reach(j); sliding a
// prismatic joint by dq moves it by |dq|. A path of the set along a straight joint-space
// motion is then at most V = sum |dq_j| reach(j) + sum |dq_j| (prismatic) long, and it bends
// with the revolute angle W = sum |dq_j| (see continuous_motion.h).
//
// The travel of a prismatic joint covers every value within its limits and its held value
// (a held value may lie outside the limits): states outside both are outside the bounds.
#pragma once

#include <vector>

#include "dss/robot/robot_model.h"

namespace dss {

/// Largest |displacement| of a prismatic joint over every value within its limits and its
/// held value; a mimic joint moves through its leader (|multiplier| times the leader's travel
/// plus |offset|). Infinity for an unbounded prismatic joint, 0 for every other joint.
/// `held`: one value per active joint.
double prismaticTravel(const RobotModel& robot, const RobotJoint& joint,
                       const std::vector<double>& held);

/// A bound on the distance between the origins of `link` and of its ancestor `stop` (-1: the
/// root) over every state: the sum of |X_PJ.t| plus travel of the joints in between.
double originOffsetBound(const RobotModel& robot, int link, int stop,
                         const std::vector<double>& held);

/// One non-fixed joint above a point set.
struct ChainTerm {
  int joint = -1;   ///< model joint index
  int active = -1;  ///< the active joint whose value drives it (a mimic joint's leader); -1: none
  double multiplier = 1.0;  ///< of that value (a mimic joint's multiplier)
  bool prismatic = false;
  /// A ball joint: `active` is the first of its four quaternion values; the motion turns by the
  /// angle between the two quaternions (about a fixed axis: the motion is a slerp).
  bool ball = false;
  double reach = 0.0;  ///< bound on the set's distance from the joint's origin
};

/// The non-fixed joints from `link` up to `stop` (exclusive; -1: up to the root), for a point
/// set within `radius` of link's origin, nearest first. `reach_at_stop` (optional) receives
/// the bound on the set's distance from stop's origin (the root's for -1).
std::vector<ChainTerm> chainAbove(const RobotModel& robot, int link, int stop, double radius,
                                  const std::vector<double>& held, double* reach_at_stop = nullptr);

/// The lowest link above (or equal to) both `a` and `b`: joints above it move both rigidly
/// together. -1 when they share no link (never in a tree).
int lowestCommonAncestor(const RobotModel& robot, int a, int b);

/// The rotation angle between two quaternions (x, y, z, w; not necessarily unit), rounded up:
/// the angle a slerp along the shorter arc turns by. Infinity when one has no direction.
double quaternionAngle(const double* a, const double* b);

/// The same four quaternion values (x, y, z, w) at a and b: a ball joint the motion holds.
inline bool sameQuaternion(const double* a, const double* b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2] && a[3] == b[3];
}

/// The unit quaternion at fraction t of the slerp from a to b (x, y, z, w; normalised first)
/// along the shorter arc, as OMPL's SO(3) interpolation moves a rotation.
void slerpQuaternion(const double* a, const double* b, double t, double* out);

/// Over the straight joint-space motion q0 -> q1 (active joint values; a ball joint's
/// quaternion moves by slerp along the shorter arc, a turn about a fixed axis at a constant
/// rate): `length` bounds the path of every point of the set (V above), `turn` is the revolute
/// angle above it (W), and `bend` bounds the second derivative |p''| of every point's path
/// p(t), t in [0, 1].
///
/// The bend: number the moving joints from the root down, dq_j their travel over the motion,
/// R_j their reach, a_j their (unit) axes, o_j their origins, W_<j the revolute travel above j.
/// A revolute joint adds dq_j a_j x (p - o_j) to p', a prismatic one dq_j a_j. Differentiating,
/// an axis turns with the joints above it (|a_j'| <= W_<j), and p - o_j moves with the
/// relative velocity of p about o_j: the joints above j turn it about o_j with the angular
/// velocity w of the link above j, the joints from j down move it as they move p (at most
/// sum over revolute k >= j of dq_k R_k, plus the prismatic travel below j). The two turns by
/// w together give (w x a_j) x r + a_j x (w x r) = w x (a_j x r) (Jacobi), r = p - o_j, at
/// most W_<j R_j. A prismatic joint's own axis turns (dq_j W_<j), and the revolute joints
/// above it turn its slide (dq_j W_<j again, Coriolis). Summing,
///   |p''| <= sum over revolute j of dq_j R_j (2 W_<j + dq_j)
///          + 2 sum over prismatic j of dq_j W_<j
/// which is at most 2 W V, exactly R dq^2 for one revolute joint (a circle), and exactly
/// L1 w1^2 + L2 (w1 + w2)^2 for the tip of an outstretched planar two-link arm.
struct MotionBound {
  double length = 0.0;
  double turn = 0.0;
  double bend = 0.0;
};
MotionBound motionBound(const std::vector<ChainTerm>& chain, const double* q0, const double* q1);

/// What motionBound reads of a motion, once for many chains: |q1 - q0| per active value (n of
/// them), and at the first value of each ball joint in `balls` its turn angle (0 when the
/// quaternion is the same at both ends).
void jointTravel(const double* q0, const double* q1, std::size_t n, const std::vector<int>& balls,
                 double* travel);
/// motionBound from jointTravel's values: the same bounds, bit for bit.
MotionBound motionBound(const std::vector<ChainTerm>& chain, const double* travel);

}  // namespace dss
