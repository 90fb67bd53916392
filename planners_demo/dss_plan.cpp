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
#include <ompl/base/MotionValidator.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/goals/GoalStates.h>
#include <ompl/config.h>
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
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "benchmark_log.h"
#include "cli.h"
#include "dss/checker/contacts.h"
#include "dss/core/simd_path.h"
#include "dss/planning/continuous_motion_validator.h"
#include "dss/planning/planning_problem.h"
#include "dss/robot/joint_states_csv.h"
#include "dss/robot/multi_dof.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "mesh_cli.h"
#include "path_replay.h"
#include "render_html.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace fs = std::filesystem;

namespace {

const char* kUsage =
    "usage: dss_plan                         (our dss_arm7 in its shelf scene)\n"
    "       dss_plan --robot R.urdf [--srdf S.srdf] --scene SCENE --request REQUEST.yaml\n"
    "       dss_plan --robot R.urdf [--srdf S.srdf] --problems DIR\n"
    "       dss_plan --benchmark [--runs N] [--log FILE] [any of the above]\n"
    "       dss_plan --summarize FILE...      (the JSON lines of several runs, one summary)\n"
    "  options: --planner NAME (RRTConnect) --checker dss|fcl-hull|fcl-mesh (dss)\n"
    "           --motion discrete|continuous|ompl (discrete) --time SECONDS (10) --seed N (1)\n"
    "           --padding r --self-padding r --resolution f (OMPL's 0.01) --simplify\n"
    "           --check-time (report checking_time_s: two clock reads per state check)\n"
    "           --mode exact|double|float (dss arithmetic, exact) --max-iterations N (dss cap, "
    "64)\n"
    "           --motion: discrete checks OMPL's states at the resolution in an order that\n"
    "           finds collisions sooner (the same verdicts), ompl with OMPL's own validator,\n"
    "           continuous certifies the whole motion\n"
    "           --motion-min-fraction f (continuous: smallest sub-motion, 1/1024)\n"
    "           --workspace XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (bounds of planar and floating\n"
    "           joints' translation; default: the request's workspace_parameters)\n"
    "           --base-table-cells N (a planar base's table against the scene: at most about\n"
    "           N cells, 0 for none; default 65536)\n"
    "           --shard K/N (with --problems: every N-th problem in name order, from the K-th)\n"
    "           --path FILE (CSV of the solution: every joint; several problems:\n"
    "           FILE.<problem>.csv)\n"
    "           --render FILE.html (one self-contained page: the robot's collision geometry\n"
    "           replaying the path, drag to orbit, wheel to zoom; obstacles the checker pruned\n"
    "           greyed, states found invalid red; with the problem not solved, the approximate\n"
    "           path or else the straight start-goal motion; with several problems\n"
    "           FILE.<problem>.html)\n"
    "  --benchmark: one ompl::tools::Benchmark experiment per problem, one planner entry per\n"
    "           planner and checker, named PLANNER[CHECKER]; --planner and --checker take\n"
    "           comma lists (checkers: dss,fcl-hull by default); --runs N per entry (10);\n"
    "           --log FILE (dss_plan_benchmark.log; with several problems FILE.<problem>.log).\n"
    "           Load with: ompl_benchmark_statistics FILE... -d results.db (package ompl-demos)\n"
    "  planners: RRTConnect RRT RRTstar LazyRRT BiTRRT pRRT PRM PRMstar LazyPRM KPIECE1\n"
    "            BKPIECE1 LBKPIECE1 EST SBL pSBL\n"
    "  exit codes: 0 every problem solved; 1 runtime error (files, model); 2 usage error;\n"
    "           3 a problem not solved (stdout then has \"solved\":false)\n"
    "  robot meshes:\n";

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
  TimedChecker(const ob::SpaceInformationPtr& si, std::shared_ptr<dss::ValidityChecker> inner)
      : ob::StateValidityChecker(si), inner_(std::move(inner)) {}
  bool isValid(const ob::State* s) const override {
    const auto t0 = std::chrono::steady_clock::now();
    const bool v = inner_->isValid(s);
    ns_ +=
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0)
            .count();
    return v;
  }
  double seconds() const { return double(ns_.load()) * 1e-9; }
  void reset() { ns_ = 0; }

 private:
  std::shared_ptr<dss::ValidityChecker> inner_;
  mutable std::atomic<long long> ns_{0};
};

