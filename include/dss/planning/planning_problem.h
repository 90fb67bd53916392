// A planning problem for OMPL: the collision model of a robot in a scene (checker_setup.h),
// the group's state space and its map to joint values, the space information, and OMPL
// validity checkers by name. Shared by dss_plan, dss_check and the tests.
#pragma once

#include <ompl/base/SpaceInformation.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "dss/checker/checker_setup.h"
#include "dss/planning/continuous_motion_validator.h"
#include "dss/planning/discrete_motion_validator.h"
#include "dss/planning/group_state_space.h"
#include "dss/planning/validity_checker.h"

namespace dss {

struct Problem {
  std::shared_ptr<const CollisionModel> model;
  std::shared_ptr<const GroupStateMap> map;
  ompl::base::SpaceInformationPtr si;
  std::string group;
  std::vector<std::string> warnings;
};

/// Builds the model for `scene` (may be empty) with the group, holding the joints outside it
/// at `start` (by name; falls back to the scene's robot state, then the default state).
Problem makeProblem(const LoadedRobot& robot, Scene scene, std::string group,
                    const std::map<std::string, double>& start, double prune_margin = 0.0);
/// The same with every option of the collision model.
Problem makeProblem(const LoadedRobot& robot, Scene scene, std::string group,
                    const std::map<std::string, double>& start,
                    const CollisionModelOptions& options);

/// An OMPL validity checker on a state checker by name; throws std::invalid_argument for an
/// unknown name.
std::shared_ptr<ValidityChecker> makeValidityChecker(const Problem& problem,
                                                     const CheckerConfig& config);

/// The discrete motion validator on the state checker of a validity checker of the problem
/// (set that validity checker on problem.si for the direct path: discrete_motion_validator.h).
/// `batched`: the vector motion validator, the same states decided in batches where the
/// checker proves them free (motionStatesFreeBatched in discrete_motion.h).
std::shared_ptr<DiscreteMotionValidator> makeDiscreteMotionValidator(const Problem& problem,
                                                                     const ValidityChecker& checker,
                                                                     bool batched = false);

/// The continuous motion validator on a DSS validity checker of the problem; throws
/// std::invalid_argument for another checker. `min_fraction`: see ContinuousMotionChecker.
std::shared_ptr<ContinuousMotionValidator> makeContinuousMotionValidator(
    const Problem& problem, const ValidityChecker& checker,
    double min_fraction = kDefaultMinFraction);

}  // namespace dss
