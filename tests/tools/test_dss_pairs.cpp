// dss_pairs end to end: the built binary is run on the shared pair samples (checked against
// their answer files per tier) and on malformed inputs (exit code 2 and a `FILE:N:` message
// naming the right line).
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "support/shared_data.h"
#include "support/temp_files.h"

namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

const std::string kTool = std::string(DSS_BINARY_DIR) + "/tools/dss_pairs";
const std::string kSampleDir = std::string(DSS_SHARED_DIR) + "/testdata/pairs_sample";
const std::vector<std::string> kSamples = {"sample_paper", "sample_near", "sample_primitives",
                                           "sample_extremes", "sample_touching"};
const std::vector<std::string> kTiers = {"robust", "near", "touching"};

struct Run {
  int exit_code = -1;
  std::string out, err;
  std::vector<std::string> outLines() const {
    std::vector<std::string> lines;
    std::istringstream in(out);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
  }
  std::string firstErrLine() const { return err.substr(0, err.find('\n')); }
};

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string quote(const std::string& s) { return "'" + s + "'"; }

/// A scratch directory for this test process (removed at exit).
fs::path scratchDir() { return dss_test::scratchDir("pairs"); }

/// Runs dss_pairs with `args` (already shell-quoted where needed), stdin from `stdin_file`.
Run runTool(const std::string& args, const std::string& stdin_file = "/dev/null") {
  const fs::path out = scratchDir() / "out.txt", err = scratchDir() / "err.txt";
  // A hang in a decision (a core bug) fails the run with exit code 124 instead of stalling.
  const std::string cmd = "timeout 120 " + quote(kTool) + " " + args + " < " + quote(stdin_file) +
                          " > " + quote(out.string()) + " 2> " + quote(err.string());
  const int status = std::system(cmd.c_str());
  Run r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = readAll(out);
  r.err = readAll(err);
  return r;
}

