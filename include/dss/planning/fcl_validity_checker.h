// The FCL-backed validity checker: the same CollisionModel (elements, obstacle pruning, pairs)
// with FCL as the narrow phase, as the reference MoveIt users know.
//
// Two prefilters (FclPrefilter):
//  - kAabb (default): what an OMPL/MoveIt + FCL checker does: every element's world AABB is
//    updated per state the way fcl::CollisionObject::computeAABB does it (a cube about the
//    geometry's bounding sphere when rotated), and a pair whose AABBs overlap (grown by the
//    padding) goes to fcl::collide (fcl::distance with a padding).
//  - kShared: the DSS checker's own sweep (bounding spheres, oriented boxes): FCL then only
//    decides the pairs that DSS would decide, which isolates the narrow-phase difference.
//
// Two geometry variants:
//  - kHull ("fcl-hull"): every convex hull (robot meshes, scene meshes) as fcl::Convex built
//    from the hull's facets: the same geometry DSS sees. Primitives as FCL primitives.
//  - kMesh ("fcl-mesh"): robot meshes as fcl::BVHModel<OBBRSS> of the original triangle mesh
//    (reloaded from the path in the element's description), as MoveIt's FCL backend does;
//    other hulls as BVH models of their facets. Primitives as FCL primitives.
// Solver settings are pinned to FCL's defaults and reported by solverDescription():
// CollisionRequest(num_max_contacts = 1, enable_contact = false, GST_LIBCCD). With a padding,
// a pair collides when fcl::distance() <= padding.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <fcl/fcl.h>

#include "dss/planning/validity_checker.h"

namespace dss {

enum class FclGeometry { kHull, kMesh };
enum class FclPrefilter { kAabb, kShared };

/// FCL geometry for one shape (hull as Convex, or as a BVH of its facets when as_mesh).
std::shared_ptr<fcl::CollisionGeometryd> fclGeometry(const AnyShape& shape, bool as_mesh,
                                                     const std::string& what);
/// A BVH model of a triangle mesh file, at the scale that makes its hull match `hull`.
std::shared_ptr<fcl::CollisionGeometryd> fclMeshGeometry(const std::string& path, const ConvexHull& hull,
                                                         const std::string& what);

class FclValidityChecker : public ModelValidityChecker {
 public:
  FclValidityChecker(const ompl::base::SpaceInformationPtr& si,
                     std::shared_ptr<const CollisionModel> model,
                     std::shared_ptr<const GroupStateMap> map, FclGeometry geometry,
                     double scene_padding = 0.0, double self_padding = 0.0,
                     FclPrefilter prefilter = FclPrefilter::kAabb);
  std::string name() const override { return geometry_ == FclGeometry::kHull ? "fcl-hull" : "fcl-mesh"; }
  FclPrefilter prefilter() const { return prefilter_; }
  /// "fcl-aabb" or "dss-sweep".
  std::string prefilterName() const { return prefilter_ == FclPrefilter::kAabb ? "fcl-aabb" : "dss-sweep"; }
  static std::string solverDescription();

  const fcl::CollisionGeometryd* elementGeometry(int e) const { return elements_[e].get(); }
  const fcl::CollisionGeometryd* obstacleGeometry(int o) const { return obstacles_[o].get(); }

 protected:
  bool collides(const double* q, const Eigen::Isometry3d* X_WL, const unsigned char* table_skip) const override;

 private:
  bool pair(const fcl::CollisionGeometryd* a, const Eigen::Isometry3d& X_A,
            const fcl::CollisionGeometryd* b, const Eigen::Isometry3d& X_B, double padding) const;

  bool collidesAabb(const Eigen::Isometry3d* X_WL) const;

  FclGeometry geometry_;
  FclPrefilter prefilter_;
  std::vector<fcl::AABBd> obstacle_boxes_;  ///< world AABBs of the obstacles (static)
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> elements_;
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> obstacles_;
};

}  // namespace dss
