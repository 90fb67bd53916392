// Mesh files from users: the vertex budget of loadMesh (counted as the file's nodes instance
// its meshes, before any copy) and mirroring scales, whose triangles are flipped so that they
// stay outward.
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "dss/mesh/mesh.h"
#include "support/temp_files.h"

namespace fs = std::filesystem;
using Eigen::Vector3d;

namespace {

std::string write(const std::string& name, const std::string& text) {
  return dss_test::writeScratch("mesh_input", name, text);
}

// A unit corner tetrahedron with outward triangles (12 STL vertices).
const char* const kTetraStl =
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

// Every triangle's normal points away from the centroid of the vertices.
bool outward(const dss::mesh::TriangleMesh& m) {
  Vector3d c = Vector3d::Zero();
  for (const auto& v : m.vertices) c += v;
  c /= double(m.vertices.size());
  for (const auto& t : m.triangles) {
    const Vector3d &a = m.vertices[t[0]], &b = m.vertices[t[1]], &d = m.vertices[t[2]];
    if ((b - a).cross(d - a).dot((a + b + d) / 3 - c) <= 0) return false;
  }
  return true;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(mesh_input)

BOOST_AUTO_TEST_CASE(the_vertex_budget_is_exact) {
  const std::string path = write("tetra.stl", kTetraStl);
  BOOST_TEST(dss::mesh::loadMesh(path, Vector3d::Ones(), 12).vertices.size() == 12u);
  try {
    dss::mesh::loadMesh(path, Vector3d::Ones(), 11);
    BOOST_ERROR("expected std::length_error");
  } catch (const std::length_error& e) {
    BOOST_TEST(std::string(e.what()) == "mesh " + path + " has more than 11 vertices");
  }
}

BOOST_AUTO_TEST_CASE(mirroring_scales_keep_triangles_outward) {
  const std::string path = write("tetra.stl", kTetraStl);
  BOOST_TEST(outward(dss::mesh::loadMesh(path)));
  for (const Vector3d& scale : {Vector3d(-1, 1, 1), Vector3d(1, -2, 1), Vector3d(-1, -1, -1),
                                Vector3d(-1, -1, 1), Vector3d(2, 3, 4)}) {
    BOOST_TEST_CONTEXT(scale.transpose()) {
      const dss::mesh::TriangleMesh m = dss::mesh::loadMesh(path, scale);
      BOOST_TEST(m.triangles.size() == 4u);
      BOOST_TEST(outward(m));
      BOOST_TEST(m.vertices[1] == Vector3d(0, scale.y(), 0));
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
