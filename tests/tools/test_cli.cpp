// The command-line helper of the executables (tools/cli.h): strict number parsing, the
// argument cursor (usage errors run in a child process, since they exit), and the real
// executables failing with exit code 2 and a `PROGRAM: WHAT` message on bad arguments.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "cli.h"
#include "support/run_tool.h"
#include "support/temp_files.h"

namespace fs = std::filesystem;

namespace {

using dss::cli::ArgCursor;
using dss::cli::parseInteger;
using dss::cli::parseNumber;

constexpr double kLowest = std::numeric_limits<double>::lowest();
constexpr double kHighest = std::numeric_limits<double>::max();
constexpr long long kMinLL = std::numeric_limits<long long>::min();
constexpr long long kMaxLL = std::numeric_limits<long long>::max();

const char* const kUsage = "usage: prog [--x N] [--y N] [--flag] [ARG...]\n";

/// An argv for "prog" followed by `args` (the strings live as long as the object).
class Argv {
 public:
  Argv(std::initializer_list<const char*> args) : strings_{"prog"} {
    strings_.insert(strings_.end(), args.begin(), args.end());
    for (std::string& s : strings_) pointers_.push_back(s.data());
    pointers_.push_back(nullptr);
  }
  int argc() const { return static_cast<int>(strings_.size()); }
  char** argv() { return pointers_.data(); }

 private:
  std::vector<std::string> strings_;
  std::vector<char*> pointers_;
};

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

std::string readFd(int fd) {
  std::string text;
  char buf[4096];
  for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) > 0;)
    text.append(buf, static_cast<std::size_t>(n));
  ::close(fd);
  return text;
}

