// Piece hulls (see piece_hull.h).
#include "piece_hull.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <utility>

#include "dss/core/any_shape.h"
#include "dss/core/convex_hull.h"

namespace dss::mesh::decomposition {
namespace {

// Points of a rough hull, which only ranks candidate cuts.
constexpr std::size_t kRoughPoints = 2000;

// Planes around a flat, collinear or tiny set: its bounding box, both sides of its best-fit
// plane and the edges of its 2-D hull in that plane. Every offset is the largest over the
// points, so each half-space holds the set whatever the rounding of its normal.
std::vector<Plane> flatPlanes(const std::vector<Vec3>& pts) {
  std::vector<Vec3> normals = {Vec3::UnitX(),  -Vec3::UnitX(), Vec3::UnitY(),
                               -Vec3::UnitY(), Vec3::UnitZ(),  -Vec3::UnitZ()};
  if (pts.size() >= 3) {
    Vec3 mean = Vec3::Zero();
    for (const Vec3& p : pts) mean += p;
    mean /= static_cast<double>(pts.size());
    const Eigen::Matrix3d axes = principalAxes(pts);
    const Vec3 n = axes.col(0), e1 = axes.col(2), e2 = axes.col(1);
    normals.push_back(n);
    normals.push_back(-n);
    // Andrew's monotone chain on the projections.
    std::vector<std::pair<double, double>> q;
    for (const Vec3& p : pts) q.emplace_back((p - mean).dot(e1), (p - mean).dot(e2));
    std::sort(q.begin(), q.end());
    q.erase(std::unique(q.begin(), q.end()), q.end());
    if (q.size() >= 3) {
      auto cross = [](const std::pair<double, double>& o, const std::pair<double, double>& a,
                      const std::pair<double, double>& b) {
        return (a.first - o.first) * (b.second - o.second) -
               (a.second - o.second) * (b.first - o.first);
      };
      std::vector<std::pair<double, double>> h(2 * q.size());
      std::size_t k = 0;
      for (std::size_t i = 0; i < q.size(); ++i) {
        while (k >= 2 && cross(h[k - 2], h[k - 1], q[i]) <= 0) --k;
        h[k++] = q[i];
      }
      for (std::size_t i = q.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross(h[k - 2], h[k - 1], q[i]) <= 0) --k;
        h[k++] = q[i];
      }
      h.resize(k - 1);
      for (std::size_t i = 0; i < h.size(); ++i) {
        const auto& a = h[i];
        const auto& b = h[(i + 1) % h.size()];
        const Vec3 outward = (b.second - a.second) * e1 - (b.first - a.first) * e2;
        if (outward.norm() > 0.0) normals.push_back(outward.normalized());
      }
    }
  }
  std::vector<Plane> planes;
  for (const Vec3& n : normals) {
    double o = -kInf;
    for (const Vec3& p : pts) o = std::max(o, n.dot(p));
    planes.push_back({n, o});
  }
  return planes;
}

}  // namespace

Eigen::Matrix3d principalAxes(const std::vector<Vec3>& pts) {
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& p : pts) cov += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  return eig.eigenvectors();
}

Hull buildHull(std::vector<Vec3> pts, const MeshData& m, HullMode mode) {
  Hull h;
  // qhull's input is made distinct by tessellate(); the exact check wants few repeats.
  if (mode == HullMode::kExact) sortUnique(pts);
  if (mode == HullMode::kRough && pts.size() > kRoughPoints) {
    // Every k-th point, and the extreme ones along the axes so that the box is exact.
    std::vector<Vec3> sub;
    const std::size_t stride = (pts.size() + kRoughPoints - 1) / kRoughPoints;
    for (std::size_t i = 0; i < pts.size(); i += stride) sub.push_back(pts[i]);
    for (int k = 0; k < 3; ++k) {
      auto cmp = [k](const Vec3& a, const Vec3& b) { return a[k] < b[k]; };
      sub.push_back(*std::min_element(pts.begin(), pts.end(), cmp));
      sub.push_back(*std::max_element(pts.begin(), pts.end(), cmp));
    }
    pts.swap(sub);
    sortUnique(pts);
  }
  for (const Vec3& p : pts) h.box.add(p);
  TriangleMesh facets;
  if (pts.size() >= 4) facets = tessellate(dss::AnyShape(dss::ConvexHull(pts)));
  if (facets.triangles.empty()) {
    sortUnique(pts);
    h.points = std::move(pts);
    h.planes = flatPlanes(h.points);
    return h;
  }
  h.full = true;
  std::vector<Vec3> vertices = facets.vertices;
  sortUnique(vertices);
  struct Facet {
    Vec3 n, a;
  };
  std::vector<Facet> fs;
  std::vector<std::size_t> facet_of;  // the triangle of each facet
  const Vec3 g = 0.5 * (h.box.lo + h.box.hi);
  for (std::size_t i = 0; i < facets.triangles.size(); ++i) {
    const auto& t = facets.triangles[i];
    const Vec3 &a = facets.vertices[t[0]], &b = facets.vertices[t[1]], &c = facets.vertices[t[2]];
    h.volume += (a - g).dot((b - g).cross(c - g)) / 6.0;
    const Vec3 n = (b - a).cross(c - a);
    const double len = n.norm();
    if (len > 0.0 && std::isfinite(len)) {
      fs.push_back({n / len, a});
      facet_of.push_back(i);
    }
  }
  h.points = vertices;
  if (mode == HullMode::kExact) {
    // A point qhull left out is dropped only when it is inside every facet plane by a margin
    // far above rounding. The facets form a closed surface with vertices in `vertices`, so
    // such a point has winding number >= 1 about it and lies in their hull. Any other point
    // is kept. Points within the ball inside every facet plane (about the box centre) pass at
    // once.
    const double margin = 1e-9 * h.box.diagonal() + 16.0 * m.margin;
    double ball = kInf;
    for (const Facet& f : fs) ball = std::min(ball, -f.n.dot(g - f.a));
    ball -= 2.0 * margin;
    for (const Vec3& p : pts) {
      if ((p - g).norm() < ball) continue;
      if (std::binary_search(vertices.begin(), vertices.end(), p, lexLess)) continue;
      bool inside = true;
      for (const Facet& f : fs)
        if (f.n.dot(p - f.a) >= -margin) {
          inside = false;
          break;
        }
      if (!inside) h.points.push_back(p);
    }
  }
  if (mode == HullMode::kExact) {
    // Offsets as the largest over the points: each half-space holds them all, whatever the
    // rounding of its normal.
    for (const Facet& f : fs) {
      double o = -kInf;
      for (const Vec3& p : h.points) o = std::max(o, f.n.dot(p));
      h.planes.push_back({f.n, o});
    }
  } else {
    // qhull leaves every vertex below every facet up to its rounding, far below the margin.
    for (std::size_t i = 0; i < fs.size(); ++i) {
      const auto& t = facets.triangles[facet_of[i]];
      double o = -kInf;
      for (int k = 0; k < 3; ++k) o = std::max(o, fs[i].n.dot(facets.vertices[t[k]]));
      h.planes.push_back({fs[i].n, o + 16.0 * m.margin});
    }
  }
  return h;
}

}  // namespace dss::mesh::decomposition
