// FclValidityChecker: FCL geometry for the model's elements and obstacles, FCL narrow phase.
#include "dss/planning/fcl_validity_checker.h"

#include <cmath>
#include <stdexcept>

#include "dss/mesh/mesh.h"

namespace dss {

namespace {

std::shared_ptr<fcl::CollisionGeometryd> bvhFrom(const mesh::TriangleMesh& m, const std::string& what) {
  if (m.triangles.empty()) throw std::runtime_error(what + ": no triangles for an FCL mesh");
  auto bvh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Triangle> tris;
  tris.reserve(m.triangles.size());
  for (const auto& t : m.triangles) tris.emplace_back(t[0], t[1], t[2]);
  bvh->beginModel(int(tris.size()), int(m.vertices.size()));
  bvh->addSubModel(m.vertices, tris);
  bvh->endModel();
  bvh->computeLocalAABB();
  return bvh;
}

// The world AABB of a geometry as fcl::CollisionObject::computeAABB makes it: the local box
// translated when the pose does not rotate, else a cube about the local bounding sphere.
fcl::AABBd worldAabb(const fcl::CollisionGeometryd& g, const Eigen::Isometry3d& X) {
  fcl::AABBd box;
  if (X.linear().isIdentity()) {
    box = fcl::translate(g.aabb_local, Eigen::Vector3d(X.translation()));
  } else {
    const Eigen::Vector3d c = X * g.aabb_center;
    const Eigen::Vector3d r = Eigen::Vector3d::Constant(g.aabb_radius);
    box.min_ = c - r;
    box.max_ = c + r;
  }
  return box;
}

bool overlap(const fcl::AABBd& a, const fcl::AABBd& b, double pad) {
  return (a.min_.array() <= b.max_.array() + pad).all() && (b.min_.array() <= a.max_.array() + pad).all();
}

}  // namespace

std::shared_ptr<fcl::CollisionGeometryd> fclGeometry(const AnyShape& shape, bool as_mesh,
                                                     const std::string& what) {
  std::shared_ptr<fcl::CollisionGeometryd> g;
  if (const auto* s = std::get_if<Sphere>(&shape)) g = std::make_shared<fcl::Sphered>(s->radius);
  else if (const auto* b = std::get_if<Box>(&shape)) g = std::make_shared<fcl::Boxd>(2.0 * b->half);
  else if (const auto* c = std::get_if<Capsule>(&shape))
    g = std::make_shared<fcl::Capsuled>(c->radius, 2.0 * c->half_length);
  else if (const auto* y = std::get_if<Cylinder>(&shape))
    g = std::make_shared<fcl::Cylinderd>(y->radius, 2.0 * y->half_length);
  else if (const auto* k = std::get_if<Cone>(&shape))
    g = std::make_shared<fcl::Coned>(k->radius, 2.0 * k->half_length);
  else if (const auto* e = std::get_if<Ellipsoid>(&shape))
    g = std::make_shared<fcl::Ellipsoidd>(e->radii);
  else {
    const mesh::TriangleMesh m = mesh::tessellate(shape);
    if (m.triangles.empty())
      throw std::runtime_error(what + ": flat hull, no facets for FCL");
    if (as_mesh) return bvhFrom(m, what);
    auto verts = std::make_shared<std::vector<fcl::Vector3d>>(m.vertices.begin(), m.vertices.end());
    auto faces = std::make_shared<std::vector<int>>();
    for (const auto& t : m.triangles) {
      faces->push_back(3);
      faces->insert(faces->end(), t.begin(), t.end());
    }
    g = std::make_shared<fcl::Convexd>(verts, int(m.triangles.size()), faces);
  }
  g->computeLocalAABB();
  return g;
}

std::shared_ptr<fcl::CollisionGeometryd> fclMeshGeometry(const std::string& path, const ConvexHull& hull,
                                                         const std::string& what) {
  mesh::TriangleMesh m = mesh::loadMesh(path);
  // The URDF scale is not kept by the robot model: recover it from the hull's extent.
  Eigen::Vector3d lo = m.vertices[0], hi = m.vertices[0];
  for (const auto& v : m.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  Eigen::Vector3d hlo = hull.points()[0], hhi = hull.points()[0];
  for (const auto& v : hull.points()) {
    hlo = hlo.cwiseMin(v);
    hhi = hhi.cwiseMax(v);
  }
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  for (int i = 0; i < 3; ++i) {
    const double ext = hi[i] - lo[i];
    if (ext > 0) scale[i] = (hhi[i] - hlo[i]) / ext;
    if (std::abs(scale[i] - 1.0) < 1e-9) scale[i] = 1.0;
  }
  if (scale != Eigen::Vector3d::Ones()) m = mesh::loadMesh(path, scale);
  return bvhFrom(m, what);
}

FclValidityChecker::FclValidityChecker(const ompl::base::SpaceInformationPtr& si,
                                       std::shared_ptr<const CollisionModel> model,
                                       std::shared_ptr<const GroupStateMap> map, FclGeometry geometry,
                                       double scene_padding, double self_padding,
                                       FclPrefilter prefilter)
    : ModelValidityChecker(si, std::move(model), std::move(map), scene_padding, self_padding),
      geometry_(geometry), prefilter_(prefilter) {
  sweep_poses_ = prefilter_ != FclPrefilter::kAabb;
  const bool mesh = geometry_ == FclGeometry::kMesh;
  for (const auto& e : model_->elements()) {
    const CollisionElement& ce = *e.source;
    const auto* hull = std::get_if<ConvexHull>(&ce.shape);
    const auto pos = ce.description.find(" mesh ");
    if (mesh && hull && pos != std::string::npos) {
      elements_.push_back(fclMeshGeometry(ce.description.substr(pos + 6), *hull, ce.description));
    } else {
      elements_.push_back(fclGeometry(ce.shape, mesh, ce.description));
    }
  }
  for (const auto& o : model_->scene().obstacles) {
    obstacles_.push_back(fclGeometry(o.shape, mesh, model_->scene().source + ": " + o.name));
    obstacle_boxes_.push_back(worldAabb(*obstacles_.back(), o.X_WO));
  }
}

std::string FclValidityChecker::solverDescription() {
  const fcl::CollisionRequestd req;
  return std::string("fcl 0.7 collide(): num_max_contacts=") + std::to_string(req.num_max_contacts) +
         ", enable_contact=" + (req.enable_contact ? "true" : "false") + ", gjk_solver_type=" +
         (req.gjk_solver_type == fcl::GST_LIBCCD ? "GST_LIBCCD" : "GST_INDEP");
}

bool FclValidityChecker::pair(const fcl::CollisionGeometryd* a, const Eigen::Isometry3d& X_A,
                              const fcl::CollisionGeometryd* b, const Eigen::Isometry3d& X_B,
                              double padding) const {
  if (padding > 0.0) {
    fcl::DistanceRequestd req;
    fcl::DistanceResultd res;
    const double d = fcl::distance(a, X_A, b, X_B, req, res);
    return d <= padding;
  }
  fcl::CollisionRequestd req;
  fcl::CollisionResultd res;
  return fcl::collide(a, X_A, b, X_B, req, res) > 0;
}

bool FclValidityChecker::collides(const double* q, const Eigen::Isometry3d* X_WL,
                                  const unsigned char* table_skip) const {
  if (prefilter_ == FclPrefilter::kAabb) return collidesAabb(X_WL);
  std::uint64_t tests = 0;
  const auto& obstacles = model_->scene().obstacles;
  const bool hit = model_->anyCollision(
      q, X_WL, scene_padding_, self_padding_,
      [&](int e, const Eigen::Isometry3d& X_WS, int o) {
        ++tests;
        return pair(elements_[e].get(), X_WS, obstacles_[o].get(), obstacles[o].X_WO, scene_padding_);
      },
      [&](int a, const Eigen::Isometry3d& X_WA, int b, const Eigen::Isometry3d& X_WB) {
        ++tests;
        return pair(elements_[a].get(), X_WA, elements_[b].get(), X_WB, self_padding_);
      },
      obb_stage_, /*inner_stage=*/obb_stage_ && geometry_ == FclGeometry::kHull, table_skip);
  slot().pair_tests.fetch_add(tests, std::memory_order_relaxed);
  return hit;
}

bool FclValidityChecker::collidesAabb(const Eigen::Isometry3d* X_WL) const {
  const CollisionModel& m = *model_;
  const auto& elements = m.elements();
  const auto& obstacles = m.scene().obstacles;
  // Per state, as a CollisionObject per element would: world poses and AABBs of the elements
  // of moving links (per-thread scratch; no allocation once warmed up).
  thread_local std::vector<Eigen::Isometry3d> X_WE;
  thread_local std::vector<fcl::AABBd> boxes;
  if (X_WE.size() < elements.size()) {
    X_WE.resize(elements.size());
    boxes.resize(elements.size());
  }
  for (std::size_t e = 0; e < elements.size(); ++e) {
    X_WE[e] = X_WL[elements[e].link] * elements[e].source->X_LS;
    boxes[e] = worldAabb(*elements_[e], X_WE[e]);
  }
  std::uint64_t tests = 0;
  bool hit = false;
  for (const auto& s : m.slots()) {
    for (int o : s.obstacles) {
      for (int e = s.first_element; e < s.first_element + s.num_elements && !hit; ++e) {
        if (!overlap(boxes[e], obstacle_boxes_[o], scene_padding_)) continue;
        ++tests;
        hit = pair(elements_[e].get(), X_WE[e], obstacles_[o].get(), obstacles[o].X_WO, scene_padding_);
      }
      if (hit) break;
    }
    if (hit) break;
  }
  for (std::size_t k = 0; k < m.selfPairs().size() && !hit; ++k) {
    const auto& sa = m.slots()[m.selfPairs()[k].a];
    const auto& sb = m.slots()[m.selfPairs()[k].b];
    for (int a = sa.first_element; a < sa.first_element + sa.num_elements && !hit; ++a)
      for (int b = sb.first_element; b < sb.first_element + sb.num_elements && !hit; ++b) {
        if (!overlap(boxes[a], boxes[b], self_padding_)) continue;
        ++tests;
        hit = pair(elements_[a].get(), X_WE[a], elements_[b].get(), X_WE[b], self_padding_);
      }
  }
  slot().pair_tests.fetch_add(tests, std::memory_order_relaxed);
  return hit;
}

}  // namespace dss
