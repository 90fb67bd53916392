// DirectFirstPlanner: the straight motion from start to goal, then the wrapped planner.
#include "dss/planning/direct_first_planner.h"

#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/base/goals/GoalStates.h>
#include <ompl/geometric/PathGeometric.h>

#include <memory>
#include <stdexcept>
#include <utility>

namespace ob = ompl::base;

namespace dss {

namespace {
const ob::PlannerPtr& checkedInner(const ob::PlannerPtr& inner) {
  if (!inner) throw std::invalid_argument("DirectFirstPlanner: no planner to wrap");
  return inner;
}
}  // namespace

DirectFirstPlanner::DirectFirstPlanner(ob::PlannerPtr inner)
    : ob::Planner(checkedInner(inner)->getSpaceInformation(),
                  checkedInner(inner)->getName() + "+direct"),
      inner_(std::move(inner)) {
  specs_ = inner_->getSpecs();
  params_.include(inner_->params());
  plannerProgressProperties_ = inner_->getPlannerProgressProperties();
}

ob::PlannerStatus DirectFirstPlanner::solve(const ob::PlannerTerminationCondition& ptc) {
  last_direct_ = false;
  checkValidity();
  // The goal's states: a GoalStates lists them, a GoalState holds one; any other goal has none.
  const ob::Goal* goal = pdef_->getGoal().get();
  const auto* listed = dynamic_cast<const ob::GoalStates*>(goal);
  const auto* single = dynamic_cast<const ob::GoalState*>(goal);
  const std::size_t num_goals = listed ? listed->getStateCount() : single ? 1 : 0;
  auto goalState = [&](std::size_t g) { return listed ? listed->getState(g) : single->getState(); };
  for (unsigned i = 0; i < pdef_->getStartStateCount() && num_goals > 0 && !ptc(); ++i) {
    const ob::State* start = pdef_->getStartState(i);
    if (!si_->satisfiesBounds(start) || !si_->isValid(start)) continue;
    for (std::size_t g = 0; g < num_goals; ++g) {
      const ob::State* end = goalState(g);
      if (!si_->satisfiesBounds(end) || !si_->isValid(end) || !si_->checkMotion(start, end))
        continue;
      pdef_->addSolutionPath(std::make_shared<ompl::geometric::PathGeometric>(si_, start, end),
                             false, 0.0, getName());
      last_direct_ = true;
      return ob::PlannerStatus::EXACT_SOLUTION;
    }
  }
  return inner_->solve(ptc);
}

void DirectFirstPlanner::clear() {
  ob::Planner::clear();
  inner_->clear();
  last_direct_ = false;
}

void DirectFirstPlanner::setup() {
  ob::Planner::setup();
  if (!inner_->isSetup()) inner_->setup();
}

void DirectFirstPlanner::setProblemDefinition(const ob::ProblemDefinitionPtr& pdef) {
  ob::Planner::setProblemDefinition(pdef);
  inner_->setProblemDefinition(pdef);
}

void DirectFirstPlanner::getPlannerData(ob::PlannerData& data) const {
  inner_->getPlannerData(data);
}

}  // namespace dss
