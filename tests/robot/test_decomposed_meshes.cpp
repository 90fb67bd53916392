// Robot meshes as convex pieces (LoadOptions::meshes, urdf_loader.h): a concave link becomes
// several elements that cover its mesh, a nearly convex one stays one hull, options per link
// and per robot, the decomposition cache (a second load reads it; a damaged or foreign file is
// recomputed, never trusted), and a link named in the options that the robot lacks is an error.
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "dss/core/any_shape_query.h"
#include "dss/mesh/decomposition_cache.h"
#include "dss/robot/urdf_loader.h"
#include "support/temp_files.h"
#include "support/thrown_message.h"

namespace fs = std::filesystem;

namespace {

// An ASCII STL of an L-shaped block (two 0.2 x 0.1 x 0.1 m arms), outward facets.
std::string lShapeStl() {
  const double px[6] = {0, 0.2, 0.2, 0.1, 0.1, 0}, pz[6] = {0, 0, 0.1, 0.1, 0.2, 0.2};
  auto v = [&](int i, int side) { return Eigen::Vector3d(px[i], 0.1 * side, pz[i]); };
  std::ostringstream os;
  os.precision(17);
  auto facet = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    os << "facet normal " << n.x() << " " << n.y() << " " << n.z() << "\n outer loop\n";
    for (const auto* p : {&a, &b, &c})
      os << "  vertex " << p->x() << " " << p->y() << " " << p->z() << "\n";
    os << " endloop\nendfacet\n";
  };
  os << "solid l\n";
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    facet(v(i, 0), v(j, 1), v(j, 0));
    facet(v(i, 0), v(i, 1), v(j, 1));
  }
  const int fan[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};
  for (const auto& f : fan) {
    facet(v(f[0], 0), v(f[1], 0), v(f[2], 0));
    facet(v(f[0], 1), v(f[2], 1), v(f[1], 1));
  }
  os << "endsolid l\n";
  return os.str();
}

// Two links: "bent" carries the L mesh, "plain" a box mesh (convex).
std::string writeRobot() {
  dss_test::writeScratch("robot", "decomposed/l.stl", lShapeStl());
  return dss_test::writeScratch("robot", "decomposed/bent.urdf", R"(<robot name="bent">
  <link name="base"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="bent"><collision><geometry><mesh filename="l.stl"/></geometry></collision></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="bent"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>)");
}

dss::LoadOptions decomposing(const std::string& cache) {
  dss::LoadOptions o;
  o.meshes.geometry = dss::MeshGeometry::kDecompose;
  o.meshes.decomposition.tolerance = 0.005;
  o.meshes.cache_dir = cache;
  return o;
}

std::vector<std::vector<Eigen::Vector3d>> piecePoints(const dss::RobotModel& m) {
  std::vector<std::vector<Eigen::Vector3d>> out;
  for (const auto& c : m.links[m.linkIndex("bent")].collisions)
    out.push_back(std::get<dss::ConvexHull>(c.shape).points());
  return out;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(decomposed_meshes)

BOOST_AUTO_TEST_CASE(a_concave_mesh_becomes_pieces_that_cover_it) {
  const std::string urdf = writeRobot();
  const dss::RobotModel hull = dss::loadUrdf(urdf);
  const auto& one = hull.links[hull.linkIndex("bent")].collisions;
  BOOST_TEST_REQUIRE(one.size() == 1u);
  BOOST_TEST(one[0].piece == -1);

  const dss::RobotModel pieces = dss::loadUrdf(urdf, decomposing(""));
  const auto& els = pieces.links[pieces.linkIndex("bent")].collisions;
  BOOST_TEST_REQUIRE(els.size() >= 2u);
  for (std::size_t i = 0; i < els.size(); ++i) {
    BOOST_TEST(els[i].piece == int(i));
    BOOST_TEST(els[i].pieces == int(els.size()));
    BOOST_TEST(els[i].concavity <= 0.005);
    BOOST_TEST(els[i].description.find("piece " + std::to_string(i + 1) + "/") !=
               std::string::npos);
    BOOST_TEST(els[i].mesh_path == one[0].mesh_path);
  }
  // The box link is a primitive: untouched.
  BOOST_TEST(pieces.links[pieces.linkIndex("base")].collisions.size() == 1u);

  // Every point of the L (seeded samples of its two arms' solid) lies in a piece; the notch
  // (inside the hull, outside the L) lies in none.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto inPiece = [&](const Eigen::Vector3d& p) {
    const dss::AnyShape point = dss::ConvexHull(std::vector<Eigen::Vector3d>{p});
    for (const auto& e : els)
      if (dss::intersect(point, Eigen::Isometry3d::Identity(), e.shape,
                         Eigen::Isometry3d::Identity())
              .intersect)
        return true;
    return false;
  };
  for (int i = 0; i < 4000; ++i) {
    Eigen::Vector3d p(0.2 * u(rng), 0.1 * u(rng), 0.1 * u(rng));                     // lower arm
    if (i % 2) p = Eigen::Vector3d(0.1 * u(rng), 0.1 * u(rng), 0.1 + 0.1 * u(rng));  // upper arm
    BOOST_TEST_REQUIRE(inPiece(p), "point " << p.transpose());
  }
  BOOST_TEST(!inPiece(Eigen::Vector3d(0.17, 0.05, 0.17)));
}

