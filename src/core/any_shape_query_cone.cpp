// intersect(AnyShape, ...) with a cone first (see any_shape_query_impl.h).
#include "any_shape_query_impl.h"

namespace dss::detail {
DSS_INSTANTIATE_INTERSECT_FIRST(Cone)
}  // namespace dss::detail
