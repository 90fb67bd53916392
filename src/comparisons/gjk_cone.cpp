// Decision GJK on AnyShape with a cone first (see comparisons_dispatch.h).
#include "comparisons_dispatch.h"

namespace dss::detail {
DSS_INSTANTIATE_COMPARISON(Comparison::kGjk, Cone)
}  // namespace dss::detail
