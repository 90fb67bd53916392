// dss_plan: joint-space motion planning with OMPL and the DSS (or FCL) validity checker.
//
// With no arguments it plans headless for our own 7-DOF arm (robots/dss_arm7) in its shelf
// scene and prints a readable summary. With --robot/--srdf/--scene/--request it solves one
// MotionBenchMaker-style problem; with --problems DIR every sceneNNNN.yaml/requestNNNN.yaml
// pair in DIR. stdout: one JSON object per problem; stderr: progress and a final summary.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <ctime>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>

#include <nlohmann/json.hpp>
#include <ompl/base/MotionValidator.h>
#include <ompl/base/goals/GoalStates.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/kpiece/BKPIECE1.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/kpiece/LBKPIECE1.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/rrt/BiTRRT.h>
#include <ompl/geometric/planners/rrt/LazyRRT.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/rrt/pRRT.h>
#include <ompl/geometric/planners/sbl/SBL.h>
#include <ompl/geometric/planners/sbl/pSBL.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "dss/planning/continuous_motion_validator.h"
#include "dss/planning/planning_problem.h"
#include "dss/scene/scene_loader.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace fs = std::filesystem;

namespace {

const char* kUsage =
    "usage: dss_plan                         (our dss_arm7 in its shelf scene)\n"
    "       dss_plan --robot R.urdf [--srdf S.srdf] --scene SCENE --request REQUEST.yaml\n"
    "       dss_plan --robot R.urdf [--srdf S.srdf] --problems DIR\n"
    "  options: --planner NAME (RRTConnect) --checker dss|fcl-hull|fcl-mesh (dss)\n"
    "           --motion discrete|continuous (discrete) --time SECONDS (10) --seed N (1)\n"
    "           --padding r --self-padding r --resolution f (OMPL's 0.01) --simplify\n"
    "           --motion-min-fraction f (continuous: smallest sub-motion, 1/1024)\n"
    "           --path FILE (CSV of the solution; with several problems FILE.<problem>.csv)\n"
    "  planners: RRTConnect RRT RRTstar LazyRRT BiTRRT pRRT PRM PRMstar LazyPRM KPIECE1\n"
    "            BKPIECE1 LBKPIECE1 EST SBL pSBL\n";

using PlannerFactory = std::function<ob::PlannerPtr(const ob::SpaceInformationPtr&)>;

const std::map<std::string, PlannerFactory>& planners() {
  static const std::map<std::string, PlannerFactory> m = {
      {"RRTConnect", [](auto si) { return std::make_shared<og::RRTConnect>(si); }},
      {"RRT", [](auto si) { return std::make_shared<og::RRT>(si); }},
      {"RRTstar", [](auto si) { return std::make_shared<og::RRTstar>(si); }},
      {"LazyRRT", [](auto si) { return std::make_shared<og::LazyRRT>(si); }},
      {"BiTRRT", [](auto si) { return std::make_shared<og::BiTRRT>(si); }},
      {"pRRT", [](auto si) { return std::make_shared<og::pRRT>(si); }},
      {"PRM", [](auto si) { return std::make_shared<og::PRM>(si); }},
      {"PRMstar", [](auto si) { return std::make_shared<og::PRMstar>(si); }},
      {"LazyPRM", [](auto si) { return std::make_shared<og::LazyPRM>(si); }},
      {"KPIECE1", [](auto si) { return std::make_shared<og::KPIECE1>(si); }},
      {"BKPIECE1", [](auto si) { return std::make_shared<og::BKPIECE1>(si); }},
      {"LBKPIECE1", [](auto si) { return std::make_shared<og::LBKPIECE1>(si); }},
      {"EST", [](auto si) { return std::make_shared<og::EST>(si); }},
      {"SBL", [](auto si) { return std::make_shared<og::SBL>(si); }},
      {"pSBL", [](auto si) { return std::make_shared<og::pSBL>(si); }},
  };
  return m;
}

// Wraps a checker and accumulates the wall time spent in isValid (for the per-problem report).
class TimedChecker : public ob::StateValidityChecker {
 public:
  TimedChecker(const ob::SpaceInformationPtr& si, std::shared_ptr<dss::ModelValidityChecker> inner)
      : ob::StateValidityChecker(si), inner_(std::move(inner)) {}
  bool isValid(const ob::State* s) const override {
    const auto t0 = std::chrono::steady_clock::now();
    const bool v = inner_->isValid(s);
    ns_ += std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count();
    return v;
  }
  double seconds() const { return double(ns_.load()) * 1e-9; }
  void reset() { ns_ = 0; }

