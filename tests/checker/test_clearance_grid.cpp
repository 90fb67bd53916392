// The clearance grid (clearance_grid.h): its "clear" must be a proof. For random boxes and
// random balls (radii drawn around the true distance, so that many sit within a hair of it),
// clear(c, r) implies every box is farther than r from c; it must also settle a good share of
// the balls that are clear, say nothing outside its region or for NaN, and an empty grid says
// nothing at all. Its candidate lists must hold every box a ball of up to their radius can
// touch, from any point of any voxel (balls placed within a hair of a box, and of voxel faces).
// With obstacles turned away from the axes, the oriented boxes make the bound tighter, and it
// stays a proof: each "clear" and each list is checked against the exact decision of the core
// on the turned box itself (ballApartObb, the sweep's test of a ball against a turned obstacle,
// likewise, down to a hair on either side of the true distance). Its upper bounds (a box within
// them of every point of a voxel) must be proofs in the same way.
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "dss/checker/clearance_grid.h"
#include "dss/checker/obb.h"
#include "dss/core/any_shape_query.h"

namespace {
// The k-th test point from a random one: every third moved onto a voxel face of the grid, then a
// hair off it (either side), where the rounding of a lookup may pick the neighbouring voxel.
Eigen::Vector3d pointFor(const dss::ClearanceGrid& grid, int k, Eigen::Vector3d c) {
  if (k % 3 != 0) return c;
  const int a = k % 9 / 3;
  const double voxel = grid.voxelSize();
  c[a] = grid.origin()[a] + voxel * std::round((c[a] - grid.origin()[a]) / voxel);
  c[a] = std::nextafter(c[a], k % 2 ? 10.0 : -10.0);
  return c;
}
}  // namespace

BOOST_AUTO_TEST_SUITE(clearance_grid)

BOOST_AUTO_TEST_CASE(clearance_grid_is_a_lower_bound) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(0.0, 0.3), f(0.0, 1.0);
  int settled = 0, clear_balls = 0;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<dss::Aabb> boxes(1 + trial % 7);
    for (auto& b : boxes) {
      const Eigen::Vector3d c(u(rng), u(rng), u(rng)), h(e(rng), e(rng), e(rng));
      b.lower = c - h;
      b.upper = c + h;
    }
    if (trial == 3) boxes[0].upper = boxes[0].lower;  // a point-sized box
    dss::Aabb region;
    region.lower = Eigen::Vector3d(-1.2, -1.1, -1.0);
    region.upper = Eigen::Vector3d(1.1, 1.2, 1.3);
    const dss::ClearanceGrid grid(region, boxes, trial % 2 ? 4096 : 65536);
    BOOST_TEST(!grid.empty());
    BOOST_TEST(grid.voxels() <= (trial % 2 ? 4096u : 65536u));
    // The bytes a four-byte gather at the last voxel reads past it: readable, and zero.
    const std::uint8_t* const bound = grid.lookup().bound;
    for (std::size_t k = 0; k < dss::ClearanceGrid::kReadPast; ++k)
      BOOST_TEST(int(bound[grid.voxels() + k]) == 0);
    for (int k = 0; k < 5000; ++k) {
      const Eigen::Vector3d c(1.3 * u(rng), 1.3 * u(rng), 1.3 * u(rng));
      double d = std::numeric_limits<double>::infinity();
      for (const auto& b : boxes) d = std::min(d, std::sqrt(dss::detail::sqDistPointAabb(c, b)));
      const double r = k % 4 == 0 ? d * (1.0 - 1e-12) : d * f(rng);
      // The grid covers the region in whole voxels: up to one voxel more on the upper sides.
      const bool inside = (c.array() >= region.lower.array()).all() &&
                          (c.array() < region.upper.array() + grid.voxelSize()).all();
      if (grid.clear(c, r)) {
        ++settled;
        BOOST_TEST(d > r);
        BOOST_TEST(inside);
        BOOST_TEST(grid.bound(c) > r);
        BOOST_TEST(grid.bound(c) <= d);
      }
      clear_balls += inside && d > r + 0.1;
    }
  }
  BOOST_TEST_MESSAGE("clearance grid settled " << settled << " balls; " << clear_balls
                                               << " inside with 0.1 m to spare");
  BOOST_TEST(settled >= clear_balls * 9 / 10);
  const dss::ClearanceGrid empty;
  BOOST_TEST(!empty.clear(Eigen::Vector3d::Zero(), 0.0));
  dss::Aabb region;
  region.lower = Eigen::Vector3d::Constant(-1.0);
  region.upper = Eigen::Vector3d::Constant(1.0);
  const dss::ClearanceGrid grid(
      region, {dss::Aabb{Eigen::Vector3d::Constant(5.0), Eigen::Vector3d::Constant(6.0)}});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  BOOST_TEST(grid.clear(Eigen::Vector3d::Zero(), 0.5));
  BOOST_TEST(!grid.clear(Eigen::Vector3d(nan, 0.0, 0.0), 0.0));
  BOOST_TEST(!grid.clear(Eigen::Vector3d(0.0, 0.0, nan), 0.0));
  BOOST_TEST(!grid.clear(Eigen::Vector3d::Zero(), nan));
  BOOST_TEST(!grid.clear(Eigen::Vector3d(2.0, 0.0, 0.0), 0.0));
  BOOST_TEST(!grid.clear(Eigen::Vector3d::Zero(), std::numeric_limits<double>::infinity()));
}

