// The pairwise decision on AnyShape (see any_shape_query.h): dispatch on the first shape's type
// to its instantiation (any_shape_query_<type>.cpp).
#include "any_shape_query_impl.h"

namespace dss {
namespace detail {
extern template Result intersectFirst<Sphere>(const Sphere&, const Eigen::Isometry3d&, const AnyShape&, const Eigen::Isometry3d&, const Options&, double, Algorithm);
extern template Result intersectFirst<Box>(const Box&, const Eigen::Isometry3d&, const AnyShape&, const Eigen::Isometry3d&, const Options&, double, Algorithm);
extern template Result intersectFirst<Capsule>(const Capsule&, const Eigen::Isometry3d&, const AnyShape&, const Eigen::Isometry3d&, const Options&, double, Algorithm);
extern template Result intersectFirst<Cylinder>(const Cylinder&, const Eigen::Isometry3d&, const AnyShape&, const Eigen::Isometry3d&, const Options&, double, Algorithm);
extern template Result intersectFirst<Cone>(const Cone&, const Eigen::Isometry3d&, const AnyShape&, const Eigen::Isometry3d&, const Options&, double, Algorithm);
extern template Result intersectFirst<Ellipsoid>(const Ellipsoid&, const Eigen::Isometry3d&, const AnyShape&, const Eigen::Isometry3d&, const Options&, double, Algorithm);
extern template Result intersectFirst<ConvexHull>(const ConvexHull&, const Eigen::Isometry3d&, const AnyShape&, const Eigen::Isometry3d&, const Options&, double, Algorithm);
}  // namespace detail

Result intersect(const AnyShape& a, const Eigen::Isometry3d& X_WA, const AnyShape& b,
                 const Eigen::Isometry3d& X_WB, const Options& opt, double padding, Algorithm algo) {
  return std::visit(
      [&](const auto& sa) { return detail::intersectFirst(sa, X_WA, b, X_WB, opt, padding, algo); }, a);
}

}  // namespace dss
