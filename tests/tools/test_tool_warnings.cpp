// dss_check and dss_plan show every warning the readers stored: the robot's (a <mimic> tag on
// a fixed joint), the SRDF's (a group_state joint without a value), the scene's (link_padding
// that is not modelled) and the request's (path constraints, which are not enforced). They were
// stored and then dropped before reaching the user.
#include <sys/wait.h>
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/temp_files.h"

namespace fs = std::filesystem;

namespace {

fs::path scratch() { return dss_test::scratchDir("tool_warnings"); }

std::string write(const std::string& name, const std::string& text) {
  const fs::path p = scratch() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

std::string quote(const std::string& s) { return "'" + s + "'"; }

struct Run {
  int exit_code = -1;
  std::string err;
  std::vector<std::string> errLines() const {
    std::vector<std::string> lines;
    std::istringstream in(err);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
  }
};

Run run(const std::string& tool, const std::vector<std::string>& args) {
  std::string cmd = "timeout 120 " + quote(std::string(DSS_BINARY_DIR) + tool);
  for (const auto& a : args) cmd += " " + quote(a);
  const std::string err = (scratch() / "err.txt").string();
  cmd += " < /dev/null > /dev/null 2> " + quote(err);
  const int status = std::system(cmd.c_str());
  Run r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err);
  std::ostringstream s;
  s << in.rdbuf();
  r.err = s.str();
  return r;
}

// A stderr line that starts with `prefix` and contains `part`.
bool hasLine(const Run& r, const std::string& prefix, const std::string& part) {
  for (const auto& l : r.errLines())
    if (l.rfind(prefix, 0) == 0 && l.find(part) != std::string::npos) return true;
  return false;
}

// base --j1 (revolute z)--> l1 --jf (fixed, with a mimic tag)--> l2
const char* const kUrdf = R"(<robot name="warned">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="l1"><collision><origin xyz="0 0 0.5"/><geometry><box size="0.1 0.1 0.6"/></geometry></collision></link>
  <link name="l2"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="jf" type="fixed"><parent link="l1"/><child link="l2"/><mimic joint="j1"/></joint>
</robot>
)";

const char* const kSrdf = R"(<robot name="warned">
  <group name="arm"><joint name="j1"/></group>
  <group_state name="home" group="arm"><joint name="j1"/></group_state>
  <disable_collisions link1="base" link2="l1" reason="Adjacent"/>
</robot>
)";

const char* const kScene = R"(name: far
link_padding: [{link_name: l1, padding: 0.1}]
world:
  collision_objects:
    - id: box
      primitives: [{type: box, dimensions: [0.1, 0.1, 0.1]}]
      primitive_poses: [{position: [5, 0, 0], orientation: [0, 0, 0, 1]}]
)";

const char* const kRequest = R"(group_name: arm
start_state:
  joint_state: {name: [j1], position: [0]}
goal_constraints:
  - joint_constraints: [{joint_name: j1, position: 0.5}]
path_constraints:
  joint_constraints: [{joint_name: j1, position: 0, tolerance_above: 1, tolerance_below: 1}]
)";

const std::string kRobotWarning = "joint 'jf' is fixed; its <mimic> tag is ignored";
const std::string kSrdfWarning = "group_state 'home' joint 'j1' has no value";
const std::string kSceneWarning = "link_padding/link_scale ignored";
const std::string kRequestWarning = "path_constraints not enforced (ignored)";

}  // namespace

BOOST_AUTO_TEST_SUITE(tool_warnings)

BOOST_AUTO_TEST_CASE(dss_check_prints_robot_srdf_and_scene_warnings) {
  const std::string urdf = write("warned.urdf", kUrdf), srdf = write("warned.srdf", kSrdf),
                    scene = write("scene.yaml", kScene);
  const Run r =
      run("/tools/dss_check", {"--robot", urdf, "--srdf", srdf, "--scene", scene, "--random", "3"});
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(hasLine(r, "dss_check: warning: " + urdf + ":", kRobotWarning), r.err);
  BOOST_TEST(hasLine(r, "dss_check: warning: " + srdf + ":3: ", kSrdfWarning), r.err);
  BOOST_TEST(hasLine(r, "dss_check: warning: " + scene + ": ", kSceneWarning), r.err);
}

BOOST_AUTO_TEST_CASE(dss_plan_prints_robot_srdf_scene_and_request_warnings) {
  const std::string urdf = write("warned.urdf", kUrdf), srdf = write("warned.srdf", kSrdf),
                    scene = write("scene.yaml", kScene), request = write("request.yaml", kRequest);
  const Run r = run("/planners_demo/dss_plan", {"--robot", urdf, "--srdf", srdf, "--scene", scene,
                                                "--request", request, "--time", "5"});
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(hasLine(r, "dss_plan: warning: " + urdf + ":", kRobotWarning), r.err);
  BOOST_TEST(hasLine(r, "dss_plan: warning: " + srdf + ":3: ", kSrdfWarning), r.err);
  BOOST_TEST(hasLine(r, "dss_plan: request: warning: " + scene + ": ", kSceneWarning), r.err);
  BOOST_TEST(hasLine(r, "dss_plan: request: warning: " + request + ":7: ", kRequestWarning), r.err);
}

BOOST_AUTO_TEST_SUITE_END()