BOOST_AUTO_TEST_CASE(candidate_lists_hold_every_box_a_ball_can_touch) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(0.0, 0.2), f(0.0, 1.0);
  std::size_t listed = 0, total = 0;
  for (int trial = 0; trial < 12; ++trial) {
    std::vector<dss::Aabb> boxes(20 + 11 * trial);  // more than one 64-bit word from trial 4
    for (auto& b : boxes) {
      const Eigen::Vector3d c(u(rng), u(rng), u(rng)), h(e(rng), e(rng), e(rng));
      b.lower = c - h;
      b.upper = c + h;
    }
    dss::Aabb region;
    region.lower = Eigen::Vector3d(-1.2, -1.1, -1.0);
    region.upper = Eigen::Vector3d(1.1, 1.2, 1.3);
    dss::ClearanceGrid grid(region, boxes, trial % 2 ? 4096 : 65536);
    const double radius = 0.05 + 0.1 * trial;
    grid.buildCandidates(boxes, radius, std::size_t(64) << 20);
    BOOST_REQUIRE(grid.candidateWords() == (boxes.size() + 63) / 64);
    BOOST_TEST(!grid.candidates(Eigen::Vector3d::Zero(), radius * 1.001));  // above the radius
    BOOST_TEST(!grid.candidates(Eigen::Vector3d(5, 0, 0), radius));         // outside the grid
    BOOST_TEST(!grid.candidates(Eigen::Vector3d(std::nan(""), 0, 0), radius));
    const double voxel = grid.voxelSize();
    for (int k = 0; k < 4000; ++k) {
      const Eigen::Vector3d c =
          pointFor(grid, k, Eigen::Vector3d(1.1 * u(rng), 1.1 * u(rng), 1.1 * u(rng)));
      const std::uint64_t* cand = grid.candidates(c, radius);
      if (!cand) continue;
      for (std::size_t b = 0; b < boxes.size(); ++b) {
        const double d = std::sqrt(dss::detail::sqDistPointAabb(c, boxes[b]));
        // A ball of the full radius, and balls just reaching the box.
        if (d <= radius || (k % 5 == 0 && d <= radius * (1.0 + 1e-12))) {
          ++total;
          const bool in = (cand[b / 64] >> (b % 64)) & 1u;
          listed += in;
          BOOST_TEST(in, "trial " << trial << " point " << k << " box " << b);
        }
      }
    }
  }
  BOOST_TEST(total > 10000u);
  BOOST_TEST(listed == total);
  // Too large for the memory allowed: no lists.
  std::vector<dss::Aabb> boxes(70);
  for (auto& b : boxes) b.lower = b.upper = Eigen::Vector3d::Zero();
  dss::Aabb region;
  region.lower = Eigen::Vector3d::Constant(-1.0);
  region.upper = Eigen::Vector3d::Constant(1.0);
  dss::ClearanceGrid grid(region, boxes, 65536);
  grid.buildCandidates(boxes, 0.1, 1024);
  BOOST_TEST(grid.candidateWords() == 0u);
  BOOST_TEST(!grid.candidates(Eigen::Vector3d::Zero(), 0.1));
}

