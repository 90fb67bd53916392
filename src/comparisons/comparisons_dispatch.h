// The instantiations behind any_shape_comparisons.h, split by algorithm and by the type of the
// first shape so that they compile in parallel (comparisons_<algorithm>_<type>.cpp).
#pragma once

#include <Eigen/Geometry>

#include "dss/core/any_shape.h"
#include "dss/core/gjk.h"
#include "dss/core/padded.h"
#include "dss/core/posed.h"
#include "dss/core/ref.h"

namespace dss::detail {

enum class Comparison { kGjk, kHybrid };

template <Comparison C, class A, class B>
Result decideComparison(const A& a, const B& b, const Options& opt) {
  if constexpr (C == Comparison::kGjk) return intersectGjk(a, b, opt);
  return intersectHybrid(a, b, opt);
}

template <Comparison C, class SA>
Result decideComparisonPosed(const SA& sa, const Eigen::Isometry3d& X_WA, const AnyShape& b,
                             const Eigen::Isometry3d& X_WB, const Options& opt, double padding) {
  return std::visit(
      [&](const auto& sb) {
        using SB = std::decay_t<decltype(sb)>;
        const Posed<Ref<SA>> pa(Ref<SA>{sa}, X_WA.linear(), X_WA.translation());
        const Posed<Ref<SB>> pb(Ref<SB>{sb}, X_WB.linear(), X_WB.translation());
        if (padding > 0.0) return decideComparison<C>(padded(pa, padding), pb, opt);
        return decideComparison<C>(pa, pb, opt);
      },
      b);
}

#define DSS_INSTANTIATE_COMPARISON(C, SA)                                                 \
  template Result decideComparisonPosed<C, SA>(const SA&, const Eigen::Isometry3d&,       \
                                               const AnyShape&, const Eigen::Isometry3d&, \
                                               const Options&, double);

}  // namespace dss::detail
