// dss_plan's problems: the scene and request files of each, read into a planning problem.
#pragma once

#include <ompl/geometric/SimpleSetup.h>

#include <string>
#include <vector>

#include "dss/planning/planning_problem.h"
#include "plan_options.h"

namespace dss_plan {

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

/// The problems the options name: the default one, every sceneNNNN.yaml/requestNNNN.yaml pair
/// of --problems (in name order; with --shard K/N every N-th from the K-th: possibly none), or
/// --scene/--request. Throws std::runtime_error for a folder without pairs.
std::vector<ProblemFiles> problemsOf(const Args& a);

/// Reads one problem's request and scene and builds its model, space and start and goal group
/// values; warnings and notes go to stderr. Throws std::runtime_error on a bad file.
LoadedProblem loadProblem(const Args& a, const dss::LoadedRobot& robot, const ProblemFiles& files);

/// The start state and the goal states (one per goal constraint set) of a loaded problem.
void setStartAndGoals(ompl::geometric::SimpleSetup& ss, const LoadedProblem& lp);

/// FILE itself, or FILE.<problem>.EXT per problem (EXT: FILE's own, else `ext`).
std::string perProblemFile(const std::string& file, const std::string& ext, const ProblemFiles& f,
                           bool per_problem);

}  // namespace dss_plan