fs::path writeFile(const std::string& name, const std::string& text) {
  const fs::path p = scratchDir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

bool haveSamples() { return fs::exists(kSampleDir + "/sample_paper.jsonl"); }

struct TierCounts {
  std::map<std::string, int> pairs, wrong, caps;
};

/// Runs one algorithm and mode over every sample file and counts, per tier, the wrong answers
/// and the cap hits against the answer files.
TierCounts runSamples(const std::string& algo, const std::string& mode) {
  TierCounts c;
  for (const std::string& name : kSamples) {
    const std::string input = kSampleDir + "/" + name + ".jsonl";
    const Run r = runTool("--algo " + algo + " --mode " + mode + " " + quote(input));
    BOOST_REQUIRE_MESSAGE(r.exit_code == 0, name << " " << algo << " " << mode << ": exit "
                                                 << r.exit_code << ": " << r.err);
    const std::vector<std::string> got = r.outLines();
    std::ifstream answers(kSampleDir + "/" + name + ".answers.jsonl");
    std::size_t i = 0;
    for (std::string line; std::getline(answers, line); ++i) {
      BOOST_REQUIRE_LT(i, got.size());
      const Json want = Json::parse(line);
      const Json have = Json::parse(got[i]);
      BOOST_REQUIRE_EQUAL(have.at("id"), want.at("id"));
      const std::string tier = want.at("tier").get<std::string>();
      ++c.pairs[tier];
      const bool wrong = have.at("intersect") != want.at("intersect");
      if (wrong) {
        ++c.wrong[tier];
        BOOST_TEST_MESSAGE("  " << algo << "/" << mode << " wrong: " << want.at("id") << " "
                                << want.at("category") << " expected " << want.at("intersect")
                                << " got " << got[i]);
      }
      c.caps[tier] += have.at("status") == "iteration_limit";
    }
    BOOST_CHECK_EQUAL(i, got.size());
  }
  std::ostringstream msg;
  msg << algo << " --mode " << mode << ":";
  for (const std::string& t : kTiers)
    msg << "  " << t << " wrong " << c.wrong[t] << "/" << c.pairs[t] << " caps " << c.caps[t];
  BOOST_TEST_MESSAGE(msg.str());
  return c;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(dss_pairs_samples)

BOOST_AUTO_TEST_CASE(exact_dss_and_hybrid_are_never_wrong, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(haveSamples());
  for (const std::string algo : {"dss", "hybrid"}) {
    TierCounts c = runSamples(algo, "exact");
    int total = 0;
    for (const std::string& t : kTiers) {
      BOOST_CHECK_MESSAGE(c.wrong[t] == 0, algo << " exact: " << c.wrong[t] << " wrong on " << t);
      total += c.pairs[t];
    }
    BOOST_CHECK_EQUAL(total, 295);
  }
}

BOOST_AUTO_TEST_CASE(double_and_float_report_their_wrong_answers, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(haveSamples());
  for (const std::string algo : {"dss", "hybrid"}) {
    TierCounts d = runSamples(algo, "double");
    BOOST_CHECK_MESSAGE(d.wrong["robust"] == 0, algo << " double wrong on the robust tier");
    runSamples(algo, "float");
  }
}

BOOST_AUTO_TEST_CASE(gjk_and_fcl_report_their_wrong_answers, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(haveSamples());
  for (const std::string mode : {"exact", "double", "float"}) runSamples("gjk", mode);
  runSamples("fcl", "double");
}

BOOST_AUTO_TEST_CASE(time_prints_one_summary_per_algorithm, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(haveSamples());
  const Run r = runTool("--algo dss,gjk,fcl --time --repeat 3 --mode double " +
                        quote(kSampleDir + "/sample_paper.jsonl"));
  BOOST_REQUIRE_EQUAL(r.exit_code, 0);
  BOOST_CHECK_EQUAL(r.outLines().size(), 87u);  // the answers of the first algorithm
  std::istringstream err(r.err);
  std::vector<std::string> algos;
  for (std::string line; std::getline(err, line);) {
    const Json s = Json::parse(line);
    algos.push_back(s.at("algo"));
    BOOST_CHECK_EQUAL(s.at("pairs"), 87);
    BOOST_CHECK_EQUAL(s.at("repetitions"), 3);
    BOOST_CHECK_GT(s.at("ns_per_pair").get<double>(), 0.0);
    BOOST_CHECK_EQUAL(s.at("mode"), "double");
  }
  BOOST_CHECK((algos == std::vector<std::string>{"dss", "gjk", "fcl"}));
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(dss_pairs_input)

const std::string kGood =
    R"({"id":"g","a":{"type":"sphere","radius":1},"b":{"type":"box","size":[1,1,1],"pose":{"position":[3,0,0],"orientation":[0,0,0,1]}}})";

BOOST_AUTO_TEST_CASE(malformed_lines_stop_with_exit_2_and_the_line) {
  struct Case {
    const char* name;
    std::string bad_line;
    const char* message_part;
  };
  const std::vector<Case> cases = {
      {"bad_json", R"({"id":"x","a":{"type":"sphere","radius":1},)", "bad JSON"},
      {"not_object", R"([1,2,3])", "expected a JSON object"},
      {"unknown_type",
       R"({"id":"x","a":{"type":"torus","radius":1},"b":{"type":"sphere","radius":1}})",
       "unknown shape type \"torus\""},
      {"missing_b", R"({"id":"x","a":{"type":"sphere","radius":1}})", "missing field \"b\""},
      {"missing_id", R"({"a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1}})",
       "missing field \"id\""},
      {"missing_size", R"({"id":"x","a":{"type":"sphere","radius":1},"b":{"type":"box"}})",
       "b: missing field \"size\""},
      {"missing_length",
       R"({"id":"x","a":{"type":"cone","radius":1},"b":{"type":"sphere","radius":1}})",
       "a: missing field \"length\""},
      {"negative_radius",
       R"({"id":"x","a":{"type":"sphere","radius":-1},"b":{"type":"sphere","radius":1}})",
       "a.radius: negative size"},
      {"negative_box",
       R"({"id":"x","a":{"type":"sphere","radius":1},"b":{"type":"box","size":[1,-2,1]}})",
       "b.size: negative size"},
      {"negative_radii",
       R"({"id":"x","a":{"type":"ellipsoid","radii":[1,1,-0.5]},"b":{"type":"sphere","radius":1}})",
       "a.radii: negative size"},
      {"overflow_number",
       R"({"id":"x","a":{"type":"sphere","radius":1e999},"b":{"type":"sphere","radius":1}})",
       "overflow"},
      {"string_size",
       R"({"id":"x","a":{"type":"capsule","radius":"1","length":1},"b":{"type":"sphere","radius":1}})",
       "a.radius: expected a number"},
      {"short_size",
       R"({"id":"x","a":{"type":"box","size":[1,1]},"b":{"type":"sphere","radius":1}})",
       "a.size: expected an array of 3 numbers"},
      {"empty_vertices",
       R"({"id":"x","a":{"type":"convex","vertices":[]},"b":{"type":"sphere","radius":1}})",
       "a.vertices: empty vertex list"},
      {"bad_vertex",
       R"({"id":"x","a":{"type":"convex","vertices":[[0,0,0],[1,2]]},"b":{"type":"sphere","radius":1}})",
       "a.vertices[1]: expected an array of 3 numbers"},
      {"zero_quaternion",
       R"({"id":"x","a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1,"pose":{"position":[0,0,0],"orientation":[0,0,0,0]}}})",
       "b.pose.orientation: zero quaternion"},
      {"missing_orientation",
       R"({"id":"x","a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1,"pose":{"position":[0,0,0]}}})",
       "b.pose: missing field \"orientation\""},
      {"non_finite_posed_vertex",
       R"({"id":"x","a":{"type":"convex","vertices":[[1e308,0,0]],"pose":{"position":[1e308,0,0],"orientation":[0,0,0,1]}},"b":{"type":"sphere","radius":1}})",
       "a.vertices: a posed vertex is not finite"},
      {"blank_line", "", "empty line"},
  };
  for (const Case& c : cases) {
    // The bad line is line 3 of 4.
    const fs::path file = writeFile(std::string(c.name) + ".jsonl",
                                    kGood + "\n" + kGood + "\n" + c.bad_line + "\n" + kGood + "\n");
    for (const std::string algo : {"dss", "fcl"}) {
      const Run r = runTool("--algo " + algo + " " + quote(file.string()));
      BOOST_CHECK_MESSAGE(r.exit_code == 2, c.name << " " << algo << ": exit " << r.exit_code);
      const std::string prefix = file.string() + ":3: ";
      const std::string first = r.firstErrLine();
      BOOST_CHECK_MESSAGE(first.compare(0, prefix.size(), prefix) == 0,
                          c.name << ": stderr starts '" << first << "'");
      BOOST_CHECK_MESSAGE(first.find(c.message_part) != std::string::npos,
                          c.name << ": '" << first << "' lacks '" << c.message_part << "'");
      BOOST_CHECK_MESSAGE(r.out.empty(), c.name << ": no answers before the error");
    }
  }
}

