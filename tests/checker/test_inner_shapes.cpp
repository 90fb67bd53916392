// Inner balls and inner boxes of the collision elements (inner_shapes.h): every ball and box
// lies inside its element's shape (points of its surface tested with exact DSS), boxesTouch
// never calls a pair of boxes farther apart than the padding touching (against exact DSS, on
// random and nearly parallel boxes), and the inner stage of the sweep never changes a
// checker's answer -- it only proves collisions earlier (random Panda states of
// MotionBenchMaker scenes, our own arm in its shelf scene, the mobile base in its aisle and the
// free flyer in its room).
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <random>

#include "dss/checker/checker_setup.h"
#include "dss/checker/element_bounds.h"
#include "dss/checker/inner_shapes.h"
#include "dss/checker/sweep.h"
#include "dss/core/any_shape_query.h"
#include "dss/robot/multi_dof.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "support/checker_fixtures.h"
#include "support/random_pose.h"
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

// Each element's inner box: its corners and random points of its faces are points of the shape.
std::size_t checkBoxesInside(const dss::CollisionModel& m) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::size_t boxes = 0;
  for (const auto& e : m.elements()) {
    if (!e.has_inner_box) continue;
    ++boxes;
    BOOST_TEST_REQUIRE((e.inner_box_h.array() > 0.0).all());
    for (int i = 0; i < 208; ++i) {
      Eigen::Vector3d f;
      if (i < 8) {
        f = Eigen::Vector3d(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
      } else {
        f = Eigen::Vector3d(u(rng), u(rng), u(rng));
        f[i % 3] = f[i % 3] < 0 ? -1.0 : 1.0;  // on a face
      }
      const Eigen::Vector3d p = e.inner_box_c + e.inner_box_h.cwiseProduct(f);
      const dss::AnyShape point = dss::ConvexHull({p});
      BOOST_TEST_REQUIRE(dss::intersect(point, Eigen::Isometry3d::Identity(), e.source->shape,
                                        Eigen::Isometry3d::Identity())
                             .intersect,
                         e.source->description << " inner box point " << p.transpose());
    }
  }
  return boxes;
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
    opt.inner_shapes = false;
    const bool without = dss::anyCollision(m, q.data(), X.data(), opt, scene, self);
    narrow = 0;
    opt.inner_shapes = true;
    const bool with = dss::anyCollision(m, q.data(), X.data(), opt, scene, self);
    BOOST_TEST_REQUIRE(with == without, "state " << k);
    colliding += with;
    if (with && narrow == 0) ++decided;
  }
  BOOST_TEST_MESSAGE(colliding << " of " << n << " states colliding, " << decided
                               << " proved by the inner stage");
  return decided;
}

dss::AnyShape box(const Eigen::Vector3d& h) { return dss::Box{h}; }

using dss_test::randomPose;

}  // namespace

