// GJK and the Hybrid on AnyShape: dispatch on the first shape's type to its instantiations.
#include "dss/comparisons/any_shape_comparisons.h"

#include "comparisons_dispatch.h"

namespace dss {
namespace detail {
#define DSS_EXTERN_COMPARISONS(SA)                                                           \
  extern DSS_INSTANTIATE_COMPARISON(Comparison::kGjk, SA) extern DSS_INSTANTIATE_COMPARISON( \
      Comparison::kHybrid, SA)
DSS_EXTERN_COMPARISONS(Sphere)
DSS_EXTERN_COMPARISONS(Box)
DSS_EXTERN_COMPARISONS(Capsule)
DSS_EXTERN_COMPARISONS(Cylinder)
DSS_EXTERN_COMPARISONS(Cone)
DSS_EXTERN_COMPARISONS(Ellipsoid)
DSS_EXTERN_COMPARISONS(ConvexHull)

namespace {
bool isIdentity(const Eigen::Isometry3d& X) { return X.matrix() == Eigen::Matrix4d::Identity(); }

template <Comparison C>
Result decide(const AnyShape& a, const Eigen::Isometry3d& X_WA, const AnyShape& b,
              const Eigen::Isometry3d& X_WB, const Options& opt, double padding) {
  const auto* ha = std::get_if<ConvexHull>(&a);
  const auto* hb = std::get_if<ConvexHull>(&b);
  if (ha && hb && !(padding > 0.0) && isIdentity(X_WA) && isIdentity(X_WB))
    return decideComparison<C>(*ha, *hb, opt);
  return std::visit(
      [&](const auto& sa) { return decideComparisonPosed<C>(sa, X_WA, b, X_WB, opt, padding); }, a);
}
}  // namespace
}  // namespace detail

Result intersectGjk(const AnyShape& a, const Eigen::Isometry3d& X_WA, const AnyShape& b,
                    const Eigen::Isometry3d& X_WB, const Options& opt, double padding) {
  return detail::decide<detail::Comparison::kGjk>(a, X_WA, b, X_WB, opt, padding);
}

Result intersectHybrid(const AnyShape& a, const Eigen::Isometry3d& X_WA, const AnyShape& b,
                       const Eigen::Isometry3d& X_WB, const Options& opt, double padding) {
  return detail::decide<detail::Comparison::kHybrid>(a, X_WA, b, X_WB, opt, padding);
}

}  // namespace dss
