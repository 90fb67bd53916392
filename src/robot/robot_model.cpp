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
  }
  return "unknown";
}

void RobotModel::rebuildIndex() {
  link_index_.clear();
  joint_index_.clear();
  for (std::size_t i = 0; i < links.size(); ++i) link_index_[links[i].name] = static_cast<int>(i);
  for (std::size_t i = 0; i < joints.size(); ++i)
    joint_index_[joints[i].name] = static_cast<int>(i);
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
  for (int j : active_joints) out.push_back(joints[j].name);
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
    const JointLimits& l = joints[active_joints[i]].limits;
    if (l.has_position_limits && (l.lower > 0.0 || l.upper < 0.0)) q[i] = 0.5 * (l.lower + l.upper);
  }
  return q;
}

}  // namespace dss
