// Decision GJK on AnyShape with a cylinder first (see comparisons_dispatch.h).
#include "comparisons_dispatch.h"

namespace dss::detail {
DSS_INSTANTIATE_COMPARISON(Comparison::kGjk, Cylinder)
}  // namespace dss::detail
