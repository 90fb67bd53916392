// The random group states the model's set-up tests its options on (pair-block balls, sphere
// chains): each group joint uniform over its limits, a continuous or unlimited one over
// [-pi, pi]; the other joints keep the values already in q (the held ones).
#pragma once

#include <random>
#include <vector>

#include "dss/checker/collision_model.h"

namespace dss::detail {

inline void drawGroupState(const CollisionModel& model, std::mt19937_64& rng,
                           std::vector<double>& q) {
  const RobotModel& m = model.robot();
  for (int a : model.groupActive()) {
    const RobotJoint& jt = m.joints[m.active_joints[a]];
    const bool bounded = jt.type != JointType::kContinuous && jt.limits.has_position_limits;
    const double lo = bounded ? jt.limits.lower : -3.141592653589793;
    const double hi = bounded ? jt.limits.upper : 3.141592653589793;
    q[a] = std::uniform_real_distribution<double>(lo, hi)(rng);
  }
}

}  // namespace dss::detail
