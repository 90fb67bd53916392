// Checker setup from files (see checker_setup.h).
#include "dss/checker/checker_setup.h"

#include <algorithm>
#include <mutex>
#include <stdexcept>

#include "dss/checker/attached_objects.h"
#include "dss/checker/dss_checker.h"
#include "dss/checker/fcl_checker.h"
#include "dss/robot/joint_state.h"
#include "dss/robot/multi_dof.h"

namespace dss {

std::vector<std::string> LoadedRobot::warnings() const {
  std::vector<std::string> out;
  if (model) out = model->warnings;
  if (srdf) out.insert(out.end(), srdf->warnings.begin(), srdf->warnings.end());
  return out;
}

LoadedRobot loadRobot(const std::string& urdf_path, const std::string& srdf_path,
                      const LoadOptions& options) {
  LoadedRobot r;
  RobotModel model = loadUrdf(urdf_path, options);
  if (!srdf_path.empty()) {
    r.srdf = loadSrdf(srdf_path, options.limits);
    // Planar and floating virtual joints become part of the model (multi_dof.h).
    for (const auto& v : r.srdf->virtual_joints)
      applyVirtualJoint(model, v.name, v.type, v.parent_frame, v.child_link, srdf_path);
  }
  r.model = std::make_shared<const RobotModel>(std::move(model));
  if (r.srdf) {
    const auto problems = checkSrdfAgainstModel(*r.model, *r.srdf);
    if (!problems.empty()) throw std::runtime_error(srdf_path + ": " + problems.front());
  }
  return r;
}

namespace {
// The bounded copies made by withWorkspace, kept while the robot they were made from lives: the
// same robot and box give the same copy, so that a folder of problems with one workspace
// shares one robot object (and the self-pair tables cached for it, self_pair_table_cache.h)
// instead of copying the robot, meshes and all, for every problem.
struct BoundedCopy {
  std::weak_ptr<const RobotModel> from;
  const RobotModel* from_ptr = nullptr;
  Eigen::Vector3d lo, hi;
  std::shared_ptr<const RobotModel> copy;
};
constexpr std::size_t kMaxBoundedCopies = 8;
std::mutex bounded_mutex;
std::vector<BoundedCopy> bounded_copies;
}  // namespace

LoadedRobot withWorkspace(const LoadedRobot& robot, const Eigen::Vector3d& lo,
                          const Eigen::Vector3d& hi) {
  if (robot.model->multi_dof_joints.empty()) return robot;
  LoadedRobot r = robot;
  {
    std::lock_guard<std::mutex> lock(bounded_mutex);
    // Copies of robots that are gone go first.
    bounded_copies.erase(std::remove_if(bounded_copies.begin(), bounded_copies.end(),
                                        [](const BoundedCopy& c) { return c.from.expired(); }),
                         bounded_copies.end());
    for (const BoundedCopy& c : bounded_copies)
      if (c.from_ptr == robot.model.get() && c.lo == lo && c.hi == hi) {
        r.model = c.copy;
        return r;
      }
  }
  auto model = std::make_shared<RobotModel>(*robot.model);
  setMultiDofTranslationBounds(*model, lo, hi);  // throws for a box that is not finite
  r.model = model;
  std::lock_guard<std::mutex> lock(bounded_mutex);
  if (bounded_copies.size() >= kMaxBoundedCopies) bounded_copies.erase(bounded_copies.begin());
  bounded_copies.push_back({robot.model, robot.model.get(), lo, hi, std::move(model)});
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

ModelSetup setupModel(const LoadedRobot& robot, Scene scene, std::string group,
                      const std::map<std::string, double>& start, double prune_margin) {
  CollisionModelOptions options;
  options.prune_margin = prune_margin;
  return setupModel(robot, std::move(scene), std::move(group), start, options);
}

ModelSetup setupModel(const LoadedRobot& robot, Scene scene, std::string group,
                      const std::map<std::string, double>& start,
                      const CollisionModelOptions& options) {
  ModelSetup s;
  s.warnings = scene.warnings;  // the scene is consumed below; its warnings stay with the setup
  s.group_active = resolveGroup(robot, &group);
  s.group = group;
  std::vector<std::string> ignored;
  std::map<std::string, double> saved = scene.robot_state;
  for (const auto& [n, v] : multiDofStateValues(*robot.model, scene.robot_multi_dof, &s.warnings))
    saved[n] = v;
  s.held = heldState(*robot.model, {saved, start}, &ignored);
  for (const auto& n : ignored)
    if (n != "virtual_joint")
      s.warnings.push_back("joint " + n +
                           " of the scene/request is not an active joint of the robot: ignored");
  // Objects the robot holds become links of its own, placed where the scene's saved robot
  // state put them (attached_objects.h); those of a request's start state where it put them
  // (its values override the saved ones).
  for (const AttachedObject& a : scene.attached)
    for (const Obstacle& o : scene.obstacles)
      if (o.object_id == a.id)
        throw std::runtime_error(a.at + ": attached object '" + a.id + "': " + scene.source +
                                 " has an object '" + a.id + "' too");
  std::shared_ptr<const RobotModel> robot_model = robot.model;
  for (const bool at_start : {false, true}) {
    std::vector<AttachedObject> objects;
    for (const AttachedObject& a : scene.attached)
      if (a.at_request_start == at_start) objects.push_back(a);
    if (objects.empty()) continue;
    const std::vector<double> attach_state =
        at_start ? heldState(*robot.model, {saved, start}) : heldState(*robot.model, {saved});
    robot_model = withAttachedObjects(robot_model, objects, attach_state, scene.fixed_frames,
                                      scene.allowed_collisions);
  }
  auto model = std::make_shared<CollisionModel>(robot_model, robot.srdf ? &*robot.srdf : nullptr,
                                                std::move(scene), s.group_active, s.held, options);
  for (const auto& w : model->warnings) s.warnings.push_back(w);
  s.model = std::move(model);
  return s;
}

std::shared_ptr<const StateChecker> makeStateChecker(std::shared_ptr<const CollisionModel> model,
                                                     const CheckerConfig& c) {
  if (c.checker == "dss") {
    DssCheckerSettings s;
    s.options = c.dss_options;
    s.obb_stage = c.obb_stage;
    s.scene_padding = c.scene_padding;
    s.self_padding = c.self_padding;
    auto checker = std::make_shared<DssChecker>(std::move(model), s);
    checker->timeChecks(c.time_checks);
    return checker;
  }
  if (c.checker == "fcl-hull" || c.checker == "fcl-mesh") {
    if (c.fcl_prefilter != "aabb" && c.fcl_prefilter != "shared")
      throw std::invalid_argument("unknown FCL prefilter '" + c.fcl_prefilter +
                                  "' (expected aabb or shared)");
    FclCheckerSettings s;
    s.geometry = c.checker == "fcl-hull" ? FclGeometry::kHull : FclGeometry::kMesh;
    s.prefilter = c.fcl_prefilter == "aabb" ? FclPrefilter::kAabb : FclPrefilter::kShared;
    s.scene_padding = c.scene_padding;
    s.self_padding = c.self_padding;
    s.obb_stage = c.obb_stage;
    auto checker = std::make_shared<FclChecker>(std::move(model), s);
    checker->timeChecks(c.time_checks);
    return checker;
  }
  throw std::invalid_argument("unknown checker '" + c.checker +
                              "' (expected dss, fcl-hull or fcl-mesh)");
}

}  // namespace dss
