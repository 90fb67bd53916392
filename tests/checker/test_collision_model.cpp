// The collision model (collision_model.h) of our arm in its shelf scene: an obstacle no link can
// reach is pruned, non-moving links are never checked against the scene, every self pair has a
// moving link, and every moving link's geometry stays inside its reach ball at random states.
#include <boost/test/unit_test.hpp>
#include <random>

#include "dss/checker/checker_setup.h"
#include "dss/scene/scene_loader.h"
#include "support/checker_fixtures.h"

BOOST_AUTO_TEST_SUITE(collision_model)

BOOST_AUTO_TEST_CASE(shelf_model_pairs_and_pruning) {
  const auto r = dss_test::loadArm();
  dss::Scene scene = dss::loadScene(dss_test::kArmDir + "/scenes/shelf.yaml");
  // A far-away obstacle that no link can reach is pruned.
  dss::Obstacle far = scene.obstacles.at(0);
  far.name = far.object_id = "far_away";
  far.X_WO.translation() += Eigen::Vector3d(50, 0, 0);
  far.X_FO = far.X_WO;
  scene.obstacles.push_back(far);
  const std::size_t n = scene.obstacles.size();
  const dss::ModelSetup p = dss::setupModel(r, scene, "arm", {});
  const auto& m = *p.model;
  BOOST_TEST_MESSAGE(m.summary());
  BOOST_TEST(m.obstaclesBefore() == n);
  BOOST_TEST(m.scene().obstacles.size() == n - 1);
  for (const auto& o : m.scene().obstacles) BOOST_TEST(o.name != "far_away");
  // Non-moving links are never checked against the scene; every self pair has a moving link.
  for (const auto& s : m.slots())
    if (!s.moves) BOOST_TEST(s.obstacles.empty());
  for (const auto& sp : m.selfPairs()) BOOST_TEST((m.slots()[sp.a].moves || m.slots()[sp.b].moves));
  // Reach balls hold every element at random states.
  std::mt19937_64 rng(5);
  for (int k = 0; k < 200; ++k) {
    const std::vector<double> q = dss_test::randomGroupState(m, rng);
    const auto X = m.kinematics().linkPoses(q);
    for (const auto& s : m.slots()) {
      if (!s.moves) continue;
      BOOST_TEST((X[s.link] * s.center_L - s.reach_center_W).norm() + s.radius <=
                 s.reach_radius + 1e-9);
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
