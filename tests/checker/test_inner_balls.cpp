// Inner balls of the collision elements (inner_balls.h): every ball lies inside its element's
// shape (points of its surface tested with exact DSS), and the inner-ball stage of the sweep
// never changes a checker's answer -- it only proves collisions earlier (random Panda states of
// MotionBenchMaker scenes, and our own arm in its shelf scene).
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <random>

#include "dss/checker/checker_setup.h"
#include "dss/checker/sweep.h"
#include "dss/core/any_shape_query.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "support/checker_fixtures.h"
#include "support/shared_data.h"

namespace fs = std::filesystem;

namespace {

const std::string kArm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
const std::string kPanda = std::string(DSS_SHARED_DIR) + "/robots/panda";
const std::string kMbm = std::string(DSS_SHARED_DIR) + "/scenes/mbm_panda";

Eigen::Vector3d randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  return Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
}

// Each element's inner balls: points on their surfaces are points of the shape (exact DSS:
// the one-point hull intersects the shape).
std::size_t checkBallsInside(const dss::CollisionModel& m) {
  std::mt19937_64 rng(5);
  std::size_t balls = 0;
  for (const auto& e : m.elements()) {
    for (int k = 0; k < e.num_inner; ++k) {
      ++balls;
      const Eigen::Vector3d c = e.inner_S[k].head<3>();
      const double r = e.inner_S[k].w();
      BOOST_TEST_REQUIRE(r > 0.0);
      for (int i = 0; i < 300; ++i) {
        const Eigen::Vector3d p = c + r * randomUnit(rng);
        const dss::AnyShape point = dss::ConvexHull({p});
        const bool inside = dss::intersect(point, Eigen::Isometry3d::Identity(), e.source->shape,
                                           Eigen::Isometry3d::Identity())
                                .intersect;
        BOOST_TEST_REQUIRE(inside,
                           e.source->description << " ball " << k << " point " << p.transpose());
      }
    }
  }
  return balls;
}

// Answers with and without the inner stage, on the same states; returns how many states the
// inner stage decided before any narrow phase.
std::size_t compareAnswers(const dss::CollisionModel& m, std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Eigen::Isometry3d> X(m.robot().links.size(), Eigen::Isometry3d::Identity());
  const auto& obstacles = m.scene().obstacles;
  std::size_t decided = 0, colliding = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::vector<double> q = dss_test::randomGroupState(m, rng);
    BOOST_REQUIRE(m.withinBounds(q.data()));
    m.kinematics().computeLinkPoses(q.data(), X.data());
    int narrow = 0;
    auto scene = [&](int e, const Eigen::Isometry3d& X_WS, int o) {
      ++narrow;
      return dss::intersect(m.elements()[e].source->shape, X_WS, obstacles[o].shape,
                            obstacles[o].X_WO)
          .intersect;
    };
    auto self = [&](int a, const Eigen::Isometry3d& X_WA, int b, const Eigen::Isometry3d& X_WB) {
      ++narrow;
      return dss::intersect(m.elements()[a].source->shape, X_WA, m.elements()[b].source->shape,
                            X_WB)
          .intersect;
    };
    dss::SweepOptions opt;
    opt.obb_stage = true;
    opt.inner_balls = false;
    const bool without = dss::anyCollision(m, q.data(), X.data(), opt, scene, self);
    narrow = 0;
    opt.inner_balls = true;
    const bool with = dss::anyCollision(m, q.data(), X.data(), opt, scene, self);
    BOOST_TEST_REQUIRE(with == without, "state " << k);
    colliding += with;
    if (with && narrow == 0) ++decided;
  }
  BOOST_TEST_MESSAGE(colliding << " of " << n << " states colliding, " << decided
                               << " proved by inner balls");
  return decided;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(inner_balls)

BOOST_AUTO_TEST_CASE(inner_balls_are_inside_and_keep_answers_on_our_arm) {
  const auto r = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  const auto req = dss::loadPlanRequestYaml(kArm + "/scenes/shelf_request.yaml");
  const dss::ModelSetup p = dss::setupModel(r, dss::loadScene(kArm + "/scenes/shelf.yaml"),
                                            req.group_name, req.startState());
  BOOST_TEST(checkBallsInside(*p.model) > 0u);
  compareAnswers(*p.model, 3000, 21);
}

BOOST_AUTO_TEST_CASE(inner_balls_are_inside_and_keep_answers_on_mbm_panda, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(fs::exists(kPanda + "/panda.urdf") && fs::exists(kMbm));
  const auto r = dss::loadRobot(kPanda + "/panda.urdf", kPanda + "/panda.srdf");
  std::size_t decided = 0;
  bool first = true;
  for (const char* folder : {"box", "bookshelf_small", "table_pick"}) {
    const std::string dir = kMbm + "/" + folder;
    const auto req = dss::loadPlanRequestYaml(dir + "/request0001.yaml");
    const dss::ModelSetup p = dss::setupModel(r, dss::loadScene(dir + "/scene0001.yaml"),
                                              req.group_name, req.startState());
    if (first) BOOST_TEST(checkBallsInside(*p.model) >= 9u);  // at least one per link hull
    first = false;
    decided += compareAnswers(*p.model, 3000, 23);
  }
  BOOST_TEST(decided > 0u);  // the stage is really used
}

BOOST_AUTO_TEST_SUITE_END()
