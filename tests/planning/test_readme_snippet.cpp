// The README's OMPL example, compiled and run as it stands in README.md (tests/planning/
// CMakeLists.txt extracts it), so that the documentation cannot rot.
#include <ompl/base/goals/GoalState.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <boost/test/unit_test.hpp>

#include "includes.inc"  // the README block's #include lines

BOOST_AUTO_TEST_SUITE(readme_snippet)

BOOST_AUTO_TEST_CASE(plans_with_the_dss_checker) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7/";
#include "body.inc"  // the README block, below its #include lines
  BOOST_TEST(solved);
  // The waypoints are valid; between them the discrete validator only looked at OMPL's
  // resolution (the continuous validator covers the gaps: test_continuous_motion.cpp).
  const og::PathGeometric& path = ss.getSolutionPath();
  BOOST_TEST(path.getStateCount() >= 2u);
  for (std::size_t i = 0; i < path.getStateCount(); ++i)
    BOOST_TEST(checker->isValid(path.getState(i)));
}

BOOST_AUTO_TEST_SUITE_END()
