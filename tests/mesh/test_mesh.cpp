// Tests of dss/mesh/mesh.h: file formats, hulls of degenerate sets, tessellations.
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>

#include "dss/mesh/mesh.h"
#include "support/temp_files.h"

namespace fs = std::filesystem;
using Eigen::Vector3d;

namespace {

fs::path tempDir() { return dss_test::scratchDir("mesh"); }

std::string write(const std::string& name, const std::string& text) {
  return dss_test::writeScratch("mesh", name, text);
}

const char* kTetraStl =
    "solid t\n"
    "facet normal 0 0 -1\n outer loop\n vertex 0 0 0\n vertex 0 1 0\n vertex 1 0 0\n "
    "endloop\nendfacet\n"
    "facet normal 0 -1 0\n outer loop\n vertex 0 0 0\n vertex 1 0 0\n vertex 0 0 1\n "
    "endloop\nendfacet\n"
    "facet normal -1 0 0\n outer loop\n vertex 0 0 0\n vertex 0 0 1\n vertex 0 1 0\n "
    "endloop\nendfacet\n"
    "facet normal 1 1 1\n outer loop\n vertex 1 0 0\n vertex 0 1 0\n vertex 0 0 1\n "
    "endloop\nendfacet\n"
    "endsolid t\n";

std::string binaryStl(const std::vector<std::array<Vector3d, 3>>& tris) {
  std::string s(80, ' ');
  const std::uint32_t n = static_cast<std::uint32_t>(tris.size());
  s.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : tris) {
    float f[12] = {0, 0, 0};
    for (int v = 0; v < 3; ++v)
      for (int k = 0; k < 3; ++k) f[3 + 3 * v + k] = static_cast<float>(t[v][k]);
    s.append(reinterpret_cast<const char*>(f), sizeof f);
    s.append(2, '\0');
  }
  return s;
}

double maxSupport(const std::vector<Vector3d>& pts, const Vector3d& d) {
  double best = -1e300;
  for (const auto& p : pts) best = std::max(best, p.dot(d));
  return best;
}

Vector3d randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  Vector3d d(n(rng), n(rng), n(rng));
  return d.normalized();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(mesh_files)

BOOST_AUTO_TEST_CASE(ascii_stl) {
  const auto m = dss::mesh::loadMesh(write("tetra.stl", kTetraStl));
  BOOST_TEST(m.triangles.size() == 4u);
  const auto hull = dss::mesh::convexHull(m.vertices, "tetra");
  BOOST_TEST(hull.size() == 4u);
  BOOST_TEST(maxSupport(hull.points(), Vector3d(1, 1, 1)) == 1.0);
}

BOOST_AUTO_TEST_CASE(binary_stl_with_scale) {
  const std::vector<std::array<Vector3d, 3>> tris = {
      {Vector3d(0, 0, 0), Vector3d(0, 1, 0), Vector3d(1, 0, 0)},
      {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 0, 1)},
      {Vector3d(0, 0, 0), Vector3d(0, 0, 1), Vector3d(0, 1, 0)},
      {Vector3d(1, 0, 0), Vector3d(0, 1, 0), Vector3d(0, 0, 1)}};
  const auto m = dss::mesh::loadMesh(write("tetra_bin.stl", binaryStl(tris)), Vector3d(2, 3, 4));
  BOOST_TEST(m.triangles.size() == 4u);
  BOOST_TEST(maxSupport(m.vertices, Vector3d::UnitX()) == 2.0);
  BOOST_TEST(maxSupport(m.vertices, Vector3d::UnitY()) == 3.0);
  BOOST_TEST(maxSupport(m.vertices, Vector3d::UnitZ()) == 4.0);
}

BOOST_AUTO_TEST_CASE(obj_with_missing_mtl_and_double_space) {
  const std::string obj =
      "mtllib does_not_exist.mtl\n"
      "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 2\nvn 0 0 1\n"
      "f  1//1 3//1 2//1\nf  1//1 2//1 4//1\nf  1//1 4//1 3//1\nf  2//1 3//1 4//1\n";
  const auto m = dss::mesh::loadMesh(write("tetra.obj", obj));
  BOOST_TEST(m.triangles.size() == 4u);
  BOOST_TEST(maxSupport(m.vertices, Vector3d::UnitZ()) == 2.0);
}

