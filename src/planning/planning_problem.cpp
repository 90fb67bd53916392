// Planning problems for OMPL (see planning_problem.h).
#include "dss/planning/planning_problem.h"

#include <stdexcept>

namespace dss {

namespace {
// The problem around a model set up for it.
Problem fromSetup(const LoadedRobot& robot, ModelSetup setup) {
  Problem p;
  p.group = setup.group;
  p.warnings = std::move(setup.warnings);
  auto map = std::make_shared<const GroupStateMap>(robot.model, setup.group_active, setup.held);
  for (const auto& w : map->warnings) p.warnings.push_back(w);
  p.map = map;
  p.model = std::move(setup.model);
  p.si = std::make_shared<ompl::base::SpaceInformation>(map->space());
  return p;
}
}  // namespace

Problem makeProblem(const LoadedRobot& robot, Scene scene, std::string group,
                    const std::map<std::string, double>& start, double prune_margin) {
  return fromSetup(robot,
                   setupModel(robot, std::move(scene), std::move(group), start, prune_margin));
}

Problem makeProblem(const LoadedRobot& robot, Scene scene, std::string group,
                    const std::map<std::string, double>& start,
                    const CollisionModelOptions& options) {
  return fromSetup(robot, setupModel(robot, std::move(scene), std::move(group), start, options));
}

std::shared_ptr<ValidityChecker> makeValidityChecker(const Problem& p,
                                                     const CheckerConfig& config) {
  return std::make_shared<ValidityChecker>(p.si, makeStateChecker(p.model, config), p.map);
}

std::shared_ptr<DiscreteMotionValidator> makeDiscreteMotionValidator(const Problem& p,
                                                                     const ValidityChecker& checker,
                                                                     bool batched) {
  return std::make_shared<DiscreteMotionValidator>(
      p.si, std::make_shared<const DiscreteMotionChecker>(checker.checkerPtr(), batched), p.map);
}

std::shared_ptr<ContinuousMotionValidator> makeContinuousMotionValidator(
    const Problem& p, const ValidityChecker& checker, double min_fraction) {
  auto dss = std::dynamic_pointer_cast<const DssChecker>(checker.checkerPtr());
  if (!dss)
    throw std::invalid_argument("the continuous motion validator needs the dss checker, not " +
                                checker.checker().name());
  return std::make_shared<ContinuousMotionValidator>(
      p.si, std::make_shared<const ContinuousMotionChecker>(std::move(dss), min_fraction), p.map);
}

}  // namespace dss
