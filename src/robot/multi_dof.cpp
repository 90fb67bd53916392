// Multi-DOF joints (see multi_dof.h).
#include "dss/robot/multi_dof.h"

#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

namespace dss {
namespace {

struct Part {
  const char* suffix;
  JointType type;
  int axis;  // 0, 1, 2 for x, y, z; -1 for the ball
};

const std::vector<Part>& partsOf(MultiDofType t) {
  static const std::vector<Part> planar = {{"x", JointType::kPrismatic, 0},
                                           {"y", JointType::kPrismatic, 1},
                                           {"theta", JointType::kContinuous, 2}};
  static const std::vector<Part> floating = {{"trans_x", JointType::kPrismatic, 0},
                                             {"trans_y", JointType::kPrismatic, 1},
                                             {"trans_z", JointType::kPrismatic, 2},
                                             {"rot", JointType::kBall, -1}};
  return t == MultiDofType::kPlanar ? planar : floating;
}

const char* typeName(MultiDofType t) { return t == MultiDofType::kPlanar ? "planar" : "floating"; }

}  // namespace

void expandMultiDofJoints(RobotModel& m,
                          const std::vector<std::pair<int, MultiDofType>>& placeholders,
                          bool from_srdf, const std::string& source) {
  if (placeholders.empty()) return;
  std::map<int, MultiDofType> which(placeholders.begin(), placeholders.end());
  for (const auto& [j, t] : which)
    if (j < 0 || j >= int(m.joints.size()) || m.joints[j].type != JointType::kFixed)
      throw std::logic_error("expandMultiDofJoints: joint " + std::to_string(j) +
                             " is not a placeholder");
  std::set<std::string> link_names, joint_names;
  for (const auto& l : m.links) link_names.insert(l.name);
  for (const auto& j : m.joints) joint_names.insert(j.name);

  const std::size_t first_new = m.multi_dof_joints.size();
  std::vector<RobotLink> links;
  std::vector<RobotJoint> joints;
  std::vector<int> new_link(m.links.size(), -1);
  std::vector<int> new_joint(m.joints.size(), -1);  // joints kept as they are
  for (std::size_t l = 0; l < m.links.size(); ++l) {
    RobotLink link = m.links[l];
    link.child_joints.clear();
    const int pj = link.parent_joint;
    if (pj < 0) {
      new_link[l] = int(links.size());
      links.push_back(std::move(link));
      continue;
    }
    const RobotJoint& old = m.joints[pj];
    int parent = new_link[old.parent_link];
    const auto it = which.find(pj);
    if (it == which.end()) {
      RobotJoint j = old;
      j.parent_link = parent;
      j.child_link = int(links.size());
      new_joint[pj] = int(joints.size());
      joints.push_back(j);
      link.parent_joint = new_joint[pj];
      link.parent_link = parent;
      new_link[l] = int(links.size());
      links.push_back(std::move(link));
      continue;
    }
    MultiDofJoint md;
    md.name = old.name;
    md.type = it->second;
    md.from_srdf = from_srdf;
    const int md_index = int(m.multi_dof_joints.size());
    const auto& parts = partsOf(md.type);
    for (std::size_t k = 0; k < parts.size(); ++k) {
      RobotJoint j;
      j.name = old.name + "/" + parts[k].suffix;
      if (!joint_names.insert(j.name).second)
        throw std::runtime_error(source + ": " + typeName(md.type) + " joint '" + old.name +
                                 "' becomes joint '" + j.name +
                                 "', but the robot already has a joint of that name");
      j.type = parts[k].type;
      j.parent_link = parent;
      j.X_PJ = k == 0 ? old.X_PJ : Eigen::Isometry3d::Identity();
      if (parts[k].axis >= 0) j.axis = Eigen::Vector3d::Unit(parts[k].axis);
      if (j.type == JointType::kBall) {
        j.limits.has_position_limits = true;
        j.limits.lower = -1.0;
        j.limits.upper = 1.0;
      }
      j.multi_dof = md_index;
      const bool last = k + 1 == parts.size();
      const int ji = int(joints.size());
      j.child_link = int(links.size());
      joints.push_back(j);
      md.joints.push_back(ji);
      if (last) {
        link.parent_joint = ji;
        link.parent_link = parent;
        new_link[l] = int(links.size());
        links.push_back(std::move(link));
      } else {
        RobotLink s;
        s.name = j.name;
        if (!link_names.insert(s.name).second)
          throw std::runtime_error(source + ": " + typeName(md.type) + " joint '" + old.name +
                                   "' needs a link named '" + s.name +
                                   "', but the robot already has a link of that name");
        s.parent_joint = ji;
        s.parent_link = parent;
        parent = int(links.size());
        links.push_back(std::move(s));
      }
    }
    m.multi_dof_joints.push_back(std::move(md));
  }
  for (std::size_t ji = 0; ji < joints.size(); ++ji)
    links[joints[ji].parent_link].child_joints.push_back(int(ji));
  // Joint indices of earlier multi-DOF joints (their parts were kept as ordinary joints).
  for (std::size_t i = 0; i < first_new; ++i)
    for (int& j : m.multi_dof_joints[i].joints) j = new_joint[j];

  // Active indices in the new joint order; mimic joints follow their leader's new index.
  std::vector<int> new_active(m.active_joints.size(), -1);
  std::vector<int> active;
  for (std::size_t ji = 0; ji < joints.size(); ++ji) {
    RobotJoint& j = joints[ji];
    const int old_active = j.active_index;
    if (j.isMoving() && j.mimic.leader.empty()) {
      j.active_index = int(active.size());
      const int n = j.type == JointType::kBall ? 4 : 1;
      for (int k = 0; k < n; ++k) {
        if (old_active >= 0) new_active[old_active + k] = int(active.size());
        active.push_back(int(ji));
      }
    }
  }
  for (auto& j : joints)
    if (j.mimic_active >= 0) j.mimic_active = new_active[j.mimic_active];
  m.links = std::move(links);
  m.joints = std::move(joints);
  m.active_joints = std::move(active);
  m.root_link = 0;
  m.rebuildIndex();
}

void applyVirtualJoint(RobotModel& m, const std::string& name, const std::string& type,
                       const std::string& parent_frame, const std::string& child_link,
                       const std::string& source) {
  if (type == "fixed") return;
  if (type != "planar" && type != "floating")
    throw std::runtime_error(source + ": virtual joint '" + name + "' has type '" + type +
                             "' (expected fixed, planar or floating)");
  const std::string where = source + ": virtual joint '" + name + "'";
  if (m.links.empty() || m.links[m.root_link].name != child_link)
    throw std::runtime_error(where + " connects link '" + child_link +
                             "', which is not the root link '" +
                             (m.links.empty() ? std::string() : m.links[m.root_link].name) +
                             "' of robot '" + m.name + "'");
  if (m.linkIndex(parent_frame) >= 0)
    throw std::runtime_error(where + ": its parent frame '" + parent_frame +
                             "' is a link of the robot");
  if (m.jointIndex(name) >= 0 || m.multiDofIndex(name) >= 0)
    throw std::runtime_error(where + ": the robot already has a joint of that name");
  // A new root and a placeholder joint to the old root, every index shifted by one.
  RobotModel r = m;
  RobotLink root;
  root.name = parent_frame;
  root.child_joints = {0};
  r.links.insert(r.links.begin(), root);
  for (std::size_t l = 1; l < r.links.size(); ++l) {
    RobotLink& link = r.links[l];
    link.parent_joint = link.parent_joint < 0 ? 0 : link.parent_joint + 1;
    link.parent_link = link.parent_link < 0 ? 0 : link.parent_link + 1;
    for (int& c : link.child_joints) ++c;
  }
  RobotJoint placeholder;
  placeholder.name = name;
  placeholder.type = JointType::kFixed;
  placeholder.parent_link = 0;
  placeholder.child_link = 1;
  r.joints.insert(r.joints.begin(), placeholder);
  for (std::size_t j = 1; j < r.joints.size(); ++j) {
    ++r.joints[j].parent_link;
    ++r.joints[j].child_link;
  }
  for (int& a : r.active_joints) ++a;
  for (auto& md : r.multi_dof_joints)
    for (int& j : md.joints) ++j;
  r.root_link = 0;
  r.rebuildIndex();
  expandMultiDofJoints(r, {{0, type == "planar" ? MultiDofType::kPlanar : MultiDofType::kFloating}},
                       true, source);
  m = std::move(r);
}

void setMultiDofTranslationBounds(RobotModel& m, const Eigen::Vector3d& lo,
                                  const Eigen::Vector3d& hi) {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(lo[k]) || !std::isfinite(hi[k]) || !(lo[k] <= hi[k]))
      throw std::invalid_argument(std::string("workspace bounds: the ") + "xyz"[k] + " range [" +
                                  std::to_string(lo[k]) + ", " + std::to_string(hi[k]) +
                                  "] is not a finite interval");
  for (const auto& md : m.multi_dof_joints)
    for (int ji : md.joints) {
      RobotJoint& j = m.joints[ji];
      if (j.type != JointType::kPrismatic) continue;
      const int k = j.axis.x() != 0 ? 0 : (j.axis.y() != 0 ? 1 : 2);
      j.limits.has_position_limits = true;
      j.limits.lower = lo[k];
      j.limits.upper = hi[k];
    }
}

