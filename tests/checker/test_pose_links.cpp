// Pose links (pose_links.h): a link rigid to a moving link through fixed joints and joints held
// outside the group (a gripper on the last arm joint) is placed from that link's pose by a
// constant transform, so the sweep needs the poses of fewer links. The kinematics restricted to
// some links gives those links the same poses as the full one; the folded sweep answers as the
// unfolded one; a state whose held joint is elsewhere takes the full path.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "dss/checker/checker_setup.h"
#include "dss/checker/dss_checker.h"
#include "dss/checker/sweep.h"
#include "dss/core/any_shape_query.h"
#include "dss/scene/scene_loader.h"

namespace {

const std::string kArm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";

dss::LoadedRobot arm() { return dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf"); }

int linkIndex(const dss::RobotModel& m, const std::string& name) {
  const int l = m.linkIndex(name);
  BOOST_REQUIRE(l >= 0);
  return l;
}

// The arm with joint7 held outside the group at `held7`: link7 and everything on it ride on link6.
std::shared_ptr<dss::CollisionModel> sixJointModel(const dss::LoadedRobot& r,
                                                   const dss::Scene& scene, double held7) {
  std::vector<double> held(r.model->numActiveJoints(), 0.0);
  held[6] = held7;
  return std::make_shared<dss::CollisionModel>(r.model, r.srdf ? &*r.srdf : nullptr, scene,
                                               std::vector<int>{0, 1, 2, 3, 4, 5}, held);
}

std::vector<double> randomState(const dss::RobotModel& m, std::mt19937_64& rng) {
  std::vector<double> q(m.numActiveJoints());
  for (std::size_t a = 0; a < q.size(); ++a) {
    const auto& j = m.joints[m.active_joints[a]];
    q[a] = std::uniform_real_distribution<double>(j.limits.lower, j.limits.upper)(rng);
  }
  return q;
}

// Exact DSS on the shapes at the poses the sweep gives (oriented-box and inner-ball stages
// on). With q (its held joints at held()): the tables read for q, then the folded sweep from
// the pose links in X. Without: no table, the unfolded sweep from every link's own pose in X.
template <class F>
bool sweepCollides(const dss::CollisionModel& m, const double* q, const Eigen::Isometry3d* X,
                   F&& count) {
  const auto& el = m.elements();
  const auto& ob = m.scene().obstacles;
  auto scene = [&](int e, const Eigen::Isometry3d& X_WS, int o) {
    count(e, X_WS);
    return dss::intersect(el[e].source->shape, X_WS, ob[o].shape, ob[o].X_WO).intersect;
  };
  auto self = [&](int a, const Eigen::Isometry3d& X_WA, int b, const Eigen::Isometry3d& X_WB) {
    count(a, X_WA);
    count(b, X_WB);
    return dss::intersect(el[a].source->shape, X_WA, el[b].source->shape, X_WB).intersect;
  };
  dss::SweepOptions opt;
  opt.obb_stage = true;
  opt.inner_shapes = true;
  std::vector<unsigned char> skip(m.selfTables().size(), 0);
  if (!q) return dss::sweep<dss::SweepPoses::kOwnLinks>(m, X, skip.data(), opt, scene, self);
  BOOST_REQUIRE(m.heldMatch(q));
  if (m.selfTables().read(q, true, opt.self_padding, skip.data())) return true;
  return dss::sweep<dss::SweepPoses::kPoseLinks>(m, X, skip.data(), opt, scene, self);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(pose_links)

BOOST_AUTO_TEST_CASE(kinematics_restricted_to_some_links_gives_them_the_same_poses) {
  const auto r = arm();
  const dss::RobotModel& m = *r.model;
  const dss::Kinematics full(m, /*all_links=*/true);
  std::vector<char> wanted(m.links.size(), 0);
  wanted[linkIndex(m, "link3")] = wanted[linkIndex(m, "link6")] = 1;
  const dss::Kinematics some(m, wanted);
  std::mt19937_64 rng(5);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < 200; ++k) {
    const std::vector<double> q = randomState(m, rng);
    const std::vector<Eigen::Isometry3d> A = full.linkPoses(q);
    std::vector<Eigen::Isometry3d> B(m.links.size());
    for (auto& X : B) X.matrix().setConstant(nan);
    some.computeLinkPoses(q.data(), B.data());
    for (std::size_t l = 0; l < m.links.size(); ++l) {
      if (wanted[l]) BOOST_TEST((A[l].matrix() == B[l].matrix()), m.links[l].name);
    }
    // Links below the wanted ones are never written.
    for (const char* name : {"link7", "tcp"}) {
      const int l = m.linkIndex(name);
      if (l >= 0) BOOST_TEST(std::isnan(B[l].matrix()(0, 0)), name);
    }
  }
  BOOST_CHECK_THROW(dss::Kinematics(m, std::vector<char>(m.links.size() + 1, 1)),
                    std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(folded_sweep_answers_as_the_unfolded_one) {
  const auto r = arm();
  const dss::Scene scene = dss::loadScene(kArm + "/scenes/shelf.yaml");
  const auto model = sixJointModel(r, scene, 0.7);
  const dss::CollisionModel& m = *model;
  const dss::RobotModel& rm = m.robot();
  // link7 and the links fixed to it are placed from link6; link6 from itself.
  const int link6 = linkIndex(rm, "link6"), link7 = linkIndex(rm, "link7");
  std::size_t riding = 0;
  for (const auto& s : m.slots()) {
    if (s.link == link6) BOOST_TEST(s.pose_link == link6);
    if (s.link == link7) BOOST_TEST(s.pose_link == link6);
    riding += s.pose_link != s.link;
  }
  BOOST_TEST(riding >= 1u);
  std::mt19937_64 rng(11);
  std::size_t colliding = 0, placed = 0;
  const int n = 4000;
  std::vector<Eigen::Isometry3d> Xs(rm.links.size()), Xf(rm.links.size());
  for (int k = 0; k < n; ++k) {
    std::vector<double> q = randomState(rm, rng);
    q[6] = m.held()[6];
    BOOST_REQUIRE(m.heldMatch(q.data()));
    m.sweepKinematics().computeLinkPoses(q.data(), Xs.data());
    m.kinematics().computeLinkPoses(q.data(), Xf.data());
    // Folded: from the pose links (q given, held joint at its value). Every shape pose the
    // narrow phase sees is the full kinematics' one up to rounding.
    const bool folded =
        sweepCollides(m, q.data(), Xs.data(), [&](int e, const Eigen::Isometry3d& X_WS) {
          const auto& el = m.elements()[e];
          const Eigen::Isometry3d ref = Xf[el.link] * el.source->X_LS;
          BOOST_TEST((X_WS.matrix() - ref.matrix()).cwiseAbs().maxCoeff() < 1e-12);
          ++placed;
        });
    // Unfolded: no q, every link from the full kinematics.
    const bool unfolded =
        sweepCollides(m, nullptr, Xf.data(), [](int, const Eigen::Isometry3d&) {});
    BOOST_TEST(folded == unfolded, "state " << k);
    colliding += unfolded;
  }
  BOOST_TEST_MESSAGE("colliding " << colliding << " of " << n << ", narrow-phase poses compared "
                                  << placed);
  BOOST_TEST(colliding > n / 20u);
  BOOST_TEST(colliding < n - n / 20u);
  BOOST_TEST(placed > 200u);
}

// The checker, with the held joint elsewhere than held(), must not use the folded placement:
// it answers as the exact sweep on the full kinematics at that value, and for some states that
// differs from the answer at the held value (so the test would catch a checker that ignored it).
BOOST_AUTO_TEST_CASE(held_joint_elsewhere_takes_the_full_path) {
  const auto r = arm();
  const dss::Scene scene = dss::loadScene(kArm + "/scenes/shelf.yaml");
  const auto model = sixJointModel(r, scene, 0.0);
  const dss::CollisionModel& m = *model;
  const dss::RobotModel& rm = m.robot();
  const dss::DssChecker checker(model);
  std::mt19937_64 rng(13);
  std::vector<Eigen::Isometry3d> X(rm.links.size());
  std::size_t differs_from_held = 0, wrong = 0, invalid = 0;
  const int n = 4000;
  for (int k = 0; k < n; ++k) {
    std::vector<double> q = randomState(rm, rng);
    BOOST_REQUIRE(q[6] != m.held()[6]);
    BOOST_REQUIRE(!m.heldMatch(q.data()));
    m.kinematics().computeLinkPoses(q.data(), X.data());
    const bool truth = sweepCollides(m, nullptr, X.data(), [](int, const Eigen::Isometry3d&) {});
    // q[6] lies within its limits: a valid input although not at its held value.
    const dss::StateVerdict verdict = checker.check(q.data());
    BOOST_TEST_REQUIRE((verdict != dss::StateVerdict::kInvalidInput), "state " << k);
    const bool valid = verdict == dss::StateVerdict::kFree;
    wrong += valid == truth;
    invalid += !valid;
    std::vector<double> qh = q;
    qh[6] = m.held()[6];
    differs_from_held += !checker.collides(qh.data()) != valid;
  }
  BOOST_TEST_MESSAGE("invalid " << invalid << ", answer differs from the held value's "
                                << differs_from_held);
  BOOST_TEST(wrong == 0u);
  BOOST_TEST(differs_from_held >= 5u);
  BOOST_TEST(invalid > n / 20u);
}

BOOST_AUTO_TEST_SUITE_END()
