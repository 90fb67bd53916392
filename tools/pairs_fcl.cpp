// FCL shapes for dss_pairs, with qhull for the faces of convex shapes.
#include "pairs_fcl.h"

#include <cstdio>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace dss {
namespace pairs {
namespace {

struct HullFaces {
  std::vector<fcl::Vector3d> vertices;
  std::vector<int> faces;  // FCL layout: n, i0, ..., i(n-1), n, ...
  int num_faces = 0;
  bool is_3d = false;
};

// The triangulated 3-D hull of the points, or is_3d = false when qhull cannot build one.
HullFaces qhullFaces(const std::vector<Vec3d>& points) {
  HullFaces out;
  if (points.size() < 4) return out;
  std::vector<coordT> coords;
  coords.reserve(3 * points.size());
  for (const Vec3d& p : points) coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  // qhull reports flat inputs as errors; they are expected here and handled by the fallback.
  static FILE* const quiet = std::fopen("/dev/null", "w");
  qhT qh_storage;
  qhT* qh = &qh_storage;
  qh_zero(qh, quiet);
  char flags[] = "qhull Qt";
  const int exitcode = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False,
                                    flags, nullptr, quiet);
  if (exitcode == 0) {
    std::vector<int> index(points.size(), -1);
    vertexT* vertex;
    FORALLvertices {
      const int id = qh_pointid(qh, vertex->point);
      index[id] = static_cast<int>(out.vertices.size());
      out.vertices.push_back(points[id]);
    }
    facetT* facet;
    FORALLfacets {
      int tri[3];
      int k = 0;
      vertexT** vertexp;
      FOREACHvertex_(facet->vertices) {
        if (k < 3) tri[k] = index[qh_pointid(qh, vertex->point)];
        ++k;
      }
      if (k != 3) continue;  // Qt gives triangles; anything else is skipped
      const fcl::Vector3d& v0 = out.vertices[tri[0]];
      const fcl::Vector3d n = (out.vertices[tri[1]] - v0).cross(out.vertices[tri[2]] - v0);
      const fcl::Vector3d outward(facet->normal[0], facet->normal[1], facet->normal[2]);
      if (n.dot(outward) < 0) std::swap(tri[1], tri[2]);
      out.faces.insert(out.faces.end(), {3, tri[0], tri[1], tri[2]});
      ++out.num_faces;
    }
    out.is_3d = out.num_faces >= 4;
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong, totlong;
  qh_memfreeshort(qh, &curlong, &totlong);
  if (!out.is_3d) out = HullFaces{};
  return out;
}

}  // namespace

FclShape makeFclShape(const ShapeSpec& s) {
  FclShape out;
  out.X_WS.linear() = s.R_WS;
  out.X_WS.translation() = s.p_WS;
  switch (s.kind) {
    case ShapeKind::kSphere:
      out.geometry = std::make_shared<fcl::Sphered>(s.radius);
      break;
    case ShapeKind::kBox:
      out.geometry = std::make_shared<fcl::Boxd>(s.dims.x(), s.dims.y(), s.dims.z());
      break;
    case ShapeKind::kCylinder:
      out.geometry = std::make_shared<fcl::Cylinderd>(s.radius, s.length);
      break;
    case ShapeKind::kCapsule:
      out.geometry = std::make_shared<fcl::Capsuled>(s.radius, s.length);
      break;
    case ShapeKind::kCone:
      out.geometry = std::make_shared<fcl::Coned>(s.radius, s.length);
      break;
    case ShapeKind::kEllipsoid:
      out.geometry = std::make_shared<fcl::Ellipsoidd>(s.dims.x(), s.dims.y(), s.dims.z());
      break;
    case ShapeKind::kConvex: {
      HullFaces h = qhullFaces(s.vertices);
      out.hull_is_3d = h.is_3d;
      if (!h.is_3d) h.vertices.assign(s.vertices.begin(), s.vertices.end());
      out.geometry = std::make_shared<fcl::Convexd>(
          std::make_shared<const std::vector<fcl::Vector3d>>(std::move(h.vertices)), h.num_faces,
          std::make_shared<const std::vector<int>>(std::move(h.faces)));
      break;
    }
  }
  out.geometry->computeLocalAABB();
  return out;
}

bool fclIntersect(const FclPair& p, double padding) {
  const fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::collide(p.a.geometry.get(), p.a.X_WS, p.b.geometry.get(), p.b.X_WS, request, result);
  if (result.isCollision()) return true;
  if (padding <= 0) return false;
  const fcl::DistanceRequestd drequest;
  fcl::DistanceResultd dresult;
  const double d =
      fcl::distance(p.a.geometry.get(), p.a.X_WS, p.b.geometry.get(), p.b.X_WS, drequest, dresult);
  return d <= padding;
}

}  // namespace pairs
}  // namespace dss
