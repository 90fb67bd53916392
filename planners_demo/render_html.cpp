// The self-contained HTML replay of a planned path (see render_html.h).
#include "render_html.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "dss/mesh/mesh.h"
#include "dss/robot/kinematics.h"
#include "render_viewer.h"  // kRenderViewer: the page around the data (generated from .html)

namespace dss_plan {

namespace {

using Json = nlohmann::json;

// Little-endian bytes of float32 / uint32 arrays (the page reads them with DataView).
void putU32(std::vector<std::uint8_t>& out, std::uint32_t u) {
  for (int k = 0; k < 4; ++k) out.push_back(std::uint8_t(u >> (8 * k)));
}
void putF32(std::vector<std::uint8_t>& out, double v) {
  const float f = float(v);
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  putU32(out, u);
}

std::string base64(const std::vector<std::uint8_t>& in) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const std::uint32_t n =
        (std::uint32_t(in[i]) << 16) | (std::uint32_t(in[i + 1]) << 8) | in[i + 2];
    for (int k = 3; k >= 0; --k) out.push_back(kAlphabet[(n >> (6 * k)) & 63]);
  }
  if (i + 1 == in.size()) {
    const std::uint32_t n = std::uint32_t(in[i]) << 16;
    out += {kAlphabet[(n >> 18) & 63], kAlphabet[(n >> 12) & 63], '=', '='};
  } else if (i + 2 == in.size()) {
    const std::uint32_t n = (std::uint32_t(in[i]) << 16) | (std::uint32_t(in[i + 1]) << 8);
    out += {kAlphabet[(n >> 18) & 63], kAlphabet[(n >> 12) & 63], kAlphabet[(n >> 6) & 63], '='};
  }
  return out;
}

// A pose as the page reads it: position, then unit quaternion [x, y, z, qw, qx, qy, qz].
std::array<double, 7> poseValues(const Eigen::Isometry3d& X) {
  const Eigen::Quaterniond q = Eigen::Quaterniond(X.linear()).normalized();
  const Eigen::Vector3d& p = X.translation();
  return {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z()};
}

Json poseJson(const Eigen::Isometry3d& X) {
  const std::array<double, 7> v = poseValues(X);
  return Json(std::vector<double>(v.begin(), v.end()));
}

// The outline of coplanar points (at least three, not all on a line) as a convex polygon in
// order, or an empty vector when they have no area.
std::vector<Eigen::Vector3d> flatOutline(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 3) return {};
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : points) c += p;
  c /= double(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  double extent = 0.0;
  for (const auto& p : points) {
    cov += (p - c) * (p - c).transpose();
    extent = std::max(extent, (p - c).norm());
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d e1 = eig.eigenvectors().col(2), e2 = eig.eigenvectors().col(1);
  // Andrew's monotone chain on the points in the plane of the two largest spreads.
  std::vector<std::pair<Eigen::Vector2d, int>> p2;
  for (std::size_t i = 0; i < points.size(); ++i)
    p2.push_back({{(points[i] - c).dot(e1), (points[i] - c).dot(e2)}, int(i)});
  std::sort(p2.begin(), p2.end(), [](const auto& a, const auto& b) {
    return a.first.x() < b.first.x() || (a.first.x() == b.first.x() && a.first.y() < b.first.y());
  });
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  const double eps = 1e-12 * extent * extent;
  std::vector<std::pair<Eigen::Vector2d, int>> hull(2 * p2.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p2.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2].first, hull[k - 1].first, p2[i].first) <= eps) --k;
    hull[k++] = p2[i];
  }
  for (std::size_t i = p2.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 2].first, hull[k - 1].first, p2[i].first) <= eps) --k;
    hull[k++] = p2[i];
  }
  if (k < 4) return {};  // the first point closes the loop: fewer than three corners
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i + 1 < k; ++i) out.push_back(points[hull[i].second]);
  return out;
}

// One shape as the page draws it: vertices in the shape frame and outward triangles. Empty
// (and a note naming `what`) when the shape has no area.
struct DrawMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

