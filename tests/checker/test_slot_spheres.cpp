// The slots' spheres in one pass (slot_spheres.h): on every instruction-set path, each centre
// must be the pose's ((R_0 x + R_1 y) + R_2 z) + t to the bit, and each "clear" bit must be the
// clearance grid's own verdict for that centre and radius plus padding. Random poses and
// spheres around random boxes, with centres put on voxel faces and a hair off them, radii at
// the stored bound and one ulp either side, centres outside the grid, NaN and infinite poses,
// an empty grid, and sphere counts around the four-lane groups and the 64-bit words.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "dss/checker/clearance_grid.h"
#include "dss/checker/slot_spheres.h"

namespace {

Eigen::Vector3d reference(const Eigen::Isometry3d& X, const Eigen::Vector3d& c) {
  const double* M = X.data();
  Eigen::Vector3d w;
  for (int i = 0; i < 3; ++i)
    w[i] = ((M[i] * c[0] + M[4 + i] * c[1]) + M[8 + i] * c[2]) + M[12 + i];
  return w;
}

bool sameBits(double a, double b) {
  return (std::isnan(a) && std::isnan(b)) || (a == b && std::signbit(a) == std::signbit(b));
}

const dss::SimdPath kPaths[] = {dss::SimdPath::kScalar, dss::SimdPath::kSse2, dss::SimdPath::kAvx2};

struct Case {
  std::vector<Eigen::Isometry3d> X;  // per link
  std::vector<dss::SlotSpheres::Sphere> own, folded;
};

// Checks every path against the reference; returns the number of clear spheres.
int checkPaths(const Case& c, const dss::ClearanceGrid& grid, double padding) {
  const dss::SlotSpheres spheres(c.own, c.folded);
  BOOST_TEST(spheres.size() == c.own.size());
  BOOST_TEST(spheres.words() == (c.own.size() + 63) / 64);
  for (std::size_t k = 0; k < c.own.size(); ++k)
    BOOST_TEST(((spheres.scene()[k / 64] >> (k % 64)) & 1) == std::uint64_t(c.own[k].scene));
  int clear_count = 0;
  for (const bool pose_links : {false, true}) {
    const std::vector<dss::SlotSpheres::Sphere>& set = pose_links ? c.folded : c.own;
    for (const dss::SimdPath path : kPaths) {
      if (!dss::simdPathAvailable(path)) {
        BOOST_TEST_MESSAGE("slot spheres: path " << dss::simdPathName(path) << " skipped");
        continue;
      }
      std::vector<Eigen::Vector3d> centers(spheres.centersWritten(),
                                           Eigen::Vector3d::Constant(-7.0));
      std::vector<std::uint64_t> clear(spheres.words() + 1, ~std::uint64_t(0));
      spheres.place(path, pose_links, c.X.data(), grid, padding, centers.data(), clear.data());
      BOOST_TEST(clear[spheres.words()] == ~std::uint64_t(0));  // nothing past the words
      for (std::size_t k = 0; k < set.size(); ++k) {
        const Eigen::Vector3d w = reference(c.X[std::size_t(set[k].link)], set[k].center);
        for (int i = 0; i < 3; ++i) BOOST_TEST(sameBits(centers[k][i], w[i]));
        const bool expected = grid.clear(w, set[k].radius + padding);
        const bool got = (clear[k / 64] >> (k % 64)) & 1;
        BOOST_TEST(got == expected,
                   "sphere " << k << " of " << set.size() << " on " << dss::simdPathName(path));
        clear_count += got;
      }
      for (std::size_t k = set.size(); k < spheres.words() * 64; ++k)
        BOOST_TEST(((clear[k / 64] >> (k % 64)) & 1) == 0u);
    }
  }
  return clear_count;
}

Eigen::Isometry3d randomPose(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Quaterniond q(u(rng), u(rng), u(rng), u(rng));
  q.normalize();
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng));
  return X;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(slot_spheres)