namespace {
// A box turned by a random rotation: its oriented box, and its world box (from its corners).
struct TurnedBox {
  dss::Obb obb;
  dss::Aabb aabb;
};
TurnedBox turnedBox(std::mt19937_64& rng, bool axis_aligned) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(0.01, 0.3);
  TurnedBox t;
  t.obb.c = Eigen::Vector3d(u(rng), u(rng), u(rng));
  t.obb.h = Eigen::Vector3d(e(rng), e(rng), 0.2 * e(rng));  // thin as a wall or a shelf
  t.obb.R =
      axis_aligned
          ? Eigen::Matrix3d::Identity()
          : Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
  t.obb.axis_aligned = axis_aligned;
  const Eigen::Vector3d extent = t.obb.R.cwiseAbs() * t.obb.h;
  t.aabb.lower = t.obb.c - extent;
  t.aabb.upper = t.obb.c + extent;
  return t;
}
// The core's exact decision: does the ball (c, r) touch the turned box?
bool ballTouches(const Eigen::Vector3d& c, double r, const dss::Obb& b) {
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity(), X_WC = Eigen::Isometry3d::Identity();
  X_WB.linear() = b.R;
  X_WB.translation() = b.c;
  X_WC.translation() = c;
  return dss::intersect(dss::AnyShape(dss::Box{b.h}), X_WB, dss::AnyShape(dss::Sphere{0.0}), X_WC,
                        dss::Options{}, r)
      .intersect;
}
// The distance from c to the turned box, in long double (the reference the radii are drawn
// around).
double distanceTo(const Eigen::Vector3d& c, const dss::Obb& b) {
  long double d2 = 0;
  for (int i = 0; i < 3; ++i) {
    long double t = 0;
    for (int k = 0; k < 3; ++k) t += (long double)b.R(k, i) * ((long double)c[k] - b.c[k]);
    const long double out = std::fabs(t) - b.h[i];
    if (out > 0) d2 += out * out;
  }
  return double(std::sqrt(d2));
}
// n turned boxes (box k axis-aligned where aligned(k)): their world boxes and oriented boxes.
struct TurnedBoxes {
  std::vector<dss::Aabb> boxes;
  std::vector<dss::Obb> obbs;
};
template <class Aligned>
TurnedBoxes turnedBoxes(std::mt19937_64& rng, int n, Aligned&& aligned) {
  TurnedBoxes t;
  for (int k = 0; k < n; ++k) {
    const TurnedBox b = turnedBox(rng, aligned(k));
    t.boxes.push_back(b.aabb);
    t.obbs.push_back(b.obb);
  }
  return t;
}
// The region the grids of these tests cover.
dss::Aabb testRegion() {
  dss::Aabb region;
  region.lower = Eigen::Vector3d(-1.2, -1.1, -1.0);
  region.upper = Eigen::Vector3d(1.1, 1.2, 1.3);
  return region;
}
}  // namespace