DrawMesh drawMesh(const dss::AnyShape& shape, const std::string& what,
                  std::vector<std::string>& notes) {
  const dss::mesh::TriangleMesh m = dss::mesh::tessellate(shape);
  DrawMesh d;
  if (!m.triangles.empty()) {
    d.vertices = m.vertices;
    // Every shape is convex: a triangle faces outwards when its normal points away from the
    // centroid of the vertices (inside the shape).
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const auto& v : m.vertices) c += v;
    c /= double(m.vertices.size());
    for (const auto& t : m.triangles) {
      const Eigen::Vector3d &a = m.vertices[t[0]], &b = m.vertices[t[1]], &e = m.vertices[t[2]];
      const bool outward = (b - a).cross(e - a).dot((a + b + e) / 3.0 - c) >= 0.0;
      d.triangles.push_back({std::uint32_t(t[0]), std::uint32_t(outward ? t[1] : t[2]),
                             std::uint32_t(outward ? t[2] : t[1])});
    }
    return d;
  }
  // A flat hull: its outline, fanned, from both sides.
  d.vertices = flatOutline(m.vertices);
  if (d.vertices.empty()) {
    notes.push_back(what + ": " + dss::describeShape(shape) +
                    " has no area (its points lie on a line): not drawn");
    return d;
  }
  for (std::uint32_t i = 1; i + 1 < d.vertices.size(); ++i) {
    d.triangles.push_back({0, i, i + 1});
    d.triangles.push_back({0, i + 1, i});
  }
  return d;
}

Json meshJson(const DrawMesh& m) {
  std::vector<std::uint8_t> v, t;
  for (const auto& p : m.vertices)
    for (int k = 0; k < 3; ++k) putF32(v, p[k]);
  for (const auto& tri : m.triangles)
    for (std::uint32_t i : tri) putU32(t, i);
  return {{"vertices", m.vertices.size()},
          {"triangles", m.triangles.size()},
          {"v", base64(v)},
          {"t", base64(t)}};
}

}  // namespace

