// The robot input budgets against real files: every URDF and SRDF in the shared robots (their
// package:// originals too) and in our own robots loads with the limits set to the largest
// value any of them needs, and lowering any one of those limits by one refuses at least one
// file with a message naming that limit. This pins the "largest seen" values documented in
// dss/robot/input_limits.h, and shows the defaults are far above them.
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "dss/robot/input_limits.h"
#include "dss/robot/srdf.h"
#include "dss/robot/urdf_loader.h"
#include "support/shared_data.h"

namespace fs = std::filesystem;

namespace {

const fs::path kShared = fs::path(DSS_SHARED_DIR) / "robots";
const fs::path kOwn = fs::path(DSS_SOURCE_DIR) / "robots";

dss::RobotInputLimits largestSeen() {
  dss::RobotInputLimits l;
  l.max_xml_depth = 5;           // robot/link/collision/geometry/mesh in every URDF
  l.max_group_depth = 2;         // panda "hand" and dss_mobile_base groups of subgroups
  l.max_mesh_vertices = 130419;  // ur5_robotiq85/meshes/robotiq_fts300.stl
  return l;
}

std::vector<fs::path> files(const std::string& extension) {
  std::vector<fs::path> out;
  for (const fs::path& root : {kShared, kOwn})
    for (const auto& e : fs::recursive_directory_iterator(root))
      if (e.is_regular_file() && e.path().extension() == extension) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

dss::LoadOptions options(const dss::RobotInputLimits& limits) {
  dss::LoadOptions o;
  // Package roots of the *.orig.urdf files, from the shared MANIFEST.
  o.mesh_paths.package_dirs["robowflex_resources"] = kShared.string();
  o.mesh_paths.package_dirs["example-robot-data"] = kShared.parent_path().string();
  o.mesh_paths.package_dirs["drake_models"] = kShared.string();
  o.mesh_paths.use_ros_package_path = false;
  o.mesh_paths.use_ament_prefix_path = false;
  o.limits = limits;
  return o;
}

// The first file refused under `limits` (SRDF groups expanded against their robot), with its
// message; empty when all load.
std::string firstRefusal(const dss::RobotInputLimits& limits) {
  try {
    for (const auto& f : files(".urdf")) dss::loadUrdf(f.string(), options(limits));
    for (const auto& f : files(".srdf")) {
      const dss::Srdf srdf = dss::loadSrdf(f.string(), limits);
      // Its robot: the URDF next to it with the shortest name that starts with the SRDF's
      // (panda.srdf: panda.urdf, not panda_collision.urdf; ur5.srdf: ur5_robot.urdf).
      fs::path urdf;
      for (const auto& u : files(".urdf"))
        if (u.parent_path() == f.parent_path() && u.stem().extension().empty() &&
            u.stem().string().rfind(f.stem().string(), 0) == 0 &&
            (urdf.empty() || u.stem().string().size() < urdf.stem().string().size()))
          urdf = u;
      const dss::RobotModel model = dss::loadUrdf(urdf.string(), options(limits));
      for (const auto& g : srdf.groups) dss::groupActiveJoints(model, srdf, g.name);
    }
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return std::string();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(robot_input_limits)

BOOST_AUTO_TEST_CASE(every_real_file_fits_the_largest_seen_values, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(fs::is_directory(kShared));
  BOOST_TEST(files(".urdf").size() == 20u + 5u);  // shared robots + ours
  BOOST_TEST(files(".srdf").size() == 5u + 4u);
  BOOST_TEST(firstRefusal(largestSeen()) == "");
}

BOOST_AUTO_TEST_CASE(each_largest_seen_value_is_needed, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(fs::is_directory(kShared));
  using Field = std::size_t dss::RobotInputLimits::*;
  const std::vector<std::pair<Field, std::string>> fields = {
      {&dss::RobotInputLimits::max_xml_depth, "max_xml_depth"},
      {&dss::RobotInputLimits::max_group_depth, "max_group_depth"},
      {&dss::RobotInputLimits::max_mesh_vertices, "max_mesh_vertices"}};
  for (const auto& [field, name] : fields) {
    BOOST_TEST_CONTEXT(name) {
      dss::RobotInputLimits lower = largestSeen();
      lower.*field -= 1;
      const std::string m = firstRefusal(lower);
      BOOST_TEST(m.find("RobotInputLimits::" + name + "; raise it with ") != std::string::npos, m);
    }
  }
}

BOOST_AUTO_TEST_CASE(defaults_are_far_above_the_largest_seen_values) {
  const dss::RobotInputLimits d, seen = largestSeen();
  BOOST_TEST(d.max_xml_depth >= 50 * seen.max_xml_depth);
  BOOST_TEST(d.max_group_depth >= 30 * seen.max_group_depth);
  BOOST_TEST(d.max_mesh_vertices >= 30 * seen.max_mesh_vertices);
}

BOOST_AUTO_TEST_SUITE_END()