BOOST_AUTO_TEST_CASE(stdin_line_numbers_and_unreadable_files) {
  const fs::path file = writeFile("stdin_bad.jsonl", kGood + "\n{\n");
  const Run r = runTool("-", file.string());
  BOOST_CHECK_EQUAL(r.exit_code, 2);
  BOOST_CHECK_EQUAL(r.firstErrLine().rfind("<stdin>:2: bad JSON", 0), 0u);

  const Run missing = runTool(quote((scratchDir() / "no_such_file.jsonl").string()));
  BOOST_CHECK_EQUAL(missing.exit_code, 2);
  BOOST_CHECK(missing.firstErrLine().find("cannot open") != std::string::npos);

  BOOST_CHECK_EQUAL(runTool("--algo nope -").exit_code, 2);
  BOOST_CHECK_EQUAL(runTool("--mode quad -").exit_code, 2);
  BOOST_CHECK_EQUAL(runTool("--algo dss,gjk -").exit_code, 2);  // a list needs --time
  BOOST_CHECK_EQUAL(runTool("--padding -1 -").exit_code, 2);
  BOOST_CHECK_EQUAL(runTool("--bogus -").exit_code, 2);
  BOOST_CHECK_EQUAL(runTool("--help").exit_code, 0);
}

BOOST_AUTO_TEST_CASE(trailing_newline_and_crlf_are_accepted) {
  const fs::path no_newline = writeFile("no_newline.jsonl", kGood + "\n" + kGood);
  const fs::path crlf = writeFile("crlf.jsonl", kGood + "\r\n" + kGood + "\r\n");
  for (const fs::path& p : {no_newline, crlf}) {
    const Run r = runTool(quote(p.string()));
    BOOST_CHECK_EQUAL(r.exit_code, 0);
    BOOST_CHECK_EQUAL(r.outLines().size(), 2u);
  }
  const fs::path empty = writeFile("empty.jsonl", "");
  const Run e = runTool(quote(empty.string()));
  BOOST_CHECK_EQUAL(e.exit_code, 0);
  BOOST_CHECK(e.out.empty());
  BOOST_CHECK_EQUAL(runTool("--time " + quote(empty.string())).exit_code, 2);  // nothing to time
  const fs::path two_newlines = writeFile("two_newlines.jsonl", kGood + "\n\n");
  const Run r = runTool(quote(two_newlines.string()));
  BOOST_CHECK_EQUAL(r.exit_code, 2);
  BOOST_CHECK(r.firstErrLine().find(":2: empty line") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(output_format_order_and_ids) {
  const std::string text =
      R"({"id":7,"a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1,"pose":{"position":[3,0,0],"orientation":[0,0,0,1]}}})"
      "\n"
      R"({"id":"touch","a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1,"pose":{"position":[2,0,0],"orientation":[0,0,0,2]}}})"
      "\n";
  const fs::path file = writeFile("format.jsonl", text);
  for (const std::string algo : {"dss", "gjk", "hybrid", "fcl"}) {
    const Run r = runTool("--algo " + algo + " " + quote(file.string()));
    BOOST_REQUIRE_EQUAL(r.exit_code, 0);
    const auto lines = r.outLines();
    BOOST_REQUIRE_EQUAL(lines.size(), 2u);
    const Json first = Json::parse(lines[0]), second = Json::parse(lines[1]);
    BOOST_CHECK_EQUAL(first.at("id"), 7);
    BOOST_CHECK_EQUAL(first.at("intersect"), false);
    BOOST_CHECK_EQUAL(first.at("status"), "decided");
    BOOST_CHECK_EQUAL(second.at("id"), "touch");
    if (algo != "fcl") {
      BOOST_CHECK(first.at("iterations").is_number_integer());
      // Exactly touching spheres (a non-unit quaternion, normalised) count as intersecting.
      BOOST_CHECK_EQUAL(second.at("intersect"), true);
    }
  }
  const Run r = runTool(quote(file.string()));
  BOOST_CHECK_EQUAL(r.out.substr(0, r.out.find('\n')),
                    R"({"id":7,"intersect":false,"status":"decided","iterations":)" +
                        Json::parse(r.outLines()[0]).at("iterations").dump() + "}");
}

