// Decision GJK on AnyShape with a ellipsoid first (see comparisons_dispatch.h).
#include "comparisons_dispatch.h"

namespace dss::detail {
DSS_INSTANTIATE_COMPARISON(Comparison::kGjk, Ellipsoid)
}  // namespace dss::detail