BOOST_AUTO_TEST_CASE(per_link_choice_and_unknown_links) {
  const std::string urdf = writeRobot();
  dss::LoadOptions o;
  o.meshes.cache_dir = "";
  o.meshes.links["bent"] = dss::MeshGeometry::kDecompose;  // robot default: hull
  const dss::RobotModel m = dss::loadUrdf(urdf, o);
  BOOST_TEST(m.links[m.linkIndex("bent")].collisions.size() >= 2u);
  o.meshes.geometry = dss::MeshGeometry::kDecompose;
  o.meshes.links["bent"] = dss::MeshGeometry::kHull;  // robot default: pieces; this link: hull
  const dss::RobotModel h = dss::loadUrdf(urdf, o);
  BOOST_TEST(h.links[h.linkIndex("bent")].collisions.size() == 1u);
  o.meshes.links["elbow"] = dss::MeshGeometry::kHull;
  const std::string msg = dss_test::thrownMessage([&] { dss::loadUrdf(urdf, o); });
  BOOST_TEST(msg.find("elbow") != std::string::npos);
  BOOST_TEST(msg.find("bent.urdf") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(the_cache_is_read_and_never_trusted_blindly) {
  const std::string urdf = writeRobot();
  const fs::path cache = dss_test::scratchDir("robot") / "decomposition_cache";
  fs::remove_all(cache);
  const dss::RobotModel first = dss::loadUrdf(urdf, decomposing(cache.string()));
  std::vector<fs::path> files;
  for (const auto& f : fs::directory_iterator(cache)) files.push_back(f.path());
  BOOST_TEST_REQUIRE(files.size() == 1u);
  BOOST_TEST(files[0].extension() == ".dssdec");
  // Read back: the same pieces, point for point.
  const dss::RobotModel second = dss::loadUrdf(urdf, decomposing(cache.string()));
  BOOST_TEST((piecePoints(first) == piecePoints(second)));

  // A file whose first piece is moved away (well formed, but mesh vertices left uncovered),
  // a foreign header and garbage: each ignored and rewritten; the load gives the same pieces.
  std::ifstream in(files[0]);
  std::stringstream text;
  text << in.rdbuf();
  const dss::mesh::TriangleMesh mesh =
      dss::mesh::loadMesh((dss_test::scratchDir("robot") / "decomposed/l.stl").string());
  const dss::mesh::DecompositionOptions options = decomposing("").meshes.decomposition;
  const std::uint64_t key = dss::mesh::decompositionKey(mesh, options);
  auto moved = dss::mesh::parseDecomposition(text.str(), key, mesh, options);
  BOOST_TEST_REQUIRE(moved.has_value());
  for (auto& p : moved->pieces[0].points) p += Eigen::Vector3d(10, 10, 10);
  const std::string uncovered = dss::mesh::formatDecomposition(key, mesh, options, *moved);
  BOOST_TEST(dss::mesh::parseDecomposition(uncovered, key, mesh, options).has_value());
  for (const std::string& bad :
       {uncovered, std::string("dss-decomposition 1\nkey 0\n"), std::string("\xff\xfe garbage")}) {
    std::ofstream(files[0], std::ios::trunc) << bad;
    BOOST_TEST(!dss::mesh::readCachedDecomposition(cache.string(), mesh, options).has_value());
    const dss::RobotModel again = dss::loadUrdf(urdf, decomposing(cache.string()));
    BOOST_TEST((piecePoints(again) == piecePoints(first)));
  }
  std::ifstream rewritten(files[0]);
  std::stringstream now;
  now << rewritten.rdbuf();
  BOOST_TEST(now.str() == text.str());
}

BOOST_AUTO_TEST_SUITE_END()
