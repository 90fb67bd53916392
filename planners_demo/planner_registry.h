// The OMPL geometric planners dss_plan runs, by name.
#pragma once

#include <ompl/base/Planner.h>

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace dss_plan {

using PlannerFactory =
    std::function<ompl::base::PlannerPtr(const ompl::base::SpaceInformationPtr&)>;

/// RRTConnect, RRT, RRTstar, LazyRRT, BiTRRT, pRRT, PRM, PRMstar, LazyPRM, KPIECE1, BKPIECE1,
/// LBKPIECE1, EST, SBL, pSBL.
const std::map<std::string, PlannerFactory>& planners();

/// Planner parameters as `--param NAME=VALUE` gives them, in the order given.
using PlannerParams = std::vector<std::pair<std::string, std::string>>;

/// Sets each parameter on `planner` through its OMPL parameter set. Throws
/// std::invalid_argument naming the planner and the parameter when the planner declares no
/// such parameter (the message lists those it declares) or rejects the value, and for a value
/// that reads as a number but is not finite (nan, inf).
void applyPlannerParams(ompl::base::Planner& planner, const PlannerParams& params);

/// Checks `params` against the planner `name` before any file is read: the planner is made on
/// a one-dimensional space and the parameters applied to it (errors as applyPlannerParams).
void checkPlannerParams(const std::string& name, const PlannerParams& params);

}  // namespace dss_plan