// The parser must be correctly rounded: 0.30000000000000004 and 0.3 are neighbouring doubles,
// and two points given as those decimals are distinct; the same decimal twice is one point.
BOOST_AUTO_TEST_CASE(numbers_are_read_to_the_exact_double) {
  const std::string text =
      R"({"id":"same","a":{"type":"convex","vertices":[[0.30000000000000004,0,0]]},"b":{"type":"convex","vertices":[[0.30000000000000004,0,0]]}})"
      "\n"
      R"({"id":"next","a":{"type":"convex","vertices":[[0.30000000000000004,0,0]]},"b":{"type":"convex","vertices":[[0.3,0,0]]}})"
      "\n"
      R"({"id":"sum","a":{"type":"convex","vertices":[[0.1,0,0]],"pose":{"position":[0.2,0,0],"orientation":[0,0,0,1]}},"b":{"type":"convex","vertices":[[0.30000000000000004,0,0]]}})"
      "\n";
  const fs::path file = writeFile("rounding.jsonl", text);
  for (const std::string algo : {"dss", "hybrid"}) {
    const Run r = runTool("--mode exact --algo " + algo + " " + quote(file.string()));
    BOOST_REQUIRE_EQUAL(r.exit_code, 0);
    const auto lines = r.outLines();
    BOOST_REQUIRE_EQUAL(lines.size(), 3u);
    BOOST_CHECK_EQUAL(Json::parse(lines[0]).at("intersect"), true);
    BOOST_CHECK_EQUAL(Json::parse(lines[1]).at("intersect"), false);
    // A posed convex shape is posed once in double: fl(0.1 + 0.2) = 0.30000000000000004.
    BOOST_CHECK_EQUAL(Json::parse(lines[2]).at("intersect"), true);
  }
}

