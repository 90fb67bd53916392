// Problem loading shared by the executables and tests.
#include "dss/planning/planning_problem.h"

#include <stdexcept>

#include "dss/planning/fcl_validity_checker.h"
#include "dss/robot/urdf_loader.h"

namespace dss {

LoadedRobot loadRobot(const std::string& urdf_path, const std::string& srdf_path) {
  LoadedRobot r;
  r.model = std::make_shared<const RobotModel>(loadUrdf(urdf_path));
  if (!srdf_path.empty()) {
    r.srdf = loadSrdf(srdf_path);
    const auto problems = checkSrdfAgainstModel(*r.model, *r.srdf);
    if (!problems.empty()) throw std::runtime_error(srdf_path + ": " + problems.front());
  }
  return r;
}

std::vector<int> resolveGroup(const LoadedRobot& robot, std::string* group) {
  if (robot.srdf) {
    if (group->empty() && !robot.srdf->groups.empty()) *group = robot.srdf->groups.front().name;
    if (!group->empty()) return groupActiveJoints(*robot.model, *robot.srdf, *group);
  } else if (!group->empty()) {
    throw std::runtime_error("group '" + *group + "' given without an SRDF");
  }
  std::vector<int> all;
  for (std::size_t i = 0; i < robot.model->numActiveJoints(); ++i) all.push_back(int(i));
  return all;
}

Problem makeProblem(const LoadedRobot& robot, Scene scene, std::string group,
                    const std::map<std::string, double>& start, double prune_margin) {
  Problem p;
  std::vector<int> active = resolveGroup(robot, &group);
  p.group = group;
  std::vector<std::string> ignored;
  std::vector<double> held = heldState(*robot.model, {scene.robot_state, start}, &ignored);
  for (const auto& n : ignored)
    if (n != "virtual_joint") p.warnings.push_back("joint " + n + " of the scene/request is not an active joint of the robot: ignored");
  auto map = std::make_shared<GroupStateMap>(robot.model, active, held);
  for (const auto& w : map->warnings) p.warnings.push_back(w);
  CollisionModelOptions options;
  options.prune_margin = prune_margin;
  auto model = std::make_shared<CollisionModel>(robot.model, robot.srdf ? &*robot.srdf : nullptr,
                                                std::move(scene), active, held, options);
  for (const auto& w : model->warnings) p.warnings.push_back(w);
  p.map = map;
  p.model = model;
  p.si = std::make_shared<ompl::base::SpaceInformation>(map->space());
  return p;
}

std::shared_ptr<ModelValidityChecker> makeChecker(const Problem& p, const CheckerConfig& c) {
  if (c.checker == "dss") {
    DssCheckerSettings s;
    s.options = c.dss_options;
    s.algorithm = c.algorithm;
    s.obb_stage = c.obb_stage;
    s.scene_padding = c.scene_padding;
    s.self_padding = c.self_padding;
    return std::make_shared<DssValidityChecker>(p.si, p.model, p.map, s);
  }
  if (c.checker == "fcl-hull" || c.checker == "fcl-mesh") {
    if (c.fcl_prefilter != "aabb" && c.fcl_prefilter != "shared")
      throw std::invalid_argument("unknown FCL prefilter '" + c.fcl_prefilter + "' (expected aabb or shared)");
    auto f = std::make_shared<FclValidityChecker>(
        p.si, p.model, p.map, c.checker == "fcl-hull" ? FclGeometry::kHull : FclGeometry::kMesh,
        c.scene_padding, c.self_padding,
        c.fcl_prefilter == "aabb" ? FclPrefilter::kAabb : FclPrefilter::kShared);
    f->setObbStage(c.obb_stage);
    return f;
  }
  throw std::invalid_argument("unknown checker '" + c.checker + "' (expected dss, fcl-hull or fcl-mesh)");
}

}  // namespace dss
