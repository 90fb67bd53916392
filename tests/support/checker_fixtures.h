// Fixtures shared by the checker and planning tests: where our own robot and the shared
// robots and scenes live, the collision model of our arm in its shelf scene, and seeded
// random states of a model's group.
#pragma once

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "dss/checker/checker_setup.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"

namespace dss_test {

inline const std::string kArmDir = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
inline const std::string kPandaDir = std::string(DSS_SHARED_DIR) + "/robots/panda";
inline const std::string kMbmPanda = std::string(DSS_SHARED_DIR) + "/scenes/mbm_panda";

inline dss::LoadedRobot loadArm() {
  return dss::loadRobot(kArmDir + "/dss_arm7.urdf", kArmDir + "/dss_arm7.srdf");
}

/// Our arm in its shelf scene, with the shelf request's group and start state.
inline dss::ModelSetup shelfSetup(const dss::LoadedRobot& robot) {
  const auto req = dss::loadPlanRequestYaml(kArmDir + "/scenes/shelf_request.yaml");
  return dss::setupModel(robot, dss::loadScene(kArmDir + "/scenes/shelf.yaml"), req.group_name,
                         req.startState());
}

/// The lower and upper value a group joint is drawn from: its limits, [-pi, pi] for a
/// continuous (or unlimited) joint.
inline std::pair<double, double> sampleRange(const dss::RobotModel& robot, int active) {
  const dss::RobotJoint& j = robot.joints[robot.active_joints[active]];
  if (j.type == dss::JointType::kContinuous || !j.limits.has_position_limits) return {-M_PI, M_PI};
  return {j.limits.lower, j.limits.upper};
}

/// A state with the group's joints uniform within their ranges (sampleRange) and every other
/// joint at its held value.
inline std::vector<double> randomGroupState(const dss::CollisionModel& m, std::mt19937_64& rng) {
  std::vector<double> q = m.held();
  for (int a : m.groupActive()) {
    const auto [lo, hi] = sampleRange(m.robot(), a);
    q[a] = std::uniform_real_distribution<double>(lo, hi)(rng);
  }
  return q;
}

}  // namespace dss_test
