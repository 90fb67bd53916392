// What every scene the scene fuzz targets read must satisfy: finite shape parameters and
// poses (the readers refuse NaN and Inf), a unique name per obstacle, and obstacles that the
// core can bound (worldAabb) and decide against a ball without a crash. Frames are resolved
// as far as the file places them.
#pragma once

#include <cmath>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "dss/core/any_shape_query.h"
#include "dss/scene/scene.h"
#include "fuzz_support.h"

namespace dss_fuzz {

inline bool shapeFinite(const dss::AnyShape& shape) {
  using namespace dss;
  if (const auto* s = std::get_if<Sphere>(&shape)) return std::isfinite(s->radius);
  if (const auto* s = std::get_if<Box>(&shape)) return s->half.allFinite();
  if (const auto* s = std::get_if<Capsule>(&shape))
    return std::isfinite(s->radius) && std::isfinite(s->half_length);
  if (const auto* s = std::get_if<Cylinder>(&shape))
    return std::isfinite(s->radius) && std::isfinite(s->half_length);
  if (const auto* s = std::get_if<Cone>(&shape))
    return std::isfinite(s->radius) && std::isfinite(s->half_length);
  if (const auto* s = std::get_if<Ellipsoid>(&shape)) return s->radii.allFinite();
  for (const auto& p : std::get<ConvexHull>(shape).points())
    if (!p.allFinite()) return false;
  return true;
}

/// Attached objects (a scene's or a request start state's): each with an id that `ids` (the
/// other objects' ids, extended here) lacks, a link, touch links with names, and finite parts
/// of that id.
inline void checkAttached(const std::vector<dss::AttachedObject>& attached,
                          std::set<std::string>& ids) {
  for (const dss::AttachedObject& a : attached) {
    if (a.id.empty() || a.link.empty()) propertyFailed("attached object without id or link");
    if (!ids.insert(a.id).second) propertyFailed("attached object id '" + a.id + "' repeated");
    if (a.parts.empty()) propertyFailed("attached object " + a.id + ": no part");
    for (const dss::Obstacle& p : a.parts) {
      if (p.object_id != a.id) propertyFailed("attached object " + a.id + ": a part of another");
      if (!shapeFinite(p.shape)) propertyFailed("attached object " + a.id + ": non-finite shape");
      if (!p.X_FO.matrix().allFinite())
        propertyFailed("attached object " + a.id + ": non-finite pose");
    }
    for (const std::string& t : a.touch_links)
      if (t.empty()) propertyFailed("attached object " + a.id + ": empty touch link");
  }
}

inline void checkScene(dss::Scene& scene) {
  std::set<std::string> names;
  for (const dss::Obstacle& o : scene.obstacles) {
    if (!names.insert(o.name).second) propertyFailed("obstacle name '" + o.name + "' repeated");
    if (!shapeFinite(o.shape)) propertyFailed("obstacle " + o.name + ": non-finite shape");
    if (!o.X_FO.matrix().allFinite()) propertyFailed("obstacle " + o.name + ": non-finite pose");
    if (o.frame_resolved && !o.X_WO.matrix().allFinite())
      propertyFailed("obstacle " + o.name + ": non-finite world pose");
  }
  // Objects the robot holds: an id no other object has, a link, finite parts of that id.
  std::set<std::string> ids;
  for (const dss::Obstacle& o : scene.obstacles) ids.insert(o.object_id);
  checkAttached(scene.attached, ids);
  std::set<std::string> multi;  // robot_state.multi_dof_joint_state
  for (const auto& [name, X] : scene.robot_multi_dof) {
    if (!multi.insert(name).second) propertyFailed("multi-DOF joint '" + name + "' repeated");
    if (!X.matrix().allFinite()) propertyFailed("multi-DOF joint " + name + ": non-finite pose");
  }
  dss::resolveFrames(scene, {}, /*require_all=*/false);
  for (const dss::Obstacle& o : scene.obstacles) {
    if (!o.frame_resolved) continue;
    (void)dss::worldAabb(o);
    const dss::Result r =
        dss::intersect(o.shape, o.X_WO, dss::Sphere{1.0}, Eigen::Isometry3d::Identity());
    (void)r;
  }
}

}  // namespace dss_fuzz
