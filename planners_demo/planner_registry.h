// The OMPL geometric planners dss_plan runs, by name.
#pragma once

#include <ompl/base/Planner.h>

#include <functional>
#include <map>
#include <string>

namespace dss_plan {

using PlannerFactory =
    std::function<ompl::base::PlannerPtr(const ompl::base::SpaceInformationPtr&)>;

/// RRTConnect, RRT, RRTstar, LazyRRT, BiTRRT, pRRT, PRM, PRMstar, LazyPRM, KPIECE1, BKPIECE1,
/// LBKPIECE1, EST, SBL, pSBL.
const std::map<std::string, PlannerFactory>& planners();

}  // namespace dss_plan
