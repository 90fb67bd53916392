// qhull wrapper for the benchmark: triangles of a 3-D hull, oriented against the centroid
// (which is interior for a full-dimensional hull), so no qhull orientation convention leaks out.
#include "qhull_faces.h"

#include <stdexcept>
#include <string>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace dss {
namespace bench {

void orientOutward(const std::vector<Vec3d>& points, const Vec3d& interior,
                   std::vector<std::array<int, 3>>& triangles) {
  for (auto& t : triangles) {
    const Vec3d n = (points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]);
    if (n.dot(interior - points[t[0]]) > 0) std::swap(t[1], t[2]);
  }
}

std::vector<std::array<int, 3>> hullTriangles(const std::vector<Vec3d>& points) {
  if (points.size() < 4) throw std::runtime_error("hullTriangles: fewer than 4 points");
  std::vector<coordT> coords;
  coords.reserve(points.size() * 3);
  Vec3d centroid = Vec3d::Zero();
  for (const auto& p : points) {
    coords.insert(coords.end(), {p.x(), p.y(), p.z()});
    centroid += p;
  }
  centroid /= double(points.size());

  qhT qh_storage;
  qhT* qh = &qh_storage;
  qh_zero(qh, stderr);
  char flags[] = "qhull Qt";
  const int code = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False, flags,
                                nullptr, stderr);
  std::vector<std::array<int, 3>> triangles;
  if (code == 0) {
    facetT* facet;
    FORALLfacets {
      std::array<int, 3> t{};
      int k = 0;
      vertexT *vertex, **vertexp;
      FOREACHvertex_(facet->vertices) {
        if (k < 3) t[k] = qh_pointid(qh, vertex->point);
        ++k;
      }
      if (k == 3) triangles.push_back(t);
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  if (code != 0 || triangles.empty())
    throw std::runtime_error("hullTriangles: qhull failed with code " + std::to_string(code));
  orientOutward(points, centroid, triangles);
  return triangles;
}

}  // namespace bench
}  // namespace dss
