// Pair blocks (pair_blocks.h): self pairs that share a slot are tested behind one ball about a
// common ancestor link of the other slots first. Skipping a block must never skip a pair that
// its own filters would pass: the sweep calls the narrow phase for exactly the element pairs,
// in the same order, that the per-pair filters alone (slot spheres, element spheres, oriented
// boxes) let through, with the folded placement (pose links) and with the full kinematics.
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <random>
#include <utility>
#include <vector>

#include "dss/checker/checker_setup.h"
#include "dss/checker/obb.h"
#include "dss/checker/sweep.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "support/shared_data.h"

namespace fs = std::filesystem;

namespace {

const std::string kPanda = std::string(DSS_SHARED_DIR) + "/robots/panda";
const std::string kMbm = std::string(DSS_SHARED_DIR) + "/scenes/mbm_panda";
const std::string kArm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";

using PairList = std::vector<std::pair<int, int>>;

// The element pairs the per-pair filters pass, in the sweep's order, from each link's pose.
PairList bruteForce(const dss::CollisionModel& m, const Eigen::Isometry3d* X, double pad) {
  PairList out;
  const auto& slots = m.slots();
  const auto& el = m.elements();
  for (const auto& p : m.selfPairs()) {
    const auto& sa = slots[p.a];
    const auto& sb = slots[p.b];
    const double r = p.radius_sum + pad;
    if ((X[sa.link] * sa.center_L - X[sb.link] * sb.center_L).squaredNorm() > r * r) continue;
    const bool single = sa.num_elements == 1 && sb.num_elements == 1;
    for (int ea = sa.first_element; ea < sa.first_element + sa.num_elements; ++ea)
      for (int eb = sb.first_element; eb < sb.first_element + sb.num_elements; ++eb) {
        const auto& a = el[ea];
        const auto& b = el[eb];
        if (!single) {
          const double rr = a.radius + b.radius + pad;
          if ((X[a.link] * a.center_L - X[b.link] * b.center_L).squaredNorm() > rr * rr) continue;
        }
        const Eigen::Isometry3d XA = X[a.link] * a.source->X_LS, XB = X[b.link] * b.source->X_LS;
        if (dss::obbApart(XA.linear(), XA * a.box_center_S, a.box_half, XB.linear(),
                          XB * b.box_center_S, b.box_half, pad))
          continue;
        out.emplace_back(ea, eb);
      }
  }
  return out;
}

void checkModel(const dss::CollisionModel& m, std::uint64_t seed) {
  const dss::RobotModel& rm = m.robot();
  std::mt19937_64 rng(seed);
  std::vector<Eigen::Isometry3d> X(rm.links.size(), Eigen::Isometry3d::Identity());
  std::vector<Eigen::Isometry3d> Xs(rm.links.size(), Eigen::Isometry3d::Identity());
  std::size_t pairs = 0, states_with_pairs = 0;
  std::vector<unsigned char> no_skip(m.selfTables().size(), 0);
  auto none = [](int, const Eigen::Isometry3d&, int) { return false; };
  for (double pad : {0.0, 0.03}) {
    for (int k = 0; k < 3000; ++k) {
      std::vector<double> q = m.held();
      for (int a : m.groupActive()) {
        const auto& j = rm.joints[rm.active_joints[a]];
        q[a] = std::uniform_real_distribution<double>(j.limits.lower, j.limits.upper)(rng);
      }
      BOOST_REQUIRE(m.heldMatch(q.data()));
      m.kinematics().computeLinkPoses(q.data(), X.data());
      m.sweepKinematics().computeLinkPoses(q.data(), Xs.data());
      // The narrow phase answers "free" so that the sweep visits every pair, with no table
      // flags set, so that every pair goes through its filters. Unfolded: every link from the
      // full kinematics. Folded: from the pose links.
      PairList unfolded, folded;
      dss::SweepOptions opt;
      opt.self_padding = pad;
      dss::sweep<dss::SweepPoses::kOwnLinks>(
          m, X.data(), no_skip.data(), opt, none,
          [&](int a, const Eigen::Isometry3d&, int b, const Eigen::Isometry3d&) {
            unfolded.emplace_back(a, b);
            return false;
          });
      dss::sweep<dss::SweepPoses::kPoseLinks>(
          m, Xs.data(), no_skip.data(), opt, none,
          [&](int a, const Eigen::Isometry3d&, int b, const Eigen::Isometry3d&) {
            folded.emplace_back(a, b);
            return false;
          });
      const PairList expected = bruteForce(m, X.data(), pad);
      BOOST_TEST_REQUIRE((unfolded == expected),
                         "state " << k << " padding " << pad << ": " << unfolded.size()
                                  << " narrow-phase pairs, expected " << expected.size());
      BOOST_TEST_REQUIRE((folded == expected), "state " << k << " padding " << pad << " (folded)");
      pairs += expected.size();
      states_with_pairs += !expected.empty();
    }
  }
  BOOST_TEST_MESSAGE(m.pairsBehindBlockBalls()
                     << " of " << m.selfPairs().size() << " self pairs behind block balls; "
                     << pairs << " narrow-phase pairs in " << states_with_pairs << " states");
  BOOST_TEST(states_with_pairs > 100u);  // the comparison sees pairs
}

}  // namespace

BOOST_AUTO_TEST_SUITE(pair_blocks)

BOOST_AUTO_TEST_CASE(blocks_skip_only_pairs_their_own_filters_skip_panda, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(fs::exists(kPanda + "/panda.urdf") &&
                fs::exists(kMbm + "/bookshelf_small/request0001.yaml"));
  const auto robot = dss::loadRobot(kPanda + "/panda.urdf", kPanda + "/panda.srdf");
  const dss::Scene scene = dss::loadScene(kMbm + "/bookshelf_small/scene0001.yaml");
  const auto req = dss::loadPlanRequestYaml(kMbm + "/bookshelf_small/request0001.yaml");
  const dss::ModelSetup p = dss::setupModel(robot, scene, req.group_name, req.startState());
  // link0, link1 and link2 against the forearm, wrist, hand and fingers.
  BOOST_TEST(p.model->pairsBehindBlockBalls() >= 15u, p.model->summary());
  checkModel(*p.model, 3);
}

// Our own arm: its balls do not pay on random states (no ball by default), so every ball is
// kept here (pair_block_min_saving 0) to check them without the shared models.
BOOST_AUTO_TEST_CASE(blocks_skip_only_pairs_their_own_filters_skip_dss_arm7) {
  const auto robot = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  const dss::Scene scene = dss::loadScene(kArm + "/scenes/shelf.yaml");
  dss::CollisionModelOptions options;
  options.pair_block_min_saving = 0.0;
  const dss::CollisionModel every(robot.model, robot.srdf ? &*robot.srdf : nullptr, scene, {},
                                  std::vector<double>(robot.model->numActiveJoints(), 0.0),
                                  options);
  BOOST_TEST(every.pairsBehindBlockBalls() >= 3u, every.summary());
  checkModel(every, 4);
  const dss::CollisionModel paying(robot.model, robot.srdf ? &*robot.srdf : nullptr, scene, {},
                                   std::vector<double>(robot.model->numActiveJoints(), 0.0));
  BOOST_TEST(paying.pairsBehindBlockBalls() <= every.pairsBehindBlockBalls());
}

BOOST_AUTO_TEST_SUITE_END()