double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

struct Args {
  std::string robot, srdf, scene, request, problems, planner = "RRTConnect", checker = "dss",
                                                     motion = "discrete", path, render;
  double min_fraction = 1.0 / 1024.0;
  double time = 10.0, padding = 0.0, self_padding = 0.0, resolution = 0.0;
  unsigned long seed = 1;
  bool simplify = false;
  bool check_time = false;  // wrap the checker in TimedChecker (costs two clock reads per check)
  dss::MeshGeometryOptions meshes;
  bool demo = false;
  dss::Options dss_options;  // --mode, --max-iterations
  bool benchmark = false;
  unsigned runs = 10;
  std::string log = "dss_plan_benchmark.log";
  std::vector<std::string> planner_list, checker_list;  // --benchmark: comma lists
  long base_table_cells = -1;          // --base-table-cells (-1: the model's default)
  long shard_k = 0, shard_n = 0;       // --shard K/N (0: every problem)
  std::vector<std::string> summarize;  // --summarize FILE...
  std::vector<double> workspace;  // --workspace: min x, y, z, max x, y, z (empty: the request's)
};

// A comma list of names; an empty or repeated name is a usage error.
std::vector<std::string> splitList(const dss::cli::ArgCursor& cli, const std::string& option,
                                   const std::string& v) {
  std::vector<std::string> out;
  std::stringstream ss(v);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item.empty()) cli.error(option + ": empty name in list '" + v + "'");
    if (std::find(out.begin(), out.end(), item) != out.end())
      cli.error(option + ": '" + item + "' listed twice");
    out.push_back(item);
  }
  if (out.empty() || v.back() == ',') cli.error(option + ": empty name in list '" + v + "'");
  return out;
}

dss::CheckerConfig checkerConfig(const Args& a, const std::string& name) {
  dss::CheckerConfig cfg;
  cfg.checker = name;
  cfg.scene_padding = a.padding;
  cfg.self_padding = a.self_padding;
  cfg.dss_options = a.dss_options;
  return cfg;
}

// Why a state a checker finds invalid is: a value outside its bounds, or the pairs that
// collide there (exact DSS on the problem's model with the run's paddings; three named).
struct Why {
  std::string text;
  bool hull = false;  ///< a mesh checked as its convex hull is involved
  /// The text with a hint when a mesh hull is involved (for a person at the terminal).
  std::string withHint() const {
    return hull ? text +
                      " (meshes are checked as their convex hulls; for a concave link, "
                      "--meshes decomposed follows the mesh more closely)"
                : text;
  }
};

Why whyInvalid(const Args& a, const dss::Problem& p, const double* q) {
  dss::DssCheckerSettings set;
  set.scene_padding = a.padding;
  set.self_padding = a.self_padding;
  const dss::DssChecker dss_checker(p.model, set);
  const auto contacts = dss::contactsAt(dss_checker, q);
  if (!contacts) return {"a value is outside the model's bounds"};
  if (contacts->empty()) return {"no pair collides under exact DSS"};
  Why why;
  for (std::size_t k = 0; k < contacts->size(); ++k) {
    why.hull |= dss::involvesMeshHull(*p.model, (*contacts)[k]);
    if (k < 3) why.text += (k ? "; " : "") + dss::describeContact(*p.model, (*contacts)[k]);
  }
  if (contacts->size() > 3) why.text += "; and " + std::to_string(contacts->size() - 3) + " more";
  return why;
}

Why whyInvalid(const Args& a, const dss::Problem& p, const ob::State* s) {
  std::vector<double> q(p.model->robot().numActiveJoints());
  if (!p.map->toJoints(s, q.data())) return {"a value is not finite or outside its bounds"};
  return whyInvalid(a, p, q.data());
}

struct Outcome {
  bool solved = false;
  double time = 0.0;
};

struct ProblemFiles {
  std::string name, scene, request;
};

