// Fuzz target: the MoveIt PlanningScene YAML reader (dss::parsePlanningSceneYaml), its source
// placed in our arm's scenes folder so that relative mesh resources (../meshes/*.stl) resolve.
// Any bytes must end in a Scene or a std::exception naming the source (key errors are tried
// strict and as warnings, by the last input byte); a scene that loads must pass
// dss_fuzz::checkScene.
#include <cstdint>
#include <exception>
#include <string>

#include "dss/scene/planning_scene_yaml.h"
#include "scene_checks.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  dss_fuzz::isolateEnvironment();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  dss::SceneLoadOptions options;
  options.unknown_keys_are_warnings = size > 0 && (data[size - 1] & 1);
  options.limits.max_mesh_vertices = 200'000;
  options.limits.max_scene_mesh_vertices = 400'000;
  options.limits.max_mesh_triangles = 400'000;
  dss::Scene scene;
  try {
    scene = dss::parsePlanningSceneYaml(text, dss_fuzz::armDir() + "/scenes/fuzz.yaml", options);
  } catch (const std::exception&) {
    return 0;
  }
  dss_fuzz::checkScene(scene);
  return 0;
}
