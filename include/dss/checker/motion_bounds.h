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

/// The unit quaternion at fraction t of the slerp from a to b (x, y, z, w; normalised first)
/// along the shorter arc, as OMPL's SO(3) interpolation moves a rotation.
void slerpQuaternion(const double* a, const double* b, double t, double* out);

/// Over the straight joint-space motion q0 -> q1 (active joint values; a ball joint's
/// quaternion moves by slerp along the shorter arc): `length` bounds the path of every point
/// of the set (V above), `turn` is the revolute angle above it (W).
struct MotionBound {
  double length = 0.0;
  double turn = 0.0;
};
MotionBound motionBound(const std::vector<ChainTerm>& chain, const double* q0, const double* q1);

}  // namespace dss
