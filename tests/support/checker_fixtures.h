// Fixtures shared by the checker and planning tests: where our own robot and the shared
// robots and scenes live, the collision model of our arm in its shelf scene, and seeded
// random states of a model's group.
#pragma once

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "dss/checker/checker_setup.h"
#include "dss/core/simd_path.h"
#include "dss/robot/multi_dof.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"

namespace dss_test {

/// A precondition for the cases about batched motion checks, which batch only where the
/// batches pay (on the AVX2 path: StateChecker::batchesPay): Boost.Test reports them skipped
/// on a CPU without AVX2 or with DSS_SIMD forcing another path.
inline boost::test_tools::assertion_result batchesRun(boost::unit_test::test_unit_id) {
  boost::test_tools::assertion_result r(dss::activeSimdPath() == dss::SimdPath::kAvx2);
  r.message() << "not on the AVX2 path: motion checks do not batch";
  return r;
}
#define DSS_NEEDS_BATCHES *boost::unit_test::precondition(dss_test::batchesRun)

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

/// An object the robot holds: one box of `size` at `X_FO` in `frame` (its holding link when
/// empty), read from `at`.
inline dss::AttachedObject heldBox(const std::string& id, const std::string& link,
                                   const Eigen::Vector3d& size, const Eigen::Isometry3d& X_FO,
                                   const std::string& frame = "", const std::string& at = "test") {
  dss::AttachedObject a;
  a.id = id;
  a.link = link;
  a.at = at;
  dss::Obstacle part;
  part.name = part.object_id = id;
  part.frame_id = frame.empty() ? link : frame;
  part.shape = dss::Box::fromSize(size);
  part.X_FO = X_FO;
  part.description = "box";
  a.parts.push_back(part);
  return a;
}

/// The same, the arm holding a bar between its fingers (an attached object on its tool link,
/// 0.4 m along the tool's z from 0.02 to 0.42), which reaches the shelf and the arm's own links.
inline dss::ModelSetup shelfSetupHoldingBar(const dss::LoadedRobot& robot) {
  const auto req = dss::loadPlanRequestYaml(kArmDir + "/scenes/shelf_request.yaml");
  dss::Scene scene = dss::loadScene(kArmDir + "/scenes/shelf.yaml");
  scene.attached.push_back(heldBox("bar", "tool", Eigen::Vector3d(0.03, 0.04, 0.4),
                                   Eigen::Isometry3d(Eigen::Translation3d(0.0, 0.0, 0.22))));
  return dss::setupModel(robot, std::move(scene), req.group_name, req.startState());
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

/// One of our multi-DOF robots (robots/NAME) bounded by its request's workspace, and its
/// model in scenes/SCENE.yaml at the request's start (multi-DOF values included).
struct MobileSetup {
  dss::LoadedRobot robot;
  dss::ModelSetup setup;
  std::string scene_file;
};
inline MobileSetup mobileSetup(const std::string& name, const std::string& scene) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/" + name;
  const auto req = dss::loadPlanRequestYaml(dir + "/scenes/" + scene + "_request.yaml");
  if (!req.workspace) throw std::runtime_error(name + ": the request has no workspace");
  MobileSetup m;
  m.robot =
      dss::withWorkspace(dss::loadRobot(dir + "/" + name + ".urdf", dir + "/" + name + ".srdf"),
                         req.workspace->first, req.workspace->second);
  std::map<std::string, double> start = req.startState();
  for (const auto& [n, v] : dss::multiDofStateValues(*m.robot.model, req.start_multi_dof))
    start[n] = v;
  m.scene_file = dir + "/scenes/" + scene + ".yaml";
  m.setup = dss::setupModel(m.robot, dss::loadScene(m.scene_file), req.group_name, start);
  return m;
}

}  // namespace dss_test
