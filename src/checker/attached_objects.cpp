#include "dss/checker/attached_objects.h"

#include <stdexcept>

#include "dss/robot/kinematics.h"

namespace dss {

std::shared_ptr<const RobotModel> withAttachedObjects(const RobotModel& robot,
                                                      const std::vector<AttachedObject>& objects,
                                                      const std::vector<double>& state,
                                                      const FrameMap& fixed_frames,
                                                      AllowedCollisionMatrix& acm) {
  auto out = std::make_shared<RobotModel>(robot);
  // Every link's pose at the state the objects were attached in (only read for parts given
  // in a frame other than their holding link).
  const Kinematics kin(robot, /*all_links=*/true);
  std::vector<Eigen::Isometry3d> X_WL(robot.links.size(), Eigen::Isometry3d::Identity());
  kin.computeLinkPoses(state.data(), X_WL.data());
  for (const AttachedObject& ao : objects) {
    const std::string what = ao.at + ": attached object '" + ao.id + "'";
    const int holder = robot.linkIndex(ao.link);
    if (holder < 0)
      throw std::runtime_error(what + ": link_name '" + ao.link + "' is not a link of robot '" +
                               robot.name + "'");
    if (out->linkIndex(ao.id) >= 0)
      throw std::runtime_error(what + ": its id is also the name of a link of robot '" +
                               robot.name +
                               "' (the allowed collision matrix could not tell them "
                               "apart)");
    const std::string joint_name = ao.id + "/attached";
    if (out->jointIndex(joint_name) >= 0)
      throw std::runtime_error(what + ": robot '" + robot.name + "' already has a joint '" +
                               joint_name + "'");
    for (const std::string& t : ao.touch_links)
      if (robot.linkIndex(t) < 0)
        throw std::runtime_error(what + ": touch link '" + t + "' is not a link of robot '" +
                                 robot.name + "'");
    const Eigen::Isometry3d X_LW = X_WL[holder].inverse();
    RobotLink link;
    link.name = ao.id;
    link.parent_link = holder;
    link.parent_joint = static_cast<int>(out->joints.size());
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
        e.X_LS = X_LW * X_WL[f] * part.X_FO;
      } else if (const auto it = fixed_frames.find(frame); it != fixed_frames.end()) {
        e.X_LS = X_LW * it->second * part.X_FO;
      } else {
        throw std::runtime_error(what + ": frame '" + frame +
                                 "' is neither a world frame, a link of robot '" + robot.name +
                                 "' nor a fixed frame of the scene");
      }
      e.X_LS.makeAffine();
      e.description =
          "attached object '" + ao.id + "' on link " + ao.link + ": " + part.description;
      link.collisions.push_back(std::move(e));
    }
    RobotJoint joint;
    joint.name = joint_name;
    joint.type = JointType::kFixed;
    joint.parent_link = holder;
    joint.child_link = static_cast<int>(out->links.size());
    out->links[static_cast<std::size_t>(holder)].child_joints.push_back(link.parent_joint);
    out->links.push_back(std::move(link));
    out->joints.push_back(std::move(joint));
    out->rebuildIndex();
    acm.allow(ao.id, ao.link);
    for (const std::string& t : ao.touch_links) acm.allow(ao.id, t);
  }
  return out;
}

}  // namespace dss
