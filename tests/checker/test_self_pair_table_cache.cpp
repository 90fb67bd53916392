// The cache of self-pair tables (self_pair_table_cache.h): models of one robot in different
// scenes share their tables, and a shared table is exactly the one a fresh build gives (cell by
// cell); a different padding, a different held value or another robot object (even loaded from
// the same files) builds its own; entries of a robot that is gone are dropped; models built in
// parallel threads get the same tables. withWorkspace gives one bounded robot object per robot
// and box, so that the problems of one workspace share it and its tables.
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <thread>

#include "dss/checker/checker_setup.h"
#include "dss/checker/self_pair_table_cache.h"
#include "dss/robot/kinematics.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"

namespace {

const std::string kArm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";

struct Arm {
  dss::LoadedRobot robot = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  dss::PlanRequest req = dss::loadPlanRequestYaml(kArm + "/scenes/shelf_request.yaml");
  dss::ModelSetup setup(bool shelf) const {
    return dss::setupModel(robot,
                           shelf ? dss::loadScene(kArm + "/scenes/shelf.yaml") : dss::Scene{},
                           req.group_name, req.startState());
  }
};

// The same tables, cell for cell, on the same pairs.
void requireSameTables(const dss::CollisionModel& a, const dss::CollisionModel& b) {
  const auto& ta = a.selfTables().tables();
  const auto& tb = b.selfTables().tables();
  BOOST_REQUIRE_EQUAL(ta.size(), tb.size());
  for (std::size_t k = 0; k < ta.size(); ++k) {
    BOOST_TEST(ta[k].num_vars == tb[k].num_vars);
    BOOST_TEST(ta[k].var[0] == tb[k].var[0]);
    BOOST_TEST(ta[k].var[1] == tb[k].var[1]);
    BOOST_TEST((ta[k].cell_state == tb[k].cell_state), "table " << k);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(self_pair_table_cache)

BOOST_AUTO_TEST_CASE(models_of_one_robot_share_tables_equal_to_fresh_ones) {
  dss::clearSelfPairTableCache();
  const Arm arm;
  const auto s0 = dss::selfPairTableCacheStats();
  const dss::ModelSetup shelf = arm.setup(true);
  const auto s1 = dss::selfPairTableCacheStats();
  const std::size_t pairs = shelf.model->selfPairs().size();
  BOOST_TEST_MESSAGE("dss_arm7: " << shelf.model->summary());
  BOOST_REQUIRE(shelf.model->selfTables().size() > 0u);
  BOOST_TEST(s1.misses - s0.misses == pairs);  // each self pair looked up once
  BOOST_TEST(s1.hits == s0.hits);
  // Another scene: every table from the cache.
  const dss::ModelSetup empty = arm.setup(false);
  const auto s2 = dss::selfPairTableCacheStats();
  BOOST_TEST(s2.hits - s1.hits == empty.model->selfPairs().size());
  BOOST_TEST(s2.misses == s1.misses);
  requireSameTables(*shelf.model, *empty.model);
  // Built afresh (cache emptied): the same cells.
  dss::clearSelfPairTableCache();
  BOOST_TEST(dss::selfPairTableCacheStats().entries == 0u);
  const dss::ModelSetup fresh = arm.setup(false);
  BOOST_TEST(dss::selfPairTableCacheStats().misses - s2.misses == pairs);
  requireSameTables(*fresh.model, *empty.model);
}

BOOST_AUTO_TEST_CASE(padding_held_values_and_robot_objects_are_part_of_the_key) {
  dss::clearSelfPairTableCache();
  const Arm arm;
  const dss::ModelSetup base = arm.setup(false);
  const std::size_t pairs = base.model->selfPairs().size();
  auto build = [&](const dss::LoadedRobot& robot, std::vector<double> held, double padding) {
    dss::CollisionModelOptions o;
    o.self_table_padding = padding;
    return std::make_shared<dss::CollisionModel>(robot.model, &*robot.srdf, dss::Scene{},
                                                 base.group_active, std::move(held), o);
  };
  // Another padding: built again, with fewer free cells.
  auto s = dss::selfPairTableCacheStats();
  const auto padded = build(arm.robot, base.held, 0.02);
  BOOST_TEST(dss::selfPairTableCacheStats().misses - s.misses == pairs);
  std::size_t free0 = 0, free1 = 0;
  for (const auto& t : base.model->selfTables().tables()) free0 += t.num_free;
  for (const auto& t : padded->selfTables().tables()) free1 += t.num_free;
  BOOST_TEST(free1 < free0);
  // A held value changed (a joint outside the group, or else a group joint's held value): built
  // again.
  std::vector<double> held = base.held;
  held.back() += 0.01;
  s = dss::selfPairTableCacheStats();
  build(arm.robot, held, 0.0);
  BOOST_TEST(dss::selfPairTableCacheStats().misses - s.misses == pairs);
  // The same files loaded again: another robot object, built again.
  {
    const Arm again;
    s = dss::selfPairTableCacheStats();
    const dss::ModelSetup other = again.setup(false);
    BOOST_TEST(dss::selfPairTableCacheStats().misses - s.misses == pairs);
    requireSameTables(*base.model, *other.model);
  }
  // That robot is gone: its entries go at the next insertion.
  s = dss::selfPairTableCacheStats();
  build(arm.robot, base.held, 0.01);
  const auto after = dss::selfPairTableCacheStats();
  BOOST_TEST(after.entries == s.entries);  // the gone robot's entries dropped, as many added
  // The original key still hits.
  s = after;
  build(arm.robot, base.held, 0.0);
  BOOST_TEST(dss::selfPairTableCacheStats().hits - s.hits == pairs);
}

BOOST_AUTO_TEST_CASE(models_built_in_parallel_get_the_same_tables) {
  dss::clearSelfPairTableCache();
  const Arm arm;
  std::shared_ptr<const dss::CollisionModel> a, b;
  std::thread ta([&] { a = arm.setup(true).model; });
  std::thread tb([&] { b = arm.setup(false).model; });
  ta.join();
  tb.join();
  requireSameTables(*a, *b);
  dss::clearSelfPairTableCache();
  requireSameTables(*arm.setup(false).model, *a);
}

BOOST_AUTO_TEST_CASE(one_bounded_robot_per_robot_and_workspace) {
  const std::string dir = std::string(DSS_SOURCE_DIR) + "/robots/dss_mobile_base";
  const auto robot = dss::loadRobot(dir + "/dss_mobile_base.urdf", dir + "/dss_mobile_base.srdf");
  const Eigen::Vector3d lo(0, -0.7, 0), hi(9, 0.7, 2);
  const auto a = dss::withWorkspace(robot, lo, hi);
  const auto b = dss::withWorkspace(robot, lo, hi);
  BOOST_TEST(a.model != robot.model);
  BOOST_TEST(a.model == b.model);  // the same object
  const auto& names = a.model->activeJointNames();
  const auto x = std::find(names.begin(), names.end(), "base/x") - names.begin();
  const auto& joint = a.model->joints[a.model->active_joints[std::size_t(x)]];
  BOOST_TEST(joint.limits.lower == 0.0);
  BOOST_TEST(joint.limits.upper == 9.0);
  // Another box, or another robot object from the same files: another copy.
  BOOST_TEST(dss::withWorkspace(robot, lo, Eigen::Vector3d(8, 0.7, 2)).model != a.model);
  const auto again = dss::loadRobot(dir + "/dss_mobile_base.urdf", dir + "/dss_mobile_base.srdf");
  BOOST_TEST(dss::withWorkspace(again, lo, hi).model != a.model);
  // Models of two problems in that workspace: the second takes every table from the cache.
  dss::clearSelfPairTableCache();
  const auto m1 = dss::setupModel(a, dss::Scene{}, "whole_body", {});
  const auto s = dss::selfPairTableCacheStats();
  const auto m2 =
      dss::setupModel(dss::withWorkspace(robot, lo, hi), dss::Scene{}, "whole_body", {});
  BOOST_TEST(dss::selfPairTableCacheStats().hits - s.hits == m2.model->selfPairs().size());
  BOOST_TEST(dss::selfPairTableCacheStats().misses == s.misses);
  requireSameTables(*m1.model, *m2.model);
}

BOOST_AUTO_TEST_CASE(the_cache_holds_a_bounded_number_of_entries) {
  // A pair far apart in the chain (no table: more than two joints between the links) looked up
  // with a held value that changes every time: a new entry each time, never more than 4096.
  dss::clearSelfPairTableCache();
  const Arm arm;
  const dss::RobotModel& m = *arm.robot.model;
  const dss::Kinematics kin(m);
  dss::SelfPairSide a, b;
  for (std::size_t l = 0; l < m.links.size(); ++l)
    if (m.links[l].hasGeometry()) {
      dss::SelfPairSide& side = a.link < 0 ? a : b;
      side.link = int(l);
      side.elements.clear();
      for (const auto& e : m.links[l].collisions) side.elements.push_back(&e);
      side.radius = 1.0;
    }
  BOOST_REQUIRE(a.link >= 0 && b.link > a.link);
  std::vector<double> held(m.numActiveJoints(), 0.0);
  const std::vector<char> in_group(m.numActiveJoints(), 1);
  std::size_t most = 0;
  for (int i = 0; i < 4200; ++i) {
    held[0] = 1e-4 * i;
    BOOST_TEST(!dss::cachedSelfPairTable(arm.robot.model, kin, held, in_group, a, b, 64, 16, 0.0));
    most = std::max(most, dss::selfPairTableCacheStats().entries);
  }
  BOOST_TEST(most == 4096u);
  dss::clearSelfPairTableCache();
}

BOOST_AUTO_TEST_SUITE_END()
