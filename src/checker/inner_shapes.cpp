// Inner balls and the inner box of an element's shape (see inner_shapes.h).
#include "dss/checker/inner_shapes.h"

#include <algorithm>
#include <limits>
#include <vector>

#include "dss/checker/ball_stage.h"
#include "dss/mesh/mesh.h"

namespace dss {

namespace {

// A hull's facet planes (n, d with n.x <= d inside, n unit); false for a flat or degenerate
// hull (no interior).
bool facetPlanes(const AnyShape& shape, std::vector<Eigen::Vector4d>* planes,
                 const mesh::TriangleMesh* tessellated = nullptr) {
  const auto& hull = std::get<ConvexHull>(shape);
  const mesh::TriangleMesh m = tessellated ? *tessellated : mesh::tessellate(shape);
  if (m.triangles.empty()) return false;
  const Eigen::Vector3d centroid = hull.center();
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d& a = m.vertices[t[0]];
    Eigen::Vector3d n = (m.vertices[t[1]] - a).cross(m.vertices[t[2]] - a);
    const double len = n.norm();
    if (!(len > 0.0)) continue;
    n /= len;
    if (n.dot(centroid - a) > 0.0) n = -n;
    planes->emplace_back(n.x(), n.y(), n.z(), n.dot(a));
  }
  return !planes->empty();
}

// Unit directions to check a shape inside `shape` against its support function: the facet
// normals and the 26 directions of the cube's faces, edges and corners.
std::vector<Eigen::Vector3d> checkDirections(const std::vector<Eigen::Vector4d>& planes) {
  std::vector<Eigen::Vector3d> dirs;
  for (const auto& p : planes) dirs.push_back(p.head<3>());
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) dirs.push_back(Eigen::Vector3d(x, y, z).normalized());
  return dirs;
}

double supportValue(const AnyShape& shape, const Eigen::Vector3d& u) {
  return std::visit([&](const auto& s) { return s.support(u, Eigen::Vector3d::Zero()).dot(u); },
                    shape);
}

// The distance from c to the boundary of `shape` (negative outside; -1 for cones, which get
// no inner balls): minus the signed distance (ball_stage.h) for a box, sphere, cylinder or
// capsule, from its facet planes for a hull.
double boundaryDistance(const AnyShape& shape, const std::vector<Eigen::Vector4d>& planes,
                        const Eigen::Vector3d& c) {
  if (std::holds_alternative<Sphere>(shape) || std::holds_alternative<Box>(shape) ||
      std::holds_alternative<Cylinder>(shape) || std::holds_alternative<Capsule>(shape)) {
    double size = 0.0;
    return -pointDistance(shape, c, &size);
  }
  if (const auto* e = std::get_if<Ellipsoid>(&shape)) return e->radii.minCoeff() - c.norm();
  if (std::holds_alternative<ConvexHull>(shape)) {
    double r = std::numeric_limits<double>::infinity();
    for (const auto& p : planes) r = std::min(r, p.w() - p.head<3>().dot(c));
    return r;
  }
  return -1.0;
}

// Whether the ball (c, r) lies inside `shape`: h(u) >= u.c + r for every checked direction u.
bool ballInside(const AnyShape& shape, const std::vector<Eigen::Vector3d>& dirs,
                const Eigen::Vector3d& c, double r) {
  for (const auto& u : dirs)
    if (!(supportValue(shape, u) >= u.dot(c) + r)) return false;
  return true;
}

}  // namespace

void innerRadii(const AnyShape& shape, const Eigen::Vector3d* c, int n, double* r,
                const mesh::TriangleMesh* tessellated) {
  std::vector<Eigen::Vector4d> planes;
  const bool hull = std::holds_alternative<ConvexHull>(shape);
  const bool solid = !hull || facetPlanes(shape, &planes, tessellated);
  const std::vector<Eigen::Vector3d> dirs = checkDirections(planes);
  for (int k = 0; k < n; ++k) {
    const double shrink = 1e-7 * (shapeMagnitude(shape) + c[k].norm()) + 1e-12;
    const double rk = solid ? boundaryDistance(shape, planes, c[k]) - shrink : -1.0;
    r[k] = rk > 0.0 && ballInside(shape, dirs, c[k], rk) ? rk : 0.0;
  }
}

