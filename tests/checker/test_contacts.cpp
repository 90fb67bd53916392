// The colliding pairs of a state (dss/checker/contacts.h): on random states of our robots in
// their scenes, and of the Panda and the UR5 in MotionBenchMaker scenes, the list is empty
// exactly when the checker says free, every pair listed collides, and the descriptions name the
// link and the object.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <random>

#include "dss/checker/contacts.h"
#include "dss/core/any_shape_query.h"
#include "support/checker_fixtures.h"
#include "support/shared_data.h"

namespace {

// Every listed pair decided again on its own: it collides.
bool listedPairsCollide(const dss::DssChecker& c, const double* q,
                        const std::vector<dss::Contact>& contacts) {
  const dss::CollisionModel& m = c.model();
  const auto X = m.kinematics().linkPoses(std::vector<double>(q, q + m.robot().numActiveJoints()));
  for (const dss::Contact& k : contacts) {
    const auto& a = m.elements()[std::size_t(k.element_a)];
    const Eigen::Isometry3d XA = X[std::size_t(a.link)] * a.source->X_LS;
    dss::Result r;
    if (k.self()) {
      const auto& b = m.elements()[std::size_t(k.element_b)];
      r = dss::intersect(a.source->shape, XA, b.source->shape,
                         X[std::size_t(b.link)] * b.source->X_LS, c.settings().options,
                         c.settings().self_padding);
    } else {
      const dss::Obstacle& o = m.scene().obstacles[std::size_t(k.obstacle)];
      r = dss::intersect(a.source->shape, XA, o.shape, o.X_WO, c.settings().options,
                         c.settings().scene_padding);
    }
    if (!r.intersect) return false;
  }
  return true;
}

struct Tally {
  int colliding = 0, scene = 0, self = 0;
};

// n random group states: contacts empty exactly when free; listed pairs collide.
Tally compareOnRandomStates(const dss::DssChecker& c, int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  Tally t;
  for (int k = 0; k < n; ++k) {
    const std::vector<double> q = dss_test::randomGroupState(c.model(), rng);
    const dss::StateVerdict v = c.check(q.data());
    const auto contacts = dss::contactsAt(c, q.data());
    BOOST_REQUIRE(contacts.has_value());
    BOOST_TEST((v == dss::StateVerdict::kColliding) == !contacts->empty(), "state " << k);
    BOOST_TEST(listedPairsCollide(c, q.data(), *contacts), "state " << k);
    t.colliding += v == dss::StateVerdict::kColliding;
    for (const dss::Contact& x : *contacts) (x.self() ? t.self : t.scene) += 1;
  }
  return t;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(contacts)

BOOST_AUTO_TEST_CASE(empty_exactly_when_free_on_our_robots) {
  const dss::LoadedRobot arm = dss_test::loadArm();
  const dss::ModelSetup shelf = dss_test::shelfSetup(arm);
  const dss_test::MobileSetup base = dss_test::mobileSetup("dss_mobile_base", "aisle");
  const dss_test::MobileSetup flyer = dss_test::mobileSetup("dss_free_flyer", "window");
  int scene_contacts = 0, self_contacts = 0;
  for (const auto& model : {shelf.model, base.setup.model, flyer.setup.model}) {
    const dss::DssChecker c(model);
    const Tally t = compareOnRandomStates(c, 1500, 7);
    BOOST_TEST(t.colliding > 0, model->robot().name);
    BOOST_TEST(t.colliding < 1500, model->robot().name);
    scene_contacts += t.scene;
    self_contacts += t.self;
  }
  // Both kinds occur (the arm folds into itself, every robot meets its scene).
  BOOST_TEST(scene_contacts > 0);
  BOOST_TEST(self_contacts > 0);
}

BOOST_AUTO_TEST_CASE(paddings_count_as_the_checker_counts_them) {
  const dss::LoadedRobot arm = dss_test::loadArm();
  const dss::ModelSetup shelf = dss_test::shelfSetup(arm);
  dss::DssCheckerSettings padded;
  padded.scene_padding = 0.03;
  padded.self_padding = 0.01;
  const dss::DssChecker c(shelf.model, padded);
  compareOnRandomStates(c, 1000, 11);
}

BOOST_AUTO_TEST_CASE(descriptions_name_the_link_and_the_object) {
  const dss::LoadedRobot arm = dss_test::loadArm();
  const dss::ModelSetup shelf = dss_test::shelfSetup(arm);
  const dss::DssChecker c(shelf.model);
  std::mt19937_64 rng(3);
  bool scene_seen = false, self_seen = false;
  for (int k = 0; k < 5000 && !(scene_seen && self_seen); ++k) {
    const std::vector<double> q = dss_test::randomGroupState(*shelf.model, rng);
    const auto contacts = dss::contactsAt(c, q.data());
    for (const dss::Contact& x : *contacts) {
      const std::string d = dss::describeContact(*shelf.model, x);
      const auto& a = shelf.model->elements()[std::size_t(x.element_a)];
      BOOST_TEST(d.find("link " + shelf.model->robot().links[std::size_t(a.link)].name) == 0, d);
      if (x.self()) {
        const auto& b = shelf.model->elements()[std::size_t(x.element_b)];
        BOOST_TEST(d.find(" with link " + shelf.model->robot().links[std::size_t(b.link)].name) !=
                       std::string::npos,
                   d);
        self_seen = true;
      } else {
        const std::string name = shelf.model->scene().obstacles[std::size_t(x.obstacle)].name;
        BOOST_TEST(d.find(" with scene object '" + name + "'") != std::string::npos, d);
        scene_seen = true;
      }
      // Our arm's links are meshes checked as hulls.
      BOOST_TEST(dss::involvesMeshHull(*shelf.model, x) ==
                 (d.find("(mesh hull)") != std::string::npos));
    }
  }
  BOOST_TEST(scene_seen);
  BOOST_TEST(self_seen);
}

BOOST_AUTO_TEST_CASE(at_most_the_contacts_asked_for_and_none_for_invalid_input) {
  const dss::LoadedRobot arm = dss_test::loadArm();
  const dss::ModelSetup shelf = dss_test::shelfSetup(arm);
  const dss::DssChecker c(shelf.model);
  std::mt19937_64 rng(5);
  int several = 0;
  for (int k = 0; k < 3000; ++k) {
    const std::vector<double> q = dss_test::randomGroupState(*shelf.model, rng);
    const auto all = dss::contactsAt(c, q.data());
    const auto one = dss::contactsAt(c, q.data(), 1);
    BOOST_REQUIRE((all && one));
    BOOST_TEST(one->size() == std::min<std::size_t>(1, all->size()));
    if (!all->empty()) {
      BOOST_TEST(one->front().element_a == all->front().element_a);
      BOOST_TEST(one->front().obstacle == all->front().obstacle);
    }
    several += all->size() > 1;
  }
  BOOST_TEST(several > 0);
  std::vector<double> q = shelf.held;
  q[std::size_t(shelf.group_active.front())] = std::nan("");
  BOOST_TEST(!dss::contactsAt(c, q.data()).has_value());
}

BOOST_AUTO_TEST_CASE(empty_exactly_when_free_on_mbm_scenes, DSS_NEEDS_SHARED) {
  const dss::LoadedRobot panda = dss::loadRobot(dss_test::sharedPath("robots/panda/panda.urdf"),
                                                dss_test::sharedPath("robots/panda/panda.srdf"));
  const dss::LoadedRobot ur5 =
      dss::loadRobot(dss_test::sharedPath("robots/ur5_robotiq85/ur5.urdf"),
                     dss_test::sharedPath("robots/ur5_robotiq85/ur5.srdf"));
  for (const char* type : {"bookshelf_small", "box", "cage", "table_under_pick"})
    for (const auto* robot : {&panda, &ur5}) {
      const std::string dir = dss_test::sharedPath(
          std::string(robot == &panda ? "scenes/mbm_panda/" : "scenes/mbm_ur5/") + type);
      const auto req = dss::loadPlanRequestYaml(dir + "/request0001.yaml");
      const dss::ModelSetup s = dss::setupModel(*robot, dss::loadScene(dir + "/scene0001.yaml"),
                                                req.group_name, req.startState());
      const dss::DssChecker c(s.model);
      const Tally t = compareOnRandomStates(c, 400, 13);
      BOOST_TEST(t.colliding > 0, type);
    }
}

BOOST_AUTO_TEST_SUITE_END()
