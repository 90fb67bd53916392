// The k-d tree of buckets (PointTree) against a scan of every point: the same nearest point
// (the least squared distance below infinity, summed as OMPL sums it, the lowest index among
// equal ones), the same k nearest and the same points within a radius, on random, clustered and
// tied points, with removals, points added in sorted order, points it cannot tell apart and
// non-finite values, on every instruction set; PointBlocks and VectorNearestNeighbors past the size
// where they hand their queries to it.
// clang-format off
#include <iostream>  // before GNAT's header, which uses std::cout without including it
// clang-format on

#include <ompl/datastructures/NearestNeighborsGNATNoThreadSafety.h>

#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <deque>
#include <limits>
#include <random>
#include <vector>

#include "dss/planning/point_blocks.h"
#include "dss/planning/point_tree.h"
#include "dss/planning/vector_nearest_neighbors.h"
#include "support/simd_paths.h"

namespace ob = ompl::base;

namespace {

constexpr std::size_t kNone = dss::PointTree::kNone;
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

using dss_test::availablePaths;

// The points by index, as PointBlocks holds them (a removal moves the last point into the
// place), and the scan every search must agree with.
struct Reference {
  unsigned dim;
  std::vector<std::vector<double>> pts;

  double squared(const std::vector<double>& p, const double* q) const {
    double s = 0.0;
    for (unsigned d = 0; d < dim; ++d) {
      const double diff = p[d] - q[d];
      s += diff * diff;
    }
    return s;
  }
  // Every (squared distance, index), a NaN distance as infinite, sorted.
  std::vector<dss::PointTree::Found> sorted(const double* q) const {
    std::vector<dss::PointTree::Found> all;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const double s = squared(pts[i], q);
      all.emplace_back(std::isnan(s) ? kInf : s, i);
    }
    std::sort(all.begin(), all.end());
    return all;
  }
  std::size_t nearest(const double* q) const {
    double best = kInf;
    std::size_t best_i = kNone;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const double s = squared(pts[i], q);
      if (s < best) best = s, best_i = i;
    }
    return best_i;
  }
};

// Points of several kinds: uniform, in tight clusters, on a small integer grid (many exact ties
// between distances), copies of earlier points, and a few with NaN or infinite values.
std::vector<double> drawPoint(int kind, unsigned dim, std::mt19937_64& rng,
                              const std::vector<std::vector<double>>& earlier) {
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> v(dim);
  switch (kind) {
    case 0:
      for (double& x : v) x = u(rng);
      break;
    case 1: {  // clusters around eight centres, some of them tiny
      const int c = int(rng() % 8);
      const double scale = c < 2 ? 1e-9 : 0.05;
      for (unsigned d = 0; d < dim; ++d) v[d] = double((c * 7 + int(d) * 3) % 5) + scale * g(rng);
      break;
    }
    case 2:
      for (double& x : v) x = double(int(rng() % 5) - 2);
      break;
    default:
      if (!earlier.empty()) return earlier[rng() % earlier.size()];
      for (double& x : v) x = u(rng);
      break;
  }
  if (rng() % 97 == 0) v[rng() % dim] = rng() % 2 ? kNaN : (rng() % 2 ? kInf : -kInf);
  return v;
}