BOOST_AUTO_TEST_CASE(padding_is_a_distance_query) {
  // Unit spheres with centres 3 apart: distance 1.
  const std::string text =
      R"({"id":"p","a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1,"pose":{"position":[3,0,0],"orientation":[0,0,0,1]}}})"
      "\n"
      R"({"id":"q","a":{"type":"convex","vertices":[[0,0,0],[1,0,0],[0,1,0],[0,0,1]]},"b":{"type":"box","size":[2,2,2],"pose":{"position":[3,0,0],"orientation":[0,0,0,1]}}})"
      "\n";
  const fs::path file = writeFile("padding.jsonl", text);
  for (const std::string algo : {"dss", "gjk", "hybrid", "fcl"}) {
    for (const std::string mode : {"exact", "double", "float"}) {
      for (const auto& [padding, expect] :
           std::vector<std::pair<std::string, bool>>{{"0", false}, {"0.9", false}, {"1.1", true}}) {
        const Run r = runTool("--algo " + algo + " --mode " + mode + " --padding " + padding + " " +
                              quote(file.string()));
        BOOST_REQUIRE_EQUAL(r.exit_code, 0);
        for (const std::string& line : r.outLines())
          BOOST_CHECK_MESSAGE(Json::parse(line).at("intersect") == expect,
                              algo << " " << mode << " padding " << padding << ": " << line);
      }
    }
  }
}

