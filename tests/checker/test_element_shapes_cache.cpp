// The cache of element bounds (element_shapes_cache.h): the models of one robot in different
// scenes take every element's sphere, local box, inner balls and inner box from one entry, equal
// to computing them afresh; another robot object (even a copy) has its own entry, and the entry
// of a robot that is gone is dropped rather than handed to a robot at the same address.
#include <boost/test/unit_test.hpp>
#include <memory>

#include "dss/checker/checker_setup.h"
#include "dss/checker/element_shapes_cache.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "support/shared_data.h"

namespace {

const std::string kArm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";

// The model's elements hold exactly what computeElementShapes gives for their sources; returns
// the elements compared and counts those with inner shapes.
int requireFreshBounds(const dss::CollisionModel& m, int* with_inner) {
  int n = 0;
  for (const dss::CollisionModel::Element& e : m.elements()) {
    const dss::ElementShapes f = dss::computeElementShapes(*e.source);
    const std::string where = m.robot().links[std::size_t(e.link)].name;
    BOOST_TEST((e.center_L == f.center_L && e.radius == f.radius), where);
    BOOST_TEST((e.box_center_S == f.box_center_S && e.box_half == f.box_half), where);
    BOOST_TEST_REQUIRE(e.num_inner == f.num_inner, where);
    for (int b = 0; b < f.num_inner; ++b) BOOST_TEST((e.inner_S[b] == f.inner_S[b]), where);
    BOOST_TEST(e.has_inner_box == f.has_inner_box, where);
    if (f.has_inner_box)
      BOOST_TEST((e.inner_box_c == f.inner_box_c && e.inner_box_h == f.inner_box_h), where);
    *with_inner += f.num_inner > 0 || f.has_inner_box;
    ++n;
  }
  return n;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(element_shapes_cache)

BOOST_AUTO_TEST_CASE(models_of_one_robot_share_bounds_equal_to_fresh_ones) {
  const dss::LoadedRobot robot = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  const dss::PlanRequest req = dss::loadPlanRequestYaml(kArm + "/scenes/shelf_request.yaml");
  const auto first = dss::cachedElementShapes(robot.model);
  BOOST_TEST(dss::cachedElementShapes(robot.model) == first);  // the same entry
  std::size_t elements = 0;
  for (const dss::RobotLink& l : robot.model->links) elements += l.collisions.size();
  BOOST_TEST(first->size() == elements);
  int with_inner = 0;
  for (bool shelf : {true, false}) {
    const dss::ModelSetup s =
        dss::setupModel(robot, shelf ? dss::loadScene(kArm + "/scenes/shelf.yaml") : dss::Scene{},
                        req.group_name, req.startState());
    BOOST_TEST(requireFreshBounds(*s.model, &with_inner) > 0);
  }
  BOOST_TEST(with_inner > 0);
  BOOST_TEST(dss::cachedElementShapes(robot.model) == first);

  // A copy of the robot is another object: its own entry, with the same bounds.
  auto copy = std::make_shared<const dss::RobotModel>(*robot.model);
  const auto copied = dss::cachedElementShapes(copy);
  BOOST_TEST(copied != first);
  BOOST_REQUIRE(copied->size() == first->size());
  for (std::size_t k = 0; k < first->size(); ++k)
    BOOST_TEST(((*copied)[k].center_L == (*first)[k].center_L &&
                (*copied)[k].radius == (*first)[k].radius));
  // Once the copy is gone its entry is dropped at the next new robot, never handed on.
  copy.reset();
  auto another = std::make_shared<const dss::RobotModel>(*robot.model);
  const auto fresh = dss::cachedElementShapes(another);
  BOOST_TEST(fresh != copied);
  BOOST_TEST(copied.use_count() == 1);  // only this test holds it now
}

BOOST_AUTO_TEST_CASE(hull_links_of_a_shared_robot_take_fresh_bounds, DSS_NEEDS_SHARED) {
  const dss::LoadedRobot robot = dss::loadRobot(dss_test::sharedPath("robots/panda/panda.urdf"),
                                                dss_test::sharedPath("robots/panda/panda.srdf"));
  int with_inner = 0, compared = 0;
  for (int k = 0; k < 2; ++k)  // built, then from the cache
    compared += requireFreshBounds(*dss::setupModel(robot, dss::Scene{}, "panda_arm", {}).model,
                                   &with_inner);
  BOOST_TEST(compared >= 20);
  BOOST_TEST(with_inner >= 10);
}

BOOST_AUTO_TEST_SUITE_END()
