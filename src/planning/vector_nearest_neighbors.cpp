// useVectorNearestNeighbors: VectorNearestNeighbors installed in OMPL's tree planners.
#include "dss/planning/vector_nearest_neighbors.h"

#include <ompl/geometric/planners/rrt/BiTRRT.h>
#include <ompl/geometric/planners/rrt/LazyRRT.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>

namespace dss {

unsigned& detail::pendingNearestDimension() {
  thread_local unsigned dim = 0;
  return dim;
}

namespace {
template <class P>
bool install(ompl::base::Planner* planner) {
  auto* p = dynamic_cast<P*>(planner);
  if (!p) return false;
  p->template setNearestNeighbors<VectorNearestNeighbors>();
  return true;
}
}  // namespace

bool useVectorNearestNeighbors(const ompl::base::PlannerPtr& planner) {
  namespace og = ompl::geometric;
  if (!planner || !planner->getSpaceInformation()) return false;
  const auto* rv = dynamic_cast<const ompl::base::RealVectorStateSpace*>(
      planner->getSpaceInformation()->getStateSpace().get());
  if (!rv || rv->getDimension() == 0) return false;
  unsigned& pending = detail::pendingNearestDimension();
  pending = rv->getDimension();
  bool done = false;
  try {
    done = install<og::RRTConnect>(planner.get()) || install<og::RRTstar>(planner.get()) ||
           install<og::RRT>(planner.get()) || install<og::LazyRRT>(planner.get()) ||
           install<og::BiTRRT>(planner.get());
  } catch (...) {
    pending = 0;
    throw;
  }
  pending = 0;
  return done;
}

}  // namespace dss
