// The decisions on AnyShape with a cone first (see any_shape_dispatch.h).
#include "any_shape_dispatch.h"

namespace dss::detail {
DSS_ANY_SHAPE_INSTANCES(, Cone)
}  // namespace dss::detail
