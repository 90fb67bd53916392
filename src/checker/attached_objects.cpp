#include "dss/checker/attached_objects.h"

#include <algorithm>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "dss/robot/kinematics.h"

namespace dss {

namespace {

// The bytes of the added links (names, holding links, shapes and placements, in order; the
// descriptions follow from them): robots with the same added links are the same robot.
void appendBytes(std::string& key, const void* p, std::size_t n) {
  key.append(static_cast<const char*>(p), n);
}
void appendDouble(std::string& key, double v) { appendBytes(key, &v, sizeof v); }
void appendName(std::string& key, const std::string& s) {
  const std::size_t n = s.size();
  appendBytes(key, &n, sizeof n);
  key += s;
}

void appendShape(std::string& key, const AnyShape& shape) {
  const std::size_t index = shape.index();
  appendBytes(key, &index, sizeof index);
  std::visit(
      [&key](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, Sphere>) {
          appendDouble(key, s.radius);
        } else if constexpr (std::is_same_v<S, Box>) {
          appendBytes(key, s.half.data(), 3 * sizeof(double));
        } else if constexpr (std::is_same_v<S, Ellipsoid>) {
          appendBytes(key, s.radii.data(), 3 * sizeof(double));
        } else if constexpr (std::is_same_v<S, ConvexHull>) {
          const std::size_t n = s.points().size();
          appendBytes(key, &n, sizeof n);
          for (const auto& p : s.points()) appendBytes(key, p.data(), 3 * sizeof(double));
        } else {  // capsule, cylinder, cone
          appendDouble(key, s.radius);
          appendDouble(key, s.half_length);
        }
      },
      shape);
}

struct AttachedCopy {
  std::weak_ptr<const RobotModel> from;
  const RobotModel* from_ptr;
  std::string key;
  std::shared_ptr<const RobotModel> copy;
};
std::mutex attached_mutex;
std::vector<AttachedCopy> attached_copies;
constexpr std::size_t kMaxAttachedCopies = 16;

}  // namespace

std::shared_ptr<const RobotModel> withAttachedObjects(
    const std::shared_ptr<const RobotModel>& robot_ptr, const std::vector<AttachedObject>& objects,
    const std::vector<double>& state, const FrameMap& fixed_frames, AllowedCollisionMatrix& acm) {
  const RobotModel& robot = *robot_ptr;
  // Every link's pose at the state the objects were attached in (only read for parts given
  // in a frame other than their holding link).
  const Kinematics kin(robot, /*all_links=*/true);
  std::vector<Eigen::Isometry3d> X_WL(robot.links.size(), Eigen::Isometry3d::Identity());
  kin.computeLinkPoses(state.data(), X_WL.data());
  std::vector<RobotLink> added;
  std::string key;
  for (const AttachedObject& ao : objects) {
    const std::string what = ao.at + ": attached object '" + ao.id + "'";
    const int holder = robot.linkIndex(ao.link);
    if (holder < 0)
      throw std::runtime_error(what + ": link_name '" + ao.link + "' is not a link of robot '" +
                               robot.name + "'");
    if (robot.linkIndex(ao.id) >= 0)
      throw std::runtime_error(what + ": its id is also the name of a link of robot '" +
                               robot.name +
                               "' (the allowed collision matrix could not tell them apart)");
    for (const RobotLink& other : added)
      if (other.name == ao.id) throw std::runtime_error(what + ": attached twice");
    if (robot.jointIndex(ao.id + "/attached") >= 0)
      throw std::runtime_error(what + ": robot '" + robot.name + "' already has a joint '" + ao.id +
                               "/attached'");
    for (const std::string& t : ao.touch_links)
      if (robot.linkIndex(t) < 0)
        throw std::runtime_error(what + ": touch link '" + t + "' is not a link of robot '" +
                                 robot.name + "'");
    const Eigen::Isometry3d X_LW = X_WL[std::size_t(holder)].inverse();
    RobotLink link;
    link.name = ao.id;
    link.parent_link = holder;
    appendName(key, ao.id);
    appendName(key, ao.link);
    for (const Obstacle& part : ao.parts) {
      CollisionElement e;
      e.shape = part.shape;
      const std::string frame = !part.frame_id.empty() && part.frame_id[0] == '/'
                                    ? part.frame_id.substr(1)
                                    : part.frame_id;
      if (frame == ao.link) {
        e.X_LS = part.X_FO;
      } else if (isWorldFrame(frame)) {
        e.X_LS = X_LW * part.X_FO;
      } else if (const int f = robot.linkIndex(frame); f >= 0) {
        e.X_LS = X_LW * X_WL[std::size_t(f)] * part.X_FO;
      } else if (const auto it = fixed_frames.find(frame); it != fixed_frames.end()) {
        e.X_LS = X_LW * it->second * part.X_FO;
      } else {
        throw std::runtime_error(what + ": frame '" + frame +
                                 "' is neither a world frame, a link of robot '" + robot.name +
                                 "' nor a fixed frame of the scene");
      }
      e.X_LS.makeAffine();
      // Without the file's name: the same object read from another file is the same link.
      e.description =
          "attached object '" + ao.id + "' on link " + ao.link + ": " + describeShape(e.shape);
      if (ao.parts.size() > 1)
        e.description += " (part " + std::to_string(link.collisions.size()) + ")";
      appendShape(key, e.shape);
      appendBytes(key, e.X_LS.matrix().data(), 16 * sizeof(double));
      link.collisions.push_back(std::move(e));
    }
    added.push_back(std::move(link));
    acm.allow(ao.id, ao.link);
    for (const std::string& t : ao.touch_links) acm.allow(ao.id, t);
  }
  {
    std::lock_guard<std::mutex> lock(attached_mutex);
    // Copies of robots that are gone go first.
    attached_copies.erase(std::remove_if(attached_copies.begin(), attached_copies.end(),
                                         [](const AttachedCopy& c) { return c.from.expired(); }),
                          attached_copies.end());
    for (const AttachedCopy& c : attached_copies)
      if (c.from_ptr == robot_ptr.get() && c.key == key) return c.copy;
  }
  auto out = std::make_shared<RobotModel>(robot);
  for (RobotLink& link : added) {
    const int holder = link.parent_link;
    RobotJoint joint;
    joint.name = link.name + "/attached";
    joint.type = JointType::kFixed;
    joint.parent_link = holder;
    joint.child_link = static_cast<int>(out->links.size());
    link.parent_joint = static_cast<int>(out->joints.size());
    out->links[std::size_t(holder)].child_joints.push_back(link.parent_joint);
    out->links.push_back(std::move(link));
    out->joints.push_back(std::move(joint));
  }
  out->rebuildIndex();
  std::lock_guard<std::mutex> lock(attached_mutex);
  if (attached_copies.size() >= kMaxAttachedCopies) attached_copies.erase(attached_copies.begin());
  attached_copies.push_back({robot_ptr, robot_ptr.get(), std::move(key), out});
  return out;
}

}  // namespace dss