int innerBalls(const AnyShape& shape, const Eigen::Vector3d& box_c, const Eigen::Vector3d& box_h,
               Eigen::Vector4d* out, int max_out) {
  std::vector<Eigen::Vector4d> planes;
  if (std::holds_alternative<ConvexHull>(shape) && !facetPlanes(shape, &planes)) return 0;
  auto radius = [&](const Eigen::Vector3d& c) { return boundaryDistance(shape, planes, c); };
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
  const std::vector<Eigen::Vector3d> dirs = checkDirections(planes);
  int n = 0;
  for (const auto& b : cand) {
    if (n == max_out) break;
    bool spread = true;
    for (int k = 0; k < n; ++k)
      if ((out[k].head<3>() - b.head<3>()).norm() < 0.5 * std::max(out[k].w(), b.w()))
        spread = false;
    if (!spread) continue;
    if (ballInside(shape, dirs, b.head<3>(), b.w())) out[n++] = b;
  }
  return n;
}

bool innerBox(const AnyShape& shape, const Eigen::Vector3d& box_c, const Eigen::Vector3d& box_h,
              Eigen::Vector3d* c, Eigen::Vector3d* h) {
  const double size = shapeMagnitude(shape) + box_c.norm();
  const double shrink = 1e-7 * size + 1e-300;
  constexpr double kInvSqrt2 = 0.70710678118654752, kInvSqrt3 = 0.57735026918962573;
  std::vector<Eigen::Vector4d> planes;
  *c = Eigen::Vector3d::Zero();
  if (const auto* b = std::get_if<Box>(&shape)) {
    *h = b->half;
  } else if (const auto* y = std::get_if<Cylinder>(&shape)) {
    *h = Eigen::Vector3d(kInvSqrt2 * y->radius, kInvSqrt2 * y->radius, y->half_length);
  } else if (const auto* k = std::get_if<Capsule>(&shape)) {
    // A square section at the radius, or one at radius/sqrt(3) reaching into the caps: the
    // larger box.
    const Eigen::Vector3d flat(kInvSqrt2 * k->radius, kInvSqrt2 * k->radius, k->half_length);
    const Eigen::Vector3d deep(kInvSqrt3 * k->radius, kInvSqrt3 * k->radius,
                               k->half_length + kInvSqrt3 * k->radius);
    *h = flat.prod() >= deep.prod() ? flat : deep;
  } else if (const auto* e = std::get_if<Ellipsoid>(&shape)) {
    *h = kInvSqrt3 * e->radii;
  } else if (std::holds_alternative<ConvexHull>(shape)) {
    if (!facetPlanes(shape, &planes)) return false;
    // Corners inside every plane, with the shrink as margin. The corners of box_c +- s.box_h
    // are linear in s, so the scales that keep them inside form a convex set containing 0:
    // bisection along one scale at a time stays inside it.
    auto fits = [&](const Eigen::Vector3d& s) {
      for (const auto& p : planes) {
        const double reach =
            p.head<3>().dot(box_c) + p.head<3>().cwiseAbs().dot(s.cwiseProduct(box_h));
        if (!(reach <= p.w() - shrink)) return false;
      }
      return true;
    };
    auto grow = [&](Eigen::Vector3d s, const Eigen::Vector3d& dir) {
      double lo = 0.0, hi = 1.0;  // s + lo*dir fits
      if (fits(s + dir)) return Eigen::Vector3d(s + dir);
      for (int it = 0; it < 40; ++it) {
        const double mid = 0.5 * (lo + hi);
        (fits(s + mid * dir) ? lo : hi) = mid;
      }
      return Eigen::Vector3d(s + lo * dir);
    };
    // The largest uniform scale, then each axis grown in turn (every order; the largest box).
    const Eigen::Vector3d uniform = grow(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
    Eigen::Vector3d best = uniform;
    int order[3] = {0, 1, 2};
    do {
      Eigen::Vector3d s = uniform;
      for (int a : order) s = grow(s, Eigen::Vector3d::Unit(a) * (1.0 - s[a]));
      if (s.prod() > best.prod()) best = s;
    } while (std::next_permutation(order, order + 3));
    *c = box_c;
    *h = best.cwiseProduct(box_h);
  } else {
    return false;  // spheres (their ball is better) and cones
  }
  *h = (h->array() - shrink).matrix();
  // A hull's box thinner than 5 % of its local box holds little of it (a flat hull); a
  // primitive's box is kept however thin (a box element's is the box itself).
  const double thinnest = std::holds_alternative<ConvexHull>(shape) ? 0.05 * box_h.maxCoeff() : 0.0;
  if (!(h->minCoeff() > thinnest)) return false;
  // Every corner inside the shape: h(u) >= u.c + |u|.h for every checked direction u.
  for (const auto& u : checkDirections(planes))
    if (!(supportValue(shape, u) >= u.dot(*c) + u.cwiseAbs().dot(*h))) return false;
  return true;
}

}  // namespace dss
