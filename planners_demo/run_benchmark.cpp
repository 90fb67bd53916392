// dss_plan --benchmark (see run_benchmark.h).
#include "run_benchmark.h"

#include <ompl/base/goals/GoalStates.h>
#include <ompl/config.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/RandomNumbers.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "benchmark_log.h"
#include "dss/planning/direct_first_planner.h"
#include "dss/planning/vector_nearest_neighbors.h"
#include "invalid_state.h"
#include "planner_registry.h"

namespace dss_plan {

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

// Runs req.runCount rounds of one run per planner entry, so that the entries alternate
// (dss, fcl-hull, dss, fcl-hull, ...) and the load of a shared machine spreads evenly over
// them; the recorded experiment is the same as one Benchmark::benchmark call would record.
class InterleavedBenchmark : public ompl::tools::Benchmark {
 public:
  using ompl::tools::Benchmark::Benchmark;
  void benchmark(const Request& req) override {
    Request one = req;
    one.runCount = 1;
    CompleteExperiment all;
    for (unsigned r = 0; r < req.runCount; ++r) {
      ompl::tools::Benchmark::benchmark(one);
      if (r == 0) {
        all = exp_;
        continue;
      }
      for (std::size_t i = 0; i < all.planners.size(); ++i) {
        auto& to = all.planners[i];
        const auto& from = exp_.planners[i];
        to.runs.insert(to.runs.end(), from.runs.begin(), from.runs.end());
        to.runsProgressData.insert(to.runsProgressData.end(), from.runsProgressData.begin(),
                                   from.runsProgressData.end());
      }
      all.totalDuration += exp_.totalDuration;
    }
    all.runCount = req.runCount;
    exp_ = all;
  }
};

std::string logFileFor(const Args& a, const ProblemFiles& f, std::size_t problem_count) {
  return perProblemFile(a.log, ".log", f, problem_count > 1);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int runBenchmark(const Args& a, const dss::LoadedRobot& robot,
                 const std::vector<ProblemFiles>& problems) {
  std::vector<std::string> logs;
  const bool tty = isatty(STDERR_FILENO) != 0;
  for (std::size_t k = 0; k < problems.size(); ++k) {
    const ProblemFiles& files = problems[k];
    LoadedProblem lp = loadProblem(a, robot, files);
    dss::Problem& p = lp.p;
    og::SimpleSetup ss(p.si);
    auto switching = std::make_shared<SwitchingChecker>(p.si);
    ss.setStateValidityChecker(switching);
    if (a.resolution > 0) p.si->setStateValidityCheckingResolution(a.resolution);
    setStartAndGoals(ss, lp);

    std::vector<std::shared_ptr<dss::ValidityChecker>> checkers;
    for (const auto& name : a.checker_list)
      checkers.push_back(dss::makeValidityChecker(p, checkerConfig(a, name)));
    switching->setActive(checkers.front().get());
    if (a.motion == "continuous")
      p.si->setMotionValidator(
          dss::makeContinuousMotionValidator(p, *checkers.front(), a.min_fraction));
    else if (a.motion == "discrete" || a.motion == "vector")  // states decided by the
      // switching checker, in our order (vector: in batches where a dss checker decides)
      p.si->setMotionValidator(
          dss::makeDiscreteMotionValidator(p, *checkers.front(), a.motion == "vector"));
    // Each invalid state explained once (by exact DSS), whichever checkers refuse it.
    const auto* goals = ss.getGoal()->as<ob::GoalStates>();
    std::vector<const ob::State*> ends = {ss.getProblemDefinition()->getStartState(0)};
    for (std::size_t g = 0; g < goals->getStateCount(); ++g) ends.push_back(goals->getState(g));
    for (std::size_t e = 0; e < ends.size(); ++e) {
      std::string why;
      for (const auto& c : checkers) {
        if (c->isValid(ends[e])) continue;
        if (why.empty()) why = whyInvalid(a, p, ends[e]).withHint();
        std::cerr << "dss_plan: " << files.name << ": warning: "
                  << (e == 0 ? std::string("start state") : "goal state " + std::to_string(e - 1))
                  << " invalid under " << c->checker().name() << ": " << why << "\n";
      }
    }

    InterleavedBenchmark b(ss, files.name);
    b.addExperimentParameter("padding", "REAL", std::to_string(a.padding));
    b.addExperimentParameter("self_padding", "REAL", std::to_string(a.self_padding));
    b.addExperimentParameter("continuous_motion", "BOOLEAN", a.motion == "continuous" ? "1" : "0");
    b.addExperimentParameter("motion_validator", "TEXT", a.motion);
    b.addExperimentParameter("dss_mode", "TEXT", dss::toString(a.dss_options.mode));
    b.addExperimentParameter("dss_max_iterations", "INTEGER",
                             std::to_string(a.dss_options.max_iterations));
    b.addExperimentParameter("nearest", "TEXT", a.nearest);
    b.addExperimentParameter("direct", "BOOLEAN", a.direct ? "1" : "0");
    for (const auto& planner : a.planner_list)
      for (const auto& c : checkers) {
        ob::PlannerPtr inner = planners().at(planner)(p.si);
        applyPlannerParams(*inner, a.planner_params);
        if (a.nearest == "vector") dss::useVectorNearestNeighbors(inner);
        if (a.direct) inner = std::make_shared<dss::DirectFirstPlanner>(inner);
        b.addPlanner(std::make_shared<CheckerBoundPlanner>(inner, c, switching));
      }
    // Paired seeds: before run j of every entry, OMPL's seed generator restarts from seed + j, so
    // the sampler the planner allocates for that run draws the same states for every checker
    // (RRTConnect[dss] and RRTConnect[fcl-hull] then explore identically wherever the checkers
    // agree, and their columns compare the checkers alone). OMPL 1.5 reseeds its seed generator
    // on RNG::setSeed even after sampling started (it logs an error, silenced during a benchmark).
    std::map<const ob::Planner*, unsigned> run_index;
    b.setPreRunEvent([&](const ob::PlannerPtr& planner) {
      const unsigned j = run_index[planner.get()]++;
      ompl::RNG::setSeed(std::uint_fast32_t(std::max<unsigned long>(a.seed, 1) + j));
    });
    std::size_t done = 0;
    const std::size_t total = a.planner_list.size() * checkers.size() * a.runs;
    b.setPostRunEvent(
        [&](const ob::PlannerPtr& planner, ompl::tools::Benchmark::RunProperties& run) {
          addRunProperties(planner, run);
          ++done;
          if (tty && (done % checkers.size() == 0 || done == total))
            std::cerr << "\r[" << k + 1 << "/" << problems.size() << "] " << files.name << ": run "
                      << done << " of " << total << std::flush;
        });

    ompl::tools::Benchmark::Request req(a.time, 4096.0, a.runs, 0.05, /*displayProgress=*/false,
                                        /*saveConsoleOutput=*/false, /*simplify=*/true);
    b.benchmark(req);
    if (tty) std::cerr << "\r";
    std::cerr << "[" << k + 1 << "/" << problems.size() << "] " << files.name << ": " << total
              << " runs done\n";
    const std::string log = logFileFor(a, files, problems.size());
    {
      std::ostringstream text;
      b.saveResultsToStream(text);
      std::string body = text.str();
      // Debian's OMPL 1.5.2 defines OMPL_VERSION as "": write the version from its numeric
      // macros so that ompl_benchmark_statistics records "OMPL 1.5.2" (Planner Arena shows it).
      const std::string bare = "OMPL version \n";
      if (body.compare(0, bare.size(), bare) == 0)
        body.replace(0, bare.size(),
                     "OMPL version " + std::to_string(OMPL_MAJOR_VERSION) + "." +
                         std::to_string(OMPL_MINOR_VERSION) + "." +
                         std::to_string(OMPL_PATCH_VERSION) + "\n");
      std::ofstream out(log);
      out << body;
      out.close();
      if (!out) throw std::runtime_error(log + ": cannot write the benchmark log");
    }
    logs.push_back(log);

    for (const auto& pe : b.getRecordedExperimentData().planners) {
      std::vector<double> times, checks, checking;
      int solved = 0;
      for (const auto& run : pe.runs) {
        auto get = [&](const char* key) {
          auto it = run.find(key);
          return it == run.end() || it->second.empty() ? 0.0 : std::stod(it->second);
        };
        solved += get("solved BOOLEAN") != 0.0;
        times.push_back(get("time REAL"));
        checks.push_back(get("validity checks INTEGER"));
        checking.push_back(get("checking time REAL"));
      }
      nlohmann::json j;
      j["problem"] = files.name;
      j["planner"] = pe.name;
      j["runs"] = pe.runs.size();
      j["solved"] = solved;
      j["median_time_s"] = median(times);
      j["median_validity_checks"] = median(checks);
      j["median_checking_time_s"] = median(checking);
      j["log"] = log;
      std::cout << j.dump() << std::endl;
    }
  }
  std::cerr << "benchmark log" << (logs.size() > 1 ? "s" : "") << " written:";
  for (const auto& l : logs) std::cerr << " " << l;
  std::cerr << "\nload with: ompl_benchmark_statistics";
  for (const auto& l : logs) std::cerr << " " << l;
  std::cerr << " -d dss_plan_benchmark.db   (Debian package ompl-demos; then plannerarena.org)\n";
  return 0;
}

}  // namespace dss_plan