// Convex shapes with more than 32 points take FCL's edge-walking support (faces from qhull);
// flat sets take the no-face fallback. Probes far from contact must agree across algorithms.
BOOST_AUTO_TEST_CASE(large_and_flat_convex_sets_agree_with_probes) {
  std::mt19937 rng(20240611);
  std::normal_distribution<double> normal;
  auto num = [](double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return std::string(buf);
  };
  // 80 points on the unit sphere (their hull contains the ball of radius 0.6 with this seed's
  // spread, far more than the probes need) and 40 points on the unit circle in z = 0.
  std::string ball = "[", disc = "[";
  for (int i = 0; i < 80; ++i) {
    const double x = normal(rng), y = normal(rng), z = normal(rng);
    const double n = std::sqrt(x * x + y * y + z * z);
    ball +=
        (i ? "," : "") + std::string("[") + num(x / n) + "," + num(y / n) + "," + num(z / n) + "]";
  }
  for (int i = 0; i < 40; ++i) {
    const double t = 2 * M_PI * i / 40;
    disc += (i ? "," : "") + std::string("[") + num(std::cos(t)) + "," + num(std::sin(t)) + ",0]";
  }
  ball += "]";
  disc += "]";
  const std::string pose = R"(,"pose":{"position":[0.25,-0.5,1],"orientation":[0.1,0.2,0.3,0.9]})";
  const Eigen::Quaterniond q = Eigen::Quaterniond(0.9, 0.1, 0.2, 0.3).normalized();
  std::string text;
  std::vector<bool> expect;
  int id = 0;
  for (int h = 0; h < 2; ++h) {
    for (int k = 0; k < 24; ++k) {
      // A probe sphere of radius 0.1 in a random direction of the hull's frame: centre at
      // distance 0.3 (deep inside) or 1.3 (outside, gap at least 0.2).
      const double x = normal(rng), y = normal(rng), z = h == 0 ? normal(rng) : 0.0;
      const double n = std::sqrt(x * x + y * y + z * z);
      const bool inside = k % 2 == 0;
      const double r = inside ? 0.3 : 1.3;
      const Eigen::Vector3d c =
          q * Eigen::Vector3d(x / n * r, y / n * r, z / n * r) + Eigen::Vector3d(0.25, -0.5, 1);
      text += R"({"id":)" + std::to_string(id++) + R"(,"a":{"type":"convex","vertices":)" +
              (h == 0 ? ball : disc) + pose +
              R"(},"b":{"type":"sphere","radius":0.1,"pose":{"position":[)" + num(c.x()) + "," +
              num(c.y()) + "," + num(c.z()) + R"(],"orientation":[0,0,0,1]}}})" + "\n";
      expect.push_back(inside);
    }
  }
  const fs::path file = writeFile("large_convex.jsonl", text);
  for (const std::string algo : {"dss", "gjk", "hybrid", "fcl"}) {
    const Run r = runTool("--algo " + algo + " " + quote(file.string()));
    BOOST_REQUIRE_EQUAL(r.exit_code, 0);
    const auto lines = r.outLines();
    BOOST_REQUIRE_EQUAL(lines.size(), expect.size());
    for (std::size_t i = 0; i < lines.size(); ++i)
      BOOST_CHECK_MESSAGE(Json::parse(lines[i]).at("intersect") == bool(expect[i]),
                          algo << ": " << lines[i]);
  }
}

BOOST_AUTO_TEST_SUITE_END()

// Input a reader must not trust: nesting that would overflow recursive code (200 000 nested
// arrays once crashed dss_pairs, the message dumping the value recursively), keys a shape does
// not have, keys given twice (nlohmann keeps the last one silently), and huge values that a
// message must not quote in full. Each is a `FILE:N:` error with exit code 2.
BOOST_AUTO_TEST_SUITE(dss_pairs_strict_input)

namespace {

struct StrictCase {
  const char* name;
  std::string bad_line;
  std::string message;  // the whole first stderr line after "FILE:3: "
};

void checkStrictCases(const std::vector<StrictCase>& cases) {
  for (const StrictCase& c : cases) {
    const fs::path file = writeFile(std::string(c.name) + ".jsonl",
                                    dss_pairs_input::kGood + "\n" + dss_pairs_input::kGood + "\n" +
                                        c.bad_line + "\n" + dss_pairs_input::kGood + "\n");
    const Run r = runTool(quote(file.string()));
    BOOST_CHECK_MESSAGE(r.exit_code == 2, c.name << ": exit " << r.exit_code);
    BOOST_CHECK_EQUAL(r.firstErrLine(), file.string() + ":3: " + c.message);
    BOOST_CHECK_MESSAGE(r.out.empty(), c.name << ": no answers before the error");
  }
}

std::string nestedArrays(std::size_t n) { return std::string(n, '[') + std::string(n, ']'); }

}  // namespace