// One scene/request pair loaded: the model and state map, and the start and goal states.
struct LoadedProblem {
  dss::Problem p;
  std::vector<double> start;               // group values
  std::vector<std::vector<double>> goals;  // group values, one per goal constraint set
  dss::Scene scene;                        // --render: the scene as loaded, before pruning
};

LoadedProblem loadProblem(const Args& a, const dss::LoadedRobot& loaded_robot,
                          const ProblemFiles& files) {
  const dss::PlanRequest req = dss::loadPlanRequestYaml(files.request);
  // Planar and floating joints: their translation within --workspace, else the request's
  // workspace_parameters (as MoveIt bounds them).
  dss::LoadedRobot robot = loaded_robot;
  if (!a.workspace.empty())
    robot =
        dss::withWorkspace(robot, Eigen::Vector3d(a.workspace[0], a.workspace[1], a.workspace[2]),
                           Eigen::Vector3d(a.workspace[3], a.workspace[4], a.workspace[5]));
  else if (req.workspace)
    robot = dss::withWorkspace(robot, req.workspace->first, req.workspace->second);
  // Every stored warning reaches the user: the request's here, the scene's with the
  // problem's below, the robot's and the SRDF's once in run().
  for (const auto& w : req.warnings)
    std::cerr << "dss_plan: " << files.name << ": warning: " << w << "\n";
  dss::Scene scene = files.scene.empty() ? dss::Scene{} : dss::loadScene(files.scene);
  dss::Scene loaded = a.render.empty() ? dss::Scene{} : scene;
  std::map<std::string, double> start = req.startState();
  {
    std::vector<std::string> notes;
    for (const auto& [n, v] : dss::multiDofStateValues(*robot.model, req.start_multi_dof, &notes))
      start[n] = v;
    for (const auto& w : notes)
      std::cerr << "dss_plan: " << files.name << ": warning: " << files.request << ": " << w
                << "\n";
  }
  dss::CollisionModelOptions options;
  options.prune_margin = a.padding;
  if (a.base_table_cells >= 0) options.base_table_cells = std::size_t(a.base_table_cells);
  LoadedProblem lp{dss::makeProblem(robot, std::move(scene), req.group_name, start, options),
                   {},
                   {},
                   std::move(loaded)};
  const dss::Problem& p = lp.p;
  {
    std::set<std::string> movable(p.map->jointNames().begin(), p.map->jointNames().end());
    std::set<std::string> held;
    for (const auto& j : robot.model->joints) held.insert(j.name);
    for (const auto& n : robot.model->activeJointNames()) held.insert(n);
    held.insert("virtual_joint");
    dss::checkRequestJoints(req, movable, held);
  }
  for (const auto& w : p.warnings)
    std::cerr << "dss_plan: " << files.name << ": warning: " << w << "\n";
  lp.start = p.map->groupValues(start);
  for (std::size_t g = 0; g < req.goals.size(); ++g) {
    std::map<std::string, double> by_name = start;
    std::set<std::string> named;
    for (const auto& jc : req.goals[g].joint_constraints) {
      by_name[jc.joint_name] = jc.position;
      named.insert(jc.joint_name);
      if (jc.tolerance_above != 0.0 || jc.tolerance_below != 0.0)
        std::cerr << "dss_plan: " << files.name << ": note: goal tolerances of " << jc.joint_name
                  << " ignored (the goal is the constraint's position)\n";
    }
    // Group values the goal does not name keep their start values: said, not assumed silently.
    std::string kept;
    std::size_t num_kept = 0;
    for (const auto& n : p.map->jointNames())
      if (!named.count(n)) kept += (num_kept++ ? ", " : "") + n;
    if (num_kept > 0)
      std::cerr << "dss_plan: " << files.name << ": note: goal_constraints[" << g
                << "] does not name " << num_kept << " of the group's "
                << p.map->jointNames().size() << " values; they keep their start values: " << kept
                << "\n";
    lp.goals.push_back(p.map->groupValues(by_name));
  }
  if (req.goals.empty()) throw std::runtime_error(files.request + ": no goal constraints");
  return lp;
}

