// Fuzz target: the robot-state CSV reader (dss::readJointStatesCsv), which takes a path: each
// input is written to a temporary file first. The robot is a small URDF of our own (below) with
// revolute, continuous, prismatic and fixed joints and a chain of two mimic joints, so that
// every kind of column is reachable. Any bytes must end in states or a std::exception naming
// the file; the states read must have one value per active joint and one line number each,
// and writing them (dss::writeJointStatesCsv) must read back into the same states, bit for bit
// (NaN as NaN).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include "dss/robot/joint_states_csv.h"
#include "dss/robot/urdf_loader.h"
#include "fuzz_support.h"

namespace {

const char* const kRobot = R"(<robot name="csv_fuzz">
  <link name="base"/> <link name="l1"/> <link name="l2"/> <link name="l3"/> <link name="l4"/>
  <link name="f1"/> <link name="f2"/> <link name="tool"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="j2" type="continuous"><parent link="l1"/><child link="l2"/><axis xyz="0 1 0"/></joint>
  <joint name="j3" type="prismatic"><parent link="l2"/><child link="l3"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.5" effort="1" velocity="1"/></joint>
  <joint name="fixed" type="fixed"><parent link="l3"/><child link="l4"/></joint>
  <joint name="finger1" type="prismatic"><parent link="l4"/><child link="f1"/>
    <axis xyz="0 1 0"/><limit lower="0" upper="0.04" effort="1" velocity="1"/></joint>
  <joint name="finger2" type="prismatic"><parent link="l4"/><child link="f2"/>
    <axis xyz="0 -1 0"/><limit lower="0" upper="0.04" effort="1" velocity="1"/>
    <mimic joint="finger1" multiplier="1" offset="0"/></joint>
  <joint name="finger3" type="revolute"><parent link="l4"/><child link="tool"/>
    <axis xyz="0 0 1"/><limit lower="-10" upper="10" effort="1" velocity="1"/>
    <mimic joint="finger2" multiplier="-2.5" offset="0.125"/></joint>
</robot>)";

const dss::RobotModel& robot() {
  static const dss::RobotModel model = dss::loadUrdfString(kRobot, "csv_fuzz.urdf", ".");
  return model;
}

bool sameBits(double a, double b) {
  if (std::isnan(a) && std::isnan(b)) return true;
  return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  (void)robot();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const dss::RobotModel& model = robot();
  const std::string path = dss_fuzz::writeTempFile("states.csv", data, size);
  dss::CsvLimits limits;
  limits.max_line_bytes = 4096;
  limits.max_columns = 64;
  limits.max_rows = 10'000;
  const std::vector<double> base = model.defaultState();
  dss::JointStatesCsv csv;
  try {
    csv = dss::readJointStatesCsv(path, model, base, limits);
  } catch (const std::exception&) {
    return 0;
  }
  if (csv.states.size() != csv.lines.size()) dss_fuzz::propertyFailed("one line per state");
  for (const auto& q : csv.states)
    if (q.size() != model.numActiveJoints()) dss_fuzz::propertyFailed("state size");
  // Round trip: what we write, we read back.
  const std::string out_path = dss_fuzz::tempDir() + "/written.csv";
  {
    std::ofstream out(out_path, std::ios::binary);
    dss::writeJointStatesCsv(out, model, csv.states);
  }
  dss::JointStatesCsv again;
  try {
    again = dss::readJointStatesCsv(out_path, model, base);
  } catch (const std::exception& e) {
    dss_fuzz::propertyFailed(std::string("written states do not read back: ") + e.what());
  }
  if (again.states.size() != csv.states.size()) dss_fuzz::propertyFailed("round trip: row count");
  for (std::size_t r = 0; r < csv.states.size(); ++r)
    for (std::size_t k = 0; k < model.numActiveJoints(); ++k)
      if (!sameBits(again.states[r][k], csv.states[r][k]))
        dss_fuzz::propertyFailed("round trip: row " + std::to_string(r) + " joint " +
                                 std::to_string(k) + " changed");
  return 0;
}
