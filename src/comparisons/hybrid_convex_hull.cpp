// The Hybrid on AnyShape with a convex hull first (see comparisons_dispatch.h).
#include "comparisons_dispatch.h"

namespace dss::detail {
DSS_INSTANTIATE_COMPARISON(Comparison::kHybrid, ConvexHull)
}  // namespace dss::detail
