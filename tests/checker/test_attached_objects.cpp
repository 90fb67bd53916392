// Objects the robot holds (a PlanningScene's robot_state.attached_collision_objects): read from
// the scene, made links of the robot by setupModel, they collide with the scene and with the
// robot's links except their touch links, under every checker; placed alike whatever frame
// the file gives them in; a bad attachment is an error naming the file, the line and the object.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <random>

#include "dss/checker/checker_setup.h"
#include "dss/checker/contacts.h"
#include "dss/robot/srdf.h"
#include "dss/robot/urdf_loader.h"
#include "dss/scene/planning_scene_yaml.h"
#include "dss/scene/scene_loader.h"
#include "support/checker_fixtures.h"
#include "support/thrown_message.h"

namespace {

constexpr double kPi = 3.14159265358979323846;

// base --j1 (z, at height 0.3)--> l1 (a bar along x to 0.6) --j2 (z, at x 0.6)--> l2 (a bar
// along x to 0.3).
const char* const kUrdf = R"(<robot name="holder">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="l1"><collision><origin xyz="0.3 0 0"/><geometry><box size="0.6 0.04 0.04"/></geometry></collision></link>
  <link name="l2"><collision><origin xyz="0.15 0 0"/><geometry><box size="0.3 0.04 0.04"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.3"/>
    <axis xyz="0 0 1"/><limit lower="-3.2" upper="3.2" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0.6 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-3.2" upper="3.2" effort="1" velocity="1"/></joint>
</robot>
)";

const char* const kSrdf = R"(<robot name="holder">
  <group name="arm"><joint name="j1"/><joint name="j2"/></group>
  <disable_collisions link1="base" link2="l1" reason="Adjacent"/>
  <disable_collisions link1="l1" link2="l2" reason="Adjacent"/>
</robot>
)";

dss::LoadedRobot holder() {
  dss::LoadedRobot r;
  r.model = std::make_shared<const dss::RobotModel>(dss::loadUrdfString(kUrdf, "holder.urdf", "."));
  r.srdf = dss::parseSrdf(kSrdf, "holder.srdf");
  return r;
}

// A post that only the rod reaches at j1 = 0: x in [0.4, 0.5], y in [0.11, 0.21], z about 0.3.
const std::string kWorld = R"(world:
  collision_objects:
    - id: post
      primitives: [{type: box, dimensions: [0.1, 0.1, 0.1]}]
      primitive_poses: [{position: [0.45, 0.16, 0.3], orientation: [0, 0, 0, 1]}]
)";

// The rod held by l1: x in [0.25, 0.65], y in [0.08, 0.12] of l1's frame, given in `frame` at
// `pose`; with the robot's saved state `state`.
std::string sceneWith(const std::string& frame, const std::string& pose, const std::string& touch,
                      const std::string& state = "j1: 0") {
  const std::string j1 = state.substr(4);
  return kWorld + "robot_state:\n  joint_state: {name: [j1, j2], position: [" + j1 +
         ", 0]}\n  attached_collision_objects:\n    - link_name: l1\n      touch_links: [" + touch +
         "]\n      object:\n        id: rod\n        header: {frame_id: " + frame +
         "}\n        primitives: [{type: box, dimensions: [0.4, 0.04, 0.04]}]\n"
         "        primitive_poses: [" +
         pose + "]\n";
}

const std::string kRodInL1 = "{position: [0.45, 0.1, 0], orientation: [0, 0, 0, 1]}";

dss::ModelSetup setup(const std::string& yaml) {
  return dss::setupModel(holder(), dss::parsePlanningSceneYaml(yaml, "held.yaml"), "arm", {});
}

bool collides(const dss::ModelSetup& s, const std::string& checker, double j1, double j2) {
  dss::CheckerConfig config;
  config.checker = checker;
  const auto c = dss::makeStateChecker(s.model, config);
  const double q[2] = {j1, j2};
  return c->collides(q);
}