/// Runs `body` in a child process (usage errors exit the process): its exit code (0 when
/// `body` returns) and what it wrote to stdout and stderr.
Outcome inChild(const std::function<void()>& body) {
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  int out[2], err[2];
  BOOST_REQUIRE(::pipe(out) == 0 && ::pipe(err) == 0);
  const pid_t pid = ::fork();
  BOOST_REQUIRE(pid >= 0);
  if (pid == 0) {
    ::dup2(out[1], STDOUT_FILENO);
    ::dup2(err[1], STDERR_FILENO);
    ::close(out[0]);
    ::close(err[0]);
    body();
    std::fflush(nullptr);
    ::_exit(0);
  }
  ::close(out[1]);
  ::close(err[1]);
  Outcome o;
  o.out = readFd(out[0]);  // the outputs are short: neither pipe fills while the other is read
  o.err = readFd(err[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return o;
}

/// Walks `args` with a cursor that knows --x (number in [0, 10]), --y (integer in [1, 5]),
/// --flag and positionals labelled "count" (integers >= 1); in a child process.
Outcome parseInChild(std::initializer_list<const char*> args) {
  return inChild([args] {
    Argv a(args);
    ArgCursor cli(a.argc(), a.argv(), "prog", kUsage);
    while (cli.next()) {
      if (cli.option("--x"))
        cli.number(0, 10);
      else if (cli.option("--y"))
        cli.integer(1, 5);
      else if (cli.flag("--flag"))
        continue;
      else if (cli.positional("count"))
        cli.integer(1, kMaxLL);
      else
        cli.unknown();
    }
  });
}

/// A usage error: exit code 2, "prog: WHAT" and the hint line on stderr, nothing on stdout.
void checkUsageError(const Outcome& o, const std::string& what) {
  BOOST_CHECK_EQUAL(o.exit_code, 2);
  BOOST_CHECK_EQUAL(o.err, "prog: " + what + "\n(prog --help for usage)\n");
  BOOST_CHECK(o.out.empty());
}

}  // namespace

BOOST_AUTO_TEST_SUITE(cli_numbers)

BOOST_AUTO_TEST_CASE(decimal_numbers_are_read_whole) {
  const std::vector<std::pair<const char*, double>> good = {
      {"1", 1.0},       {"-2.5", -2.5}, {"+3", 3.0}, {"1e3", 1000.0}, {".5", 0.5},
      {"5.", 5.0},      {"1E-3", 1e-3}, {"0", 0.0},  {"0.1", 0.1},    {"007", 7.0},
      {"1e308", 1e308}, {"1e-400", 0.0}};  // below the subnormals: rounds to zero
  for (const auto& [text, value] : good) {
    const auto x = parseNumber(text, kLowest, kHighest);
    BOOST_REQUIRE_MESSAGE(x.has_value(), "'" << text << "' rejected");
    BOOST_CHECK_EQUAL(*x, value);
  }
  // The nearest double: "0.1" is read correctly rounded, as strtod does.
  BOOST_CHECK_EQUAL(*parseNumber("0.30000000000000004", 0, 1), 0.1 + 0.2);
}

BOOST_AUTO_TEST_CASE(anything_but_one_finite_decimal_number_is_rejected) {
  // Hexadecimal is rejected on purpose: strtod would read "0x10" as 16, but on a command
  // line it is far more likely a typo than an intended hex float.
  for (const char* text :
       {"",    " ",    " 1",  "1 ",       "1\n",  "1e",   "1e+",   "1x",    "10x",   "x",
        "-",   "+",    ".",   "1..2",     "1,5",  "--1",  "nan",   "NaN",   "-nan",  "nan(1)",
        "inf", "-inf", "INF", "infinity", "0x10", "0X10", "-0x10", "0x1p3", "1e999", "-1e999"})
    BOOST_CHECK_MESSAGE(!parseNumber(text, kLowest, kHighest), "'" << text << "' accepted");
}

BOOST_AUTO_TEST_CASE(numbers_outside_the_range_are_rejected) {
  BOOST_CHECK(!parseNumber("-1", 0, 10));
  BOOST_CHECK(!parseNumber("-1e-300", 0, 10));
  BOOST_CHECK(!parseNumber("10.000001", 0, 10));
  BOOST_CHECK_EQUAL(*parseNumber("10", 0, 10), 10.0);
  BOOST_CHECK_EQUAL(*parseNumber("0", 0, 10), 0.0);
  BOOST_CHECK(parseNumber("-0", 0, 10).has_value());  // -0 == 0
  BOOST_CHECK(!parseNumber("1e-7", 1e-6, 1e6));
}

BOOST_AUTO_TEST_CASE(integers_are_signed_decimal_digits_only) {
  BOOST_CHECK_EQUAL(*parseInteger("0", kMinLL, kMaxLL), 0);
  BOOST_CHECK_EQUAL(*parseInteger("42", kMinLL, kMaxLL), 42);
  BOOST_CHECK_EQUAL(*parseInteger("+7", kMinLL, kMaxLL), 7);
  BOOST_CHECK_EQUAL(*parseInteger("-3", kMinLL, kMaxLL), -3);
  BOOST_CHECK_EQUAL(*parseInteger("010", kMinLL, kMaxLL), 10);  // decimal, not octal
  BOOST_CHECK_EQUAL(*parseInteger("9223372036854775807", kMinLL, kMaxLL), kMaxLL);
  BOOST_CHECK_EQUAL(*parseInteger("-9223372036854775808", kMinLL, kMaxLL), kMinLL);
  for (const char* text :
       {"", "+", "-", " 1", "1 ", "1e3", "1.0", "1.", "0x10", "10x", "x", "nan", "inf", "--1",
        "+-1", "1_000", "9223372036854775808", "-9223372036854775809", "99999999999999999999"})
    BOOST_CHECK_MESSAGE(!parseInteger(text, kMinLL, kMaxLL), "'" << text << "' accepted");
}

BOOST_AUTO_TEST_CASE(integers_outside_the_range_are_rejected) {
  BOOST_CHECK(!parseInteger("-1", 0, 10));
  BOOST_CHECK(!parseInteger("0", 1, 10));
  BOOST_CHECK(!parseInteger("11", 0, 10));
  BOOST_CHECK_EQUAL(*parseInteger("10", 0, 10), 10);
  BOOST_CHECK_EQUAL(*parseInteger("-0", 0, 10), 0);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(cli_cursor)

BOOST_AUTO_TEST_CASE(options_flags_and_positionals) {
  Argv a({"--x=1.5", "--y", "2", "--flag", "file", "-", "-5", "--name=a=b", "--empty=", "--", "--x",
          "-h"});
  ArgCursor cli(a.argc(), a.argv(), "prog", kUsage);
  BOOST_REQUIRE(cli.next());
  BOOST_CHECK(!cli.option("--y"));
  BOOST_CHECK(!cli.flag("--y"));
  BOOST_CHECK(!cli.positional());
  BOOST_REQUIRE(cli.option("--x"));
  BOOST_CHECK(cli.name() == "--x");
  BOOST_CHECK_EQUAL(cli.number(0, 10), 1.5);
  BOOST_REQUIRE(cli.next());
  BOOST_REQUIRE(cli.option("--y"));
  BOOST_CHECK_EQUAL(cli.integer(1, 5), 2);
  BOOST_CHECK_EQUAL(cli.integer(1, 5), 2);  // read twice: the value is taken once
  BOOST_REQUIRE(cli.next());
  BOOST_CHECK(cli.flag("--flag"));
  BOOST_REQUIRE(cli.next());
  BOOST_REQUIRE(cli.positional("FILE"));
  BOOST_CHECK_EQUAL(std::string(cli.value()), "file");
  BOOST_CHECK(cli.name() == "FILE");
  BOOST_REQUIRE(cli.next());
  BOOST_REQUIRE(cli.positional());  // "-" (stdin) is a positional
  BOOST_CHECK_EQUAL(std::string(cli.value()), "-");
  BOOST_REQUIRE(cli.next());
  BOOST_REQUIRE(cli.positional());  // so is a negative number
  BOOST_CHECK_EQUAL(cli.integer(-10, 0), -5);
  BOOST_REQUIRE(cli.next());
  BOOST_REQUIRE(cli.option("--name"));  // the value is everything after the first '='
  BOOST_CHECK_EQUAL(std::string(cli.value()), "a=b");
  BOOST_REQUIRE(cli.next());
  BOOST_REQUIRE(cli.option("--empty"));
  BOOST_CHECK_EQUAL(std::string(cli.value()), "");
  BOOST_REQUIRE(cli.next());  // after "--", options are positionals
  BOOST_REQUIRE(cli.positional());
  BOOST_CHECK_EQUAL(std::string(cli.value()), "--x");
  BOOST_REQUIRE(cli.next());
  BOOST_REQUIRE(cli.positional());
  BOOST_CHECK_EQUAL(std::string(cli.value()), "-h");
  BOOST_CHECK(!cli.next());
  BOOST_CHECK(!cli.next());
}

BOOST_AUTO_TEST_CASE(a_value_may_start_with_a_dash) {
  Argv a({"--x", "-1", "--y", "--flag"});
  ArgCursor cli(a.argc(), a.argv(), "prog", kUsage);
  BOOST_REQUIRE(cli.next() && cli.option("--x"));
  BOOST_CHECK_EQUAL(cli.number(-5, 5), -1.0);
  BOOST_REQUIRE(cli.next() && cli.option("--y"));
  BOOST_CHECK_EQUAL(std::string(cli.value()), "--flag");
  BOOST_CHECK(!cli.next());
}

BOOST_AUTO_TEST_CASE(good_arguments_run_through) {
  const Outcome o = parseInChild({"--x=1", "--x", "1", "--y=5", "--flag", "7", "--", "8"});
  BOOST_CHECK_EQUAL(o.exit_code, 0);
  BOOST_CHECK(o.err.empty());
}

BOOST_AUTO_TEST_CASE(usage_errors_name_the_option_and_the_text) {
  checkUsageError(parseInChild({"--x"}), "--x needs a value");
  checkUsageError(parseInChild({"--flag", "--y"}), "--y needs a value");
  checkUsageError(parseInChild({"--flag=1"}), "--flag takes no value, got '--flag=1'");
  checkUsageError(parseInChild({"--flag="}), "--flag takes no value, got '--flag='");
  checkUsageError(parseInChild({"--bogus"}), "unknown option --bogus");
  checkUsageError(parseInChild({"--bogus=3"}), "unknown option --bogus");
  checkUsageError(parseInChild({"-q"}), "unknown option -q");
  checkUsageError(parseInChild({"--x", "1e"}),
                  "--x: expected a finite number in [0, 10], got '1e'");
  checkUsageError(parseInChild({"--x=nan"}), "--x: expected a finite number in [0, 10], got 'nan'");
  checkUsageError(parseInChild({"--x=inf"}), "--x: expected a finite number in [0, 10], got 'inf'");
  checkUsageError(parseInChild({"--x=0x10"}),
                  "--x: expected a finite number in [0, 10], got '0x10'");
  checkUsageError(parseInChild({"--x="}), "--x: expected a finite number in [0, 10], got ''");
  checkUsageError(parseInChild({"--x", "-1"}),
                  "--x: expected a finite number in [0, 10], got '-1'");
  checkUsageError(parseInChild({"--x", "11"}),
                  "--x: expected a finite number in [0, 10], got '11'");
  checkUsageError(parseInChild({"--y", "0"}), "--y: expected an integer in [1, 5], got '0'");
  checkUsageError(parseInChild({"--y", "2.0"}), "--y: expected an integer in [1, 5], got '2.0'");
  checkUsageError(parseInChild({"10x"}), "count: expected an integer >= 1, got '10x'");
  checkUsageError(parseInChild({"-3"}), "count: expected an integer >= 1, got '-3'");
  checkUsageError(parseInChild({"--help=1"}), "--help takes no value");
}

BOOST_AUTO_TEST_CASE(help_prints_the_usage_and_exits_0) {
  for (const char* help : {"--help", "-h"}) {
    const Outcome o = parseInChild({"--x", "1", help, "--bogus"});
    BOOST_CHECK_EQUAL(o.exit_code, 0);
    BOOST_CHECK_EQUAL(o.out, kUsage);
    BOOST_CHECK(o.err.empty());
  }
}

BOOST_AUTO_TEST_CASE(usage_error_exits_2) {
  const Outcome o = inChild([] { dss::cli::usageError("tool", "what went wrong"); });
  BOOST_CHECK_EQUAL(o.exit_code, dss::cli::kExitUsage);
  BOOST_CHECK_EQUAL(o.err, "tool: what went wrong\n(tool --help for usage)\n");
}

BOOST_AUTO_TEST_SUITE_END()

// The executables themselves: bad numbers and unknown options are usage errors (exit 2,
// "PROGRAM: ..." and the hint line on stderr); runtime errors keep exit code 1.
namespace {

const std::string kArm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7/dss_arm7.urdf";

/// Runs tool `name` with `args` (support/run_tool.h).
Outcome runTool(const std::string& name, const std::vector<std::string>& args) {
  const dss_test::ToolRun r = dss_test::runTool(name, args);
  Outcome o;
  o.exit_code = r.exit_code;
  o.out = r.out;
  o.err = r.err;
  return o;
}

/// `name args` fails as a usage error whose message contains `part`.
void checkToolUsageError(const std::string& name, const std::vector<std::string>& args,
                         const std::string& part) {
  std::string shown = name;
  for (const std::string& a : args) shown += " " + a;
  const Outcome o = runTool(name, args);
  BOOST_CHECK_MESSAGE(o.exit_code == 2, shown << ": exit " << o.exit_code << ", stderr: " << o.err);
  const std::string first = o.err.substr(0, o.err.find('\n'));
  BOOST_CHECK_MESSAGE(first.rfind(name + ": ", 0) == 0 && first.find(part) != std::string::npos,
                      shown << ": first stderr line '" << first << "' lacks '" << part << "'");
  BOOST_CHECK_MESSAGE(o.err.find("(" + name + " --help for usage)") != std::string::npos,
                      shown << ": no hint line in '" << o.err << "'");
}

}  // namespace

BOOST_AUTO_TEST_SUITE(cli_executables)

BOOST_AUTO_TEST_CASE(every_executable_has_help) {
  for (const std::string name : {"dss_check", "dss_pairs", "dss_disabled_pairs", "dss_robot_timing",
                                 "dss_scene_timing", "dss_plan", "dss_decompose"}) {
    const Outcome o = runTool(name, {"--help"});
    BOOST_CHECK_MESSAGE(o.exit_code == 0, name << " --help: exit " << o.exit_code);
    BOOST_CHECK_MESSAGE(o.out.rfind("usage: " + name, 0) == 0,
                        name << " --help: '" << o.out << "'");
  }
}

BOOST_AUTO_TEST_CASE(dss_disabled_pairs_reads_samples_and_seed_strictly) {
  checkToolUsageError("dss_disabled_pairs", {kArm, "10x"},
                      "samples: expected an integer in [1, 2147483647], got '10x'");
  checkToolUsageError("dss_disabled_pairs", {kArm, "0"}, "samples: expected an integer");
  checkToolUsageError("dss_disabled_pairs", {kArm, "1e4"}, "got '1e4'");
  checkToolUsageError("dss_disabled_pairs", {kArm, "10", "-1"},
                      "seed: expected an integer >= 0, got '-1'");
  checkToolUsageError("dss_disabled_pairs", {kArm, "10", "1", "extra"},
                      "unexpected argument 'extra'");
  checkToolUsageError("dss_disabled_pairs", {kArm, "--package"}, "--package needs a value");
  checkToolUsageError("dss_disabled_pairs", {kArm, "--package", "nodir"},
                      "--package: expected name=dir");
  checkToolUsageError("dss_disabled_pairs", {kArm, "--samples=5"}, "unknown option --samples");
  checkToolUsageError("dss_disabled_pairs", {}, "no robot.urdf");
  // A runtime error keeps exit code 1.
  BOOST_CHECK_EQUAL(runTool("dss_disabled_pairs", {"/no/such/robot.urdf", "10"}).exit_code, 1);
}

BOOST_AUTO_TEST_CASE(timing_tools_read_numbers_strictly) {
  checkToolUsageError("dss_robot_timing", {kArm, "1e6"},
                      "states: expected an integer in [1, 2147483647], got '1e6'");
  checkToolUsageError("dss_robot_timing", {kArm, "0"}, "states");
  checkToolUsageError("dss_robot_timing", {kArm, "10", "more"}, "unexpected argument 'more'");
  checkToolUsageError("dss_robot_timing", {"--states", "10"}, "unknown option --states");
  BOOST_CHECK_EQUAL(runTool("dss_robot_timing", {"/no/such/robot.urdf", "10"}).exit_code, 1);
  checkToolUsageError("dss_scene_timing", {"--repeats", "0", "x.yaml"},
                      "--repeats: expected an integer in [1, 1000000], got '0'");
  checkToolUsageError("dss_scene_timing", {"--repeats=3x", "x.yaml"}, "got '3x'");
  checkToolUsageError("dss_scene_timing", {"--repeats"}, "--repeats needs a value");
  checkToolUsageError("dss_scene_timing", {"--bogus", "x.yaml"}, "unknown option --bogus");
  checkToolUsageError("dss_scene_timing", {}, "no scene file");
  BOOST_CHECK_EQUAL(
      runTool("dss_scene_timing", {"--repeats", "1", "/no/such/scene.yaml"}).exit_code, 1);
}

BOOST_AUTO_TEST_CASE(dss_check_and_dss_plan_usage_errors_exit_2) {
  checkToolUsageError("dss_check", {"--robot", kArm, "--random", "1e"},
                      "--random: expected an integer in [1, 1000000000], got '1e'");
  checkToolUsageError("dss_check", {"--robot", kArm, "--random", "10", "--padding", "nan"},
                      "--padding");
  checkToolUsageError("dss_check", {"--robot", kArm, "--random", "10", "--threads", "0"},
                      "--threads");
  checkToolUsageError("dss_check", {"--robot", kArm, "--random", "10", "--seed", "-1"}, "--seed");
  checkToolUsageError("dss_check", {"--robot", kArm, "--random", "10", "--mode", "quad"}, "--mode");
  checkToolUsageError("dss_check", {"--robot", kArm, "--describe=yes"},
                      "--describe takes no value");
  checkToolUsageError("dss_check", {"--robot", kArm, "--random", "10", "--scene-mesh-parts", "0"},
                      "--scene-mesh-parts");
  checkToolUsageError("dss_check", {"--robot", kArm, "--bogus"}, "unknown option --bogus");
  checkToolUsageError("dss_check", {"--random", "10"}, "--robot is required");
  checkToolUsageError("dss_check", {"--robot", kArm}, "--states or --random is required");
  BOOST_CHECK_EQUAL(
      runTool("dss_check", {"--robot", "/no/such/robot.urdf", "--random", "10"}).exit_code, 1);

  checkToolUsageError("dss_plan", {"--seed", "-1"},
                      "--seed: expected an integer in [0, 4294967295], got '-1'");
  checkToolUsageError("dss_plan", {"--time", "inf"}, "--time");
  checkToolUsageError("dss_plan", {"--scene-mesh-parts", "4097"}, "--scene-mesh-parts");
  checkToolUsageError("dss_plan", {"--runs", "2x", "--benchmark"}, "--runs");
  checkToolUsageError("dss_plan", {"--planner", "RRTX"}, "unknown planner 'RRTX'");
  checkToolUsageError("dss_plan", {"--simplify=1"}, "--simplify takes no value");
  checkToolUsageError("dss_plan", {"--bogus"}, "unknown option --bogus");
  checkToolUsageError("dss_plan", {"extra"}, "unexpected argument 'extra'");
  checkToolUsageError(
      "dss_plan", {"--workspace", "0,0,0,1,1"},
      "--workspace: expected 6 finite numbers separated by commas, got '0,0,0,1,1'");
  checkToolUsageError("dss_check", {"--workspace", "0,0,0,1,1,nan"}, "--workspace: expected 6");
  checkToolUsageError("dss_check", {"--workspace", "0,0,0,1,1,1,"}, "--workspace: expected 6");
  BOOST_CHECK_EQUAL(
      runTool("dss_plan", {"--robot", "/no/such/robot.urdf", "--request", "/no/such/request.yaml"})
          .exit_code,
      1);

  // Mesh options (dss_check and dss_plan share them) and dss_decompose.
  checkToolUsageError("dss_check", {"--robot", kArm, "--random", "10", "--meshes", "voxels"},
                      "--meshes: expected hull or decomposed, got 'voxels'");
  checkToolUsageError("dss_plan", {"--decompose-tolerance", "0"}, "--decompose-tolerance");
  checkToolUsageError("dss_plan", {"--decompose-max-pieces", "65"}, "--decompose-max-pieces");
  checkToolUsageError("dss_check", {"--robot", kArm, "--random", "10", "--decompose-links", ","},
                      "--decompose-links: empty link name");
  BOOST_CHECK_EQUAL(
      runTool("dss_check", {"--robot", kArm, "--random", "10", "--decompose-links", "no_such_link"})
          .exit_code,
      1);
  checkToolUsageError("dss_decompose", {}, "give --robot or --mesh");
  checkToolUsageError("dss_decompose", {"--mesh", "a.stl", "--links", "l1"},
                      "--links needs --robot");
  checkToolUsageError("dss_decompose", {"--mesh", "a.stl", "--scale", "0"}, "--scale");
  checkToolUsageError("dss_decompose", {"--mesh", "a.stl", "--tolerance", "-1"}, "--tolerance");
  BOOST_CHECK_EQUAL(
      runTool("dss_decompose", {"--mesh", "/no/such/mesh.stl", "--cache", "none"}).exit_code, 1);
  BOOST_CHECK_EQUAL(
      runTool("dss_decompose", {"--robot", kArm, "--links", "no_such_link", "--cache", "none"})
          .exit_code,
      1);

  checkToolUsageError("dss_pairs", {"--repeat", "0x", "-"}, "--repeat: expected an integer");
  checkToolUsageError("dss_pairs", {"--padding", "1e", "-"},
                      "--padding: expected a finite number >= 0, got '1e'");
}

// dss_check reads a scene mesh as one hull per connected part (two boards a metre apart: two
// obstacles), or as one hull with --scene-mesh-parts 1.
BOOST_AUTO_TEST_CASE(dss_check_scene_mesh_parts) {
  const fs::path scene = dss_test::scratchDir("cli") / "mesh_parts.yaml";
  {
    std::ofstream out(scene);
    out << "world:\n  collision_objects:\n    - id: boards\n      meshes:\n        - vertices: [";
    for (double x0 : {1.0, 2.0})
      for (int i = 0; i < 4; ++i)
        out << (x0 == 1.0 && i == 0 ? "" : ", ") << "[" << x0 + (i & 1 ? 0.02 : 0.0) << ", "
            << (i & 2 ? 0.5 : -0.5) << ", 0]";
    out << "]\n          triangles: [[0, 1, 2], [1, 3, 2], [4, 5, 6], [5, 7, 6]]\n"
           "      mesh_poses:\n        - {position: [0, 0, 0.5], orientation: [0, 0, 0, 1]}\n";
  }
  auto total = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"--robot", kArm, "--scene", scene.string(), "--describe"};
    args.insert(args.end(), extra.begin(), extra.end());
    const Outcome o = runTool("dss_check", args);
    BOOST_TEST_REQUIRE(o.exit_code == 0, o.err);
    const std::string key = "\"obstacles_total\": ";
    const std::size_t at = o.out.find(key);
    BOOST_TEST_REQUIRE(at != std::string::npos, o.out);
    return std::stoi(o.out.substr(at + key.size()));
  };
  BOOST_TEST(total({}) == 2);
  BOOST_TEST(total({"--scene-mesh-parts", "1"}) == 1);
  fs::remove(scene);
}

BOOST_AUTO_TEST_SUITE_END()
