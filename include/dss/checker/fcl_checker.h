// The FCL state checker: the same collision model (elements, obstacle pruning, pairs, bounds)
// with FCL as the narrow phase, as the reference MoveIt users know.
//
// Two prefilters (FclPrefilter):
//  - kAabb (default): what an OMPL/MoveIt + FCL checker does: every element's world AABB is
//    updated per state the way fcl::CollisionObject::computeAABB does it (a cube about the
//    geometry's bounding sphere when rotated), and a pair whose AABBs overlap (grown by the
//    padding) goes to fcl::collide (fcl::distance with a padding).
//  - kShared: the DSS checker's own sweep (sweep.h): FCL then only decides the pairs that DSS
//    would decide, which isolates the narrow-phase difference. With meshes, the stages that
//    prove a collision of the hulls (inner balls, colliding table cells) are left out.
//
// Two geometry variants:
//  - kHull ("fcl-hull"): every convex hull (robot meshes, scene meshes) as fcl::Convex built
//    from the hull's facets: the same geometry DSS sees. Primitives as FCL primitives.
//  - kMesh ("fcl-mesh"): robot meshes as fcl::BVHModel<OBBRSS> of the original triangle mesh
//    (reloaded from the element's mesh file at its scale), as MoveIt's FCL backend does; other
//    hulls as BVH models of their facets. Primitives as FCL primitives.
// Solver settings are pinned to FCL's defaults and reported by solverDescription():
// CollisionRequest(num_max_contacts = 1, enable_contact = false, GST_LIBCCD). With a padding,
// a pair collides when fcl::distance() <= padding.
#pragma once

#include <fcl/fcl.h>

#include <memory>
#include <string>
#include <vector>

#include "dss/checker/state_checker.h"

namespace dss {

enum class FclGeometry { kHull, kMesh };
enum class FclPrefilter { kAabb, kShared };

struct FclCheckerSettings {
  FclGeometry geometry = FclGeometry::kHull;
  FclPrefilter prefilter = FclPrefilter::kAabb;
  double scene_padding = 0.0;
  double self_padding = 0.0;
  bool obb_stage = true;  ///< kShared: the sweep's oriented-box stage (and inner balls for kHull)
};

/// FCL geometry for one shape (hull as Convex, or as a BVH of its facets when as_mesh).
std::shared_ptr<fcl::CollisionGeometryd> fclGeometry(const AnyShape& shape, bool as_mesh,
                                                     const std::string& what);
/// A BVH model of a triangle mesh file at a scale.
std::shared_ptr<fcl::CollisionGeometryd> fclMeshGeometry(const std::string& path,
                                                         const Eigen::Vector3d& scale,
                                                         const std::string& what);

class FclChecker : public StateChecker {
 public:
  using Settings = FclCheckerSettings;
  FclChecker(std::shared_ptr<const CollisionModel> model, const Settings& settings = {});

  std::string name() const override {
    return settings_.geometry == FclGeometry::kHull ? "fcl-hull" : "fcl-mesh";
  }
  const Settings& settings() const { return settings_; }
  /// "fcl-aabb" or "dss-sweep".
  std::string prefilterName() const {
    return settings_.prefilter == FclPrefilter::kAabb ? "fcl-aabb" : "dss-sweep";
  }
  static std::string solverDescription();

  const fcl::CollisionGeometryd* elementGeometry(int e) const { return elements_[e].get(); }
  const fcl::CollisionGeometryd* obstacleGeometry(int o) const { return obstacles_[o].get(); }

 private:
  bool collidesWithinBounds(const double* q, CounterSlots::Slot& counters) const override;
  bool pair(const fcl::CollisionGeometryd* a, const Eigen::Isometry3d& X_A,
            const fcl::CollisionGeometryd* b, const Eigen::Isometry3d& X_B, double padding) const;
  bool collidesAabb(const Eigen::Isometry3d* X_WL, std::uint64_t* tests) const;

  Settings settings_;
  std::vector<fcl::AABBd> obstacle_boxes_;  ///< world AABBs of the obstacles (static)
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> elements_;
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> obstacles_;
};

}  // namespace dss
