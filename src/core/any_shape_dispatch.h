// The instantiations behind any_shape_query.h and any_shape_sweep.h, split by the type of the
// first shape so that they compile in parallel: any_shape_<type>.cpp instantiates
// decidePosed and decideSwept for one type, against every type of second shape.
#pragma once

#include <Eigen/Geometry>

#include "dss/core/any_shape.h"
#include "dss/core/dss.h"
#include "dss/core/padded.h"
#include "dss/core/posed.h"
#include "dss/core/ref.h"
#include "dss/core/swept.h"

namespace dss::detail {

template <class S>
Posed<Ref<S>> posedRef(const S& s, const Eigen::Isometry3d& X) {
  return Posed<Ref<S>>(Ref<S>{s}, X.linear(), X.translation());
}

template <class S>
SweptHull<Ref<S>> sweptRef(const S& s, const Eigen::Isometry3d& X0, const Eigen::Isometry3d& X1) {
  SweptHull<Ref<S>> h{Ref<S>{s}};
  h.R0 = X0.linear();
  h.R1 = X1.linear();
  h.p0 = X0.translation();
  h.p1 = X1.translation();
  return h;
}

template <class SA>
Result decidePosed(const SA& sa, const Eigen::Isometry3d& X_WA, const AnyShape& b,
                   const Eigen::Isometry3d& X_WB, const Options& opt, double padding) {
  return std::visit(
      [&](const auto& sb) {
        const auto pa = posedRef(sa, X_WA);
        const auto pb = posedRef(sb, X_WB);
        if (padding > 0.0) return intersect(padded(pa, padding), pb, opt);
        return intersect(pa, pb, opt);
      },
      b);
}

template <class SA>
Result decideSwept(const SA& sa, const Eigen::Isometry3d& X_WA0, const Eigen::Isometry3d& X_WA1,
                   double padding, const AnyShape& b, const Eigen::Isometry3d& X_WB0,
                   const Eigen::Isometry3d* X_WB1, const Options& opt) {
  return std::visit(
      [&](const auto& sb) {
        const auto a = padded(sweptRef(sa, X_WA0, X_WA1), padding);
        if (X_WB1) return intersect(a, sweptRef(sb, X_WB0, *X_WB1), opt);
        return intersect(a, posedRef(sb, X_WB0), opt);
      },
      b);
}

// PREFIX: nothing to instantiate, `extern` to declare an instantiation made elsewhere.
#define DSS_ANY_SHAPE_INSTANCES(PREFIX, SA)                                                    \
  PREFIX template Result decidePosed<SA>(const SA&, const Eigen::Isometry3d&, const AnyShape&, \
                                         const Eigen::Isometry3d&, const Options&, double);    \
  PREFIX template Result decideSwept<SA>(                                                      \
      const SA&, const Eigen::Isometry3d&, const Eigen::Isometry3d&, double, const AnyShape&,  \
      const Eigen::Isometry3d&, const Eigen::Isometry3d*, const Options&);

}  // namespace dss::detail
