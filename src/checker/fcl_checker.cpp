// FclChecker: FCL geometry for the model's elements and obstacles, FCL narrow phase (see
// fcl_checker.h).
#include "dss/checker/fcl_checker.h"

#include <cmath>
#include <stdexcept>

#include "dss/checker/sweep.h"
#include "dss/mesh/mesh.h"

namespace dss {

namespace {

std::shared_ptr<fcl::CollisionGeometryd> bvhFrom(const mesh::TriangleMesh& m,
                                                 const std::string& what) {
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
  return (a.min_.array() <= b.max_.array() + pad).all() &&
         (b.min_.array() <= a.max_.array() + pad).all();
}

}  // namespace

std::shared_ptr<fcl::CollisionGeometryd> fclGeometry(const AnyShape& shape, bool as_mesh,
                                                     const std::string& what) {
  std::shared_ptr<fcl::CollisionGeometryd> g;
  if (const auto* s = std::get_if<Sphere>(&shape))
    g = std::make_shared<fcl::Sphered>(s->radius);
  else if (const auto* b = std::get_if<Box>(&shape))
    g = std::make_shared<fcl::Boxd>(2.0 * b->half);
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
    if (m.triangles.empty()) throw std::runtime_error(what + ": flat hull, no facets for FCL");
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

std::shared_ptr<fcl::CollisionGeometryd> fclMeshGeometry(const std::string& path,
                                                         const Eigen::Vector3d& scale,
                                                         const std::string& what) {
  return bvhFrom(mesh::loadMesh(path, scale), what);
}

FclChecker::FclChecker(std::shared_ptr<const CollisionModel> model, const Settings& settings)
    : StateChecker(std::move(model)), settings_(settings) {
  const CollisionModel& m = this->model();
  const bool mesh = settings_.geometry == FclGeometry::kMesh;
  for (const auto& e : m.elements()) {
    const CollisionElement& ce = *e.source;
    if (mesh && !ce.mesh_path.empty())
      elements_.push_back(fclMeshGeometry(ce.mesh_path, ce.mesh_scale, ce.description));
    else
      elements_.push_back(fclGeometry(ce.shape, mesh, ce.description));
  }
  for (const auto& o : m.scene().obstacles) {
    obstacles_.push_back(fclGeometry(o.shape, mesh, m.scene().source + ": " + o.name));
    obstacle_boxes_.push_back(worldAabb(*obstacles_.back(), o.X_WO));
  }
}

std::string FclChecker::solverDescription() {
  const fcl::CollisionRequestd req;
  return std::string("fcl 0.7 collide(): num_max_contacts=") +
         std::to_string(req.num_max_contacts) +
         ", enable_contact=" + (req.enable_contact ? "true" : "false") + ", gjk_solver_type=" +
         (req.gjk_solver_type == fcl::GST_LIBCCD ? "GST_LIBCCD" : "GST_INDEP");
}

bool FclChecker::pair(const fcl::CollisionGeometryd* a, const Eigen::Isometry3d& X_A,
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

namespace {
struct Scratch {
  std::vector<Eigen::Isometry3d> X_WL;
  std::vector<unsigned char> skip;
  std::vector<Eigen::Isometry3d> X_WE;
  std::vector<fcl::AABBd> boxes;
};
Scratch& scratch() {
  thread_local Scratch s;
  return s;
}
}  // namespace

bool FclChecker::collidesWithinBounds(const double* q, CounterSlots::Slot& c) const {
  const CollisionModel& m = model();
  Scratch& s = scratch();
  if (s.X_WL.size() < m.robot().links.size())
    s.X_WL.resize(m.robot().links.size(), Eigen::Isometry3d::Identity());
  if (s.skip.size() < m.selfTables().size()) s.skip.resize(m.selfTables().size());
  std::uint64_t tests = 0;
  bool hit;
  if (settings_.prefilter == FclPrefilter::kAabb) {
    m.kinematics().computeLinkPoses(q, s.X_WL.data());
    hit = collidesAabb(s.X_WL.data(), &tests);
  } else {
    const bool held = m.heldMatch(q);
    const bool hulls = settings_.geometry == FclGeometry::kHull;
    hit = m.selfTables().read(q, held, settings_.self_padding, s.skip.data(),
                              /*colliding_cells=*/hulls);
    if (!hit) {
      (held ? m.sweepKinematics() : m.kinematics()).computeLinkPoses(q, s.X_WL.data());
      const auto& obstacles = m.scene().obstacles;
      auto scene = [&](int e, const Eigen::Isometry3d& X_WS, int o) {
        ++tests;
        return pair(elements_[e].get(), X_WS, obstacles_[o].get(), obstacles[o].X_WO,
                    settings_.scene_padding);
      };
      auto self = [&](int a, const Eigen::Isometry3d& X_WA, int b, const Eigen::Isometry3d& X_WB) {
        ++tests;
        return pair(elements_[a].get(), X_WA, elements_[b].get(), X_WB, settings_.self_padding);
      };
      SweepOptions opt;
      opt.scene_padding = settings_.scene_padding;
      opt.self_padding = settings_.self_padding;
      opt.obb_stage = settings_.obb_stage;
      opt.inner_shapes = settings_.obb_stage && hulls;
      hit = held ? sweep<SweepPoses::kPoseLinks>(m, s.X_WL.data(), s.skip.data(), opt, scene, self)
                 : sweep<SweepPoses::kOwnLinks>(m, s.X_WL.data(), s.skip.data(), opt, scene, self);
    }
  }
  if (tests) c.add(c.pair_tests, tests);
  return hit;
}

bool FclChecker::collidesAabb(const Eigen::Isometry3d* X_WL, std::uint64_t* tests) const {
  const CollisionModel& m = model();
  const auto& elements = m.elements();
  const auto& obstacles = m.scene().obstacles;
  const double scene_padding = settings_.scene_padding, self_padding = settings_.self_padding;
  // Per state, as a CollisionObject per element would: world poses and AABBs of the elements
  // (per-thread scratch; no allocation once warmed up).
  Scratch& s = scratch();
  if (s.X_WE.size() < elements.size()) {
    s.X_WE.resize(elements.size());
    s.boxes.resize(elements.size());
  }
  for (std::size_t e = 0; e < elements.size(); ++e) {
    s.X_WE[e] = X_WL[elements[e].link] * elements[e].source->X_LS;
    s.boxes[e] = worldAabb(*elements_[e], s.X_WE[e]);
  }
  for (const auto& slot : m.slots()) {
    for (int o : slot.obstacles) {
      for (int e = slot.first_element; e < slot.first_element + slot.num_elements; ++e) {
        if (!overlap(s.boxes[e], obstacle_boxes_[o], scene_padding)) continue;
        ++*tests;
        if (pair(elements_[e].get(), s.X_WE[e], obstacles_[o].get(), obstacles[o].X_WO,
                 scene_padding))
          return true;
      }
    }
  }
  for (const auto& p : m.selfPairs()) {
    const auto& sa = m.slots()[p.a];
    const auto& sb = m.slots()[p.b];
    for (int a = sa.first_element; a < sa.first_element + sa.num_elements; ++a)
      for (int b = sb.first_element; b < sb.first_element + sb.num_elements; ++b) {
        if (!overlap(s.boxes[a], s.boxes[b], self_padding)) continue;
        ++*tests;
        if (pair(elements_[a].get(), s.X_WE[a], elements_[b].get(), s.X_WE[b], self_padding))
          return true;
      }
  }
  return false;
}

}  // namespace dss