// n random group states of the model: dss and fcl-hull give the same verdict on each. The
// colliding states, and per name of `names` the contacts (by exact DSS) that name it.
struct Agreement {
  int colliding = 0;
  std::vector<int> found;
};
Agreement agreeWithFcl(const std::shared_ptr<const dss::CollisionModel>& model, int n,
                       unsigned seed, const std::vector<std::string>& names) {
  dss::DssChecker c(model, {});
  dss::CheckerConfig fcl;
  fcl.checker = "fcl-hull";
  const auto f = dss::makeStateChecker(model, fcl);
  std::mt19937_64 rng(seed);
  Agreement out;
  out.found.assign(names.size(), 0);
  for (int k = 0; k < n; ++k) {
    const std::vector<double> q = dss_test::randomGroupState(*model, rng);
    const bool hit = c.collides(q.data());
    BOOST_TEST(hit == f->collides(q.data()), "state " << k);
    out.colliding += hit;
    if (!hit) continue;
    const auto contacts = dss::contactsAt(c, q.data());
    BOOST_REQUIRE(contacts.has_value());
    for (const dss::Contact& x : *contacts) {
      const std::string d = dss::describeContact(c.model(), x);
      for (std::size_t i = 0; i < names.size(); ++i)
        out.found[i] += d.find(names[i]) != std::string::npos;
    }
  }
  return out;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(attached_objects)

BOOST_AUTO_TEST_CASE(the_reader_keeps_link_touch_links_and_parts) {
  const dss::Scene s = dss::parsePlanningSceneYaml(sceneWith("l1", kRodInL1, "l2"), "held.yaml");
  BOOST_TEST(s.warnings.empty());
  BOOST_TEST(s.obstacles.size() == 1u);  // the post; the rod is not a world obstacle
  BOOST_REQUIRE(s.attached.size() == 1u);
  const dss::AttachedObject& a = s.attached[0];
  BOOST_TEST(a.id == "rod");
  BOOST_TEST(a.link == "l1");
  BOOST_TEST(a.touch_links == std::vector<std::string>{"l2"});
  BOOST_REQUIRE(a.parts.size() == 1u);
  BOOST_TEST(a.parts[0].frame_id == "l1");
  BOOST_TEST((a.parts[0].X_FO.translation() - Eigen::Vector3d(0.45, 0.1, 0)).norm() == 0.0);
  BOOST_TEST(a.at.rfind("held.yaml:", 0) == 0u, a.at);
}

BOOST_AUTO_TEST_CASE(the_held_object_collides_with_the_scene) {
  for (const std::string checker : {"dss", "fcl-hull", "fcl-mesh"}) {
    BOOST_TEST_CONTEXT(checker) {
      const dss::ModelSetup held = setup(sceneWith("l1", kRodInL1, "l2"));
      const dss::ModelSetup empty = setup(kWorld);
      // j1 = 0: the rod is in the post; the arm alone is 0.09 away from it.
      BOOST_TEST(collides(held, checker, 0.0, 0.0));
      BOOST_TEST(!collides(empty, checker, 0.0, 0.0));
      // Turned away, nothing touches.
      BOOST_TEST(!collides(held, checker, kPi, 0.0));
      BOOST_TEST(!collides(held, checker, -0.5, 0.0));
    }
  }
  const dss::ModelSetup held = setup(sceneWith("l1", kRodInL1, "l2"));
  dss::DssChecker c(held.model, {});
  const double q[2] = {0.0, 0.0};
  const auto contacts = dss::contactsAt(c, q);
  BOOST_REQUIRE(contacts.has_value());
  BOOST_REQUIRE(contacts->size() == 1u);
  const std::string text = dss::describeContact(c.model(), contacts->front());
  BOOST_TEST(text == "attached object 'rod' on link l1 with scene object 'post'", text);
}

BOOST_AUTO_TEST_CASE(touch_links_may_touch_it_the_other_links_may_not) {
  // j2 = pi/2 folds l2 across the rod (l2 along y from x = 0.6; the rod reaches x = 0.65).
  const double j1 = kPi;  // away from the post
  for (const std::string checker : {"dss", "fcl-hull"}) {
    BOOST_TEST_CONTEXT(checker) {
      BOOST_TEST(collides(setup(sceneWith("l1", kRodInL1, "")), checker, j1, kPi / 2));
      BOOST_TEST(!collides(setup(sceneWith("l1", kRodInL1, "l2")), checker, j1, kPi / 2));
      // Folded the other way, l2 misses the rod.
      BOOST_TEST(!collides(setup(sceneWith("l1", kRodInL1, "")), checker, j1, -kPi / 2));
    }
  }
  // The holding link may always touch it (MoveIt's rule): a rod through l1 is no collision.
  const std::string through = "{position: [0.3, 0, 0], orientation: [0, 0, 0, 1]}";
  BOOST_TEST(!collides(setup(sceneWith("l1", through, "")), "dss", kPi, 0.0));
}

BOOST_AUTO_TEST_CASE(parts_given_in_other_frames_are_placed_at_the_saved_state) {
  // The same rod given in the world at j1 = 0.7 and in l2's frame (at j2 = 0: x shifted by
  // 0.6): the element is placed in l1 as when given in l1's frame.
  const double a = 0.7, c = std::cos(a), s = std::sin(a);
  const Eigen::Vector3d p_world(0.45 * c - 0.1 * s, 0.45 * s + 0.1 * c, 0.3);
  const double qz = std::sin(a / 2), qw = std::cos(a / 2);
  auto num = [](double v) {
    char b[64];
    std::snprintf(b, sizeof b, "%.17g", v);
    return std::string(b);
  };
  const std::string in_world = "{position: [" + num(p_world.x()) + ", " + num(p_world.y()) + ", " +
                               num(p_world.z()) + "], orientation: [0, 0, " + num(qz) + ", " +
                               num(qw) + "]}";
  const std::string in_l2 = "{position: [-0.15, 0.1, 0], orientation: [0, 0, 0, 1]}";
  const dss::ModelSetup ref = setup(sceneWith("l1", kRodInL1, "l2"));
  for (const auto& [frame, pose, state] :
       {std::tuple<std::string, std::string, std::string>{"world", in_world, "j1: " + num(a)},
        {"/world", in_world, "j1: " + num(a)},
        {"l2", in_l2, "j1: 0"}}) {
    BOOST_TEST_CONTEXT(frame) {
      const dss::ModelSetup m = setup(sceneWith(frame, pose, "l2", state));
      const int lr = ref.model->robot().linkIndex("rod"), lm = m.model->robot().linkIndex("rod");
      BOOST_REQUIRE(lr >= 0);
      BOOST_REQUIRE(lm >= 0);
      const auto& er = ref.model->robot().links[std::size_t(lr)].collisions.at(0);
      const auto& em = m.model->robot().links[std::size_t(lm)].collisions.at(0);
      BOOST_TEST((er.X_LS.matrix() - em.X_LS.matrix()).cwiseAbs().maxCoeff() < 1e-12);
      BOOST_TEST(collides(m, "dss", 0.0, 0.0));
      BOOST_TEST(!collides(m, "dss", kPi, 0.0));
    }
  }
}

BOOST_AUTO_TEST_CASE(a_request_start_object_is_placed_at_the_start_state) {
  // The scene saved j1 = 0; the request starts at j1 = 0.7 and holds the rod given in the world
  // there: it lands in l1 as the rod given in l1's frame.
  const double a = 0.7, c = std::cos(a), s = std::sin(a);
  dss::Scene scene = dss::parsePlanningSceneYaml(kWorld, "held.yaml");
  Eigen::Isometry3d X_WR(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()));
  X_WR.translation() = Eigen::Vector3d(0.45 * c - 0.1 * s, 0.45 * s + 0.1 * c, 0.3);
  dss::AttachedObject rod = dss_test::heldBox("rod", "l1", Eigen::Vector3d(0.4, 0.04, 0.04), X_WR,
                                              "world", "request.yaml:4");
  rod.at_request_start = true;
  scene.attached.push_back(rod);
  const dss::ModelSetup m = dss::setupModel(holder(), scene, "arm", {{"j1", a}});
  const dss::ModelSetup ref = setup(sceneWith("l1", kRodInL1, "l2"));
  const auto& robot = m.model->robot();
  const auto& em = robot.links.at(std::size_t(robot.linkIndex("rod"))).collisions.at(0);
  const auto& er = ref.model->robot()
                       .links.at(std::size_t(ref.model->robot().linkIndex("rod")))
                       .collisions.at(0);
  BOOST_TEST((er.X_LS.matrix() - em.X_LS.matrix()).cwiseAbs().maxCoeff() < 1e-12);
  // Held by the scene instead, the same part is placed at the saved j1 = 0: elsewhere.
  scene.attached[0].at_request_start = false;
  const dss::ModelSetup saved = dss::setupModel(holder(), scene, "arm", {{"j1", a}});
  const auto& es = saved.model->robot()
                       .links.at(std::size_t(saved.model->robot().linkIndex("rod")))
                       .collisions.at(0);
  BOOST_TEST((er.X_LS.matrix() - es.X_LS.matrix()).cwiseAbs().maxCoeff() > 0.1);
  // An id the scene's world uses too is refused.
  scene.attached[0].id = "post";
  const std::string msg =
      dss_test::thrownMessage([&] { dss::setupModel(holder(), scene, "arm", {}); });
  BOOST_TEST(msg.find("request.yaml:4: attached object 'post'") == 0u, msg);
  BOOST_TEST(msg.find("has an object 'post' too") != std::string::npos, msg);
}

