// intersect(AnyShape, ...) with a capsule first (see any_shape_query_impl.h).
#include "any_shape_query_impl.h"

namespace dss::detail {
DSS_INSTANTIATE_INTERSECT_FIRST(Capsule)
}  // namespace dss::detail