// A unit tetrahedron in centimetres, Z_UP.
const std::string kTetraDae = R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="centimeter" meter="0.01"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries>
    <geometry id="g" name="g"><mesh>
      <source id="g-pos"><float_array id="g-pos-array" count="12">0 0 0 1 0 0 0 1 0 0 0 2</float_array>
        <technique_common><accessor source="#g-pos-array" count="4" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common></source>
      <vertices id="g-vtx"><input semantic="POSITION" source="#g-pos"/></vertices>
      <triangles count="4"><input semantic="VERTEX" source="#g-vtx" offset="0"/>
        <p>0 2 1 0 1 3 0 3 2 1 2 3</p></triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes><visual_scene id="s"><node id="n"><instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>)";

BOOST_AUTO_TEST_CASE(collada_units_applied_up_axis_ignored) {
  // Expect 0.01 m and no rotation.
  const auto m = dss::mesh::loadMesh(write("tetra.dae", kTetraDae));
  BOOST_TEST(m.triangles.size() == 4u);
  BOOST_TEST(std::abs(maxSupport(m.vertices, Vector3d::UnitZ()) - 0.02) < 1e-9);  // z stays z
  BOOST_TEST(std::abs(maxSupport(m.vertices, Vector3d::UnitY()) - 0.01) < 1e-9);
  BOOST_TEST(std::abs(maxSupport(m.vertices, Vector3d::UnitX()) - 0.01) < 1e-9);
}

