// Setting up a checker from the files users have: the robot (URDF, SRDF), the group, the
// held joint values (scene robot state, request start), the collision model for a scene, and
// a state checker by name ("dss", "fcl-hull", "fcl-mesh"). Shared by the executables, the
// benchmarks, the OMPL setup (dss/planning/planning_problem.h) and the tests.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dss/checker/collision_model.h"
#include "dss/checker/state_checker.h"
#include "dss/core/result.h"
#include "dss/robot/srdf.h"
#include "dss/robot/urdf_loader.h"
#include "dss/scene/scene.h"

namespace dss {

struct LoadedRobot {
  std::shared_ptr<const RobotModel> model;
  std::optional<Srdf> srdf;

  /// The stored warnings of the URDF and then the SRDF readers (to be shown to the user once
  /// per robot; setupModel does not repeat them).
  std::vector<std::string> warnings() const;
};

/// srdf_path may be empty. Throws std::runtime_error naming the file. `options` go to the
/// URDF reader; their `limits` also to the SRDF reader.
LoadedRobot loadRobot(const std::string& urdf_path, const std::string& srdf_path,
                      const LoadOptions& options = {});

/// The robot with the translation of its planar and floating joints bounded by the box
/// [lo, hi] (setMultiDofTranslationBounds; e.g. a request's workspace_parameters); the robot
/// itself when it has no such joint. The same robot and box give the same bounded robot object
/// while the robot lives (thread-safe), so that models of many problems share it and its cached
/// self-pair tables. Throws std::invalid_argument for a box that is not finite.
LoadedRobot withWorkspace(const LoadedRobot& robot, const Eigen::Vector3d& lo,
                          const Eigen::Vector3d& hi);

/// The group's active joints: the SRDF group when named, else the SRDF's first group when there
/// is one, else every active joint. `group` receives the chosen name ("" for all).
std::vector<int> resolveGroup(const LoadedRobot& robot, std::string* group);

struct ModelSetup {
  std::shared_ptr<const CollisionModel> model;
  std::string group;
  std::vector<int> group_active;
  std::vector<double> held;  ///< one value per active joint
  /// The scene reader's stored warnings, then those of the setup and the collision model.
  std::vector<std::string> warnings;
};

/// The collision model for `scene` (may be empty) and the group, holding the joints outside it
/// at `start` (by name; falls back to the scene's robot state, then the default state).
ModelSetup setupModel(const LoadedRobot& robot, Scene scene, std::string group,
                      const std::map<std::string, double>& start, double prune_margin = 0.0);
/// The same with every option of the collision model (pruning margin, tables).
ModelSetup setupModel(const LoadedRobot& robot, Scene scene, std::string group,
                      const std::map<std::string, double>& start,
                      const CollisionModelOptions& options);

struct CheckerConfig {
  std::string checker = "dss";  ///< dss | fcl-hull | fcl-mesh
  double scene_padding = 0.0;
  double self_padding = 0.0;
  Options dss_options;
  bool obb_stage = true;  ///< oriented-box stage (dss, and fcl-* with the shared sweep)
  /// fcl-* only: "aabb" (FCL's own world AABBs, as an OMPL/MoveIt + FCL checker does) or
  /// "shared" (the DSS checker's sweep).
  std::string fcl_prefilter = "aabb";
  /// Every check adds its wall time to the checker's counters (StateChecker::timeChecks).
  bool time_checks = false;
};

/// A state checker by name; throws std::invalid_argument for an unknown name or prefilter.
std::shared_ptr<const StateChecker> makeStateChecker(std::shared_ptr<const CollisionModel> model,
                                                     const CheckerConfig& config);

}  // namespace dss
