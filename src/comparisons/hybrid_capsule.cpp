// The Hybrid on AnyShape with a capsule first (see comparisons_dispatch.h).
#include "comparisons_dispatch.h"

namespace dss::detail {
DSS_INSTANTIATE_COMPARISON(Comparison::kHybrid, Capsule)
}  // namespace dss::detail
