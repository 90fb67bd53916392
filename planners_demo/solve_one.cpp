// dss_plan's single solve (see solve_one.h).
#include "solve_one.h"

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/goals/GoalStates.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/SimpleSetup.h>

#include <chrono>
#include <ctime>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "dss/core/simd_path.h"
#include "dss/planning/continuous_motion_validator.h"
#include "dss/planning/direct_first_planner.h"
#include "dss/planning/discrete_motion_validator.h"
#include "dss/planning/vector_nearest_neighbors.h"
#include "dss/robot/joint_states_csv.h"
#include "invalid_state.h"
#include "path_replay.h"
#include "planner_registry.h"
#include "render_html.h"

namespace dss_plan {

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
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
  const PathReplay replay = replayPath(lp.p, checker, path);
  RenderPage page;
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
  writeRenderHtml(file, page, &notes);
  for (const auto& n : notes)
    std::cerr << "dss_plan: " << files.name << ": warning: render: " << n << "\n";
  std::cerr << "dss_plan: " << files.name << ": render written to " << file << " ("
            << replay.path_states << " path states, " << replay.samples_invalid << " of "
            << replay.samples_checked << " checked states invalid)\n";
}

}  // namespace

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
  ss.setStateValidityChecker(checker);
  if (a.resolution > 0) p.si->setStateValidityCheckingResolution(a.resolution);
  auto factory = planners().find(a.planner);
  const ob::PlannerPtr planner = factory->second(p.si);
  applyPlannerParams(*planner, a.planner_params);
  ss.setPlanner(a.direct ? std::make_shared<dss::DirectFirstPlanner>(planner) : planner);
  setStartAndGoals(ss, lp);
  const ob::State* s0 = ss.getProblemDefinition()->getStartState(0);
  const ob::State* g0 = ss.getGoal()->as<ob::GoalStates>()->getState(0);
  std::shared_ptr<dss::ContinuousMotionValidator> cmv;
  if (a.motion == "continuous") {
    cmv = dss::makeContinuousMotionValidator(p, *checker, a.min_fraction);
    p.si->setMotionValidator(cmv);
  } else if (a.motion == "discrete" || a.motion == "vector") {
    p.si->setMotionValidator(dss::makeDiscreteMotionValidator(p, *checker, a.motion == "vector"));
  }  // "ompl": the space information's default, OMPL's DiscreteMotionValidator
  const bool vector_nearest = a.nearest == "vector" && dss::useVectorNearestNeighbors(planner);
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
  // A problem whose start is invalid, or none of whose goal states is, has no solution: it is
  // not planned (OMPL's tree planners would spend the whole time limit sampling for a valid goal
  // state) and counts at the time limit in the summary, as a plan that ran out of time.
  const auto* goal_states = ss.getGoal()->as<ob::GoalStates>();
  bool some_goal_valid = goal_valid;
  for (std::size_t g = 1; g < goal_states->getStateCount() && !some_goal_valid; ++g)
    some_goal_valid = checker->isValid(goal_states->getState(g));
  const bool plan = start_valid && some_goal_valid;
  const dss::CheckerCounters counters0 = checker->counters();

  // The time limit is checked by the planner itself at every iteration (a clock read). OMPL's
  // solve(seconds) would, for limits of 1 s and more, start a timer thread per solve, and its
  // start and join cost about 1 ms of wall time here: more than many of these plans take.
  const double cpu0 = threadCpuSeconds();
  const ob::PlannerStatus status =
      plan ? ss.solve(ob::timedPlannerTerminationCondition(a.time))
           : ob::PlannerStatus(start_valid ? ob::PlannerStatus::INVALID_GOAL
                                           : ob::PlannerStatus::INVALID_START);
  const double cpu = threadCpuSeconds() - cpu0;
  const bool solved = status == ob::PlannerStatus::EXACT_SOLUTION;
  const double t = plan ? ss.getLastPlanComputationTime() : 0.0;
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
  j["batch_free_states"] = counters.batch_free;
  j["pair_tests"] = counters.pair_tests;
  j["motion_checks"] = dss::motionChecks(*mv);
  j["checker"] = checker->checker().name();
  j["simd"] = dss::simdPathName(dss::activeSimdPath());
  if (a.check_time) j["checking_time_s"] = double(counters.checking_ns) * 1e-9;
  j["planner"] = a.planner;
  if (!a.planner_params.empty()) {
    nlohmann::json pj = nlohmann::json::object();
    for (const auto& [name, value] : a.planner_params) pj[name] = value;
    j["planner_params"] = pj;
  }
  j["motion"] = a.motion;
  j["nearest"] = vector_nearest ? "vector" : "ompl";
  // Solved by the straight motion alone (the wrapped planner did not run).
  const bool direct_solved =
      a.direct && plan && ss.getPlanner()->as<dss::DirectFirstPlanner>()->lastWasDirect();
  if (a.direct) j["direct"] = direct_solved;
  j["seed"] = a.seed;
  j["cap_hits"] = counters.cap_hits;
  if (cmv) j["sub_motions"] = cmv->motionChecker().subMotions();
  if (const auto* dmv = dynamic_cast<const dss::DiscreteMotionValidator*>(mv.get())) {
    // Where the checks went: motions towards new states, and from a state just found free
    // towards a held one (RRTConnect's connections).
    auto kind = [dmv](dss::MotionOrder order) {
      const dss::MotionCounts c = dmv->counts(order);
      return nlohmann::json{{"motions", c.motions},
                            {"colliding", c.colliding},
                            {"exact_states", c.exact_states},
                            {"batch_free_states", c.batch_free_states}};
    };
    j["motions_to_new"] = kind(dss::MotionOrder::kEndFirst);
    j["motions_to_held"] = kind(dss::MotionOrder::kEndLast);
  }
  if (!start_valid) j["start_invalid"] = true, j["start_invalid_why"] = start_why.text;
  if (!goal_valid) j["goal_invalid"] = true, j["goal_invalid_why"] = goal_why.text;
  if (!plan) j["planned"] = false;
  std::cout << j.dump() << std::endl;
  if (readable) {
    std::cout << "\n"
              << robot.model->name << " in " << files.scene << "\n  " << p.model->summary()
              << "\n  group '" << p.group << "' (" << p.map->dimension() << " joints), planner "
              << a.planner << (a.direct ? " after the straight motion" : "") << ", checker "
              << checker->checker().name() << "\n  " << (solved ? "solved" : "NOT solved") << " in "
              << t * 1e3 << " ms: path of " << path_states << " states, length " << length
              << " rad; " << counters.checks << " state checks ("
              << (counters.checks ? t * 1e6 / double(counters.checks) : 0.0)
              << " us of planning per check), " << j["motion_checks"] << " motion checks"
              << (direct_solved ? " (the straight motion, free)" : "") << "\n";
  }
  if (!a.render.empty()) writeRender(a, lp, *checker, ss, files, status);
  return {solved, plan ? t : a.time};
}

}  // namespace dss_plan
