// Every URDF and SRDF in ../shared/robots loads with the counts its MANIFEST states.
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <iostream>
#include <map>
#include <random>

#include "dss/robot/collision_pairs.h"
#include "dss/robot/kinematics.h"
#include "dss/robot/srdf.h"
#include "dss/robot/urdf_loader.h"
#include "support/shared_data.h"

namespace fs = std::filesystem;

namespace {

const fs::path kRobots = fs::path(DSS_SHARED_DIR) / "robots";

bool haveShared() { return fs::is_directory(kRobots); }

struct Expected {
  std::string file;
  std::size_t links, joints, active;
  std::map<std::string, std::size_t> shapes;  // shape type name -> count
};

// From ../shared/robots/MANIFEST.md ("DOF" = active joints: non-fixed, non-mimic).
const std::vector<Expected> kExpected = {
    {"panda/panda", 12, 11, 8, {{"convex", 11}}},
    {"panda_vamp/panda", 13, 12, 7, {{"convex", 11}}},
    {"panda_vamp/panda_spherized", 13, 12, 7, {{"sphere", 59}}},
    {"panda_description/panda", 13, 12, 8, {{"convex", 9}, {"box", 8}}},
    {"panda_description/panda_collision", 13, 12, 8, {{"cylinder", 13}, {"sphere", 26}}},
    {"ur5_robotiq85/ur5", 22, 21, 6, {{"convex", 17}, {"box", 1}}},
    {"ur5_robotiq85/ur5_spherized", 22, 21, 6, {{"sphere", 40}}},
    {"ur_description/ur5_robot", 11, 10, 6, {{"convex", 7}, {"box", 1}}},
    {"iiwa_description/iiwa14_primitive_collision", 11, 10, 7, {{"cylinder", 6}, {"convex", 2}}},
    {"iiwa_description/iiwa14_spheres_collision", 11, 10, 7, {{"sphere", 12}, {"cylinder", 1}}},
};

std::map<std::string, std::size_t> shapeCounts(const dss::RobotModel& m) {
  std::map<std::string, std::size_t> out;
  for (const auto& l : m.links)
    for (const auto& c : l.collisions) ++out[dss::shapeTypeName(c.shape)];
  return out;
}

void checkModel(const dss::RobotModel& m, const Expected& e) {
  BOOST_TEST(m.links.size() == e.links);
  BOOST_TEST(m.joints.size() == e.joints);
  BOOST_TEST(m.numActiveJoints() == e.active);
  BOOST_TEST((shapeCounts(m) == e.shapes));
  // Parents precede children; every joint connects its parent and child.
  for (std::size_t l = 1; l < m.links.size(); ++l) BOOST_TEST(m.links[l].parent_link < int(l));
  for (const auto& j : m.joints) {
    BOOST_TEST(m.links[j.child_link].parent_joint == m.jointIndex(j.name));
    if (j.isMoving()) BOOST_TEST(std::abs(j.axis.norm() - 1.0) < 1e-15);
  }
}

dss::LoadOptions origOptions() {
  dss::LoadOptions o;
  // Package roots from the MANIFEST; `meshes` resolves relative to the URDF by itself.
  o.mesh_paths.package_dirs["robowflex_resources"] = kRobots.string();
  o.mesh_paths.package_dirs["example-robot-data"] = kRobots.parent_path().string();
  o.mesh_paths.package_dirs["drake_models"] = kRobots.string();
  o.mesh_paths.use_ros_package_path = false;
  o.mesh_paths.use_ament_prefix_path = false;
  return o;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(shared_robots)

BOOST_AUTO_TEST_CASE(every_urdf_loads_with_manifest_counts, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(haveShared());
  for (const auto& e : kExpected) {
    BOOST_TEST_CONTEXT(e.file) {
      const auto m = dss::loadUrdf((kRobots / (e.file + ".urdf")).string());
      checkModel(m, e);
    }
  }
}

BOOST_AUTO_TEST_CASE(every_orig_urdf_loads_with_package_roots, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(haveShared());
  for (const auto& e : kExpected) {
    BOOST_TEST_CONTEXT(e.file << ".orig") {
      const auto m = dss::loadUrdf((kRobots / (e.file + ".orig.urdf")).string(), origOptions());
      checkModel(m, e);
      // Same hulls as the rewritten file.
      const auto r = dss::loadUrdf((kRobots / (e.file + ".urdf")).string());
      for (std::size_t l = 0; l < m.links.size(); ++l)
        for (std::size_t c = 0; c < m.links[l].collisions.size(); ++c) {
          const auto* a = std::get_if<dss::ConvexHull>(&m.links[l].collisions[c].shape);
          const auto* b = std::get_if<dss::ConvexHull>(&r.links[l].collisions[c].shape);
          if (a && b) BOOST_TEST(a->points() == b->points());
        }
    }
  }
  // Without the package roots a package:// mesh is an error naming the link and the URI.
  dss::LoadOptions none;
  none.mesh_paths.use_ros_package_path = none.mesh_paths.use_ament_prefix_path = false;
  try {
    dss::loadUrdf((kRobots / "panda/panda.orig.urdf").string(), none);
    BOOST_FAIL("expected an exception");
  } catch (const std::runtime_error& ex) {
    const std::string msg = ex.what();
    BOOST_TEST(msg.find("panda_link0") != std::string::npos);
    BOOST_TEST(msg.find("package://robowflex_resources/panda/meshes/collision/link0.stl") !=
               std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(srdfs_load_and_match_their_urdfs, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(haveShared());
  struct S {
    std::string srdf;
    std::vector<std::string> urdfs;
    std::size_t disabled, groups, states;
  };
  const std::vector<S> cases = {
      {"panda/panda.srdf", {"panda/panda.urdf"}, 34, 3, 5},
      {"panda_vamp/panda.srdf",
       {"panda_vamp/panda.urdf", "panda_vamp/panda_spherized.urdf"},
       34,
       3,
       5},
      {"panda_description/panda.srdf",
       {"panda_description/panda.urdf", "panda_description/panda_collision.urdf"},
       35,
       3,
       1},
      {"ur5_robotiq85/ur5.srdf",
       {"ur5_robotiq85/ur5.urdf", "ur5_robotiq85/ur5_spherized.urdf"},
       88,
       2,
       3},
      {"ur_description/ur5.srdf", {"ur_description/ur5_robot.urdf"}, 10, 0, 0},
  };
  for (const auto& c : cases) {
    BOOST_TEST_CONTEXT(c.srdf) {
      const auto srdf = dss::loadSrdf((kRobots / c.srdf).string());
      BOOST_TEST(srdf.disabled_collisions.size() == c.disabled);
      BOOST_TEST(srdf.groups.size() == c.groups);
      BOOST_TEST(srdf.group_states.size() == c.states);
      for (const auto& u : c.urdfs) {
        const auto model = dss::loadUrdf((kRobots / u).string());
        const auto problems = dss::checkSrdfAgainstModel(model, srdf);
        for (const auto& p : problems) BOOST_TEST_MESSAGE(p);
        BOOST_TEST(problems.empty());
        const auto pairs = dss::selfCollisionPairs(model, &srdf);
        BOOST_TEST_MESSAGE(u << ": " << pairs.summary());
        BOOST_TEST(!pairs.pairs.empty());
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(panda_groups_and_states, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(haveShared());
  const auto model = dss::loadUrdf((kRobots / "panda/panda.urdf").string());
  const auto srdf = dss::loadSrdf((kRobots / "panda/panda.srdf").string());
  const auto arm = dss::groupActiveJoints(model, srdf, "panda_arm");
  BOOST_TEST(arm.size() == 7u);
  for (std::size_t i = 0; i < arm.size(); ++i)
    BOOST_TEST(model.joints[model.active_joints[arm[i]]].name ==
               "panda_joint" + std::to_string(i + 1));
  const auto hand = dss::groupActiveJoints(model, srdf, "hand");
  BOOST_TEST(hand.size() == 1u);  // finger_joint2 mimics finger_joint1
  BOOST_TEST(dss::groupActiveJoints(model, srdf, "panda_arm_hand").size() == 8u);
  const auto* ready = srdf.groupState("panda_arm", "ready");
  BOOST_REQUIRE(ready);
  BOOST_TEST(ready->values.size() == 7u);
  BOOST_TEST(ready->values[1].second == -0.785);
  BOOST_CHECK_THROW(dss::groupActiveJoints(model, srdf, "no_such_group"), std::runtime_error);
  // In VAMP's Panda the fingers are fixed: the hand group has no active joint.
  const auto vamp = dss::loadUrdf((kRobots / "panda_vamp/panda.urdf").string());
  BOOST_TEST(dss::groupActiveJoints(
                 vamp, dss::loadSrdf((kRobots / "panda_vamp/panda.srdf").string()), "hand")
                 .empty());
  BOOST_TEST(!vamp.warnings.empty());  // mimic tag on a fixed joint is reported
  // urdfdom's own warnings are kept (MANIFEST: material 'black' used before its definition).
  const auto ur5 = dss::loadUrdf((kRobots / "ur5_robotiq85/ur5.urdf").string());
  BOOST_TEST(ur5.warnings.size() == 1u);
  BOOST_TEST(ur5.warnings.at(0).find("material 'black' undefined") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(panda_fk_geometry_only_matches_all_links, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(haveShared());
  for (const char* f : {"panda/panda.urdf", "ur5_robotiq85/ur5.urdf",
                        "iiwa_description/iiwa14_primitive_collision.urdf"}) {
    const auto model = dss::loadUrdf((kRobots / f).string());
    const dss::Kinematics fast(model), all(model, true);
    BOOST_TEST(all.updatedLinks().size() == model.links.size());
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(-3, 3);
    std::vector<double> q(model.numActiveJoints());
    for (int s = 0; s < 100; ++s) {
      for (auto& v : q) v = u(rng);
      const auto A = fast.linkPoses(q), B = all.linkPoses(q);
      for (int l : fast.updatedLinks()) BOOST_TEST((A[l].matrix() - B[l].matrix()).norm() < 1e-14);
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()

#include "dss/robot/joint_state.h"

BOOST_AUTO_TEST_SUITE(shared_robot_states)

BOOST_AUTO_TEST_CASE(mbm_quirks_warn_not_refuse, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(haveShared());
  const auto panda = dss::loadUrdf((kRobots / "panda/panda.urdf").string());
  std::vector<std::string> notes;
  const auto q = dss::assembleState(
      panda,
      {{"panda_joint1", 0.1}, {"panda_finger_joint1", 0.065}, {"panda_finger_joint2", 0.065}},
      "mbm start", &notes);
  BOOST_TEST(notes.size() == 1u);  // the finger above 0.04; finger 2 agrees with its leader
  BOOST_TEST(q[panda.joints[panda.jointIndex("panda_finger_joint1")].active_index] == 0.065);
  const auto ur5 = dss::loadUrdf((kRobots / "ur5_robotiq85/ur5.urdf").string());
  notes.clear();
  dss::assembleState(ur5, {{"shoulder_pan_joint", 0.0}, {"robotiq_85_left_knuckle_joint", 0.0}},
                     "ur5 start", &notes);
  BOOST_TEST(notes.size() == 1u);  // a fixed Robotiq joint is ignored, with a note
}

BOOST_AUTO_TEST_SUITE_END()