BOOST_AUTO_TEST_CASE(models_holding_the_same_object_share_one_robot) {
  const dss::LoadedRobot robot = holder();
  auto model = [&](const std::string& yaml, const std::string& file) {
    return dss::setupModel(robot, dss::parsePlanningSceneYaml(yaml, file), "arm", {}).model;
  };
  const auto a = model(sceneWith("l1", kRodInL1, "l2"), "a.yaml");
  const auto b = model(sceneWith("l1", kRodInL1, ""), "b.yaml");  // touch links: the matrix's
  const auto c = model(
      sceneWith("l1", "{position: [0.45, 0.1, 0.001], orientation: [0, 0, 0, 1]}", "l2"), "c.yaml");
  BOOST_TEST(&a->robot() == &b->robot());
  BOOST_TEST(&a->robot() != &c->robot());
  BOOST_TEST(&a->robot() != robot.model.get());
  // Sharing the robot does not share the touch links: b's folded l2 collides, a's does not.
  const double q[2] = {kPi, kPi / 2};
  BOOST_TEST(!dss::DssChecker(a).collides(q));
  BOOST_TEST(dss::DssChecker(b).collides(q));
}

BOOST_AUTO_TEST_CASE(random_states_agree_with_fcl_and_reach_the_rod) {
  const dss::ModelSetup m = setup(sceneWith("l1", kRodInL1, "l2"));
  const Agreement a = agreeWithFcl(m.model, 2000, 11, {"rod"});
  BOOST_TEST(a.colliding > 0);
  BOOST_TEST(a.found[0] > 0);
}