 private:
  std::shared_ptr<dss::ModelValidityChecker> inner_;
  mutable std::atomic<long long> ns_{0};
};

double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

struct Args {
  std::string robot, srdf, scene, request, problems, planner = "RRTConnect", checker = "dss",
                                                     motion = "discrete", path;
  double min_fraction = 1.0 / 1024.0;
  double time = 10.0, padding = 0.0, self_padding = 0.0, resolution = 0.0;
  unsigned long seed = 1;
  bool simplify = false;
  bool demo = false;
};

struct Outcome {
  bool solved = false;
  double time = 0.0;
};

struct ProblemFiles {
  std::string name, scene, request;
};

Outcome solveOne(const Args& a, const dss::LoadedRobot& robot, const ProblemFiles& files, bool readable) {
  const dss::PlanRequest req = dss::loadPlanRequestYaml(files.request);
  dss::Scene scene = files.scene.empty() ? dss::Scene{} : dss::loadScene(files.scene);
  const std::map<std::string, double> start = req.startState();
  dss::Problem p = dss::makeProblem(robot, std::move(scene), req.group_name, start, a.padding);
  {
    std::set<std::string> movable(p.map->jointNames().begin(), p.map->jointNames().end());
    std::set<std::string> held;
    for (const auto& j : robot.model->joints) held.insert(j.name);
    held.insert("virtual_joint");
    dss::checkRequestJoints(req, movable, held);
  }
  for (const auto& w : p.warnings) std::cerr << "dss_plan: " << files.name << ": warning: " << w << "\n";

  dss::CheckerConfig cfg;
  cfg.checker = a.checker;
  cfg.scene_padding = a.padding;
  cfg.self_padding = a.self_padding;
  auto checker = dss::makeChecker(p, cfg);

  og::SimpleSetup ss(p.si);
  auto timed = std::make_shared<TimedChecker>(p.si, checker);
  ss.setStateValidityChecker(timed);
  if (a.resolution > 0) p.si->setStateValidityCheckingResolution(a.resolution);
  auto factory = planners().find(a.planner);
  ss.setPlanner(factory->second(p.si));

  ob::ScopedState<> s0(p.si->getStateSpace());
  const std::vector<double> g0 = p.map->groupValues(start);
  p.map->fromGroupValues(g0.data(), s0.get());
  ss.setStartState(s0);
  auto goal = std::make_shared<ob::GoalStates>(p.si);
  for (const auto& gc : req.goals) {
    std::map<std::string, double> by_name = start;
    for (const auto& jc : gc.joint_constraints) {
      by_name[jc.joint_name] = jc.position;
      if (jc.tolerance_above != 0.0 || jc.tolerance_below != 0.0)
        std::cerr << "dss_plan: " << files.name << ": note: goal tolerances of " << jc.joint_name
                  << " ignored (the goal is the constraint's position)\n";
    }
    ob::ScopedState<> gs(p.si->getStateSpace());
    const std::vector<double> gv = p.map->groupValues(by_name);
    p.map->fromGroupValues(gv.data(), gs.get());
    goal->addState(gs);
  }
  if (req.goals.empty()) throw std::runtime_error(files.request + ": no goal constraints");
  ss.setGoal(goal);
  std::shared_ptr<dss::ContinuousMotionValidator> cmv;
  if (a.motion == "continuous") {
    cmv = std::make_shared<dss::ContinuousMotionValidator>(
        p.si, std::dynamic_pointer_cast<dss::DssValidityChecker>(checker), a.min_fraction);
    p.si->setMotionValidator(cmv);
  }
  ss.setup();
  const bool start_valid = checker->isValid(s0.get());
  const bool goal_valid = checker->isValid(goal->getState(0));
  checker->resetCounters();
  timed->reset();

  const double cpu0 = threadCpuSeconds();
  const ob::PlannerStatus status = ss.solve(a.time);
  const double cpu = threadCpuSeconds() - cpu0;
  const bool solved = status == ob::PlannerStatus::EXACT_SOLUTION;
  const double t = ss.getLastPlanComputationTime();
  const auto counters = checker->counters();
  const auto mv = p.si->getMotionValidator();
  double length = 0.0;
  std::size_t path_states = 0;
  if (solved) {
    if (a.simplify) ss.simplifySolution();
    length = ss.getSolutionPath().length();
    path_states = ss.getSolutionPath().getStateCount();
    if (!a.path.empty()) {
      std::string file = a.path;
      if (!a.problems.empty()) file += "." + files.name + ".csv";
      std::ofstream out(file);
      if (!out) throw std::runtime_error(file + ": cannot write");
      const auto& names = p.map->jointNames();
      for (std::size_t i = 0; i < names.size(); ++i) out << (i ? "," : "") << names[i];
      out << "\n" << std::setprecision(17);
      std::vector<double> g(names.size());
      for (auto* s : ss.getSolutionPath().getStates()) {
        p.map->toGroupValues(s, g.data());
        for (std::size_t i = 0; i < g.size(); ++i) out << (i ? "," : "") << g[i];
        out << "\n";
      }
    }
  }
  nlohmann::json j;
  j["problem"] = files.name;
  j["solved"] = solved;
  j["status"] = status.asString();
  j["planning_time_s"] = t;
  j["planning_cpu_s"] = cpu;  // this thread's CPU time: robust when the machine is shared
  j["path_length"] = length;
  j["path_states"] = path_states;
  j["validity_checks"] = counters.checks;
  j["motion_checks"] = mv->getValidMotionCount() + mv->getInvalidMotionCount();
  j["checker"] = checker->name();
  j["checking_time_s"] = timed->seconds();
  j["planner"] = a.planner;
  j["motion"] = a.motion;
  j["cap_hits"] = counters.cap_hits;
  if (cmv) j["sub_motions"] = cmv->subMotions();
  if (!start_valid) j["start_invalid"] = true;
  if (!goal_valid) j["goal_invalid"] = true;
  std::cout << j.dump() << std::endl;
  if (readable) {
    std::cout << "\n" << robot.model->name << " in " << files.scene << "\n  "
              << p.model->summary() << "\n  group '" << p.group << "' (" << p.map->dimension()
              << " joints), planner " << a.planner << ", checker " << checker->name() << "\n  "
              << (solved ? "solved" : "NOT solved") << " in " << t * 1e3 << " ms: path of "
              << path_states << " states, length " << length << " rad; " << counters.checks
              << " state checks (" << (counters.checks ? t * 1e6 / double(counters.checks) : 0.0)
              << " us of planning per check), " << j["motion_checks"] << " motion checks\n";
  }
  return {solved, t};
}

std::vector<ProblemFiles> listProblems(const std::string& dir) {
  std::vector<ProblemFiles> out;
  const std::regex re("scene(\\d+)\\.yaml");
  if (!fs::is_directory(dir)) throw std::runtime_error(dir + ": not a directory");
  for (const auto& e : fs::directory_iterator(dir)) {
    std::smatch m;
    const std::string name = e.path().filename().string();
    if (!std::regex_match(name, m, re)) continue;
    const fs::path req = fs::path(dir) / ("request" + m[1].str() + ".yaml");
    if (!fs::exists(req)) {
      std::cerr << "dss_plan: " << e.path().string() << ": no " << req.filename().string() << ": skipped\n";
      continue;
    }
    const std::string stem = fs::path(dir).filename().string();
    out.push_back({(stem.empty() ? std::string() : stem + "/") + m[1].str(), e.path().string(), req.string()});
  }
  std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.name < y.name; });
  if (out.empty()) throw std::runtime_error(dir + ": no sceneNNNN.yaml/requestNNNN.yaml pairs");
  return out;
}

