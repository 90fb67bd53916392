// Bounding spheres and local boxes of collision elements (see element_bounds.h).
#include "dss/checker/element_bounds.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dss {

void elementSphere(const AnyShape& shape, const Eigen::Isometry3d& X_LS, Eigen::Vector3d* center_L,
                   double* radius) {
  if (const auto* hull = std::get_if<ConvexHull>(&shape)) {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (const auto& p : hull->points()) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const Eigen::Vector3d m = 0.5 * (lo + hi);
    double rr = 0.0;
    for (const auto& p : hull->points()) rr = std::max(rr, (p - m).norm());
    *center_L = X_LS * m;
    *radius = rr * (1.0 + 1e-12) + 1e-12;
    return;
  }
  // Primitives about their origin: the farthest point of a box is a corner, of a cylinder or
  // a cone a point of a rim (the cone's apex is nearer), of an ellipsoid the end of its longest
  // axis (shapeMagnitude is a cheaper, looser bound for boxes, cylinders and cones).
  double r = shapeMagnitude(shape);
  if (const auto* b = std::get_if<Box>(&shape))
    r = b->half.norm();
  else if (const auto* y = std::get_if<Cylinder>(&shape))
    r = std::hypot(y->radius, y->half_length);
  else if (const auto* n = std::get_if<Cone>(&shape))
    r = std::hypot(n->radius, n->half_length);
  *center_L = X_LS.translation();
  *radius = r * (1.0 + 1e-12) + 1e-12;
}

void localBox(const AnyShape& shape, Eigen::Vector3d* c, Eigen::Vector3d* h) {
  *c = Eigen::Vector3d::Zero();
  if (const auto* s = std::get_if<Sphere>(&shape)) {
    *h = Eigen::Vector3d::Constant(s->radius);
  } else if (const auto* b = std::get_if<Box>(&shape)) {
    *h = b->half;
  } else if (const auto* k = std::get_if<Capsule>(&shape)) {
    *h = Eigen::Vector3d(k->radius, k->radius, k->half_length + k->radius);
  } else if (const auto* y = std::get_if<Cylinder>(&shape)) {
    *h = Eigen::Vector3d(y->radius, y->radius, y->half_length);
  } else if (const auto* n = std::get_if<Cone>(&shape)) {
    *h = Eigen::Vector3d(n->radius, n->radius, n->half_length);
  } else if (const auto* e = std::get_if<Ellipsoid>(&shape)) {
    *h = e->radii;
  } else {
    const auto& hull = std::get<ConvexHull>(shape);
    Eigen::Vector3d lo = hull.points()[0], hi = lo;
    for (const auto& p : hull.points()) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    *c = 0.5 * (lo + hi);
    *h = 0.5 * (hi - lo);
  }
  *h += Eigen::Vector3d::Constant(1e-9 * (1.0 + h->maxCoeff() + c->cwiseAbs().maxCoeff()));
}

}  // namespace dss
