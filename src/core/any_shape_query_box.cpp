// intersect(AnyShape, ...) with a box first (see any_shape_query_impl.h).
#include "any_shape_query_impl.h"

namespace dss::detail {
DSS_INSTANTIATE_INTERSECT_FIRST(Box)
}  // namespace dss::detail