// What assimp would trust is checked first (mesh_file_check.h), each error naming the file and
// the line: a stray character in a Collada number list (assimp appended one index until 3 GB
// were gone, found by fuzz/fuzz_mesh), counts larger than the file (assimp reserved them before
// reading), formats other than STL, DAE and OBJ.
BOOST_AUTO_TEST_CASE(mesh_files_are_checked_before_assimp) {
  auto refused = [](const std::string& name, const std::string& text, const std::string& what) {
    const std::string path = write(name, text);
    try {
      dss::mesh::loadMesh(path);
      BOOST_ERROR(name << ": expected an error");
    } catch (const std::runtime_error& e) {
      const std::string m = e.what();
      BOOST_TEST(m.find(path) != std::string::npos, m);
      BOOST_TEST(m.find(what) != std::string::npos, m);
    }
  };
  auto with = [](const std::string& from, const std::string& to) {
    std::string t = kTetraDae;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  refused("comma.dae", with("0 1 3 0 3 2", "0 1 3,0 3 2"), "line 12: <p> holds a character");
  refused("letter.DAE", with("0 0 0 1 0 0", "0 0 x 1 0 0"), "line 6: <float_array>");
  refused("count.dae", with("<triangles count=\"4\"", "<triangles count=\"2000000000\""),
          "line 11: <triangles> declares a count larger than the file");
  // assimp crashed on an array without a count (found by fuzz/fuzz_mesh).
  refused("nocount.dae", with("count=\"12\"", "couft=\"12\""),
          "line 6: <float_array> needs a count attribute of digits");
  refused("short.dae", with("count=\"12\"", "count=\"11\""),
          "line 6: <float_array> holds 12 values, not its count 11");
  refused("past.dae", with("count=\"4\" stride", "count=\"5\" stride"),
          "line 7: <accessor> reads past its array 'g-pos-array' of 12 values");
  refused("nosource.dae", with("source=\"#g-pos-array\"", "source=\"#elsewhere\""),
          "line 7: <accessor> needs a source naming an array of the file");
  refused("noprimcount.dae", with("<triangles count=\"4\"", "<triangles"),
          "line 11: <triangles> needs a count attribute of digits");
  std::string deep = kTetraDae, open, close;
  for (int i = 0; i < 300; ++i) open += "<a>", close += "</a>";
  deep.insert(deep.find("<asset>"), open + close);
  refused("deep.dae", deep, "XML nesting deeper than 256 levels");
  refused("latin1.dae", with("<asset>", "<asset><!-- \xE9 -->"), "is not UTF-8 (byte 0xE9)");
  refused("tetra.fbx", kTetraDae, "the format '.fbx' is not read");
  refused("tetra", kTetraDae, "a file without an extension is not read");
  // Signs, exponents and line breaks are numbers and white space; a count the file can hold
  // is fine.
  auto m = dss::mesh::loadMesh(
      write("signs.dae", with("0 0 0 1 0 0 0 1 0 0 0 2", "+0 -0 0e0\n1E0 0 0 0 1.0 0 0 0 2")));
  BOOST_TEST(m.triangles.size() == 4u);

  // assimp's PLY reader aborted the process on a binary face list of length zero.
  refused("zero_faces.ply",
          "ply\nformat binary_little_endian 1.0\nelement face 1\nproperty list uchar int "
          "vertex_indices\nend_header\n" +
              std::string(1, '\0'),
          "the format '.ply' is not read");
}

BOOST_AUTO_TEST_CASE(errors_name_the_path) {
  const std::string missing = (tempDir() / "nope.stl").string();
  try {
    dss::mesh::loadMesh(missing);
    BOOST_FAIL("expected an exception");
  } catch (const std::runtime_error& e) {
    BOOST_TEST(std::string(e.what()).find(missing) != std::string::npos);
  }
  const std::string empty = write("empty.stl", "");
  try {
    dss::mesh::loadMesh(empty);
    BOOST_FAIL("expected an exception");
  } catch (const std::runtime_error& e) {
    BOOST_TEST(std::string(e.what()).find(empty) != std::string::npos);
  }
  const std::string garbage = write("garbage.obj", "this is not a mesh\n");
  BOOST_CHECK_THROW(dss::mesh::loadMesh(garbage), std::runtime_error);
  BOOST_CHECK_THROW(dss::mesh::loadMesh(write("t2.stl", kTetraStl), Vector3d(1, NAN, 1)),
                    std::runtime_error);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(hulls)

BOOST_AUTO_TEST_CASE(cube_with_interior_points) {
  std::vector<Vector3d> pts;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-0.99, 0.99);
  for (int i = 0; i < 200; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
  for (int i = 0; i < 8; ++i) pts.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
  dss::mesh::HullInfo info;
  const auto hull = dss::mesh::convexHull(pts, "cube", &info);
  BOOST_TEST(info.full_dimensional);
  BOOST_TEST(hull.size() == 8u);
}

BOOST_AUTO_TEST_CASE(many_points_climb_and_agree_with_scan) {
  std::vector<Vector3d> pts;
  std::mt19937_64 rng(5);
  for (int i = 0; i < 2000; ++i)
    pts.push_back(randomUnit(rng) * (1.0 + 0.1 * std::uniform_real_distribution<double>()(rng)));
  const auto hull = dss::mesh::convexHull(pts, "ball");
  BOOST_TEST(hull.climbs());
  for (int i = 0; i < 2000; ++i) {
    const Vector3d d = randomUnit(rng);
    // Climbing reaches a maximiser: the same value as the scan over all input points.
    BOOST_TEST(hull.points()[hull.supportIndex(d)].dot(d) == maxSupport(pts, d));
  }
}

// Cells of the climbing cube map whose support vertex is certified answer without a dot
// product: on a robot-sized hull most of them are, and the answer must still be a maximiser
// for every direction, including directions on cell corners and edges, within rounding of
// them, and far from unit length.
BOOST_AUTO_TEST_CASE(certified_cells_give_maximisers) {
  std::mt19937_64 rng(11);
  std::vector<Vector3d> pts;
  for (int i = 0; i < 150; ++i) {
    const Vector3d u = randomUnit(rng);
    pts.push_back(Vector3d(0.05 * u.x(), 0.08 * u.y(), 0.15 * u.z()) + Vector3d(0.01, -0.02, 0.1));
  }
  const auto hull = dss::mesh::convexHull(pts, "ellipsoid");
  BOOST_TEST_REQUIRE(hull.climbs());
  const std::size_t cells = 6 * dss::kSeedGrid * dss::kSeedGrid;
  BOOST_TEST(hull.certifiedCells() > cells / 4, hull.certifiedCells()
                                                    << " of " << cells << " certified");
  BOOST_TEST(hull.certifiedCells() < cells);
  auto check = [&](const Vector3d& d) {
    BOOST_TEST_REQUIRE(hull.points()[hull.supportIndex(d)].dot(d) == maxSupport(hull.points(), d),
                       "d = " << d.transpose());
  };
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const int G = dss::kSeedGrid;
  for (int face = 0; face < 6; ++face)
    for (int i = 0; i <= G; ++i)
      for (int j = 0; j <= G; ++j)
        for (const double eps : {0.0, 1e-15, -1e-15, 1e-9, -1e-9}) {
          const int k = face / 2;
          Vector3d d;
          d[k] = face % 2 ? -1.0 : 1.0;
          d[(k + 1) % 3] = -1.0 + 2.0 * i / G + eps;
          d[(k + 2) % 3] = -1.0 + 2.0 * j / G - eps;
          check(d);
          check(1e-200 * d);
          check(1e200 * d);
        }
  for (int n = 0; n < 20000; ++n) check(Vector3d(unit(rng), unit(rng), unit(rng)));
  // Zero and non-finite directions: some vertex, no crash.
  for (const Vector3d& d : {Vector3d(0, 0, 0), Vector3d(NAN, 0, 1), Vector3d(INFINITY, 1, 0)}) {
    const int v = hull.supportIndex(d);
    BOOST_TEST((v >= 0 && v < int(hull.size())));
  }
}

// A hull with so many vertices that some cube-map cells hold more candidates than they keep:
// those cells climb along hull edges, and every answer is still a maximiser.
BOOST_AUTO_TEST_CASE(crowded_cells_climb) {
  std::mt19937_64 rng(13);
  std::vector<Vector3d> pts;
  for (int i = 0; i < 6000; ++i) pts.push_back(randomUnit(rng));
  const auto hull = dss::mesh::convexHull(pts, "sphere");
  BOOST_TEST_REQUIRE(hull.climbs());
  BOOST_TEST(hull.climbingCells() > 0u);
  BOOST_TEST(hull.climbingCells() < 6u * dss::kSeedGrid * dss::kSeedGrid);
  for (int n = 0; n < 5000; ++n) {
    const Vector3d d = randomUnit(rng);
    BOOST_TEST_REQUIRE(hull.points()[hull.supportIndex(d)].dot(d) == maxSupport(hull.points(), d));
  }
}

BOOST_AUTO_TEST_CASE(degenerate_sets_fall_back_to_points) {
  dss::mesh::HullInfo info;
  // flat square with a duplicate and an interior point
  std::vector<Vector3d> flat = {Vector3d(0, 0, 1), Vector3d(1, 0, 1), Vector3d(1, 1, 1),
                                Vector3d(0, 1, 1), Vector3d(0, 0, 1), Vector3d(0.5, 0.5, 1)};
  auto h = dss::mesh::convexHull(flat, "flat", &info);
  BOOST_TEST(!info.full_dimensional);
  BOOST_TEST(h.size() == 5u);  // distinct points
  BOOST_TEST(maxSupport(h.points(), Vector3d(1, 1, 0)) == 2.0);
  // collinear
  h = dss::mesh::convexHull({Vector3d(0, 0, 0), Vector3d(1, 1, 1), Vector3d(2, 2, 2),
                             Vector3d(3, 3, 3), Vector3d(4, 4, 4)},
                            "line", &info);
  BOOST_TEST(!info.full_dimensional);
  BOOST_TEST(maxSupport(h.points(), Vector3d(1, 0, 0)) == 4.0);
  // one point, repeated
  h = dss::mesh::convexHull({Vector3d(1, 2, 3), Vector3d(1, 2, 3), Vector3d(1, 2, 3)}, "point");
  BOOST_TEST(h.size() == 1u);
  // tiny (1e-12) but full-dimensional: either answer is correct as long as support is exact
  std::vector<Vector3d> tiny = {Vector3d(0, 0, 0), Vector3d(1e-12, 0, 0), Vector3d(0, 1e-12, 0),
                                Vector3d(0, 0, 1e-12)};
  h = dss::mesh::convexHull(tiny, "tiny");
  BOOST_TEST(maxSupport(h.points(), Vector3d(1, 1, 1)) == 1e-12);
}

// qhull sees the points scaled by a power of two: the same integer clouds scaled by 2^k at
// the ends of the double range give the same hull (the vertices scaled by 2^k, bit for bit)
// and supports equal to the scan's. Unscaled, 2^-1000 made qhull's facet normals vanish and
// crash it (found by fuzz/fuzz_core).
BOOST_AUTO_TEST_CASE(hulls_at_extreme_scales) {
  std::mt19937_64 rng(17);
  std::uniform_int_distribution<int> coord(-1000, 1000);
  for (int cloud = 0; cloud < 20; ++cloud) {
    std::vector<Vector3d> ints;
    const int n = 40 + 10 * (cloud % 5);
    for (int i = 0; i < n; ++i) ints.emplace_back(coord(rng), coord(rng), coord(rng));
    dss::mesh::HullInfo info0;
    const auto h0 = dss::mesh::convexHull(ints, "ints", &info0);
    BOOST_TEST_REQUIRE(info0.full_dimensional);
    for (const int k : {-1060, -1000, -600, 600, 1000, 1012}) {
      std::vector<Vector3d> scaled;
      for (const Vector3d& p : ints)
        scaled.emplace_back(std::ldexp(p.x(), k), std::ldexp(p.y(), k), std::ldexp(p.z(), k));
      dss::mesh::HullInfo info;
      const auto h = dss::mesh::convexHull(scaled, "scaled", &info);
      BOOST_TEST(info.full_dimensional, "k " << k);
      BOOST_TEST(h.size() == h0.size(), "k " << k);
      for (int t = 0; t < 200; ++t) {
        const Vector3d d = randomUnit(rng);
        BOOST_TEST_REQUIRE(h.points()[h.supportIndex(d)].dot(d) == maxSupport(scaled, d),
                           "k " << k << ", d = " << d.transpose());
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(bad_input_throws_naming_the_source) {
  try {
    dss::mesh::convexHull({}, "link x collision[2]");
    BOOST_FAIL("expected an exception");
  } catch (const std::runtime_error& e) {
    BOOST_TEST(std::string(e.what()).find("link x collision[2]") != std::string::npos);
  }
  BOOST_CHECK_THROW(dss::mesh::convexHull({Vector3d(0, 0, 0), Vector3d(NAN, 0, 0)}, "nan"),
                    std::runtime_error);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(tessellation)

// The hull of a tessellation lies inside the primitive (vertices on its surface) and within
// the chord error of it: for a curve of radius r split in n segments the gap is at most
// r (1 - cos(pi/n)); latitude bands double the step, hence the bound r (1 - cos(2 pi/n)).
BOOST_AUTO_TEST_CASE(hull_of_tessellation_agrees_with_primitive) {
  const int n = 32;
  const double chord = 1.0 - std::cos(2.0 * M_PI / n);
  struct Case {
    dss::AnyShape shape;
    double radius;  // curvature radius scaling the chord error (0: exact)
  };
  const std::vector<Case> cases = {
      {dss::Box::fromSize(Vector3d(0.2, 0.4, 1.0)), 0.0},
      {dss::Sphere{0.7}, 0.7},
      {dss::Cylinder::fromLength(0.3, 1.2), 0.3},
      {dss::Cone::fromLength(0.5, 0.8), 0.5},
      {dss::Capsule::fromLength(0.25, 0.9), 0.25},
      {dss::Ellipsoid{Vector3d(0.3, 0.5, 0.9)}, 0.9},
  };
  std::mt19937_64 rng(11);
  for (const auto& c : cases) {
    const auto mesh = dss::mesh::tessellate(c.shape, n);
    BOOST_TEST_CONTEXT(dss::shapeTypeName(c.shape)) {
      BOOST_TEST(!mesh.triangles.empty());
      // closed surface: every edge used by two triangles
      std::map<std::pair<int, int>, int> edges;
      for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k)
          ++edges[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
      for (const auto& [e, count] : edges) BOOST_TEST(count == 2);
      const auto hull = dss::mesh::convexHull(mesh.vertices, "tessellation");
      for (int i = 0; i < 500; ++i) {
        const Vector3d d = randomUnit(rng);
        const double exact = std::visit(
            [&](const auto& s) { return s.support(d, Vector3d::Zero()).dot(d); }, c.shape);
        const double approx = hull.support(d, Vector3d::Zero()).dot(d);
        BOOST_TEST(approx <= exact + 1e-12);  // k = 1e4 ulps of unit-size coordinates
        BOOST_TEST(approx >= exact - c.radius * chord - 1e-12);
      }
    }
  }
  // A hull tessellates to its own facets.
  const auto box = dss::mesh::tessellate(dss::Box::fromSize(Vector3d(1, 2, 3)));
  const auto again =
      dss::mesh::tessellate(dss::AnyShape(dss::mesh::convexHull(box.vertices, "box")));
  BOOST_TEST(again.vertices.size() == 8u);
  BOOST_TEST(again.triangles.size() == 12u);
  BOOST_CHECK_THROW(dss::mesh::tessellate(dss::Sphere{1.0}, 2), std::invalid_argument);
}

BOOST_AUTO_TEST_SUITE_END()
