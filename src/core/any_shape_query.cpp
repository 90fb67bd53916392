// The decisions on AnyShape (any_shape_query.h, any_shape_sweep.h): dispatch on the first
// shape's type to its instantiations (any_shape_<type>.cpp).
#include "dss/core/any_shape_query.h"

#include "any_shape_dispatch.h"
#include "dss/core/any_shape_sweep.h"

namespace dss {
namespace detail {
// Instantiated in their own files: not here.
DSS_ANY_SHAPE_INSTANCES(extern, Sphere)
DSS_ANY_SHAPE_INSTANCES(extern, Box)
DSS_ANY_SHAPE_INSTANCES(extern, Capsule)
DSS_ANY_SHAPE_INSTANCES(extern, Cylinder)
DSS_ANY_SHAPE_INSTANCES(extern, Cone)
DSS_ANY_SHAPE_INSTANCES(extern, Ellipsoid)
DSS_ANY_SHAPE_INSTANCES(extern, ConvexHull)

namespace {
bool isIdentity(const Eigen::Isometry3d& X) { return X.matrix() == Eigen::Matrix4d::Identity(); }
}  // namespace
}  // namespace detail

Result intersect(const AnyShape& a, const Eigen::Isometry3d& X_WA, const AnyShape& b,
                 const Eigen::Isometry3d& X_WB, const Options& opt, double padding) {
  const auto* ha = std::get_if<ConvexHull>(&a);
  const auto* hb = std::get_if<ConvexHull>(&b);
  if (ha && hb && !(padding > 0.0) && detail::isIdentity(X_WA) && detail::isIdentity(X_WB))
    return intersect(*ha, *hb, opt);  // world vertices: exact in Mode::kExact
  return std::visit(
      [&](const auto& sa) { return detail::decidePosed(sa, X_WA, b, X_WB, opt, padding); }, a);
}

Result intersectSwept(const AnyShape& a, const Eigen::Isometry3d& X_WA0,
                      const Eigen::Isometry3d& X_WA1, double padding, const AnyShape& b,
                      const Eigen::Isometry3d& X_WB, const Options& opt) {
  return std::visit(
      [&](const auto& sa) {
        return detail::decideSwept(sa, X_WA0, X_WA1, padding, b, X_WB, nullptr, opt);
      },
      a);
}

Result intersectSwept(const AnyShape& a, const Eigen::Isometry3d& X_WA0,
                      const Eigen::Isometry3d& X_WA1, double padding, const AnyShape& b,
                      const Eigen::Isometry3d& X_WB0, const Eigen::Isometry3d& X_WB1,
                      const Options& opt) {
  return std::visit(
      [&](const auto& sa) {
        return detail::decideSwept(sa, X_WA0, X_WA1, padding, b, X_WB0, &X_WB1, opt);
      },
      a);
}

}  // namespace dss
