// dss_plan --render: one self-contained HTML page that replays a planned path in 3-D. The page
// is the viewer (render_viewer.html: a small canvas-2D renderer written for it, no network
// access, nothing external) followed by one JSON block of data: every robot collision element
// and every obstacle of the scene as loaded is tessellated once in its shape frame
// (dss::mesh::tessellate; little-endian float32 vertices and uint32 triangles, base64), with
// its constant pose (X_LS for an element, X_WO for an obstacle; position and unit quaternion
// w, x, y, z); each frame of the replay (path_replay.h) stores the pose of every link with
// geometry (float32, base64), so an element is drawn at X_WL(t) * X_LS. Obstacles the
// collision model kept are drawn solid, those it pruned (no moving link reaches them) greyed
// and translucent; the stretches of path where the checker found states invalid are red, each
// listed with its cause when the caller gives one.
// Triangles face outwards (every shape is convex); a flat hull is drawn as its outline polygon
// from both sides; a hull with no area (points on a line) cannot be drawn: it is listed in the
// page's notes and returned to the caller.
#pragma once

#include <string>
#include <vector>

#include "dss/checker/collision_model.h"
#include "dss/scene/scene.h"
#include "path_replay.h"

namespace dss_plan {

struct RenderPage {
  std::string title;    ///< e.g. the problem name
  std::string summary;  ///< one line: outcome, planner, checker
  bool solved = false;
  std::string path_kind;  ///< what the path is, e.g. "solution path"
  const dss::CollisionModel* model = nullptr;
  /// The scene as loaded, before the model pruned it (frames may be unresolved).
  const dss::Scene* loaded_scene = nullptr;
  const PathReplay* replay = nullptr;
  /// Why each invalid stretch of the replay is invalid (one line each, e.g. the colliding
  /// pairs at its first invalid sample), or empty.
  std::vector<std::string> span_causes;
};

/// The page; `notes` (optional) receives what it could not draw, one line each. Throws
/// std::invalid_argument when an input is missing, std::runtime_error when an obstacle of the
/// loaded scene cannot be placed (names the scene and the obstacle).
std::string renderHtml(const RenderPage& page, std::vector<std::string>* notes = nullptr);

/// Writes renderHtml(page, notes) to `file`; throws std::runtime_error "FILE: cannot write ..."
/// when the file cannot be written.
void writeRenderHtml(const std::string& file, const RenderPage& page,
                     std::vector<std::string>* notes = nullptr);

}  // namespace dss_plan
