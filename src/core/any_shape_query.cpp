// The pairwise decision on AnyShape (see any_shape_query.h): dispatch on the first shape's type
// to its instantiation (any_shape_query_<type>.cpp).
#include "any_shape_query_impl.h"

namespace dss {
namespace detail {
// Instantiated in their own files: not here.
extern DSS_INSTANTIATE_INTERSECT_FIRST(Sphere)
extern DSS_INSTANTIATE_INTERSECT_FIRST(Box)
extern DSS_INSTANTIATE_INTERSECT_FIRST(Capsule)
extern DSS_INSTANTIATE_INTERSECT_FIRST(Cylinder)
extern DSS_INSTANTIATE_INTERSECT_FIRST(Cone)
extern DSS_INSTANTIATE_INTERSECT_FIRST(Ellipsoid)
extern DSS_INSTANTIATE_INTERSECT_FIRST(ConvexHull)
}  // namespace detail

Result intersect(const AnyShape& a, const Eigen::Isometry3d& X_WA, const AnyShape& b,
                 const Eigen::Isometry3d& X_WB, const Options& opt, double padding, Algorithm algo) {
  return std::visit(
      [&](const auto& sa) { return detail::intersectFirst(sa, X_WA, b, X_WB, opt, padding, algo); }, a);
}

}  // namespace dss