void setStartAndGoals(og::SimpleSetup& ss, const LoadedProblem& lp) {
  const auto& si = lp.p.si;
  ob::ScopedState<> s0(si->getStateSpace());
  lp.p.map->fromGroupValues(lp.start.data(), s0.get());
  ss.setStartState(s0);
  auto goal = std::make_shared<ob::GoalStates>(si);
  for (const auto& gv : lp.goals) {
    ob::ScopedState<> gs(si->getStateSpace());
    lp.p.map->fromGroupValues(gv.data(), gs.get());
    goal->addState(gs);
  }
  ss.setGoal(goal);
}

// FILE itself, or FILE.<problem>.EXT per problem (EXT: FILE's own, else `ext`).
std::string perProblemFile(const std::string& file, const std::string& ext, const ProblemFiles& f,
                           bool per_problem) {
  if (!per_problem) return file;
  std::string name = f.name;
  std::replace(name.begin(), name.end(), '/', '_');
  const fs::path p(file);
  const std::string e = p.has_extension() ? p.extension().string() : ext;
  return (p.parent_path() / (p.stem().string() + "." + name + e)).string();
}

// --render: the page for the solution path (approximate when not solved; without any path,
// the straight motion from the start to the first goal), every state along it checked.
void writeRender(const Args& a, const LoadedProblem& lp, const dss::ValidityChecker& checker,
                 og::SimpleSetup& ss, const ProblemFiles& files, const ob::PlannerStatus& status) {
  const ob::State* s0 = ss.getProblemDefinition()->getStartState(0);
  const ob::State* g0 = ss.getGoal()->as<ob::GoalStates>()->getState(0);
  const bool solved = status == ob::PlannerStatus::EXACT_SOLUTION;
  const bool have_path = ss.haveSolutionPath();
  const og::PathGeometric path =
      have_path ? ss.getSolutionPath() : og::PathGeometric(lp.p.si, s0, g0);
  const dss_plan::PathReplay replay = dss_plan::replayPath(lp.p, checker, path);
  dss_plan::RenderPage page;
  page.title = files.name;
  page.summary = std::string(solved ? "solved" : "NOT solved") + " (" + status.asString() +
                 "), planner " + a.planner + ", checker " + checker.checker().name() + ", motion " +
                 a.motion;
  page.solved = solved;
  page.path_kind = solved      ? "solution path"
                   : have_path ? "approximate path (the goal not reached)"
                               : "straight start-goal motion (no path found)";
  page.model = lp.p.model.get();
  page.loaded_scene = &lp.scene;
  page.replay = &replay;
  for (const auto& q : replay.span_first_q)
    page.span_causes.push_back(whyInvalid(a, lp.p, q.data()).text);
  const std::string file = perProblemFile(a.render, ".html", files, !a.problems.empty());
  std::vector<std::string> notes;
  dss_plan::writeRenderHtml(file, page, &notes);
  for (const auto& n : notes)
    std::cerr << "dss_plan: " << files.name << ": warning: render: " << n << "\n";
  std::cerr << "dss_plan: " << files.name << ": render written to " << file << " ("
            << replay.path_states << " path states, " << replay.samples_invalid << " of "
            << replay.samples_checked << " checked states invalid)\n";
}

