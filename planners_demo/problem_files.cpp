// dss_plan's problems (see problem_files.h).
#include "problem_files.h"

#include <ompl/base/goals/GoalStates.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <regex>
#include <set>

#include "dss/robot/multi_dof.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"

namespace dss_plan {

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace fs = std::filesystem;

namespace {

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

}  // namespace

std::vector<ProblemFiles> problemsOf(const Args& a) {
  if (a.default_problem) return {{"dss_arm7/shelf", a.scene, a.request}};
  if (a.problems.empty()) return {{fs::path(a.request).stem().string(), a.scene, a.request}};
  std::vector<ProblemFiles> problems = listProblems(a.problems);
  if (a.shard_n == 0) return problems;
  // Every N-th problem in name order, from the K-th: shards 1..N cover every problem once,
  // whatever the machines they run on.
  std::vector<ProblemFiles> share;
  for (std::size_t k = 0; k < problems.size(); ++k)
    if (long(k % std::size_t(a.shard_n)) == a.shard_k - 1) share.push_back(problems[k]);
  return share;
}

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
  dss::SceneLoadOptions scene_options;
  scene_options.max_mesh_parts = a.scene_mesh_parts;
  dss::Scene scene =
      files.scene.empty() ? dss::Scene{} : dss::loadScene(files.scene, scene_options);
  // The objects the start state holds are held throughout the plan, as MoveIt plans.
  scene.attached.insert(scene.attached.end(), req.start_attached.begin(), req.start_attached.end());
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

std::string perProblemFile(const std::string& file, const std::string& ext, const ProblemFiles& f,
                           bool per_problem) {
  if (!per_problem) return file;
  std::string name = f.name;
  std::replace(name.begin(), name.end(), '/', '_');
  const fs::path p(file);
  const std::string e = p.has_extension() ? p.extension().string() : ext;
  return (p.parent_path() / (p.stem().string() + "." + name + e)).string();
}

}  // namespace dss_plan