BOOST_AUTO_TEST_CASE(every_path_places_the_same_centres_and_the_grids_verdicts) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(0.0, 0.3), f(0.0, 1.0);
  dss::Aabb region;
  region.lower = Eigen::Vector3d(-1.2, -1.1, -1.0);
  region.upper = Eigen::Vector3d(1.1, 1.2, 1.3);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  int clear_total = 0, spheres_total = 0;
  const std::size_t counts[] = {0, 1, 3, 4, 5, 11, 63, 64, 65, 130};
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<dss::Aabb> boxes(1 + trial % 5);
    for (auto& b : boxes) {
      const Eigen::Vector3d c(u(rng), u(rng), u(rng)), h(e(rng), e(rng), e(rng));
      b.lower = c - h;
      b.upper = c + h;
    }
    const dss::ClearanceGrid grid(region, boxes, trial % 2 ? 4096 : 65536);
    const std::size_t n = counts[trial % 10];
    Case c;
    const int links = 1 + trial % 6;
    for (int l = 0; l < links; ++l) c.X.push_back(randomPose(rng));
    if (trial % 8 == 5) c.X[0].translation().x() = nan;
    if (trial % 8 == 6) c.X[0].linear()(1, 2) = inf;
    for (std::size_t k = 0; k < n; ++k) {
      dss::SlotSpheres::Sphere s;
      s.link = int(rng() % std::uint64_t(links));
      s.center = Eigen::Vector3d(0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng));
      s.radius = 0.2 * f(rng);
      s.scene = k % 3 != 1;
      // Every fourth centre lands on a voxel face of the grid, a hair to either side (the
      // pose's translation moved so that the world centre sits there).
      if (k % 4 == 0) {
        const Eigen::Isometry3d& X = c.X[std::size_t(s.link)];
        Eigen::Vector3d w = reference(X, s.center);
        const int a = int(k % 3);
        const double voxel = grid.voxelSize();
        const double face =
            grid.origin()[a] + voxel * std::round((w[a] - grid.origin()[a]) / voxel);
        s.center +=
            X.linear().transpose().col(a) * (std::nextafter(face, k % 8 ? 9.0 : -9.0) - w[a]);
      }
      // Every fifth radius at the stored bound (bound * quantum > r is false there), or one
      // ulp below it.
      if (k % 5 == 2) {
        const double b = grid.bound(reference(c.X[std::size_t(s.link)], s.center));
        s.radius = k % 10 == 2 ? b : std::nextafter(b, 0.0);
      }
      c.own.push_back(s);
      dss::SlotSpheres::Sphere g = s;
      g.link = int(rng() % std::uint64_t(links));
      g.center = Eigen::Vector3d(2.0 * u(rng), 2.0 * u(rng), 2.0 * u(rng));  // some outside
      c.folded.push_back(g);
    }
    clear_total += checkPaths(c, grid, trial % 3 == 0 ? 0.0 : 0.01);
    spheres_total += int(2 * 3 * n);
  }
  BOOST_TEST_MESSAGE("slot spheres: " << clear_total << " of " << spheres_total
                                      << " placements clear");
  BOOST_TEST(clear_total > spheres_total / 10);  // the bits are not all zero
}

BOOST_AUTO_TEST_CASE(an_empty_grid_clears_nothing) {
  std::mt19937_64 rng(43);
  Case c;
  c.X = {randomPose(rng), randomPose(rng)};
  for (int k = 0; k < 9; ++k) {
    c.own.push_back({k % 2, Eigen::Vector3d(0.1 * k, 0.0, 0.0), 0.0, true});
    c.folded.push_back({1 - k % 2, Eigen::Vector3d(0.0, 0.1 * k, 0.0), 0.0, true});
  }
  BOOST_TEST(checkPaths(c, dss::ClearanceGrid(), 0.0) == 0);
}

BOOST_AUTO_TEST_CASE(mismatched_sets_are_refused) {
  const std::vector<dss::SlotSpheres::Sphere> one(1), two(2);
  BOOST_CHECK_THROW(dss::SlotSpheres(one, two), std::invalid_argument);
}

BOOST_AUTO_TEST_SUITE_END()
