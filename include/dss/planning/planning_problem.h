// Loading a planning problem (robot, SRDF, scene, request) into a collision model, a group
// state map and validity checkers by name ("dss", "fcl-hull", "fcl-mesh"). Shared by
// dss_check, dss_plan and the tests.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <ompl/base/SpaceInformation.h>

#include "dss/planning/collision_model.h"
#include "dss/planning/group_state_space.h"
#include "dss/planning/validity_checker.h"
#include "dss/scene/plan_request.h"

namespace dss {

struct LoadedRobot {
  std::shared_ptr<const RobotModel> model;
  std::optional<Srdf> srdf;
};

/// srdf_path may be empty. Throws std::runtime_error naming the file.
LoadedRobot loadRobot(const std::string& urdf_path, const std::string& srdf_path);

/// The group's active joints: the SRDF group when named, else the SRDF's first group when
/// there is one, else every active joint. `group` receives the chosen name ("" for all).
std::vector<int> resolveGroup(const LoadedRobot& robot, std::string* group);

struct CheckerConfig {
  std::string checker = "dss";  ///< dss | fcl-hull | fcl-mesh
  double scene_padding = 0.0;
  double self_padding = 0.0;
  Options dss_options;
  Algorithm algorithm = Algorithm::kDss;
  bool obb_stage = true;  ///< oriented-box stage (dss, and fcl-* with the shared sweep)
  /// fcl-* only: "aabb" (FCL's own world AABBs, as an OMPL/MoveIt + FCL checker does) or
  /// "shared" (the DSS checker's sphere and oriented-box sweep).
  std::string fcl_prefilter = "aabb";
};

struct Problem {
  std::shared_ptr<const CollisionModel> model;
  std::shared_ptr<const GroupStateMap> map;
  ompl::base::SpaceInformationPtr si;
  std::string group;
  std::vector<std::string> warnings;
};

/// Builds the model for `scene` (may be empty) with the group, holding the joints outside it at
/// `start` (by name; falls back to the scene's robot state, then the default state).
Problem makeProblem(const LoadedRobot& robot, Scene scene, std::string group,
                    const std::map<std::string, double>& start, double prune_margin = 0.0);

/// A checker by name; throws std::invalid_argument for an unknown name.
std::shared_ptr<ModelValidityChecker> makeChecker(const Problem& problem, const CheckerConfig& config);

}  // namespace dss
