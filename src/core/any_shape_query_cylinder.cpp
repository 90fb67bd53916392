// intersect(AnyShape, ...) with a cylinder first (see any_shape_query_impl.h).
#include "any_shape_query_impl.h"

namespace dss::detail {
DSS_INSTANTIATE_INTERSECT_FIRST(Cylinder)
}  // namespace dss::detail
