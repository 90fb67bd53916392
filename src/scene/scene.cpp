// Obstacle bounds, the allowed collision matrix and frame resolution of a Scene.
#include "dss/scene/scene.h"

#include <algorithm>
#include <set>
#include <sstream>
#include <type_traits>

#include "dss/scene/scene_error.h"

namespace dss {

namespace {

std::string stripSlash(const std::string& f) {
  return (!f.empty() && f[0] == '/') ? f.substr(1) : f;
}

}  // namespace

Aabb worldAabb(const Obstacle& o) {
  const Eigen::Matrix3d R = o.X_WO.linear();
  const Eigen::Vector3d p = o.X_WO.translation();
  Aabb box;
  std::visit(
      [&](const auto& s) {
        for (int k = 0; k < 3; ++k) {
          // Row k of R is the world axis k in the shape frame.
          const Eigen::Vector3d d_S = R.row(k).transpose();
          const Eigen::Vector3d hi = s.support(d_S, Eigen::Vector3d::Zero());
          const Eigen::Vector3d lo = s.support(-d_S, Eigen::Vector3d::Zero());
          box.upper[k] = R.row(k).dot(hi) + p[k];
          box.lower[k] = R.row(k).dot(lo) + p[k];
        }
      },
      o.shape);
  return box;
}

std::string describeShape(const AnyShape& shape) {
  std::ostringstream out;
  std::visit(
      [&](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, Sphere>) {
          out << "sphere r " << s.radius;
        } else if constexpr (std::is_same_v<S, Box>) {
          out << "box " << 2 * s.half.x() << " x " << 2 * s.half.y() << " x " << 2 * s.half.z();
        } else if constexpr (std::is_same_v<S, Capsule>) {
          out << "capsule r " << s.radius << " length " << 2 * s.half_length;
        } else if constexpr (std::is_same_v<S, Cylinder>) {
          out << "cylinder r " << s.radius << " length " << 2 * s.half_length;
        } else if constexpr (std::is_same_v<S, Cone>) {
          out << "cone r " << s.radius << " length " << 2 * s.half_length;
        } else if constexpr (std::is_same_v<S, Ellipsoid>) {
          out << "ellipsoid " << s.radii.x() << " " << s.radii.y() << " " << s.radii.z();
        } else {
          out << "convex (" << s.size() << " vertices)";
        }
      },
      shape);
  return out.str();
}

void AllowedCollisionMatrix::allow(const std::string& a, const std::string& b) {
  pairs_.insert(a < b ? std::make_pair(a, b) : std::make_pair(b, a));
}

void AllowedCollisionMatrix::allowAlways(const std::string& name) { always_.insert(name); }

bool AllowedCollisionMatrix::allowed(const std::string& a, const std::string& b) const {
  if (always_.count(a) || always_.count(b)) return true;
  return pairs_.count(a < b ? std::make_pair(a, b) : std::make_pair(b, a)) > 0;
}

std::vector<std::string> Scene::objectIds() const {
  std::vector<std::string> ids;
  std::set<std::string> seen;
  for (const auto& o : obstacles)
    if (seen.insert(o.object_id).second) ids.push_back(o.object_id);
  return ids;
}

std::vector<std::string> Scene::unresolvedFrames() const {
  std::set<std::string> frames;
  for (const auto& o : obstacles)
    if (!o.frame_resolved) frames.insert(o.frame_id);
  return {frames.begin(), frames.end()};
}

bool isWorldFrame(const std::string& frame_id) {
  const std::string f = stripSlash(frame_id);
  return f.empty() || f == "world";
}

void resolveFrames(Scene& scene, const FrameMap& frames, bool require_all) {
  for (auto& o : scene.obstacles) {
    const std::string f = stripSlash(o.frame_id);
    const Eigen::Isometry3d* X_WF = nullptr;
    auto it = frames.find(f);
    if (it == frames.end()) it = frames.find(o.frame_id);
    if (it != frames.end()) {
      X_WF = &it->second;
    } else {
      auto jt = scene.fixed_frames.find(f);
      if (jt != scene.fixed_frames.end()) X_WF = &jt->second;
    }
    if (X_WF) {
      o.X_WO = *X_WF * o.X_FO;
      o.frame_resolved = true;
    } else if (isWorldFrame(f)) {
      o.X_WO = o.X_FO;
      o.frame_resolved = true;
    } else if (require_all) {
      throw SceneError(scene.source + ": object '" + o.object_id + "' is placed in frame '" +
                       o.frame_id + "', which is neither the world nor a known frame");
    }
  }
}

}  // namespace dss
