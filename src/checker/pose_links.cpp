// Pose links (see pose_links.h).
#include "dss/checker/pose_links.h"

namespace dss {

PoseLinks poseLinks(const RobotModel& m, const Kinematics& kin, const std::vector<double>& held,
                    const std::vector<char>& in_group) {
  // Parents come before children in model order.
  PoseLinks p;
  p.pose_of.assign(m.links.size(), -1);
  p.X_PL.assign(m.links.size(), Eigen::Isometry3d::Identity());
  for (std::size_t l = 0; l < m.links.size(); ++l) {
    const RobotLink& link = m.links[l];
    p.pose_of[l] = int(l);
    if (link.parent_joint < 0) continue;
    const RobotJoint& j = m.joints[link.parent_joint];
    const int lead = j.active_index >= 0 ? j.active_index : j.mimic_active;
    if (lead >= 0 && in_group[lead]) continue;  // moves with the group: a pose link itself
    const double v = kin.jointValue(held.data(), link.parent_joint);
    const Eigen::Isometry3d motion =
        jointMotion(j, j.type == JointType::kBall ? held.data() + j.active_index : &v);
    if (!motion.matrix().allFinite()) continue;
    p.pose_of[l] = p.pose_of[link.parent_link];
    p.X_PL[l] = p.X_PL[link.parent_link] * j.X_PJ * motion;
  }
  return p;
}

}  // namespace dss
