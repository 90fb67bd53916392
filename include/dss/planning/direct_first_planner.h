// A planner that tries the straight motion first: from each valid start state to each goal
// state, checked by the space information's motion validator; the first free one is the
// solution (a path of two states), and only when none is free does the wrapped planner run,
// on the same problem, with the same termination condition.
//
// OMPL's tree planners never try that motion themselves: a problem whose start sees its goal
// still grows both trees until they meet. Where the straight motion collides, the attempt
// costs the ends' checks and the motion's checks up to its first collision, on top of the plan.
//
// Only goals made of states are tried (ompl::base::GoalState, as SimpleSetup's
// setStartAndGoalStates makes, and ompl::base::GoalStates, with the goals derived from them);
// any other goal goes to the wrapped planner directly. Each end is checked (bounds, then the
// validity checker) before the motion, whose validator may take its first state as valid.
#pragma once

#include <ompl/base/Planner.h>

#include <string>

namespace dss {

class DirectFirstPlanner : public ompl::base::Planner {
 public:
  /// Named "<inner's name>+direct".
  explicit DirectFirstPlanner(ompl::base::PlannerPtr inner);

  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override;
  void clear() override;
  void setup() override;
  void setProblemDefinition(const ompl::base::ProblemDefinitionPtr& pdef) override;
  void getPlannerData(ompl::base::PlannerData& data) const override;

  const ompl::base::PlannerPtr& inner() const { return inner_; }
  /// Whether the last solve() ended with a straight motion (the wrapped planner did not run).
  bool lastWasDirect() const { return last_direct_; }

 private:
  ompl::base::PlannerPtr inner_;
  bool last_direct_ = false;
};

}  // namespace dss