Outcome solveOne(const Args& a, const dss::LoadedRobot& robot, const ProblemFiles& files,
                 bool readable) {
  // The problem's setup: its request and scene read, the workspace applied and the model built
  // (the robot is loaded once per process, before).
  const auto setup_begin = std::chrono::steady_clock::now();
  LoadedProblem lp = loadProblem(a, robot, files);
  dss::Problem& p = lp.p;
  auto checker = dss::makeValidityChecker(p, checkerConfig(a, a.checker));
  const double setup_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - setup_begin).count();

  og::SimpleSetup ss(p.si);
  // The planner sees our checker itself unless checking time is asked for: the clock reads of
  // TimedChecker cost about as much as a tenth of a DSS state check.
  std::shared_ptr<TimedChecker> timed;
  if (a.check_time) {
    timed = std::make_shared<TimedChecker>(p.si, checker);
    ss.setStateValidityChecker(timed);
  } else {
    ss.setStateValidityChecker(checker);
  }
  if (a.resolution > 0) p.si->setStateValidityCheckingResolution(a.resolution);
  auto factory = planners().find(a.planner);
  ss.setPlanner(factory->second(p.si));
  setStartAndGoals(ss, lp);
  const ob::State* s0 = ss.getProblemDefinition()->getStartState(0);
  const ob::State* g0 = ss.getGoal()->as<ob::GoalStates>()->getState(0);
  std::shared_ptr<dss::ContinuousMotionValidator> cmv;
  if (a.motion == "continuous") {
    cmv = dss::makeContinuousMotionValidator(p, *checker, a.min_fraction);
    p.si->setMotionValidator(cmv);
  } else if (a.motion == "discrete") {
    p.si->setMotionValidator(dss::makeDiscreteMotionValidator(p, *checker));
  }  // "ompl": the space information's default, OMPL's DiscreteMotionValidator
  ss.setup();
  const bool start_valid = checker->isValid(s0);
  const bool goal_valid = checker->isValid(g0);
  const Why start_why = start_valid ? Why{} : whyInvalid(a, p, s0);
  const Why goal_why = goal_valid ? Why{} : whyInvalid(a, p, g0);
  if (!start_valid)
    std::cerr << "dss_plan: " << files.name << ": warning: start state invalid under "
              << checker->checker().name() << ": " << start_why.withHint() << "\n";
  if (!goal_valid)
    std::cerr << "dss_plan: " << files.name << ": warning: goal state invalid under "
              << checker->checker().name() << ": " << goal_why.withHint() << "\n";
  const dss::CheckerCounters counters0 = checker->counters();
  if (timed) timed->reset();

  // The time limit is checked by the planner itself at every iteration (a clock read). OMPL's
  // solve(seconds) would, for limits of 1 s and more, start a timer thread per solve, and its
  // start and join cost about 1 ms of wall time here: more than many of these plans take.
  const double cpu0 = threadCpuSeconds();
  const ob::PlannerStatus status = ss.solve(ob::timedPlannerTerminationCondition(a.time));
  const double cpu = threadCpuSeconds() - cpu0;
  const bool solved = status == ob::PlannerStatus::EXACT_SOLUTION;
  const double t = ss.getLastPlanComputationTime();
  const dss::CheckerCounters counters = checker->counters() - counters0;
  const auto mv = p.si->getMotionValidator();
  double length = 0.0;
  std::size_t path_states = 0;
  if (solved) {
    if (a.simplify) ss.simplifySolution();
    length = ss.getSolutionPath().length();
    path_states = ss.getSolutionPath().getStateCount();
    if (!a.path.empty()) {
      // Every joint of the robot (the group's, the held ones and mimic joints), so that the
      // file reads back into dss_check --states.
      const std::string file = perProblemFile(a.path, ".csv", files, !a.problems.empty());
      std::ofstream out(file);
      if (!out) throw std::runtime_error(file + ": cannot write");
      std::vector<std::vector<double>> states;
      std::vector<double> q(p.model->robot().numActiveJoints());
      for (auto* s : ss.getSolutionPath().getStates()) {
        p.map->toJoints(s, q.data());
        states.push_back(q);
      }
      dss::writeJointStatesCsv(out, p.model->robot(), states);
      if (!out) throw std::runtime_error(file + ": cannot write");
    }
  }
  nlohmann::json j;
  j["problem"] = files.name;
  j["solved"] = solved;
  j["status"] = status.asString();
  j["planning_time_s"] = t;
  j["planning_cpu_s"] = cpu;  // this thread's CPU time: robust when the machine is shared
  j["setup_s"] = setup_s;
  j["path_length"] = length;
  j["path_states"] = path_states;
  j["validity_checks"] = counters.checks;
  j["colliding_states"] = counters.collisions;
  j["pair_tests"] = counters.pair_tests;
  j["motion_checks"] = dss::motionChecks(*mv);
  j["checker"] = checker->checker().name();
  j["simd"] = dss::simdPathName(dss::activeSimdPath());
  if (timed) j["checking_time_s"] = timed->seconds();
  j["planner"] = a.planner;
  j["motion"] = a.motion;
  j["seed"] = a.seed;
  j["cap_hits"] = counters.cap_hits;
  if (cmv) j["sub_motions"] = cmv->motionChecker().subMotions();
  if (!start_valid) j["start_invalid"] = true, j["start_invalid_why"] = start_why.text;
  if (!goal_valid) j["goal_invalid"] = true, j["goal_invalid_why"] = goal_why.text;
  std::cout << j.dump() << std::endl;
  if (readable) {
    std::cout << "\n"
              << robot.model->name << " in " << files.scene << "\n  " << p.model->summary()
              << "\n  group '" << p.group << "' (" << p.map->dimension() << " joints), planner "
              << a.planner << ", checker " << checker->checker().name() << "\n  "
              << (solved ? "solved" : "NOT solved") << " in " << t * 1e3 << " ms: path of "
              << path_states << " states, length " << length << " rad; " << counters.checks
              << " state checks (" << (counters.checks ? t * 1e6 / double(counters.checks) : 0.0)
              << " us of planning per check), " << j["motion_checks"] << " motion checks\n";
  }
  if (!a.render.empty()) writeRender(a, lp, *checker, ss, files, status);
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
      std::cerr << "dss_plan: " << e.path().string() << ": no " << req.filename().string()
                << ": skipped\n";
      continue;
    }
    const std::string stem = fs::path(dir).filename().string();
    out.push_back({(stem.empty() ? std::string() : stem + "/") + m[1].str(), e.path().string(),
                   req.string()});
  }
  std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.name < y.name; });
  if (out.empty()) throw std::runtime_error(dir + ": no sceneNNNN.yaml/requestNNNN.yaml pairs");
  return out;
}

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