std::vector<double> drawQuery(unsigned dim, std::mt19937_64& rng, const Reference& ref) {
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  std::vector<double> q(dim);
  switch (rng() % 6) {
    case 0:  // on a point
      if (!ref.pts.empty()) {
        q = ref.pts[rng() % ref.pts.size()];
        break;
      }
      [[fallthrough]];
    case 1:
      for (double& x : q) x = u(rng);
      break;
    case 2:  // on the grid: ties
      for (double& x : q) x = 0.5 * double(int(rng() % 9) - 4);
      break;
    case 3:  // far outside every box
      for (double& x : q) x = 1e6 * u(rng);
      break;
    default:
      for (double& x : q) x = u(rng);
      if (rng() % 8 == 0) q[rng() % dim] = rng() % 2 ? kNaN : kInf;
      break;
  }
  return q;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(point_tree)

BOOST_AUTO_TEST_CASE(finds_what_a_scan_finds_with_additions_and_removals) {
  std::mt19937_64 rng(2024);
  int queries = 0;
  for (int round = 0; round < 48; ++round) {
    const unsigned dim = 1 + unsigned(round % 9);
    const int kind = round % 4;
    const std::size_t target =
        std::size_t(std::vector<int>{0, 1, 17, 150, 400, 1500, 5000}[round % 7]);
    Reference ref{dim, {}};
    std::vector<dss::PointTree> trees;
    for (auto p : availablePaths()) trees.emplace_back(dim, p);
    for (std::size_t step = 0; step < target + target / 3; ++step) {
      if (step % 4 == 3 && !ref.pts.empty()) {  // remove one: the last point takes its index
        const std::size_t i = std::size_t(rng() % ref.pts.size());
        const std::size_t last = ref.pts.size() - 1;
        for (auto& t : trees) t.swapRemove(i, last);
        ref.pts[i] = ref.pts[last];
        ref.pts.pop_back();
      } else {
        const std::vector<double> v =
            drawPoint(kind == 3 ? int(rng() % 4) : kind, dim, rng, ref.pts);
        for (auto& t : trees) t.insert(ref.pts.size(), v.data());
        ref.pts.push_back(v);
      }
      if (step % (target >= 1500 ? 97 : 5) != 0 && step + 1 != target + target / 3) continue;
      for (int k = 0; k < 4; ++k, ++queries) {
        const std::vector<double> q = drawQuery(dim, rng, ref);
        const std::size_t expected = ref.nearest(q.data());
        // The k nearest, and the points within the distance of one of them (included) and
        // one ulp below it (excluded).
        const std::vector<dss::PointTree::Found> all = ref.sorted(q.data());
        const std::size_t kk = std::size_t(rng() % 40);
        std::vector<dss::PointTree::Found> k_expected(all.begin(),
                                                      all.begin() + std::min(kk, all.size()));
        const double r_at = all.empty() ? 1.0 : std::sqrt(all[rng() % all.size()].first);
        std::vector<dss::PointTree::Found> found;
        for (std::size_t t = 0; t < trees.size(); ++t) {
          trees[t].nearestK(q.data(), kk, found);
          BOOST_REQUIRE_MESSAGE(found == k_expected, "k nearest, k = " << kk);
          for (const double r : {r_at, std::nextafter(r_at, 0.0)}) {
            std::vector<dss::PointTree::Found> r_expected;
            for (const auto& e : all)
              if (std::sqrt(ref.squared(ref.pts[e.second], q.data())) <= r)
                r_expected.emplace_back(ref.squared(ref.pts[e.second], q.data()), e.second);
            trees[t].withinRadius(q.data(), r, found);
            BOOST_REQUIRE_MESSAGE(found == r_expected, "within " << r << ": " << found.size()
                                                                 << " points, expected "
                                                                 << r_expected.size());
          }
        }
        for (std::size_t t = 0; t < trees.size(); ++t) {
          BOOST_REQUIRE_EQUAL(trees[t].size(), ref.pts.size());
          const std::size_t got = trees[t].nearest(q.data());
          BOOST_REQUIRE_MESSAGE(got == expected,
                                "round " << round << " dim " << dim << " points " << ref.pts.size()
                                         << " path " << dss::simdPathName(availablePaths()[t])
                                         << ": nearest " << got << ", expected " << expected);
        }
      }
    }
  }
  BOOST_TEST_MESSAGE(queries << " queries");
}

BOOST_AUTO_TEST_CASE(points_added_in_sorted_order_leave_a_shallow_tree) {
  // Each new point goes to the last bucket: without rebuilding, the tree would be a chain of
  // buckets, 20 000 / kBucket of them.
  for (auto path : availablePaths()) {
    const unsigned dim = 3;
    Reference ref{dim, {}};
    dss::PointTree tree(dim, path);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < 20000; ++i) {
      const std::vector<double> v = {double(i) * 1e-3, u(rng), u(rng)};
      tree.insert(ref.pts.size(), v.data());
      ref.pts.push_back(v);
    }
    // A balanced tree of 20 000 points in buckets of kBucket is about log2(20 000 / kBucket)
    // deep; it may grow to twice that, and some.
    const int balanced = int(std::ceil(std::log2(20000.0 / double(dss::PointTree::kBucket) + 1.0)));
    BOOST_CHECK_LE(tree.depth(), 2 * balanced + 8);
    BOOST_CHECK_GE(tree.depth(), balanced - 1);
    for (int k = 0; k < 300; ++k) {
      const std::vector<double> q = {u(rng) * 25.0 - 2.0, u(rng), u(rng)};
      BOOST_REQUIRE_EQUAL(tree.nearest(q.data()), ref.nearest(q.data()));
    }
  }
}

