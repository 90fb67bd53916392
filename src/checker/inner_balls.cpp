// Inner balls of an element's shape (see inner_balls.h).
#include "dss/checker/inner_balls.h"

#include <algorithm>
#include <limits>
#include <vector>

#include "dss/mesh/mesh.h"

namespace dss {

int innerBalls(const AnyShape& shape, const Eigen::Vector3d& box_c, const Eigen::Vector3d& box_h,
               Eigen::Vector4d* out, int max_out) {
  std::vector<Eigen::Vector4d> planes;  // n, d with n.x <= d inside
  if (const auto* hull = std::get_if<ConvexHull>(&shape)) {
    const mesh::TriangleMesh m = mesh::tessellate(shape);
    if (m.triangles.empty()) return 0;  // flat or degenerate: no interior
    const Eigen::Vector3d centroid = hull->center();
    for (const auto& t : m.triangles) {
      const Eigen::Vector3d& a = m.vertices[t[0]];
      Eigen::Vector3d n = (m.vertices[t[1]] - a).cross(m.vertices[t[2]] - a);
      const double len = n.norm();
      if (!(len > 0.0)) continue;
      n /= len;
      if (n.dot(centroid - a) > 0.0) n = -n;
      planes.emplace_back(n.x(), n.y(), n.z(), n.dot(a));
    }
  }
  auto radius = [&](const Eigen::Vector3d& c) -> double {
    if (const auto* s = std::get_if<Sphere>(&shape)) return s->radius - c.norm();
    if (const auto* b = std::get_if<Box>(&shape)) return (b->half - c.cwiseAbs()).minCoeff();
    if (const auto* y = std::get_if<Cylinder>(&shape))
      return std::min(y->radius - c.head<2>().norm(), y->half_length - std::abs(c.z()));
    if (const auto* k = std::get_if<Capsule>(&shape))
      return k->radius -
             Eigen::Vector3d(c.x(), c.y(), std::max(0.0, std::abs(c.z()) - k->half_length)).norm();
    if (const auto* e = std::get_if<Ellipsoid>(&shape)) return e->radii.minCoeff() - c.norm();
    if (std::holds_alternative<ConvexHull>(shape)) {
      double r = std::numeric_limits<double>::infinity();
      for (const auto& p : planes) r = std::min(r, p.w() - p.head<3>().dot(c));
      return r;
    }
    return -1.0;  // cone: no inner balls
  };
  const double size = shapeMagnitude(shape) + box_c.norm();
  const double shrink = 1e-7 * size + 1e-12;
  int axis = 0;
  box_h.maxCoeff(&axis);
  std::vector<Eigen::Vector4d> cand;
  for (int i = -8; i <= 8; ++i) {
    Eigen::Vector3d c = box_c;
    c[axis] += 0.1 * i * box_h[axis];
    const double r = radius(c) - shrink;
    if (r > 0.05 * box_h.maxCoeff()) cand.emplace_back(c.x(), c.y(), c.z(), r);
  }
  std::sort(cand.begin(), cand.end(),
            [](const Eigen::Vector4d& a, const Eigen::Vector4d& b) { return a.w() > b.w(); });
  // Directions to check each ball against the support function: a ball inside the shape has
  // h(u) >= u.c + r for every unit u.
  std::vector<Eigen::Vector3d> dirs;
  for (const auto& p : planes) dirs.push_back(p.head<3>());
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) dirs.push_back(Eigen::Vector3d(x, y, z).normalized());
  int n = 0;
  for (const auto& b : cand) {
    if (n == max_out) break;
    bool spread = true;
    for (int k = 0; k < n; ++k)
      if ((out[k].head<3>() - b.head<3>()).norm() < 0.5 * std::max(out[k].w(), b.w()))
        spread = false;
    if (!spread) continue;
    bool inside = true;
    for (const auto& u : dirs) {
      const double h = std::visit(
          [&](const auto& s) { return s.support(u, Eigen::Vector3d::Zero()).dot(u); }, shape);
      if (!(h >= u.dot(b.head<3>()) + b.w())) inside = false;
    }
    if (inside) out[n++] = b;
  }
  return n;
}

}  // namespace dss
