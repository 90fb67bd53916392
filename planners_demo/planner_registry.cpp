// The planners dss_plan runs (see planner_registry.h).
#include "planner_registry.h"

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
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

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "quiet_ompl.h"

namespace dss_plan {

namespace og = ompl::geometric;

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

namespace {

// A value that strtod reads whole as a number that is not finite ("nan", "inf", "1e999").
bool nonFiniteNumber(const std::string& v) {
  if (v.empty()) return false;
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  return end == v.c_str() + v.size() && !std::isfinite(x);
}

}  // namespace

void applyPlannerParams(ompl::base::Planner& planner, const PlannerParams& params) {
  const QuietOmpl quiet;  // setParam logs its own error for a value it rejects
  for (const auto& [name, value] : params) {
    const std::string what = planner.getName() + " parameter '" + name + "'";
    if (!planner.params().hasParam(name)) {
      std::vector<std::string> names;
      planner.params().getParamNames(names);
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
      throw std::invalid_argument(planner.getName() + " has no parameter '" + name + "' (" +
                                  (list.empty() ? std::string("it has none") : "it has: " + list) +
                                  ")");
    }
    if (nonFiniteNumber(value))
      throw std::invalid_argument(what + ": '" + value + "' is not a finite number");
    bool set = false;
    try {  // OMPL throws for a number it cannot read, and returns false for other values
      set = planner.params().setParam(name, value);
    } catch (const std::exception&) {
    }
    if (!set) throw std::invalid_argument(what + ": value '" + value + "' rejected");
  }
}

void checkPlannerParams(const std::string& name, const PlannerParams& params) {
  if (params.empty()) return;
  auto space = std::make_shared<ompl::base::RealVectorStateSpace>(1);
  space->setBounds(0.0, 1.0);
  auto si = std::make_shared<ompl::base::SpaceInformation>(space);
  const ompl::base::PlannerPtr planner = planners().at(name)(si);
  applyPlannerParams(*planner, params);
}

}  // namespace dss_plan