BOOST_AUTO_TEST_CASE(points_it_cannot_tell_apart_and_non_finite_values) {
  for (auto path : availablePaths()) {
    const unsigned dim = 4;
    Reference ref{dim, {}};
    dss::PointTree tree(dim, path);
    const std::vector<double> same = {1, 2, 3, 4}, nan_point = {kNaN, 0, 0, 0},
                              inf_point = {kInf, 0, 0, 0};
    // 200 copies of one point and NaN points in one bucket that cannot split.
    for (int i = 0; i < 300; ++i) {
      const std::vector<double>& v = i % 3 == 2 ? nan_point : same;
      tree.insert(ref.pts.size(), v.data());
      ref.pts.push_back(v);
    }
    const double q[4] = {0, 0, 0, 0};
    BOOST_CHECK_EQUAL(tree.nearest(q), 0u);  // the first of the equal ones
    BOOST_CHECK_EQUAL(tree.nearest(same.data()), 0u);
    // A NaN or infinite query: no point below infinity.
    const double qn[4] = {0, kNaN, 0, 0}, qi[4] = {0, 0, -kInf, 0};
    BOOST_CHECK(tree.nearest(qn) == kNone);
    BOOST_CHECK(tree.nearest(qi) == kNone);
    // Removing the first copies moves later ones into their places.
    for (int k = 0; k < 5; ++k) {
      const std::size_t last = ref.pts.size() - 1;
      tree.swapRemove(0, last);
      ref.pts[0] = ref.pts[last];
      ref.pts.pop_back();
      BOOST_REQUIRE_EQUAL(tree.nearest(q), ref.nearest(q));
    }
    // An infinite point is never nearest; a finite one among spread points still is.
    tree.insert(ref.pts.size(), inf_point.data());
    ref.pts.push_back(inf_point);
    const std::vector<double> near = {0.5, 0.5, 0.5, 0.5};
    tree.insert(ref.pts.size(), near.data());
    ref.pts.push_back(near);
    BOOST_CHECK_EQUAL(tree.nearest(q), ref.pts.size() - 1);
    tree.clear();
    BOOST_CHECK_EQUAL(tree.size(), 0u);
    BOOST_CHECK(tree.nearest(q) == kNone);
  }
}

BOOST_AUTO_TEST_CASE(point_blocks_with_the_tree_find_what_their_scan_finds) {
  std::mt19937_64 rng(77);
  const unsigned dim = 7;
  for (auto path : availablePaths()) {
    dss::PointBlocks with(dim, path), scan(dim, path, std::numeric_limits<std::size_t>::max());
    Reference ref{dim, {}};
    for (int step = 0; step < 3000; ++step) {
      if (step % 9 == 4) {
        const std::size_t i = std::size_t(rng() % ref.pts.size());
        with.swapRemove(i);
        scan.swapRemove(i);
        ref.pts[i] = ref.pts.back();
        ref.pts.pop_back();
        continue;
      }
      const std::vector<double> v = drawPoint(int(rng() % 4), dim, rng, ref.pts);
      with.push(v.data());
      scan.push(v.data());
      ref.pts.push_back(v);
      if (step % 7 != 0) continue;
      const std::vector<double> q = drawQuery(dim, rng, ref);
      BOOST_REQUIRE_EQUAL(with.nearest(q.data()), scan.nearest(q.data()));
      std::vector<dss::PointBlocks::Found> a, b;
      with.nearestK(q.data(), 10, a);
      scan.nearestK(q.data(), 10, b);
      BOOST_REQUIRE(a == b);
      const double r = b.empty() ? 1.0 : std::sqrt(b.back().first);
      with.withinRadius(q.data(), r, a);
      scan.withinRadius(q.data(), r, b);
      BOOST_REQUIRE(a == b);
    }
    BOOST_CHECK_GT(with.size(), dss::PointBlocks::kTreeFrom);
  }
}

BOOST_AUTO_TEST_CASE(vector_nearest_neighbors_past_the_tree_size_answer_as_gnat) {
  struct Item {
    ob::State* state;
  };
  const unsigned dim = 7;
  auto space = std::make_shared<ob::RealVectorStateSpace>(dim);
  std::deque<Item> items;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  auto add = [&] {
    items.push_back({space->allocState()});
    double* v = items.back().state->as<ob::RealVectorStateSpace::StateType>()->values;
    for (unsigned d = 0; d < dim; ++d) v[d] = u(rng);
    return &items.back();
  };
  auto distance = [&](Item* const& a, Item* const& b) {
    return space->distance(a->state, b->state);
  };
  dss::VectorNearestNeighbors<Item*> vec(dim);
  ompl::NearestNeighborsGNATNoThreadSafety<Item*> gnat;
  gnat.setDistanceFunction(distance);
  for (int i = 0; i < 2000; ++i) {
    Item* it = add();
    vec.add(it);
    gnat.add(it);
    if (i % 10 != 0) continue;
    Item* q = add();
    BOOST_REQUIRE_EQUAL(vec.nearest(q), gnat.nearest(q));
  }
  BOOST_CHECK(!vec.usesTree());  // the GNAT is never used by default
  for (Item& it : items) space->freeState(it.state);
}

BOOST_AUTO_TEST_SUITE_END()
