// The chain of balls along an element (see dss/checker/sphere_chain.h).
#include "dss/checker/sphere_chain.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "dss/checker/element_bounds.h"
#include "dss/checker/inner_shapes.h"
#include "dss/mesh/mesh.h"

namespace dss {

SphereChain sphereChain(const AnyShape& shape, const Eigen::Vector3d& box_c,
                        const Eigen::Vector3d& box_h) {
  SphereChain chain;
  const double grow = 1e-9 * (1.0 + shapeMagnitude(shape) + box_c.norm());
  int axis = 0;
  box_h.maxCoeff(&axis);
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  const double next = std::max(box_h[a1], box_h[a2]);
  const double ratio = next > 0.0 ? box_h[axis] / next : double(SphereChain::kMaxPoints);
  const int n = static_cast<int>(
      std::clamp(std::round(ratio), 1.0, static_cast<double>(SphereChain::kMaxPoints)));
  const double slab = box_h[axis] / n;  // half the slab's length
  chain.num_points = n;
  for (int k = 0; k < n; ++k) {
    chain.center_S[k] = box_c;
    chain.center_S[k][axis] += slab * (2 * k + 1) - box_h[axis];
  }
  mesh::TriangleMesh m;  // a hull's, for its slabs and its facets
  if (std::holds_alternative<ConvexHull>(shape)) {
    // The hull cut by a slab is a polytope whose vertices are the hull's vertices within the
    // slab and the points where the hull's edges cross the slab's planes: the farthest of them
    // from the point bounds the cut part. The edges are the tessellation's; a flat hull has
    // none, and takes every segment between two of its points instead (their crossings are
    // points of the hull, its edges' among them).
    m = mesh::tessellate(shape);
    const std::vector<Eigen::Vector3d>& points =
        m.triangles.empty() ? std::get<ConvexHull>(shape).points() : m.vertices;
    std::vector<std::pair<int, int>> edges;
    for (const auto& t : m.triangles)
      for (int e = 0; e < 3; ++e) edges.emplace_back(t[e], t[(e + 1) % 3]);
    if (m.triangles.empty())
      for (int i = 0; i < int(points.size()); ++i)
        for (int j = i + 1; j < int(points.size()); ++j) edges.emplace_back(i, j);
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d& c = chain.center_S[k];
      const double a = c[axis] - slab, b = c[axis] + slab;
      double r2 = 0.0;
      for (const auto& v : points)
        if (v[axis] >= a && v[axis] <= b) r2 = std::max(r2, (v - c).squaredNorm());
      for (const auto& [i, j] : edges) {
        const Eigen::Vector3d &v = points[std::size_t(i)], &w = points[std::size_t(j)];
        for (const double plane : {a, b})
          if ((v[axis] - plane) * (w[axis] - plane) < 0.0) {
            const Eigen::Vector3d x = v + (w - v) * ((plane - v[axis]) / (w[axis] - v[axis]));
            r2 = std::max(r2, (x - c).squaredNorm());
          }
      }
      chain.outer[k] = std::sqrt(r2) + grow;
    }
  } else {
    const auto* cylinder = std::get_if<Cylinder>(&shape);
    const double r = cylinder && axis == 2
                         ? std::hypot(cylinder->radius, slab)  // the rims of the slab
                         : std::sqrt(slab * slab + box_h[a1] * box_h[a1] + box_h[a2] * box_h[a2]);
    for (int k = 0; k < n; ++k) chain.outer[k] = r + grow;
  }
  // A single point at the bounding sphere's centre keeps that sphere when it is smaller (a
  // sphere's, a disc's).
  Eigen::Vector3d center;
  double radius;
  elementSphere(shape, Eigen::Isometry3d::Identity(), &center, &radius);
  if (n == 1 && center == chain.center_S[0]) chain.outer[0] = std::min(chain.outer[0], radius);
  innerRadii(shape, chain.center_S, n, chain.inner,
             std::holds_alternative<ConvexHull>(shape) ? &m : nullptr);
  return chain;
}

}  // namespace dss