BOOST_AUTO_TEST_CASE(oriented_boxes_tighten_the_bound_and_it_stays_a_proof) {
  std::mt19937_64 rng(37);
  std::uniform_real_distribution<double> u(-1.0, 1.0), f(0.0, 1.0);
  int settled_obb = 0, settled_aabb = 0, checked = 0;
  for (int trial = 0; trial < 12; ++trial) {
    std::vector<dss::Aabb> boxes;
    std::vector<dss::Obb> obbs;
    for (int k = 0; k < 1 + trial % 5; ++k) {
      const TurnedBox t = turnedBox(rng, k == 1);  // one axis-aligned box among turned ones
      boxes.push_back(t.aabb);
      obbs.push_back(t.obb);
    }
    dss::Aabb region;
    region.lower = Eigen::Vector3d(-1.2, -1.1, -1.0);
    region.upper = Eigen::Vector3d(1.1, 1.2, 1.3);
    const std::size_t voxels = trial % 2 ? 4096 : 65536;
    const dss::ClearanceGrid with_obbs(region, boxes, obbs, voxels);
    const dss::ClearanceGrid world_boxes(region, boxes, voxels);
    BOOST_REQUIRE(with_obbs.voxels() == world_boxes.voxels());
    const double half_diagonal = 0.5 * std::sqrt(3.0) * with_obbs.voxelSize();
    const double q = dss::ClearanceGrid::kQuantum;
    for (int k = 0; k < 3000; ++k) {
      const Eigen::Vector3d c(1.2 * u(rng), 1.2 * u(rng), 1.2 * u(rng));
      double d = std::numeric_limits<double>::infinity();
      for (const auto& b : obbs) d = std::min(d, distanceTo(c, b));
      const double r = k % 4 == 0 ? d * (1.0 - 1e-12) : k % 4 == 1 ? d * (1.0 + 1e-12) : d * f(rng);
      // Never looser than the world boxes alone measured from the voxel's centre (for boxes
      // along the axes the grid measures from the voxel's cube, which gains up to half a
      // diagonal).
      BOOST_TEST(with_obbs.bound(c) >= world_boxes.bound(c) - half_diagonal - q);
      settled_aabb += world_boxes.clear(c, r);
      if (!with_obbs.clear(c, r)) continue;
      ++settled_obb;
      BOOST_TEST(d > r);
      ++checked;  // and the exact decision
      for (const auto& b : obbs)
        BOOST_TEST(!ballTouches(c, r, b), "trial " << trial << " ball " << k);
    }
  }
  BOOST_TEST_MESSAGE("turned boxes: the grid settled "
                     << settled_obb << " balls with oriented boxes, " << settled_aabb
                     << " with world boxes alone");
  BOOST_TEST(checked > 1000);
  BOOST_TEST(settled_obb >
             settled_aabb * 21 / 20);  // turned thin boxes fill little of their world box
  // Oriented boxes that do not match the world boxes in number: ignored, the grid is empty.
  dss::Aabb region;
  region.lower = Eigen::Vector3d::Constant(-1.0);
  region.upper = Eigen::Vector3d::Constant(1.0);
  const TurnedBox t = turnedBox(rng, false);
  BOOST_TEST(dss::ClearanceGrid(region, {t.aabb, t.aabb}, {t.obb}).empty());
}

BOOST_AUTO_TEST_CASE(candidate_lists_with_oriented_boxes_hold_every_box_a_ball_can_touch) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::size_t listed = 0, total = 0, listed_any = 0, listed_any_aabb = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const auto [boxes, obbs] = turnedBoxes(rng, 20 + 13 * trial, [](int k) { return k % 7 == 0; });
    const dss::Aabb region = testRegion();
    dss::ClearanceGrid grid(region, boxes, obbs, 4096);
    dss::ClearanceGrid plain(region, boxes, 4096);
    const double radius = 0.05 + 0.05 * trial;
    grid.buildCandidates(boxes, radius, std::size_t(64) << 20, obbs);
    plain.buildCandidates(boxes, radius, std::size_t(64) << 20);
    BOOST_REQUIRE(grid.candidateWords() == (boxes.size() + 63) / 64);
    for (int k = 0; k < 1500; ++k) {
      const Eigen::Vector3d c(1.1 * u(rng), 1.1 * u(rng), 1.1 * u(rng));
      const std::uint64_t* cand = grid.candidates(c, radius);
      const std::uint64_t* cand_plain = plain.candidates(c, radius);
      if (!cand) continue;
      for (std::size_t b = 0; b < boxes.size(); ++b) {
        const bool in = (cand[b / 64] >> (b % 64)) & 1u;
        listed_any += in;
        listed_any_aabb += (cand_plain[b / 64] >> (b % 64)) & 1u;
        if (distanceTo(c, obbs[b]) > 1.5 * radius) continue;
        if (!ballTouches(c, radius, obbs[b])) continue;
        ++total;
        listed += in;
        BOOST_TEST(in, "trial " << trial << " point " << k << " box " << b);
      }
    }
  }
  BOOST_TEST(total > 1000u);
  BOOST_TEST(listed == total);
  BOOST_TEST_MESSAGE("candidates listed: " << listed_any << " with oriented boxes, "
                                           << listed_any_aabb << " with world boxes alone");
  BOOST_TEST(listed_any < listed_any_aabb);
}

