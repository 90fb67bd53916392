// Fuzz target: the URDF world reader (dss::loadUrdfWorld), which takes a path: each input is
// written to a temporary file first. Mesh URIs resolve through the package folder
// `dss_arm7` (package://dss_arm7/meshes/...), so the arm's meshes can be reached. Any bytes
// must end in a Scene or a std::exception naming the file; a scene that loads must pass
// dss_fuzz::checkScene. The last input byte chooses whether movable joints are refused.
#include <cstdint>
#include <exception>
#include <string>

#include "dss/scene/urdf_world.h"
#include "scene_checks.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  dss_fuzz::isolateEnvironment();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = dss_fuzz::writeTempFile("world.urdf", data, size);
  dss::SceneLoadOptions options;
  options.package_dirs["dss_arm7"] = dss_fuzz::armDir();
  options.urdf_require_fixed_joints = size > 0 && (data[size - 1] & 1);
  options.limits.max_mesh_vertices = 200'000;
  options.limits.max_scene_mesh_vertices = 400'000;
  dss::Scene scene;
  try {
    scene = dss::loadUrdfWorld(path, options);
  } catch (const std::exception&) {
    return 0;
  }
  dss_fuzz::checkScene(scene);
  return 0;
}
