// intersect(AnyShape, ...) with a ellipsoid first (see any_shape_query_impl.h).
#include "any_shape_query_impl.h"

namespace dss::detail {
DSS_INSTANTIATE_INTERSECT_FIRST(Ellipsoid)
}  // namespace dss::detail