BOOST_AUTO_TEST_CASE(ball_apart_from_a_turned_box_at_the_boundary) {
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> u(-1.0, 1.0), f(0.01, 0.5);
  int apart = 0;
  for (int k = 0; k < 2000; ++k) {
    const TurnedBox t = turnedBox(rng, k % 5 == 0);
    // A point off a face, an edge or a corner of the box, at distance d from it.
    Eigen::Vector3d local(u(rng), u(rng), u(rng));
    Eigen::Vector3d on = local.cwiseProduct(t.obb.h), dir = Eigen::Vector3d::Zero();
    for (int i = 0; i <= k % 3; ++i) {  // 1, 2 or 3 axes out: a face, an edge, a corner
      const int a = (k + i) % 3;
      const double s = local[a] >= 0 ? 1.0 : -1.0;
      on[a] = s * t.obb.h[a];
      dir[a] = s;
    }
    const double d = f(rng);
    const Eigen::Vector3d c = t.obb.R * (on + d * dir.normalized()) + t.obb.c;
    // Apart a hair inside the true distance (1e-6 relative: far above the test's margin), not
    // apart a hair beyond it, and never for NaN.
    BOOST_TEST(dss::ballApartObb(c, d * (1.0 - 1e-6), t.obb), "ball " << k);
    BOOST_TEST(!dss::ballApartObb(c, d * (1.0 + 1e-12), t.obb), "ball " << k);
    BOOST_TEST(!dss::ballApartObb(c, d, t.obb), "ball " << k);
    apart += dss::ballApartObb(c, d * (1.0 - 1e-6), t.obb);
  }
  BOOST_TEST(apart == 2000);
  const TurnedBox t = turnedBox(rng, false);
  const double nan = std::numeric_limits<double>::quiet_NaN(),
               inf = std::numeric_limits<double>::infinity();
  BOOST_TEST(!dss::ballApartObb(Eigen::Vector3d(nan, 5.0, 5.0), 0.1, t.obb));
  BOOST_TEST(!dss::ballApartObb(Eigen::Vector3d(5.0, 5.0, 5.0), nan, t.obb));
  BOOST_TEST(!dss::ballApartObb(Eigen::Vector3d(5.0, 5.0, 5.0), inf, t.obb));
  BOOST_TEST(dss::ballApartObb(Eigen::Vector3d(5.0, 5.0, 5.0), 0.1, t.obb));
  BOOST_TEST(!dss::ballApartObb(t.obb.c, 0.0, t.obb));  // inside
}

