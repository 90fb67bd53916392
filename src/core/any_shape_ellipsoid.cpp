// The decisions on AnyShape with a ellipsoid first (see any_shape_dispatch.h).
#include "any_shape_dispatch.h"

namespace dss::detail {
DSS_ANY_SHAPE_INSTANCES(, Ellipsoid)
}  // namespace dss::detail
