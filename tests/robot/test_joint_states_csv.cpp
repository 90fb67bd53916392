// Robot states as CSV (joint_states_csv.h): a written file reads back into the same states;
// columns may name any active or mimic joint, and the others keep the base values; a mimic
// column must agree with its leader; every malformed file is an error naming the file and the
// line, and a cell is one number with blanks around it; the readers' limits hold.
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "dss/robot/joint_states_csv.h"
#include "dss/robot/urdf_loader.h"
#include "support/temp_files.h"

namespace fs = std::filesystem;

namespace {

fs::path tempDir() { return dss_test::scratchDir("csv"); }

std::string write(const std::string& name, const std::string& text) {
  return dss_test::writeScratch("csv", name, text);
}

// Active joints j1 (revolute) and j2 (prismatic); m mimics j1 (2 q + 0.5); f is fixed.
const char* kRobot = R"(<?xml version="1.0"?>
<robot name="csvbot">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="l4"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="f" type="fixed"><parent link="l1"/><child link="l2"/></joint>
  <joint name="j2" type="prismatic"><parent link="l2"/><child link="l3"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.5" effort="1" velocity="1"/></joint>
  <joint name="m" type="revolute"><parent link="l1"/><child link="l4"/><axis xyz="0 1 0"/>
    <limit lower="-10" upper="10" effort="1" velocity="1"/><mimic joint="j1" multiplier="2" offset="0.5"/></joint>
</robot>
)";

const dss::RobotModel& robot() {
  static const dss::RobotModel r = dss::loadUrdf(write("csvbot.urdf", kRobot));
  return r;
}

// The message of the error reading `text`, or "" when it reads.
std::string errorOf(const std::string& name, const std::string& text,
                    const dss::CsvLimits& limits = {}) {
  try {
    dss::readJointStatesCsv(write(name, text), robot(), {0.25, 0.125}, limits);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(joint_states_csv)

BOOST_AUTO_TEST_CASE(written_states_read_back_exactly) {
  const dss::RobotModel& r = robot();
  const int j1 = r.joints[r.jointIndex("j1")].active_index,
            j2 = r.joints[r.jointIndex("j2")].active_index;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-3, 3);
  std::vector<std::vector<double>> states;
  for (int i = 0; i < 200; ++i) {
    std::vector<double> q(r.numActiveJoints());
    q[j1] = u(rng);
    q[j2] = std::abs(u(rng)) / 6;
    states.push_back(q);
  }
  std::ostringstream out;
  dss::writeJointStatesCsv(out, r, states);
  BOOST_TEST(out.str().rfind("j1,j2,m\n", 0) == 0u, "header: " << out.str().substr(0, 20));
  const dss::JointStatesCsv back =
      dss::readJointStatesCsv(write("round.csv", out.str()), r, {9, 9});
  BOOST_TEST(back.states == states);
  BOOST_TEST(back.lines.front() == 2);
  BOOST_TEST(back.lines.back() == 201);
}

BOOST_AUTO_TEST_CASE(columns_set_their_joints_and_the_others_keep_the_base) {
  const dss::JointStatesCsv csv =
      dss::readJointStatesCsv(write("j2.csv", "j2\n0.5\n\n0.25\nnan\n"), robot(), {1.5, 0});
  BOOST_REQUIRE(csv.states.size() == 3u);
  BOOST_TEST(csv.states[0][0] == 1.5);
  BOOST_TEST(csv.states[0][1] == 0.5);
  BOOST_TEST(csv.states[1][1] == 0.25);
  BOOST_TEST(std::isnan(csv.states[2][1]));  // a NaN state is the checker's to refuse
  BOOST_TEST(csv.lines[1] == 4);             // blank lines are skipped, lines still counted
}

BOOST_AUTO_TEST_CASE(a_mimic_column_must_agree_with_its_leader) {
  // m = 2 j1 + 0.5
  BOOST_TEST(errorOf("mimic_ok.csv", "j1,m\n1,2.5\n-1,-1.5\n").empty());
  const std::string e = errorOf("mimic_bad.csv", "j1,m\n1,2.5\n0.5,1.0\n");
  BOOST_TEST(contains(e, "mimic_bad.csv:3"), e);
  BOOST_TEST(contains(e, "mimic joint 'm'"), e);
  BOOST_TEST(contains(e, "'j1'"), e);
  // Without its leader's column the mimic joint must agree with the base value of j1 (0.25).
  BOOST_TEST(errorOf("mimic_base.csv", "m\n1.0\n").empty());
  BOOST_TEST(!errorOf("mimic_base_bad.csv", "m\n1.1\n").empty());
  // A leader at an infinity puts its mimic at the same one, as written files say (found by
  // fuzz/fuzz_joint_states_csv: a number too large for a double read as inf, written back
  // with its mimic at inf, then refused); NaN puts it at NaN.
  BOOST_TEST(errorOf("mimic_inf.csv", "j1,m\n1e999,inf\n-inf,-inf\nnan,nan\n").empty());
  BOOST_TEST(!errorOf("mimic_inf_bad.csv", "j1,m\ninf,-inf\n").empty());
}

BOOST_AUTO_TEST_CASE(a_cell_is_one_number_with_blanks_around_it) {
  // Blanks (spaces, tabs, a CR before the newline) around a number are not part of it; the
  // last line may end without a newline.
  const dss::JointStatesCsv csv = dss::readJointStatesCsv(
      write("blanks.csv", " j1 ,\tj2\r\n 1.5 ,\t0.25\t\r\n+2,1e-1\n-0,.5"), robot(), {0, 0});
  BOOST_REQUIRE(csv.states.size() == 3u);
  BOOST_TEST(csv.states[0] == (std::vector<double>{1.5, 0.25}));
  BOOST_TEST(csv.states[1] == (std::vector<double>{2, 0.1}));
  BOOST_TEST(csv.states[2][1] == 0.5);
  BOOST_TEST(std::signbit(csv.states[2][0]));
  // Anything else in the cell is an error naming the cell: a second number, a unit, a NUL
  // byte, only blanks.
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"j1,j2\n0,1 2\n", "'1 2' is not a number"},
      {"j1,j2\n0.5m,0\n", "'0.5m' is not a number"},
      {std::string("j1,j2\n1\0"
                   "5,0\n",
                   11),
       "column 'j1'"},
      {"j1,j2\n0, \t \n", "column 'j2': '' is not a number"},
  };
  for (const auto& [text, part] : bad) {
    const std::string e = errorOf("cell.csv", text);
    BOOST_TEST(contains(e, "cell.csv:2"), e);
    BOOST_TEST(contains(e, part), e);
  }
}