// --benchmark: one OMPL Benchmark experiment per problem, written to its own log file.
int runBenchmark(const Args& a, const dss::LoadedRobot& robot,
                 const std::vector<ProblemFiles>& problems) {
  std::vector<std::string> logs;
  const bool tty = isatty(STDERR_FILENO) != 0;
  for (std::size_t k = 0; k < problems.size(); ++k) {
    const ProblemFiles& files = problems[k];
    LoadedProblem lp = loadProblem(a, robot, files);
    dss::Problem& p = lp.p;
    og::SimpleSetup ss(p.si);
    auto switching = std::make_shared<dss_plan::SwitchingChecker>(p.si);
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
    else if (a.motion == "discrete")  // states decided by the switching checker, in our order
      p.si->setMotionValidator(dss::makeDiscreteMotionValidator(p, *checkers.front()));
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
    for (const auto& planner : a.planner_list)
      for (const auto& c : checkers)
        b.addPlanner(std::make_shared<dss_plan::CheckerBoundPlanner>(planners().at(planner)(p.si),
                                                                     c, switching));
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
          dss_plan::addRunProperties(planner, run);
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

// "summary: solved S of N (planner, checker, seed); planning time median ..., p95 ...".
void printSummary(std::ostream& out, int solved, std::vector<double> times,
                  const std::string& planner, const std::string& checker, unsigned long seed) {
  std::sort(times.begin(), times.end());
  const double median = times[times.size() / 2];
  const double p95 =
      times[std::min(times.size() - 1, std::size_t(std::ceil(0.95 * times.size())) - 1)];
  const std::ios::fmtflags flags = out.flags();
  const std::streamsize precision = out.precision();
  out << "summary: solved " << solved << " of " << times.size() << " (" << planner << ", "
      << checker << ", seed " << seed << "); planning time median " << std::fixed
      << std::setprecision(3) << median * 1e3 << " ms, p95 " << p95 * 1e3 << " ms\n";
  out.flags(flags);
  out.precision(precision);
}

// --summarize: the JSON lines of several runs (shards of one problem folder, say) merged into
// the summary one run over all of them prints. Every line must come from the same planner,
// checker and seed, and name each problem once.
int summarizeRuns(const std::vector<std::string>& files) {
  std::vector<double> times;
  std::set<std::string> seen;
  int solved = 0;
  std::string planner, checker;
  unsigned long seed = 0;
  for (const std::string& file : files) {
    std::ifstream in(file);
    if (!in) throw std::runtime_error(file + ": cannot open");
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      const std::string where = file + ":" + std::to_string(n);
      nlohmann::json j;
      try {
        j = nlohmann::json::parse(line);
        const std::string problem = j.at("problem");
        const std::string p = j.at("planner"), c = j.at("checker");
        const unsigned long s = j.at("seed");
        if (seen.empty()) planner = p, checker = c, seed = s;
        if (p != planner || c != checker || s != seed)
          throw std::runtime_error("planner " + p + ", checker " + c + ", seed " +
                                   std::to_string(s) + " differ from the first line's (" + planner +
                                   ", " + checker + ", " + std::to_string(seed) + ")");
        if (!seen.insert(problem).second)
          throw std::runtime_error("problem '" + problem + "' appears twice");
        solved += j.at("solved").get<bool>();
        times.push_back(j.at("planning_time_s").get<double>());
      } catch (const std::exception& e) {
        throw std::runtime_error(where + ": " + e.what());
      }
    }
  }
  if (times.empty()) throw std::runtime_error("--summarize: no result lines in the files given");
  printSummary(std::cout, solved, times, planner, checker, seed);
  return solved == int(times.size()) ? 0 : 3;
}

int run(int argc, char** argv) {
  Args a;
  a.demo = argc == 1;
  bool checker_given = false, runs_given = false, log_given = false;
  const std::string usage = std::string(kUsage) + dss::cli::kMeshOptionsUsage;
  dss::cli::ArgCursor cli(argc, argv, "dss_plan", usage.c_str());
  while (cli.next()) {
    if (dss::cli::meshOption(cli, &a.meshes)) continue;
    if (cli.option("--robot"))
      a.robot = cli.value();
    else if (cli.option("--srdf"))
      a.srdf = cli.value();
    else if (cli.option("--scene"))
      a.scene = cli.value();
    else if (cli.option("--request"))
      a.request = cli.value();
    else if (cli.option("--problems"))
      a.problems = cli.value();
    else if (cli.option("--planner"))
      a.planner = cli.value();
    else if (cli.option("--checker"))
      a.checker = cli.value(), checker_given = true;
    else if (cli.option("--motion"))
      a.motion = cli.value();
    else if (cli.option("--time"))
      a.time = cli.number(1e-6, 1e6);
    else if (cli.option("--seed"))
      a.seed = static_cast<unsigned long>(cli.integer(0, 4294967295));
    else if (cli.option("--padding"))
      a.padding = cli.number(0.0, 1e3);
    else if (cli.option("--self-padding"))
      a.self_padding = cli.number(0.0, 1e3);
    else if (cli.option("--workspace"))
      a.workspace = cli.numbers(6);
    else if (cli.option("--base-table-cells"))
      a.base_table_cells = static_cast<long>(cli.integer(0, 1 << 24));
    else if (cli.option("--resolution"))
      a.resolution = cli.number(0.0, 1.0);
    else if (cli.option("--path"))
      a.path = cli.value();
    else if (cli.option("--render")) {
      a.render = cli.value();
      if (a.render.empty()) cli.error("--render: empty file name");
    } else if (cli.flag("--simplify"))
      a.simplify = true;
    else if (cli.flag("--check-time"))
      a.check_time = true;
    else if (cli.option("--motion-min-fraction"))
      a.min_fraction = cli.number(1e-12, 1.0);
    else if (cli.option("--mode")) {
      const std::string m = cli.value();
      if (m == "exact")
        a.dss_options.mode = dss::Mode::kExact;
      else if (m == "double")
        a.dss_options.mode = dss::Mode::kDouble;
      else if (m == "float")
        a.dss_options.mode = dss::Mode::kFloat;
      else
        cli.error("--mode: expected exact, double or float, got '" + m + "'");
    } else if (cli.option("--max-iterations"))
      a.dss_options.max_iterations = static_cast<int>(cli.integer(1, 1000000));
    else if (cli.flag("--benchmark"))
      a.benchmark = true;
    else if (cli.option("--runs"))
      a.runs = static_cast<unsigned>(cli.integer(1, 1000000)), runs_given = true;
    else if (cli.option("--log"))
      a.log = cli.value(), log_given = true;
    else if (cli.flag("--demo"))
      a.demo = true;
    else if (cli.option("--shard")) {
      const std::string v = cli.value();
      const auto slash = v.find('/');
      const auto k = dss::cli::parseInteger(v.substr(0, slash).c_str(), 1, 1000000);
      const auto n = slash == std::string::npos
                         ? std::nullopt
                         : dss::cli::parseInteger(v.substr(slash + 1).c_str(), 1, 1000000);
      if (!k || !n || *k > *n) cli.error("--shard: expected K/N with 1 <= K <= N, got '" + v + "'");
      a.shard_k = *k, a.shard_n = *n;
    } else if (cli.flag("--summarize"))
      a.summarize.push_back("");  // files follow as positionals
    else if (!a.summarize.empty() && cli.positional("FILE"))
      a.summarize.push_back(cli.value());
    else
      cli.unknown();
  }
  if (!a.summarize.empty()) {
    a.summarize.erase(a.summarize.begin());
    if (a.summarize.empty()) cli.error("--summarize needs the JSON-lines files of the runs");
    return summarizeRuns(a.summarize);
  }
  if (a.shard_n > 0 && a.problems.empty()) cli.error("--shard needs --problems");
  if (a.benchmark && !checker_given) a.checker = "dss,fcl-hull";
  a.planner_list = splitList(cli, "--planner", a.planner);
  a.checker_list = splitList(cli, "--checker", a.checker);
  for (const auto& pl : a.planner_list)
    if (planners().find(pl) == planners().end())
      cli.error("--planner: unknown planner '" + pl + "' (dss_plan --help lists them)");
  for (const auto& c : a.checker_list)
    if (c != "dss" && c != "fcl-hull" && c != "fcl-mesh")
      cli.error("--checker: unknown checker '" + c + "' (dss, fcl-hull, fcl-mesh)");
  if (a.motion != "discrete" && a.motion != "continuous" && a.motion != "ompl")
    cli.error("--motion: expected discrete, continuous or ompl, got '" + a.motion + "'");
  if (a.motion == "continuous" && a.checker_list != std::vector<std::string>{"dss"})
    cli.error("--motion continuous needs --checker dss (the continuous validator is DSS's)");
  if (!a.benchmark) {
    if (a.planner_list.size() > 1) cli.error("--planner: a list of planners needs --benchmark");
    if (a.checker_list.size() > 1) cli.error("--checker: a list of checkers needs --benchmark");
    if (runs_given) cli.error("--runs needs --benchmark");
    if (log_given) cli.error("--log needs --benchmark");
  } else {
    if (!a.path.empty()) cli.error("--path is not available with --benchmark");
    if (!a.render.empty()) cli.error("--render is not available with --benchmark");
    if (a.log.empty()) cli.error("--log: empty file name");
  }

  std::vector<ProblemFiles> problems;
  if (a.robot.empty() && a.request.empty() && a.problems.empty()) a.demo = true;  // options only
  if (a.demo && a.robot.empty()) {
    const std::string root = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
    a.robot = root + "/dss_arm7.urdf";
    a.srdf = root + "/dss_arm7.srdf";
    problems.push_back(
        {"dss_arm7/shelf", root + "/scenes/shelf.yaml", root + "/scenes/shelf_request.yaml"});
  } else {
    if (a.robot.empty()) cli.error("--robot is required");
    if (!a.problems.empty()) {
      problems = listProblems(a.problems);
      if (a.shard_n > 0) {
        // Every N-th problem in name order, from the K-th: shards 1..N cover every problem
        // once, whatever the machines they run on.
        std::vector<ProblemFiles> share;
        for (std::size_t k = 0; k < problems.size(); ++k)
          if (long(k % std::size_t(a.shard_n)) == a.shard_k - 1) share.push_back(problems[k]);
        problems = std::move(share);
        if (problems.empty()) {
          std::cerr << "dss_plan: shard " << a.shard_k << "/" << a.shard_n << " of " << a.problems
                    << " holds no problem\n";
          return 0;
        }
      }
    } else if (!a.request.empty())
      problems.push_back({fs::path(a.request).stem().string(), a.scene, a.request});
    else
      cli.error("--request or --problems is required");
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
      const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
      ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
      ompl::RNG::setSeed(a.seed);
      ompl::msg::setLogLevel(level);
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

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "dss_plan: " << e.what() << "\n";
    return 1;
  }
}