namespace {
// Both boxes turned about z only (their z edges exactly parallel, as a mobile base against
// upright shelves), B then tilted about x by a tiny angle when `tilt` (nearly parallel edges).
void turnAboutZ(std::mt19937_64& rng, bool tilt, Eigen::Isometry3d* XA, Eigen::Isometry3d* XB) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  XA->linear() = Eigen::AngleAxisd(u(rng) * 6.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  XB->linear() = Eigen::AngleAxisd(u(rng) * 6.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  if (tilt)
    XB->linear() =
        XB->linear() * Eigen::AngleAxisd(std::ldexp(u(rng), -static_cast<int>(u(rng) * 60)),
                                         Eigen::Vector3d::UnitX())
                           .toRotationMatrix();
}
}  // namespace

BOOST_AUTO_TEST_SUITE(inner_shapes)

// boxesTouch against exact DSS with the same padding: never "touch" for a pair that exact DSS
// finds apart; and it proves most clearly overlapping pairs (so the test can fail both ways).
// Poses: random, yaw-only (the edges along z exactly parallel, as a mobile base against
// upright shelves), and yaw-only turned by a tiny angle about x (nearly parallel edges).
BOOST_AUTO_TEST_CASE(boxes_touch_only_when_exact_dss_agrees) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t touching = 0, proved = 0, deep[3] = {}, deep_proved[3] = {};
  for (int i = 0; i < 60000; ++i) {
    const double scale = std::ldexp(1.0, static_cast<int>(u(rng) * 20) - 10);
    const Eigen::Vector3d ha = scale * Eigen::Vector3d(0.05 + u(rng), 0.05 + u(rng), 0.05 + u(rng));
    const Eigen::Vector3d hb = scale * Eigen::Vector3d(0.05 + u(rng), 0.05 + u(rng), 0.05 + u(rng));
    Eigen::Isometry3d XA = randomPose(rng, scale), XB = randomPose(rng, scale);
    const int kind = i % 3;
    if (kind > 0) turnAboutZ(rng, kind == 2, &XA, &XB);
    const double pad = i % 4 == 0 ? 0.0 : 0.1 * scale * u(rng);
    const bool touch =
        dss::boxesTouch(XA.linear(), XA.translation(), ha, XB.linear(), XB.translation(), hb, pad);
    const bool exact = dss::intersect(box(ha), XA, box(hb), XB, {}, pad).intersect;
    BOOST_TEST_REQUIRE((!touch || exact), "pair " << i << ": boxesTouch without a collision");
    touching += exact;
    proved += touch;
    // Clearly overlapping: the boxes shrunk by a fifth still intersect. Proved unless a tilt
    // leaves two edges nearly but not exactly parallel (sine in [1e-12, 1e-6]), where rounding
    // cannot decide their cross axis.
    if (dss::intersect(box(0.8 * ha), XA, box(0.8 * hb), XB).intersect) {
      ++deep[kind];
      deep_proved[kind] += touch;
    }
  }
  BOOST_TEST_MESSAGE(proved << " of " << touching << " touching pairs proved; clearly overlapping: "
                            << deep_proved[0] << "/" << deep[0] << " random, " << deep_proved[1]
                            << "/" << deep[1] << " yaw only, " << deep_proved[2] << "/" << deep[2]
                            << " nearly parallel");
  for (int kind = 0; kind < 3; ++kind) BOOST_TEST(deep[kind] > 1000u);
  BOOST_TEST(deep_proved[0] == deep[0]);
  BOOST_TEST(deep_proved[1] == deep[1]);
  BOOST_TEST(deep_proved[2] >= deep[2] / 2);
}