BOOST_AUTO_TEST_CASE(malformed_files_name_the_file_and_the_line) {
  struct Case {
    const char* name;
    std::string text;
    std::vector<const char*> parts;
  };
  const std::vector<Case> cases = {
      {"unknown.csv",
       "j1,elbow\n0,0\n",
       {"unknown.csv:1", "'elbow' is not a joint of robot csvbot"}},
      {"fixed.csv", "j1,f\n0,0\n", {"fixed.csv:1", "joint 'f' is fixed"}},
      {"twice.csv", "j1,j1\n0,0\n", {"twice.csv:1", "'j1' appears twice"}},
      {"empty_name.csv", "j1,,j2\n0,0,0\n", {"empty_name.csv:1", "empty joint name"}},
      {"count.csv", "j1,j2\n0,0\n0\n", {"count.csv:3", "1 values, the header has 2"}},
      {"number.csv", "j1,j2\n0,0x\n", {"number.csv:2", "column 'j2': '0x' is not a number"}},
      {"blank.csv", "j1,j2\n0,\n", {"blank.csv:2", "column 'j2': '' is not a number"}},
      {"nothing.csv", "\n \n", {"nothing.csv", "no header"}},
  };
  for (const Case& c : cases) {
    const std::string e = errorOf(c.name, c.text);
    for (const char* part : c.parts) BOOST_TEST(contains(e, part), c.name << ": " << e);
  }
  const std::string missing = errorOf("missing_file_that_is_not_there/x.csv", "");
  BOOST_TEST(!missing.empty());
}

BOOST_AUTO_TEST_CASE(limits_are_errors_that_name_the_limit) {
  dss::CsvLimits small;
  small.max_line_bytes = 16;
  small.max_columns = 2;
  small.max_rows = 2;
  std::string e = errorOf("long.csv", "j1\n0.000000000000000000001\n", small);
  BOOST_TEST(contains(e, "long.csv:2"), e);
  BOOST_TEST(contains(e, "CsvLimits::max_line_bytes"), e);
  e = errorOf("wide.csv", "j1,j2,m\n", small);
  BOOST_TEST(contains(e, "CsvLimits::max_columns"), e);
  e = errorOf("tall.csv", "j1\n0\n0\n0\n", small);
  BOOST_TEST(contains(e, "tall.csv:4"), e);
  BOOST_TEST(contains(e, "CsvLimits::max_rows"), e);
  BOOST_TEST(errorOf("fits.csv", "j1\n0\n0\n", small).empty());
}

BOOST_AUTO_TEST_SUITE_END()