// Every voxel holds the distance from the voxel (a cube) to the nearest obstacle's world box, or
// for a turned obstacle the larger of its world box's and its oriented box's distances from the
// voxel's centre less half the voxel's diagonal, rounded down to the quantum (at most one quantum
// lower, for the rounding margin), up to the largest byte: also in a scene wider than a byte's
// reach, where rows of voxels far from a box skip it, and with turned boxes among axis-aligned
// ones.
BOOST_AUTO_TEST_CASE(every_voxel_holds_the_distance_at_its_centre_to_the_quantum) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(0.0, 0.3);
  const double q = dss::ClearanceGrid::kQuantum;
  for (int trial = 0; trial < 8; ++trial) {
    const double spread = trial < 4 ? 1.0 : 6.0;  // 6: most rows are beyond a byte of a box
    std::vector<dss::Aabb> boxes;
    std::vector<dss::Obb> obbs;
    for (int k = 0; k < 2 + trial; ++k) {
      if (trial % 2) {
        TurnedBox t = turnedBox(rng, k % 2 == 0);
        const Eigen::Vector3d shift(spread * u(rng), spread * u(rng), spread * u(rng));
        t.aabb.lower += shift;
        t.aabb.upper += shift;
        t.obb.c += shift;
        boxes.push_back(t.aabb);
        obbs.push_back(t.obb);
      } else {
        const Eigen::Vector3d c(spread * u(rng), spread * u(rng), spread * u(rng)),
            h(e(rng), e(rng), e(rng));
        boxes.push_back(dss::Aabb{c - h, c + h});
      }
    }
    dss::Aabb region;
    region.lower = Eigen::Vector3d::Constant(-1.1 * spread);
    region.upper = Eigen::Vector3d(1.2, 1.0, 1.1) * spread;
    const dss::ClearanceGrid grid(region, boxes, obbs, 32768);
    const double size = grid.voxelSize(), half_diagonal = 0.5 * std::sqrt(3.0) * size;
    std::size_t visited = 0;
    int saturated = 0, positive = 0;
    const Eigen::Vector3d o = grid.origin();
    for (double z = o.z() + 0.5 * size; z < region.upper.z() + 0.5 * size; z += size)
      for (double y = o.y() + 0.5 * size; y < region.upper.y() + 0.5 * size; y += size)
        for (double x = o.x() + 0.5 * size; x < region.upper.x() + 0.5 * size; x += size) {
          const Eigen::Vector3d c(x, y, z);
          double d = std::numeric_limits<double>::infinity();
          for (std::size_t k = 0; k < boxes.size(); ++k) {
            const dss::Aabb& b = boxes[k];
            const bool turned = !obbs.empty() && !obbs[k].axis_aligned;
            const Eigen::Vector3d gap =
                ((c - b.center()).cwiseAbs() - 0.5 * (b.upper - b.lower)).array() -
                (turned ? 0.0 : 0.5 * size);
            double dk = gap.cwiseMax(0.0).norm();
            if (turned) dk = std::max(dk, distanceTo(c, obbs[k])) - half_diagonal;
            d = std::min(d, dk);
          }
          const double expected = std::max(0.0, std::min(255.0, std::floor(d / q)));
          const double got = grid.bound(c) / q;
          ++visited;
          saturated += got == 255.0;
          positive += got > 0.0;
          BOOST_TEST_REQUIRE(
              (got == expected || got == expected - 1.0 || (expected == 0.0 && got == 0.0)),
              "trial " << trial << " voxel at " << c.transpose() << ": " << got
                       << " quanta, expected " << expected);
        }
    BOOST_TEST(visited == grid.voxels());
    BOOST_TEST(positive > 0);
    if (spread > 1.0) BOOST_TEST(saturated > 0);
  }
}

