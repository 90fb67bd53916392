// Tests of dss/mesh/mesh_parts.h: parts are the sets of triangles linked by shared vertex
// coordinates; every vertex lands in exactly one set; vertices no triangle uses form the last
// set; beyond the cap neighbouring sets are joined without losing a point.
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <tuple>

#include "dss/mesh/mesh_parts.h"
#include "support/thrown_message.h"

using dss::mesh::meshParts;
using dss::mesh::TriangleMesh;
using Eigen::Vector3d;

namespace {

using Key = std::tuple<double, double, double>;
Key key(const Vector3d& p) { return {p.x(), p.y(), p.z()}; }

// The 12 triangles of the box [lo, hi], STL style (every triangle with its own three vertex
// entries), appended to m.
void addBoxSoup(TriangleMesh& m, const Vector3d& lo, const Vector3d& hi) {
  auto corner = [&](int i) {
    return Vector3d(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  };
  static const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces)
    for (const auto& tri : {std::array<int, 3>{f[0], f[1], f[2]}, {f[0], f[2], f[3]}}) {
      const int base = static_cast<int>(m.vertices.size());
      for (int c : tri) m.vertices.push_back(corner(c));
      m.triangles.push_back({base, base + 1, base + 2});
    }
}

std::set<Key> keys(const std::vector<Vector3d>& pts) {
  std::set<Key> s;
  for (const auto& p : pts) s.insert(key(p));
  return s;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(mesh_parts)

BOOST_AUTO_TEST_CASE(separate_boxes_are_separate_parts_whatever_the_vertex_layout) {
  TriangleMesh m;
  addBoxSoup(m, Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  addBoxSoup(m, Vector3d(3, 0, 0), Vector3d(4, 1, 2));
  const auto parts = meshParts(m, 16, "two boxes");
  BOOST_REQUIRE(parts.size() == 2u);
  // Each part is its box's 8 corners, each once (the soup repeats them 4-6 times).
  for (const auto& p : parts) BOOST_TEST(p.size() == 8u);
  BOOST_TEST(keys(parts[0]).count(key(Vector3d(1, 1, 1))) == 1u);
  BOOST_TEST(keys(parts[1]).count(key(Vector3d(4, 1, 2))) == 1u);
  // One hull per mesh when asked for.
  const auto one = meshParts(m, 1, "two boxes");
  BOOST_REQUIRE(one.size() == 1u);
  BOOST_TEST(one[0].size() == 16u);
}

BOOST_AUTO_TEST_CASE(boxes_touching_at_a_corner_are_one_part) {
  TriangleMesh m;
  addBoxSoup(m, Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  addBoxSoup(m, Vector3d(1, 1, 1), Vector3d(2, 2, 2));  // shares the corner (1, 1, 1)
  BOOST_TEST(meshParts(m, 16, "corner").size() == 1u);
  // A hair apart: two parts.
  TriangleMesh n;
  addBoxSoup(n, Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  addBoxSoup(n, Vector3d(std::nextafter(1.0, 2.0), 1, 1), Vector3d(2, 2, 2));
  BOOST_TEST(meshParts(n, 16, "apart").size() == 2u);
}

BOOST_AUTO_TEST_CASE(unused_vertices_are_the_last_set) {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}, {0, 0, 1}, {5, 5, 5}, {6, 5, 5}};
  m.triangles = {{0, 1, 2}, {0, 1, 4}};
  const auto parts = meshParts(m, 16, "m");
  BOOST_REQUIRE(parts.size() == 2u);
  BOOST_TEST(parts[0].size() == 4u);
  BOOST_TEST(parts[1].size() == 2u);  // (5, 5, 5) once, and (6, 5, 5)
  // Without triangles every vertex is unused: one set, as the hull of all of them.
  TriangleMesh cloud;
  cloud.vertices = m.vertices;
  const auto all = meshParts(cloud, 16, "cloud");
  BOOST_REQUIRE(all.size() == 1u);
  BOOST_TEST(all[0].size() == 6u);
}

BOOST_AUTO_TEST_CASE(random_soups_split_into_their_clusters) {
  std::mt19937 rng(20261128);
  std::uniform_real_distribution<double> u(-10.0, 10.0), size(0.01, 0.5);
  for (int trial = 0; trial < 50; ++trial) {
    const int k = 1 + static_cast<int>(rng() % 12);
    // Boxes on a coarse lattice, so that they never touch.
    std::vector<std::pair<Vector3d, Vector3d>> boxes;
    std::set<Key> cells;
    while (static_cast<int>(boxes.size()) < k) {
      const Vector3d lo(std::floor(u(rng)), std::floor(u(rng)), std::floor(u(rng)));
      if (!cells.insert(key(lo)).second) continue;
      boxes.push_back({lo, lo + Vector3d(size(rng), size(rng), size(rng))});
    }
    TriangleMesh m;
    for (const auto& b : boxes) addBoxSoup(m, b.first, b.second);
    // Shuffle the triangles: the parts must not depend on their order.
    std::shuffle(m.triangles.begin(), m.triangles.end(), rng);
    const auto parts = meshParts(m, 64, "soup");
    BOOST_REQUIRE(parts.size() == boxes.size());
    std::set<Key> seen;
    for (const auto& p : parts) {
      BOOST_TEST(p.size() == 8u);
      for (const auto& x : p) BOOST_TEST(seen.insert(key(x)).second);  // in one set only
    }
    BOOST_TEST(seen == keys(m.vertices));
    // Capped: every point still in exactly one group, groups ordered along the longest axis.
    const std::size_t cap = 1 + rng() % 4;
    const auto groups = meshParts(m, cap, "soup");
    BOOST_TEST(groups.size() == std::min<std::size_t>(cap, boxes.size()));
    std::set<Key> joined;
    for (const auto& g : groups) {
      BOOST_TEST(!g.empty());
      for (const auto& x : g) BOOST_TEST(joined.insert(key(x)).second);
    }
    BOOST_TEST(joined == keys(m.vertices));
  }
}

BOOST_AUTO_TEST_CASE(joined_groups_are_runs_along_the_longest_axis) {
  TriangleMesh m;
  for (int i = 0; i < 40; ++i)
    addBoxSoup(m, Vector3d(2.0 * i, 0, 0), Vector3d(2.0 * i + 1.0, 1, 1));
  const auto groups = meshParts(m, 8, "row");
  BOOST_REQUIRE(groups.size() == 8u);
  double previous_max = -std::numeric_limits<double>::infinity();
  for (const auto& g : groups) {
    BOOST_TEST(g.size() == 40u);  // five boxes each
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& x : g) lo = std::min(lo, x.x()), hi = std::max(hi, x.x());
    BOOST_TEST(lo > previous_max);
    BOOST_TEST(hi - lo == 9.0);
    previous_max = hi;
  }
}

BOOST_AUTO_TEST_CASE(degenerate_meshes) {
  TriangleMesh tri;
  tri.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  tri.triangles = {{0, 1, 2}};
  BOOST_TEST(meshParts(tri, 4, "t").size() == 1u);
  TriangleMesh same;  // every vertex at one point, degenerate triangles
  same.vertices = {{1, 2, 3}, {1, 2, 3}, {1, 2, 3}};
  same.triangles = {{0, 1, 2}, {2, 1, 0}};
  const auto p = meshParts(same, 4, "s");
  BOOST_REQUIRE(p.size() == 1u);
  BOOST_TEST(p[0].size() == 1u);
}

BOOST_AUTO_TEST_CASE(bad_meshes_are_errors_naming_the_mesh) {
  TriangleMesh empty;
  BOOST_TEST(dss_test::thrownMessage<std::runtime_error>([&] {
               meshParts(empty, 4, "E");
             }).find("E: ") == 0u);
  TriangleMesh bad;
  bad.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  bad.triangles = {{0, 1, 3}};
  const std::string m =
      dss_test::thrownMessage<std::runtime_error>([&] { meshParts(bad, 4, "B"); });
  BOOST_TEST(m.find("B: triangle index 3 out of range") == 0u);
  bad.triangles = {{0, 1, -1}};
  BOOST_CHECK_THROW(meshParts(bad, 4, "B"), std::runtime_error);
  bad.triangles = {{0, 1, 2}};
  BOOST_CHECK_THROW(meshParts(bad, 0, "B"), std::runtime_error);
  bad.vertices[1].y() = std::numeric_limits<double>::quiet_NaN();
  BOOST_CHECK_THROW(meshParts(bad, 4, "B"), std::runtime_error);
}

// How far a hull reaches beyond its mesh: nowhere for a convex solid, across the opening of an
// open box (at least the distance from the lid's facet centroids to the walls, at most the
// distance from the lid's centre), nothing for a point cloud.
BOOST_AUTO_TEST_CASE(hull_excess_is_a_lower_bound_of_the_reach_beyond_the_mesh) {
  TriangleMesh box;
  addBoxSoup(box, Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  auto hullOf = [](const TriangleMesh& m) { return dss::mesh::convexHull(m.vertices, "test"); };
  BOOST_TEST(dss::mesh::hullExcess(box, hullOf(box)) < 1e-12);
  // The same box without its top face (z = 1): triangles 2 and 3 of addBoxSoup.
  TriangleMesh open = box;
  open.triangles.erase(open.triangles.begin() + 2, open.triangles.begin() + 4);
  const double e = dss::mesh::hullExcess(open, hullOf(open));
  BOOST_TEST(e >= 1.0 / 3.0 - 1e-12);
  BOOST_TEST(e <= 0.5);
  // Any budget keeps it a lower bound.
  BOOST_TEST(dss::mesh::hullExcess(open, hullOf(open), 1) <= 0.5);
  // Two boxes a metre apart in one hull: the gap.
  TriangleMesh two = box;
  addBoxSoup(two, Vector3d(2, 0, 0), Vector3d(3, 1, 1));
  const double g = dss::mesh::hullExcess(two, hullOf(two));
  BOOST_TEST(g > 0.3);
  BOOST_TEST(g <= 0.5 + 1e-12);
  TriangleMesh cloud;
  cloud.vertices = box.vertices;
  BOOST_TEST(dss::mesh::hullExcess(cloud, hullOf(cloud)) == 0.0);
}

BOOST_AUTO_TEST_SUITE_END()
