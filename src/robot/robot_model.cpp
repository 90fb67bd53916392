// Name lookup and small queries on RobotModel.
#include "dss/robot/robot_model.h"

#include <stdexcept>

namespace dss {

const char* toString(JointType t) {
  switch (t) {
    case JointType::kFixed:
      return "fixed";
    case JointType::kRevolute:
      return "revolute";
    case JointType::kContinuous:
      return "continuous";
    case JointType::kPrismatic:
      return "prismatic";
    case JointType::kBall:
      return "ball";
  }
  return "unknown";
}

Eigen::Isometry3d jointMotion(const RobotJoint& j, const double* v) {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  switch (j.type) {
    case JointType::kFixed:
      break;
    case JointType::kRevolute:
    case JointType::kContinuous:
      motion.linear() = Eigen::AngleAxisd(v[0], j.axis).toRotationMatrix();
      break;
    case JointType::kPrismatic:
      motion.translation() = v[0] * j.axis;
      break;
    case JointType::kBall:
      motion.linear() = Eigen::Quaterniond(v[3], v[0], v[1], v[2]).normalized().toRotationMatrix();
      break;
  }
  return motion;
}

void RobotModel::rebuildIndex() {
  link_index_.clear();
  joint_index_.clear();
  for (std::size_t i = 0; i < links.size(); ++i) link_index_[links[i].name] = static_cast<int>(i);
  for (std::size_t i = 0; i < joints.size(); ++i)
    joint_index_[joints[i].name] = static_cast<int>(i);
}

int RobotModel::variableIndex(const std::string& n) const {
  const int j = jointIndex(n);
  if (j >= 0)
    return joints[j].active_index >= 0 && joints[j].type != JointType::kBall
               ? joints[j].active_index
               : -1;
  // A ball joint's variable: its name and _x, _y, _z or _w.
  if (n.size() < 3 || n[n.size() - 2] != '_') return -1;
  const int b = jointIndex(n.substr(0, n.size() - 2));
  if (b < 0 || joints[b].type != JointType::kBall || joints[b].active_index < 0) return -1;
  const std::size_t k = std::string("xyzw").find(n.back());
  return k == std::string::npos ? -1 : joints[b].active_index + int(k);
}

int RobotModel::multiDofIndex(const std::string& n) const {
  for (std::size_t i = 0; i < multi_dof_joints.size(); ++i)
    if (multi_dof_joints[i].name == n) return static_cast<int>(i);
  return -1;
}

int RobotModel::linkIndex(const std::string& n) const {
  const auto it = link_index_.find(n);
  return it == link_index_.end() ? -1 : it->second;
}

int RobotModel::jointIndex(const std::string& n) const {
  const auto it = joint_index_.find(n);
  return it == joint_index_.end() ? -1 : it->second;
}

int RobotModel::linkIndexOrThrow(const std::string& n) const {
  const int i = linkIndex(n);
  if (i < 0)
    throw std::out_of_range("robot '" + name + "' (" + source + ") has no link '" + n + "'");
  return i;
}

int RobotModel::jointIndexOrThrow(const std::string& n) const {
  const int i = jointIndex(n);
  if (i < 0)
    throw std::out_of_range("robot '" + name + "' (" + source + ") has no joint '" + n + "'");
  return i;
}

std::vector<std::string> RobotModel::activeJointNames() const {
  std::vector<std::string> out;
  for (std::size_t a = 0; a < active_joints.size(); ++a) {
    const RobotJoint& j = joints[active_joints[a]];
    if (j.type == JointType::kBall)
      out.push_back(j.name + "_" + "xyzw"[a - std::size_t(j.active_index)]);
    else
      out.push_back(j.name);
  }
  return out;
}

std::size_t RobotModel::numCollisionElements() const {
  std::size_t n = 0;
  for (const auto& l : links) n += l.collisions.size();
  return n;
}

int RobotModel::rigidAncestor(int link) const {
  while (links[link].parent_joint >= 0 && !joints[links[link].parent_joint].isMoving())
    link = links[link].parent_link;
  return link;
}

std::vector<double> RobotModel::defaultState() const {
  std::vector<double> q(active_joints.size(), 0.0);
  for (std::size_t i = 0; i < active_joints.size(); ++i) {
    const RobotJoint& j = joints[active_joints[i]];
    const JointLimits& l = j.limits;
    if (j.type == JointType::kBall) {  // the identity rotation
      q[i] = i - std::size_t(j.active_index) == 3 ? 1.0 : 0.0;
    } else if (l.has_position_limits && (l.lower > 0.0 || l.upper < 0.0))
      q[i] = 0.5 * (l.lower + l.upper);
  }
  return q;
}

}  // namespace dss
