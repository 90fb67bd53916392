// Fuzz target: mesh files through the project's mesh loader (dss::mesh::loadMesh, assimp) and
// the convex hull the models build from them (dss::mesh::convexHull, qhull). The first byte
// chooses the file name's extension (its value mod 3: .stl, .obj, .dae) and, when its value
// divided by 3 is odd, a mirroring scale (-1, 1, 1); the rest is the file. Any bytes must end
// in a mesh or a std::exception naming the path; a mesh that loads must have finite vertices
// and triangles indexing them, its hull's points must be among them, and the hull's support
// must return one of its points for every axis direction.
#include <cstdint>
#include <exception>
#include <string>

#include "dss/mesh/mesh.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* const kExtensions[] = {"stl", "obj", "dae"};
  const std::uint8_t selector = data[0];
  const std::string path =
      dss_fuzz::writeTempFile(std::string("mesh.") + kExtensions[selector % 3], data + 1, size - 1);
  const Eigen::Vector3d scale =
      (selector / 3) % 2 ? Eigen::Vector3d(-1, 1, 1) : Eigen::Vector3d::Ones();
  dss::mesh::TriangleMesh m;
  try {
    m = dss::mesh::loadMesh(path, scale, 200'000);
  } catch (const std::exception&) {
    return 0;
  }
  if (m.vertices.empty()) dss_fuzz::propertyFailed("a loaded mesh without vertices");
  for (const auto& v : m.vertices)
    if (!v.allFinite()) dss_fuzz::propertyFailed("a loaded mesh with a non-finite vertex");
  const int n = static_cast<int>(m.vertices.size());
  for (const auto& t : m.triangles)
    for (int i : t)
      if (i < 0 || i >= n) dss_fuzz::propertyFailed("a triangle indexes a missing vertex");
  dss::ConvexHull hull;
  try {
    hull = dss::mesh::convexHull(m.vertices, "fuzz mesh");
  } catch (const std::exception& e) {
    dss_fuzz::propertyFailed(std::string("no hull for a loaded mesh: ") + e.what());
  }
  for (int axis = 0; axis < 6; ++axis) {
    const Eigen::Vector3d d = (axis < 3 ? 1.0 : -1.0) * Eigen::Vector3d::Unit(axis % 3);
    const Eigen::Vector3d s = hull.support(d, Eigen::Vector3d::Zero());
    bool found = false;
    for (const auto& v : m.vertices) found = found || v == s;
    if (!found) dss_fuzz::propertyFailed("hull support is not a mesh vertex");
  }
  return 0;
}
