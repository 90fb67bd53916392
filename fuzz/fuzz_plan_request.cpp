// Fuzz target: the MotionPlanRequest YAML reader (dss::parsePlanRequestYaml), then the request's
// joints checked against a fixed set of movable and held joint names
// (dss::checkRequestJoints). Any bytes must end in a PlanRequest or a std::exception naming
// the source (key errors are tried strict and as warnings, by the last input byte); a request
// that loads must have one position per start joint and only finite values; its multi-DOF start
// transforms are finite rigid transforms with distinct names, its workspace corners finite and
// ordered, its start state's attached objects as a scene's (scene_checks.h).
#include <cmath>
#include <cstdint>
#include <exception>
#include <set>
#include <string>

#include "dss/scene/plan_request.h"
#include "fuzz_support.h"
#include "scene_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  dss::PlanRequestOptions options;
  options.unknown_keys_are_warnings = size > 0 && (data[size - 1] & 1);
  options.limits.max_mesh_vertices = 200'000;  // attached objects' meshes, as in the scene targets
  options.limits.max_scene_mesh_vertices = 400'000;
  options.limits.max_mesh_triangles = 400'000;
  dss::PlanRequest request;
  try {
    request = dss::parsePlanRequestYaml(text, "fuzz_request.yaml", options);
  } catch (const std::exception&) {
    return 0;
  }
  if (request.start_names.size() != request.start_positions.size())
    dss_fuzz::propertyFailed("start names and positions differ in length");
  for (double v : request.start_positions)
    if (!std::isfinite(v)) dss_fuzz::propertyFailed("a non-finite start position");
  for (const auto& g : request.goals)
    for (const auto& c : g.joint_constraints)
      if (!std::isfinite(c.position) || !std::isfinite(c.tolerance_above) ||
          !std::isfinite(c.tolerance_below) || !std::isfinite(c.weight))
        dss_fuzz::propertyFailed("a non-finite goal constraint value");
  std::set<std::string> multi;
  for (const auto& [name, X] : request.start_multi_dof) {
    if (!multi.insert(name).second) dss_fuzz::propertyFailed("a multi-DOF joint given twice");
    if (!X.matrix().allFinite() ||
        !(X.linear().transpose() * X.linear()).isApprox(Eigen::Matrix3d::Identity(), 1e-9))
      dss_fuzz::propertyFailed("a multi-DOF start transform that is not a finite rigid motion");
  }
  if (request.workspace) {
    const auto& [lo, hi] = *request.workspace;
    if (!lo.allFinite() || !hi.allFinite() || !(lo.array() <= hi.array()).all())
      dss_fuzz::propertyFailed("workspace corners not finite and ordered");
  }
  std::set<std::string> ids;
  dss_fuzz::checkAttached(request.start_attached, ids);
  for (const dss::AttachedObject& a : request.start_attached)
    if (!a.at_request_start) dss_fuzz::propertyFailed("a start state object not marked so");
  (void)request.startState();
  static const std::set<std::string> movable = {"joint1", "joint2", "joint3", "shoulder_pan"};
  static const std::set<std::string> held = {"finger_joint", "gripper"};
  try {
    (void)dss::checkRequestJoints(request, movable, held);
  } catch (const std::exception&) {
  }
  return 0;
}