// At the boundary: B slid along a random direction to the last position where exact DSS finds
// the boxes apart (bisection), random and yaw-only orientations: never "touch" there, and a
// slide of 1e-6 of the size deeper is proved.
BOOST_AUTO_TEST_CASE(boxes_touch_at_the_contact_boundary) {
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> n;
  std::size_t deeper_proved = 0;
  const int kPairs = 3000;
  for (int i = 0; i < kPairs; ++i) {
    const Eigen::Vector3d ha(0.05 + u(rng), 0.05 + u(rng), 0.05 + u(rng));
    const Eigen::Vector3d hb(0.05 + u(rng), 0.05 + u(rng), 0.05 + u(rng));
    Eigen::Isometry3d XA = randomPose(rng, 0.0), XB = randomPose(rng, 0.0);
    if (i % 2) {
      XA.linear() = Eigen::AngleAxisd(u(rng) * 6.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      XB.linear() = Eigen::AngleAxisd(u(rng) * 6.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    }
    const Eigen::Vector3d dir = Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
    auto at = [&](double d) {
      Eigen::Isometry3d X = XB;
      X.translation() = d * dir;
      return X;
    };
    double lo = 0.0, hi = 10.0;  // lo: intersecting, hi: apart
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (dss::intersect(box(ha), XA, box(hb), at(mid)).intersect ? lo : hi) = mid;
    }
    BOOST_TEST_REQUIRE(!dss::boxesTouch(XA.linear(), XA.translation(), ha, XB.linear(),
                                        at(hi).translation(), hb, 0.0),
                       "pair " << i);
    deeper_proved += dss::boxesTouch(XA.linear(), XA.translation(), ha, XB.linear(),
                                     at(hi - 1e-6).translation(), hb, 0.0);
  }
  BOOST_TEST_MESSAGE(deeper_proved << " of " << kPairs << " proved 1e-6 inside the boundary");
  BOOST_TEST(deeper_proved >= std::size_t(kPairs * 9 / 10));
}

BOOST_AUTO_TEST_CASE(boxes_touch_edge_cases) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d h(1, 1, 1);
  // Face to face: apart by 0.1, touching with a padding of 0.2, not with 0.05; overlapping.
  BOOST_TEST(!dss::boxesTouch(I, {0, 0, 0}, h, I, {2.1, 0, 0}, h, 0.0));
  BOOST_TEST(!dss::boxesTouch(I, {0, 0, 0}, h, I, {2.1, 0, 0}, h, 0.05));
  BOOST_TEST(dss::boxesTouch(I, {0, 0, 0}, h, I, {2.1, 0, 0}, h, 0.2));
  BOOST_TEST(dss::boxesTouch(I, {0, 0, 0}, h, I, {1.9, 0, 0}, h, 0.0));
  // Exactly in contact is not proved (the margin), a hair deeper is.
  BOOST_TEST(!dss::boxesTouch(I, {0, 0, 0}, h, I, {2.0, 0, 0}, h, 0.0));
  BOOST_TEST(dss::boxesTouch(I, {0, 0, 0}, h, I, {2.0 - 1e-6, 0, 0}, h, 0.0));
  // Corner to corner along the diagonal: a padding of pad/sqrt(3) per axis would reach, the
  // true distance (sqrt(3) * 0.1) does not.
  BOOST_TEST(!dss::boxesTouch(I, {0, 0, 0}, h, I, {2.1, 2.1, 2.1}, h, 0.1));
  BOOST_TEST(dss::boxesTouch(I, {0, 0, 0}, h, I, {2.1, 2.1, 2.1}, h, 0.1 * std::sqrt(3.0) * 1.01));
  // A thin post through a slab, edges parallel: proved.
  const Eigen::Matrix3d Rz = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  BOOST_TEST(
      dss::boxesTouch(Rz, {0, 0, 0}, {0.3, 0.2, 0.05}, I, {0.1, 0.05, 0}, {0.02, 0.02, 1}, 0.0));
  // NaN anywhere: not proved.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  BOOST_TEST(!dss::boxesTouch(I, {nan, 0, 0}, h, I, {0, 0, 0}, h, 0.0));
  BOOST_TEST(!dss::boxesTouch(I, {0, 0, 0}, h, I, {0, 0, 0}, h, nan));
  BOOST_TEST(!dss::boxesTouch(I * nan, {0, 0, 0}, h, I, {0, 0, 0}, h, 0.0));
}