BOOST_AUTO_TEST_CASE(a_crate_on_our_mobile_base_agrees_with_fcl) {
  // The base link's crate gets its own cells in the base-scene table; a tray on the gripper
  // rides the whole body.
  dss_test::MobileSetup mob = dss_test::mobileSetup("dss_mobile_base", "aisle");
  dss::Scene scene = dss::loadScene(mob.scene_file);
  auto at = [](double x, double y, double z) {
    return Eigen::Isometry3d(Eigen::Translation3d(x, y, z));
  };
  scene.attached.push_back(
      dss_test::heldBox("crate", "base_link", {0.3, 0.3, 0.2}, at(0.0, 0.45, 0.3)));
  scene.attached.push_back(
      dss_test::heldBox("tray", "gripper_link", {0.3, 0.3, 0.02}, at(0.15, 0.0, 0.0)));
  const dss::ModelSetup m = dss::setupModel(mob.robot, scene, mob.setup.group, {});
  const Agreement a = agreeWithFcl(m.model, 3000, 23, {"'crate'", "'tray'"});
  BOOST_TEST(a.found[0] > 0);
  BOOST_TEST(a.found[1] > 0);
}

BOOST_AUTO_TEST_CASE(bad_attachments_name_the_file_the_line_and_the_object) {
  auto setupMessage = [](const std::string& yaml) {
    return dss_test::thrownMessage([&] { setup(yaml); });
  };
  std::string unknown_link = sceneWith("l1", kRodInL1, "l2");
  unknown_link.replace(unknown_link.find("link_name: l1"), 13, "link_name: l9");
  std::string m = setupMessage(unknown_link);
  BOOST_TEST(m.find("held.yaml:") != std::string::npos, m);
  BOOST_TEST(m.find("attached object 'rod'") != std::string::npos, m);
  BOOST_TEST(m.find("link_name 'l9'") != std::string::npos, m);
  m = setupMessage(sceneWith("l1", kRodInL1, "l7"));
  BOOST_TEST(m.find("touch link 'l7'") != std::string::npos, m);
  m = setupMessage(sceneWith("nowhere", kRodInL1, "l2"));
  BOOST_TEST(m.find("frame 'nowhere'") != std::string::npos, m);
  std::string clash = sceneWith("l1", kRodInL1, "l2");
  clash.replace(clash.find("id: rod"), 7, "id: l2");
  m = setupMessage(clash);
  BOOST_TEST(m.find("also the name of a link") != std::string::npos, m);
  // An id the world already uses: the reader refuses the file.
  std::string twice = sceneWith("l1", kRodInL1, "l2");
  twice.replace(twice.find("id: rod"), 7, "id: post");
  m = dss_test::thrownMessage([&] { dss::parsePlanningSceneYaml(twice, "held.yaml"); });
  BOOST_TEST(m.find("object 'post' given twice") != std::string::npos, m);
  m = dss_test::thrownMessage([&] {
    dss::parsePlanningSceneYaml(
        kWorld + "robot_state:\n  attached_collision_objects:\n    - {object: {id: x}}\n",
        "held.yaml");
  });
  BOOST_TEST(m.find("link_name") != std::string::npos, m);
}

BOOST_AUTO_TEST_SUITE_END()
