// Fuzz target: the MoveIt `.scene` text reader (dss::parseSceneText), old and new formats. Any
// bytes must end in a Scene or a std::exception naming the source and line; a scene that
// loads must pass dss_fuzz::checkScene.
#include <cstdint>
#include <exception>
#include <string>

#include "dss/scene/scene_text.h"
#include "scene_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  dss::SceneLoadOptions options;
  options.limits.max_mesh_vertices = 200'000;
  options.limits.max_scene_mesh_vertices = 400'000;
  options.limits.max_mesh_triangles = 400'000;
  dss::Scene scene;
  try {
    scene = dss::parseSceneText(text, "fuzz.scene", options);
  } catch (const std::exception&) {
    return 0;
  }
  dss_fuzz::checkScene(scene);
  return 0;
}
