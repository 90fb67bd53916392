// intersect(AnyShape, ...) with a sphere first (see any_shape_query_impl.h).
#include "any_shape_query_impl.h"

namespace dss::detail {
DSS_INSTANTIATE_INTERSECT_FIRST(Sphere)
}  // namespace dss::detail