// The upper bounds (buildUpper) must be proofs too: where one is known, some box lies within it
// of every point of the voxel (checked against the exact distance and the core's decision on
// the box itself, for points anywhere in the voxels and within a hair of their faces), and it
// is known wherever a box is nearer than the cap by 2.4 voxels (the bound exceeds the distance
// from the voxel's centre by at most 1.5 voxels for a turned box, and the centre lies within
// half a diagonal of the point). cell() holds both bounds, and the same for a point given in a
// pose's frame; outside the grid and for NaN it says nothing.
BOOST_AUTO_TEST_CASE(upper_bounds_are_proofs_and_cells_hold_both_bounds) {
  std::mt19937_64 rng(47);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double q = dss::ClearanceGrid::kQuantum;
  const std::uint8_t unknown = dss::ClearanceGrid::kUnknown;
  int known = 0, near = 0, near_known = 0, framed_same = 0, framed = 0;
  for (int trial = 0; trial < 10; ++trial) {
    const auto [boxes, obbs] = turnedBoxes(rng, 1 + trial % 6, [](int k) { return k % 2 == 0; });
    const dss::Aabb region = testRegion();
    dss::ClearanceGrid grid(region, boxes, obbs, trial % 2 ? 4096 : 32768);
    BOOST_TEST(!grid.hasCells());
    const double cap = 0.1 + 0.05 * trial;
    grid.buildUpper(obbs, cap);
    BOOST_REQUIRE(grid.hasCells());
    const double voxel = grid.voxelSize(), slack = 2.4 * voxel;
    for (int k = 0; k < 4000; ++k) {
      const Eigen::Vector3d c =
          pointFor(grid, k, Eigen::Vector3d(1.1 * u(rng), 1.1 * u(rng), 1.1 * u(rng)));
      const std::uint16_t v = grid.cell(c);
      BOOST_TEST((v & 0xff) * q == grid.bound(c));
      double d = std::numeric_limits<double>::infinity();
      for (const auto& b : obbs) d = std::min(d, distanceTo(c, b));
      const bool in_grid =
          (c.array() >= region.lower.array()).all() && (c.array() < region.upper.array()).all();
      if (in_grid && d + slack < cap) {
        ++near;
        near_known += (v >> 8) != unknown;
      }
      if ((v >> 8) == unknown) continue;
      ++known;
      const double upper = (v >> 8) * q;
      BOOST_TEST(d <= upper, "trial " << trial << " point " << k);
      BOOST_TEST(upper < cap + q);  // rounded up to the quantum
      bool touches = false;
      for (const auto& b : obbs) touches = touches || ballTouches(c, upper, b);
      BOOST_TEST(touches, "trial " << trial << " point " << k);
      // The same cell through a pose: a point of a frame X placed there.
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      X.linear() =
          Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
      X.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng));
      const Eigen::Vector3d p = X.inverse() * c;
      const std::uint16_t w = grid.cell(grid.frame(X), p);
      if (k % 3 != 0) {  // off the faces, the two roundings almost always agree
        ++framed;
        framed_same += w == grid.cell(X * p);
      }
      if ((w >> 8) != unknown) {
        double dw = std::numeric_limits<double>::infinity();
        for (const auto& b : obbs) dw = std::min(dw, distanceTo(X * p, b));
        BOOST_TEST(dw <= (w >> 8) * q);
      }
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    BOOST_TEST(grid.cell(Eigen::Vector3d(nan, 0, 0)) == dss::ClearanceGrid::kOutside);
    BOOST_TEST(grid.cell(Eigen::Vector3d(0, 0, 5.0)) == dss::ClearanceGrid::kOutside);
    BOOST_TEST(grid.cell(grid.frame(Eigen::Isometry3d::Identity()), Eigen::Vector3d(0, nan, 0)) ==
               dss::ClearanceGrid::kOutside);
  }
  BOOST_TEST_MESSAGE("upper bounds: " << known << " points known, " << near_known << " of " << near
                                      << " within the cap less 2.4 voxels");
  BOOST_TEST(known > 2000);
  BOOST_TEST(near_known == near);
  BOOST_TEST(framed_same >= framed * 99 / 100);
  // Without boxes: only the lower bounds, every upper one unknown.
  dss::Aabb region;
  region.lower = Eigen::Vector3d::Constant(-1.0);
  region.upper = Eigen::Vector3d::Constant(1.0);
  const TurnedBox t = turnedBox(rng, true);
  dss::ClearanceGrid grid(region, {t.aabb}, {t.obb});
  grid.buildUpper({}, 0.5);
  BOOST_REQUIRE(grid.hasCells());
  BOOST_TEST((grid.cell(t.obb.c) >> 8) == unknown);
  BOOST_TEST((grid.cell(Eigen::Vector3d(0.9, 0.9, 0.9)) & 0xff) * q ==
             grid.bound(Eigen::Vector3d(0.9, 0.9, 0.9)));
  // An empty grid: nothing at all.
  dss::ClearanceGrid empty;
  empty.buildUpper({t.obb}, 0.5);
  BOOST_TEST(!empty.hasCells());
  BOOST_TEST(empty.cell(Eigen::Vector3d::Zero()) == dss::ClearanceGrid::kOutside);
}

BOOST_AUTO_TEST_SUITE_END()