bool hasUnboundedMultiDofJoint(const RobotModel& m) {
  for (const auto& md : m.multi_dof_joints)
    for (int ji : md.joints)
      if (m.joints[ji].type == JointType::kPrismatic && !m.joints[ji].limits.has_position_limits)
        return true;
  return false;
}

std::vector<std::pair<std::string, double>> multiDofValues(const RobotModel& m, int index,
                                                           const Eigen::Isometry3d& X) {
  const MultiDofJoint& md = m.multi_dof_joints.at(index);
  const Eigen::Vector3d t = X.translation();
  const Eigen::Matrix3d R = X.linear();
  const std::string& n = md.name;
  if (md.type == MultiDofType::kPlanar)
    return {{n + "/x", t.x()}, {n + "/y", t.y()}, {n + "/theta", std::atan2(R(1, 0), R(0, 0))}};
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  return {{n + "/trans_x", t.x()}, {n + "/trans_y", t.y()}, {n + "/trans_z", t.z()},
          {n + "/rot_x", q.x()},   {n + "/rot_y", q.y()},   {n + "/rot_z", q.z()},
          {n + "/rot_w", q.w()}};
}

std::map<std::string, double> multiDofStateValues(
    const RobotModel& m, const std::vector<std::pair<std::string, Eigen::Isometry3d>>& named,
    std::vector<std::string>* notes) {
  std::map<std::string, double> out;
  for (const auto& [name, X] : named) {
    const int md = m.multiDofIndex(name);
    if (md < 0) {
      if (notes && !X.isApprox(Eigen::Isometry3d::Identity(), 1e-12))
        notes->push_back("multi-DOF joint '" + name +
                         "' is not a planar or floating joint of robot '" + m.name +
                         "': its non-identity transform is ignored");
      continue;
    }
    for (const auto& [variable, value] : multiDofValues(m, md, X)) out[variable] = value;
  }
  return out;
}

}  // namespace dss
