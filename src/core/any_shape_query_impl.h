// The pairwise decision on AnyShape, split by the type of the first shape so that the seven
// instantiations (each for every second shape type, mode and algorithm) compile in parallel:
// any_shape_query_<type>.cpp instantiates intersectFirst for one type.
#pragma once

#include "dss/core/any_shape_query.h"

namespace dss::detail {

template <class SA>
Result intersectFirst(const SA& sa, const Eigen::Isometry3d& X_WA, const AnyShape& b,
                      const Eigen::Isometry3d& X_WB, const Options& opt, double padding, Algorithm algo) {
  return std::visit(
      [&](const auto& sb) {
        using SB = std::decay_t<decltype(sb)>;
        const Posed<Ref<SA>> pa(Ref<SA>{sa}, X_WA.linear(), X_WA.translation());
        const Posed<Ref<SB>> pb(Ref<SB>{sb}, X_WB.linear(), X_WB.translation());
        if (padding > 0.0) return decide(padded(pa, padding), pb, opt, algo);
        return decide(pa, pb, opt, algo);
      },
      b);
}

#define DSS_INSTANTIATE_INTERSECT_FIRST(SA)                                                       \
  template Result intersectFirst<SA>(const SA&, const Eigen::Isometry3d&, const AnyShape&,       \
                                     const Eigen::Isometry3d&, const Options&, double, Algorithm);

}  // namespace dss::detail