// The reproducer: 200 000 nested arrays, alone on a line and as a shape.
BOOST_AUTO_TEST_CASE(deep_nesting_is_refused_before_parsing) {
  const std::string prefix = R"({"id":"x","a":)";
  checkStrictCases({
      {"deep_line", nestedArrays(200000),
       "column 65: arrays and objects nest deeper than the limit of 64 "
       "(PairsInputLimits::max_depth in tools/pairs_input.h)"},
      {"deep_shape", prefix + nestedArrays(200000) + R"(,"b":{"type":"sphere","radius":1}})",
       "column " + std::to_string(prefix.size() + 64) +
           ": arrays and objects nest deeper than the limit of 64 "
           "(PairsInputLimits::max_depth in tools/pairs_input.h)"},
      // Brackets inside strings do not nest.
      {"brackets_in_string",
       R"({"id":")" + std::string(100, '[') + R"(","a":{"type":"sphere","radius":1},"b":5})",
       "b: expected a shape object, got 5"},
  });
  // At the limit the line is parsed (and refused for what it is, not for its depth).
  checkStrictCases({{"depth_64", prefix + nestedArrays(63) + R"(,"b":{"type":"sphere"}})",
                     "a: expected a shape object, got [[[[...]]]]"}});
}

BOOST_AUTO_TEST_CASE(unknown_fields_are_errors) {
  checkStrictCases({
      {"unknown_top",
       R"({"id":"x","a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1},"c":1})",
       R"(pair: unknown field "c" (a pair has "id", "a", "b"))"},
      {"radius_on_box",
       R"({"id":"x","a":{"type":"box","size":[1,1,1],"radius":1},"b":{"type":"sphere","radius":1}})",
       R"(a: unknown field "radius" (a box has "type", "size", "pose"))"},
      {"misspelled_pose",
       R"({"id":"x","a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1,"Pose":{"position":[3,0,0],"orientation":[0,0,0,1]}}})",
       R"(b: unknown field "Pose" (a sphere has "type", "radius", "pose"))"},
      {"pose_field",
       R"({"id":"x","a":{"type":"cone","radius":1,"length":1,"pose":{"position":[0,0,0],"orientation":[0,0,0,1],"rotation":[0,0,0,1]}},"b":{"type":"sphere","radius":1}})",
       R"(a.pose: unknown field "rotation" (a pose has "position", "orientation"))"},
      {"convex_field",
       R"({"id":"x","a":{"type":"convex","vertices":[[0,0,0]],"faces":[]},"b":{"type":"sphere","radius":1}})",
       R"(a: unknown field "faces" (a convex shape has "type", "vertices", "pose"))"},
  });
}

BOOST_AUTO_TEST_CASE(duplicate_keys_are_errors) {
  checkStrictCases({
      {"duplicate_id",
       R"({"id":"x","id":"y","a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1}})",
       R"(duplicate key "id" in an object (each key may appear once))"},
      {"duplicate_radius",
       R"({"id":"x","a":{"type":"sphere","radius":1,"radius":2},"b":{"type":"sphere","radius":1}})",
       R"(duplicate key "radius" in an object (each key may appear once))"},
      {"duplicate_position",
       R"({"id":"x","a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1,"pose":{"position":[0,0,0],"orientation":[0,0,0,1],"position":[9,0,0]}}})",
       R"(duplicate key "position" in an object (each key may appear once))"},
  });
  // The same key in different objects is fine.
  const fs::path ok = writeFile("same_key_elsewhere.jsonl", dss_pairs_input::kGood + "\n");
  BOOST_CHECK_EQUAL(runTool(quote(ok.string())).exit_code, 0);
}

BOOST_AUTO_TEST_CASE(messages_quote_values_briefly) {
  std::string big = "[";
  for (int i = 0; i < 100000; ++i) big += (i ? ",1" : "1");
  big += "]";
  checkStrictCases({
      {"huge_id",
       R"({"id":)" + big + R"(,"a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1}})",
       // The first 60 characters of the array: "[1" and 29 ",1", then "...".
       "id: expected a string or a number, got [1" +
           [] {
             std::string s;
             for (int i = 0; i < 29; ++i) s += ",1";
             return s;
           }() +
           "..."},
      {"long_type",
       R"({"id":"x","a":{"type":")" + std::string(5000, 't') +
           R"("},"b":{"type":"sphere","radius":1}})",
       "a.type: unknown shape type \"" + std::string(59, 't') + "..."},
  });
}

BOOST_AUTO_TEST_SUITE_END()
