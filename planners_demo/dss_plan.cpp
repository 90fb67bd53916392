// dss_plan: joint-space motion planning with OMPL and the DSS (or FCL) validity checker.
//
// With no arguments it plans headless for our own 7-DOF arm (robots/dss_arm7) in its shelf
// scene and prints a readable summary. With --robot/--srdf/--scene/--request it solves one
// MotionBenchMaker-style problem; with --problems DIR every sceneNNNN.yaml/requestNNNN.yaml
// pair in DIR. stdout: one JSON object per problem; stderr: progress and a final summary.
// With --benchmark it runs ompl::tools::Benchmark instead (one experiment per problem, one
// planner entry per planner and checker, e.g. RRTConnect[dss] and RRTConnect[fcl-hull]) and
// writes OMPL benchmark logs for ompl_benchmark_statistics / Planner Arena (benchmark_log.h).
// With --render it also writes an HTML page replaying each path in 3-D (render_html.h).
//
// The pieces: plan_options.h (the command line), problem_files.h (the problems read),
// solve_one.h (one plan), run_benchmark.h (--benchmark), plan_summary.h (the summary line and
// --summarize), invalid_state.h (why a start or goal is invalid).
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <iomanip>
#include <iostream>

#include "plan_options.h"
#include "plan_summary.h"
#include "problem_files.h"
#include "quiet_ompl.h"
#include "run_benchmark.h"
#include "solve_one.h"

namespace dss_plan {
namespace {

int run(int argc, char** argv) {
  const Args a = parseArgs(argc, argv);
  if (!a.summarize.empty()) return summarizeRuns(a.summarize);
  const std::vector<ProblemFiles> problems = problemsOf(a);
  if (problems.empty()) {
    std::cerr << "dss_plan: shard " << a.shard_k << "/" << a.shard_n << " of " << a.problems
              << " holds no problem\n";
    return 0;
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  ompl::RNG::setSeed(a.seed);
  dss::LoadOptions load;
  load.meshes = a.meshes;
  const dss::LoadedRobot robot = dss::loadRobot(a.robot, a.srdf, load);
  for (const auto& w : robot.warnings()) std::cerr << "dss_plan: warning: " << w << "\n";
  if (a.benchmark) return runBenchmark(a, robot, problems);

  std::vector<double> times;
  int solved = 0;
  for (std::size_t k = 0; k < problems.size(); ++k) {
    // Each problem starts from the same seed, so that its result does not depend on which
    // problems ran before it (shards and one whole run agree). OMPL reseeds its seed
    // generator when asked again, and logs an error saying so: silenced.
    if (k > 0) {
      const QuietOmpl quiet;
      ompl::RNG::setSeed(a.seed);
    }
    const Outcome o = solveOne(a, robot, problems[k], a.demo);
    solved += o.solved;
    times.push_back(o.time);
    if (problems.size() > 1)
      std::cerr << "[" << k + 1 << "/" << problems.size() << "] " << problems[k].name << " "
                << (o.solved ? "solved" : "FAILED") << " " << std::fixed << std::setprecision(2)
                << o.time * 1e3 << " ms" << std::defaultfloat << "\n";
  }
  printSummary(a.demo ? std::cout : std::cerr, solved, times, a.planner, a.checker, a.seed);
  return solved == int(problems.size()) ? 0 : 3;
}

}  // namespace
}  // namespace dss_plan

int main(int argc, char** argv) {
  try {
    return dss_plan::run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "dss_plan: " << e.what() << "\n";
    return 1;
  }
}