int run(int argc, char** argv) {
  Args a;
  a.demo = argc == 1;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(s + " needs a value");
      return argv[++i];
    };
    if (s == "--robot") a.robot = value();
    else if (s == "--srdf") a.srdf = value();
    else if (s == "--scene") a.scene = value();
    else if (s == "--request") a.request = value();
    else if (s == "--problems") a.problems = value();
    else if (s == "--planner") a.planner = value();
    else if (s == "--checker") a.checker = value();
    else if (s == "--motion") a.motion = value();
    else if (s == "--time") a.time = std::stod(value());
    else if (s == "--seed") a.seed = std::stoul(value());
    else if (s == "--padding") a.padding = std::stod(value());
    else if (s == "--self-padding") a.self_padding = std::stod(value());
    else if (s == "--resolution") a.resolution = std::stod(value());
    else if (s == "--path") a.path = value();
    else if (s == "--simplify") a.simplify = true;
    else if (s == "--motion-min-fraction") a.min_fraction = std::stod(value());
    else if (s == "--demo") a.demo = true;
    else if (s == "-h" || s == "--help") {
      std::cout << kUsage;
      return 0;
    } else throw std::invalid_argument("unknown argument '" + s + "'\n" + kUsage);
  }
  if (planners().find(a.planner) == planners().end())
    throw std::invalid_argument("unknown planner '" + a.planner + "'\n" + kUsage);
  if (a.motion == "continuous" && a.checker != "dss")
    throw std::invalid_argument("--motion continuous needs --checker dss");
  if (a.motion != "discrete" && a.motion != "continuous") throw std::invalid_argument("--motion must be discrete or continuous");
  if (a.checker != "dss" && a.checker != "fcl-hull" && a.checker != "fcl-mesh")
    throw std::invalid_argument("unknown checker '" + a.checker + "' (dss, fcl-hull, fcl-mesh)");

  std::vector<ProblemFiles> problems;
  if (a.robot.empty() && a.request.empty() && a.problems.empty()) a.demo = true;  // options only
  if (a.demo && a.robot.empty()) {
    const std::string root = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
    a.robot = root + "/dss_arm7.urdf";
    a.srdf = root + "/dss_arm7.srdf";
    problems.push_back({"dss_arm7/shelf", root + "/scenes/shelf.yaml", root + "/scenes/shelf_request.yaml"});
  } else {
    if (a.robot.empty()) throw std::invalid_argument(std::string("--robot is required\n") + kUsage);
    if (!a.problems.empty()) problems = listProblems(a.problems);
    else if (!a.request.empty())
      problems.push_back({fs::path(a.request).stem().string(), a.scene, a.request});
    else throw std::invalid_argument(std::string("--request or --problems is required\n") + kUsage);
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  ompl::RNG::setSeed(a.seed);
  const dss::LoadedRobot robot = dss::loadRobot(a.robot, a.srdf);

  std::vector<double> times;
  int solved = 0;
  for (std::size_t k = 0; k < problems.size(); ++k) {
    const Outcome o = solveOne(a, robot, problems[k], a.demo);
    solved += o.solved;
    times.push_back(o.time);
    if (problems.size() > 1)
      std::cerr << "[" << k + 1 << "/" << problems.size() << "] " << problems[k].name << " "
                << (o.solved ? "solved" : "FAILED") << " " << std::fixed << std::setprecision(2)
                << o.time * 1e3 << " ms" << std::defaultfloat << "\n";
  }
  std::sort(times.begin(), times.end());
  const double median = times[times.size() / 2];
  const double p95 = times[std::min(times.size() - 1, std::size_t(std::ceil(0.95 * times.size())) - 1)];
  std::ostream& sum = a.demo ? std::cout : std::cerr;
  sum << "summary: solved " << solved << " of " << problems.size() << " (" << a.planner << ", "
      << a.checker << ", seed " << a.seed << "); planning time median " << median * 1e3 << " ms, p95 "
      << p95 * 1e3 << " ms\n";
  return solved == int(problems.size()) ? 0 : 2;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "dss_plan: " << e.what() << "\n";
    return 1;
  }
}
