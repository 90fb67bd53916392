// The instruction sets this CPU runs (dss/core/simd_path.h), scalar first: tests run each.
#pragma once

#include <vector>

#include "dss/core/simd_path.h"

namespace dss_test {

inline std::vector<dss::SimdPath> availablePaths() {
  std::vector<dss::SimdPath> paths;
  for (auto p : {dss::SimdPath::kScalar, dss::SimdPath::kSse2, dss::SimdPath::kAvx2})
    if (dss::simdPathAvailable(p)) paths.push_back(p);
  return paths;
}

}  // namespace dss_test