std::string renderHtml(const RenderPage& page, std::vector<std::string>* notes_out) {
  if (!page.model || !page.loaded_scene || !page.replay)
    throw std::invalid_argument("renderHtml: model, loaded scene and replay are required");
  const dss::CollisionModel& model = *page.model;
  const dss::RobotModel& robot = model.robot();
  const PathReplay& replay = *page.replay;
  if (replay.frame_t.empty() || replay.frame_t.size() != replay.frame_q.size())
    throw std::invalid_argument("renderHtml: the replay has no frames");
  std::vector<std::string> notes;
  Json shapes = Json::array();

  // The robot: every collision element of the model, grouped by link.
  std::vector<int> links;  // model link index of each drawn link
  std::map<int, int> drawn_link;
  Json elements = Json::array();
  for (const auto& e : model.elements()) {
    auto it = drawn_link.find(e.link);
    if (it == drawn_link.end()) {
      it = drawn_link.emplace(e.link, int(links.size())).first;
      links.push_back(e.link);
    }
    shapes.push_back(meshJson(drawMesh(e.source->shape, e.source->description, notes)));
    elements.push_back({{"link", it->second},
                        {"shape", shapes.size() - 1},
                        {"pose", poseJson(e.source->X_LS)},
                        {"name", e.source->description}});
  }
  Json link_names = Json::array();
  for (int l : links) link_names.push_back(robot.links[l].name);

  // The obstacles: the scene as loaded; those the model kept carry its world pose, the
  // pruned ones are placed here in the same frames the model used (links at the held state).
  std::map<std::string, const dss::Obstacle*> kept;
  for (const auto& o : model.scene().obstacles) kept[o.name] = &o;
  dss::Scene loaded = *page.loaded_scene;
  {
    const std::vector<Eigen::Isometry3d> X_WL =
        dss::Kinematics(robot, /*all_links=*/true).linkPoses(model.held());
    dss::FrameMap frames;
    for (std::size_t l = 0; l < robot.links.size(); ++l) frames[robot.links[l].name] = X_WL[l];
    dss::resolveFrames(loaded, frames, /*require_all=*/false);
  }
  Json obstacles = Json::array();
  std::size_t kept_count = 0;
  for (const auto& o : loaded.obstacles) {
    const auto k = kept.find(o.name);
    const bool is_kept = k != kept.end();
    if (!is_kept && !o.frame_resolved)
      throw std::runtime_error(loaded.source + ": obstacle '" + o.name + "': frame '" + o.frame_id +
                               "' cannot be placed for drawing");
    kept_count += is_kept;
    const dss::Obstacle& placed = is_kept ? *k->second : o;
    shapes.push_back(meshJson(drawMesh(placed.shape, "obstacle " + o.name, notes)));
    obstacles.push_back({{"name", o.name},
                         {"shape", shapes.size() - 1},
                         {"pose", poseJson(placed.X_WO)},
                         {"kept", is_kept}});
  }
  if (kept_count != kept.size())
    throw std::runtime_error(loaded.source +
                             ": the collision model holds obstacles the loaded scene does not");

  // Frames: the pose of every drawn link at each frame of the replay.
  std::vector<std::uint8_t> frame_t, frame_poses;
  std::vector<Eigen::Isometry3d> X_WL(robot.links.size(), Eigen::Isometry3d::Identity());
  for (std::size_t f = 0; f < replay.frame_q.size(); ++f) {
    if (replay.frame_q[f].size() != robot.numActiveJoints())
      throw std::invalid_argument("renderHtml: a frame does not match the robot's joints");
    putF32(frame_t, replay.frame_t[f]);
    model.kinematics().computeLinkPoses(replay.frame_q[f].data(), X_WL.data());
    for (int l : links)
      for (double x : poseValues(X_WL[l])) putF32(frame_poses, x);
  }
  Json spans = Json::array();
  for (const auto& s : replay.invalid_spans) spans.push_back({s.first, s.second});

  Json d;
  d["title"] = page.title;
  d["summary"] = page.summary;
  d["solved"] = page.solved;
  d["pathKind"] = page.path_kind;
  d["pathStates"] = replay.path_states;
  d["robot"] = robot.name;
  d["scene"] = loaded.source.empty() ? std::string("(no scene)") : loaded.source;
  d["shapes"] = std::move(shapes);
  d["links"] = std::move(link_names);
  d["elements"] = std::move(elements);
  d["obstacles"] = std::move(obstacles);
  d["frames"] = {
      {"count", replay.frame_t.size()}, {"t", base64(frame_t)}, {"poses", base64(frame_poses)}};
  d["samplesChecked"] = replay.samples_checked;
  d["samplesInvalid"] = replay.samples_invalid;
  d["invalidSpans"] = std::move(spans);
  if (!page.span_causes.empty() && page.span_causes.size() != replay.invalid_spans.size())
    throw std::invalid_argument("renderHtml: one cause per invalid stretch, or none");
  d["invalidCauses"] = page.span_causes;
  d["notes"] = notes;
  // '<' only occurs inside JSON strings: as \u003c it cannot end the script element.
  std::string data;
  for (char c : d.dump(-1, ' ', false, Json::error_handler_t::replace)) {
    if (c == '<')
      data += "\\u003c";
    else
      data += c;
  }

  const std::string viewer = kRenderViewer;
  const std::string marker = "@DSS_PLAN_DATA@";
  const std::size_t at = viewer.find(marker);
  if (at == std::string::npos) throw std::logic_error("render_viewer.html: no data marker");
  if (notes_out) *notes_out = notes;
  return viewer.substr(0, at) + data + viewer.substr(at + marker.size());
}

void writeRenderHtml(const std::string& file, const RenderPage& page,
                     std::vector<std::string>* notes) {
  const std::string html = renderHtml(page, notes);
  std::ofstream out(file, std::ios::binary);
  if (!out) throw std::runtime_error(file + ": cannot write (" + std::strerror(errno) + ")");
  out << html;
  out.close();
  if (!out) throw std::runtime_error(file + ": cannot write (" + std::strerror(errno) + ")");
}

}  // namespace dss_plan