// boxStages gives exactly what obbApart and then boxesTouch give: random, yaw-only and nearly
// parallel poses at every scale, pairs near contact (B slid to a random gap around the
// padding), inner boxes a little smaller than the outer ones (and equal), obstacles with the
// identity rotation through boxStagesAxisAligned, and NaN anywhere (kUnknown, as both tests
// then answer false).
BOOST_AUTO_TEST_CASE(box_stages_answer_as_the_two_stages_in_turn) {
  std::mt19937_64 rng(47);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t count[3] = {};
  auto expected = [](const Eigen::Isometry3d& XA, const Eigen::Vector3d& ho,
                     const Eigen::Vector3d& hi, const Eigen::Isometry3d& XB,
                     const Eigen::Vector3d& hbo, const Eigen::Vector3d& hbi, double pad) {
    if (dss::obbApart(XA.linear(), XA.translation(), ho, XB.linear(), XB.translation(), hbo, pad))
      return dss::BoxStage::kApart;
    return dss::boxesTouch(XA.linear(), XA.translation(), hi, XB.linear(), XB.translation(), hbi,
                           pad)
               ? dss::BoxStage::kTouch
               : dss::BoxStage::kUnknown;
  };
  for (int i = 0; i < 200000; ++i) {
    const double scale = std::ldexp(1.0, static_cast<int>(u(rng) * 12) - 6);
    const Eigen::Vector3d ho = scale * Eigen::Vector3d(0.05 + u(rng), 0.05 + u(rng), 0.05 + u(rng));
    const Eigen::Vector3d hbo =
        scale * Eigen::Vector3d(0.05 + u(rng), 0.05 + u(rng), 0.05 + u(rng));
    const Eigen::Vector3d hi = i % 5 == 0 ? ho : Eigen::Vector3d(ho * (1.0 - 1e-7 * (1 + u(rng))));
    const Eigen::Vector3d hbi = i % 7 == 0 ? Eigen::Vector3d(hbo * 0.999) : hbo;
    Eigen::Isometry3d XA = randomPose(rng, scale), XB = randomPose(rng, scale);
    const int kind = i % 4;
    if (kind == 1 || kind == 2) turnAboutZ(rng, kind == 2, &XA, &XB);
    if (kind == 3) XB.linear().setIdentity();  // an axis-aligned obstacle
    const double pad = i % 3 == 0 ? 0.0 : 0.1 * scale * u(rng);
    if (i % 2) {  // near contact: along the centre line, to a gap around the padding
      const Eigen::Vector3d d = XB.translation() - XA.translation();
      if (d.norm() > 0) XB.translation() = XA.translation() + d * (0.6 + 0.5 * u(rng));
    }
    const dss::BoxStage want = expected(XA, ho, hi, XB, hbo, hbi, pad);
    const dss::BoxStage got = dss::boxStages(XA.linear(), XA.translation(), ho, hi, XB.linear(),
                                             XB.translation(), hbo, hbi, pad);
    BOOST_TEST_REQUIRE((got == want), "pair " << i);
    if (kind == 3)
      BOOST_TEST_REQUIRE((dss::boxStagesAxisAligned(XA.linear(), XA.translation(), ho, hi,
                                                    XB.translation(), hbo, hbi, pad) == want),
                         "pair " << i << ", axis-aligned");
    ++count[static_cast<int>(want)];
  }
  BOOST_TEST_MESSAGE(count[0] << " apart, " << count[1] << " touching, " << count[2] << " unknown");
  for (std::size_t c : count) BOOST_TEST(c > 1000u);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d h(1, 1, 1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  BOOST_TEST(
      (dss::boxStages(I, {nan, 0, 0}, h, h, I, {0, 0, 0}, h, h, 0.0) == dss::BoxStage::kUnknown));
  BOOST_TEST((dss::boxStagesAxisAligned(I, {0, 0, 0}, h, h, {0, 0, 0}, h, h, nan) ==
              dss::BoxStage::kUnknown));
  BOOST_TEST((dss::boxStages(I * nan, {0, 0, 0}, h, h, I, {3, 0, 0}, h, h, 0.0) ==
              dss::BoxStage::kUnknown));
}

// innerBox of each primitive: inside (exact DSS on its corners) and as large as promised.
BOOST_AUTO_TEST_CASE(inner_box_of_primitives) {
  const std::vector<std::pair<dss::AnyShape, double>> shapes = {
      {dss::Box{Eigen::Vector3d(0.3, 0.2, 0.1)}, 0.3 * 0.2 * 0.1},
      {dss::Cylinder{0.1, 0.4}, 0.5 * 0.1 * 0.1 * 0.4},
      {dss::Capsule{0.1, 0.4}, 0.5 * 0.1 * 0.1 * 0.4},
      {dss::Capsule{0.1, 0.0}, std::pow(0.1 / std::sqrt(3.0), 3)},
      {dss::Ellipsoid{Eigen::Vector3d(0.3, 0.2, 0.1)}, 0.3 * 0.2 * 0.1 / std::pow(3.0, 1.5)},
  };
  for (const auto& [shape, volume] : shapes) {
    Eigen::Vector3d bc, bh, c, h;
    dss::localBox(shape, &bc, &bh);
    BOOST_TEST_REQUIRE(dss::innerBox(shape, bc, bh, &c, &h), dss::shapeTypeName(shape));
    BOOST_TEST(h.prod() == volume, boost::test_tools::tolerance(1e-5));
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3d p =
          c + h.cwiseProduct(Eigen::Vector3d(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1));
      BOOST_TEST(dss::intersect(dss::ConvexHull({p}), Eigen::Isometry3d::Identity(), shape,
                                Eigen::Isometry3d::Identity())
                     .intersect);
    }
  }
  Eigen::Vector3d bc, bh, c, h;
  for (const dss::AnyShape& none :
       {dss::AnyShape(dss::Sphere{0.1}), dss::AnyShape(dss::Cone{0.1, 0.2}),
        dss::AnyShape(
            dss::ConvexHull(std::vector<Eigen::Vector3d>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}))}) {
    dss::localBox(none, &bc, &bh);
    BOOST_TEST(!dss::innerBox(none, bc, bh, &c, &h));
  }
  // A hull: the cube with its corners cut off keeps most of the cube.
  std::vector<Eigen::Vector3d> pts;
  for (int k = 0; k < 8; ++k)
    for (int a = 0; a < 3; ++a) {
      Eigen::Vector3d p(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1);
      p[a] *= 0.8;
      pts.push_back(p);
    }
  const dss::AnyShape cut = dss::ConvexHull(pts);
  dss::localBox(cut, &bc, &bh);
  BOOST_TEST_REQUIRE(dss::innerBox(cut, bc, bh, &c, &h));
  BOOST_TEST(h.prod() > 0.5);
  BOOST_TEST(h.maxCoeff() < 1.0);
}

