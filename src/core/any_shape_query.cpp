// The decisions on AnyShape (any_shape_query.h, any_shape_sweep.h): dispatch on the first
// shape's type to its instantiations (any_shape_<type>.cpp).
#include "dss/core/any_shape_query.h"

#include <cmath>
#include <type_traits>

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

// x * 0 is 0 for a finite x and NaN for a NaN or an infinity, so one sum of such products
// tells whether every number of a query is finite, at the cost of a few vector operations.
// The search itself meets most non-finite numbers, but not all: a ball ignores its rotation,
// a cylinder its radius along its axis, a zero iteration cap stops before the first support,
// and a NaN padding would read as none.
double nonFinite(const AnyShape& s) {
  return std::visit(
      [](const auto& x) -> double {
        using S = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<S, Sphere>) {
          return x.radius * 0.0;
        } else if constexpr (std::is_same_v<S, Box>) {
          return (x.half * 0.0).sum();
        } else if constexpr (std::is_same_v<S, Ellipsoid>) {
          return (x.radii * 0.0).sum();
        } else if constexpr (std::is_same_v<S, ConvexHull>) {
          return 0.0;  // its constructor refuses non-finite points
        } else {
          return x.radius * 0.0 + x.half_length * 0.0;
        }
      },
      s);
}
double nonFinite(const Eigen::Isometry3d& X) { return (X.matrix().topRows<3>() * 0.0).sum(); }
bool validInput(const AnyShape& a, const Eigen::Isometry3d& X_WA, const AnyShape& b,
                const Eigen::Isometry3d& X_WB, double padding) {
  return !std::isnan(nonFinite(a) + nonFinite(b) + nonFinite(X_WA) + nonFinite(X_WB) +
                     padding * 0.0);
}
Result invalidInput() {
  Result r;
  r.status = Status::kInvalidInput;
  return r;
}
}  // namespace
}  // namespace detail

Result intersect(const AnyShape& a, const Eigen::Isometry3d& X_WA, const AnyShape& b,
                 const Eigen::Isometry3d& X_WB, const Options& opt, double padding) {
  if (!detail::validInput(a, X_WA, b, X_WB, padding)) return detail::invalidInput();
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
  if (!detail::validInput(a, X_WA0, b, X_WB, padding) || std::isnan(detail::nonFinite(X_WA1)))
    return detail::invalidInput();
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
  if (!detail::validInput(a, X_WA0, b, X_WB0, padding) ||
      std::isnan(detail::nonFinite(X_WA1) + detail::nonFinite(X_WB1)))
    return detail::invalidInput();
  return std::visit(
      [&](const auto& sa) {
        return detail::decideSwept(sa, X_WA0, X_WA1, padding, b, X_WB0, &X_WB1, opt);
      },
      a);
}

}  // namespace dss
