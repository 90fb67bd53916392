// Tests on the public robots and scenes of the shared folder (DSS_SHARED_DIR: the Panda, the
// UR5, MotionBenchMaker scenes, certified pair samples). Such a test case carries the decorator
// DSS_NEEDS_SHARED: CTest runs the cases of an area that carry it as their own entry,
// <area>_shared, which reports itself skipped when the folder is absent (tests/CMakeLists.txt).
// Inside, a missing file is a failure, never a silent pass.
#pragma once

#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <string>

#define DSS_NEEDS_SHARED *boost::unit_test::label("shared")

namespace dss_test {

/// DSS_SHARED_DIR/relative, required to exist.
inline std::string sharedPath(const std::string& relative) {
  const std::string p = std::string(DSS_SHARED_DIR) + "/" + relative;
  BOOST_REQUIRE_MESSAGE(std::filesystem::exists(p), p << " not found in the shared folder");
  return p;
}

}  // namespace dss_test