BOOST_AUTO_TEST_CASE(inner_balls_are_inside_and_keep_answers_on_our_arm) {
  const auto r = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  const auto req = dss::loadPlanRequestYaml(kArm + "/scenes/shelf_request.yaml");
  const dss::ModelSetup p = dss::setupModel(r, dss::loadScene(kArm + "/scenes/shelf.yaml"),
                                            req.group_name, req.startState());
  BOOST_TEST(checkBallsInside(*p.model) > 0u);
  BOOST_TEST(checkBoxesInside(*p.model) > 0u);
  compareAnswers(*p.model, 3000, 21);
}

// The mobile base (bumper hull, deck box, wheel cylinders) among its shelves and the free
// flyer (two boxes) in its room: the inner boxes are inside and decide most collisions.
BOOST_AUTO_TEST_CASE(inner_boxes_keep_answers_on_the_mobile_robots) {
  for (const char* name : {"dss_mobile_base", "dss_free_flyer"}) {
    const std::string scene = std::string(name) == "dss_mobile_base" ? "aisle" : "window";
    const dss::ModelSetup p = dss_test::mobileSetup(name, scene).setup;
    BOOST_TEST(checkBoxesInside(*p.model) >= 2u);
    BOOST_TEST(compareAnswers(*p.model, 4000, 29) > 1000u, name);
  }
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
    if (first) {
      BOOST_TEST(checkBallsInside(*p.model) >= 9u);  // at least one per link hull
      checkBoxesInside(*p.model);  // rounded links: boxes only where they beat the balls
    }
    first = false;
    decided += compareAnswers(*p.model, 3000, 23);
  }
  BOOST_TEST(decided > 0u);  // the stage is really used
}

BOOST_AUTO_TEST_SUITE_END()
