// The planners dss_plan runs (see planner_registry.h).
#include "planner_registry.h"

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

}  // namespace dss_plan
