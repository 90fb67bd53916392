// Kinematic-tree check of a model that urdfdom accepted (internal to the URDF readers: the
// robot loader and the URDF-as-world reader).
//
// urdfdom links its joints without checking that they form a tree. A link that is the child
// of two joints (a closed chain, or a cycle through links reachable from the root) keeps one
// of them as its parent while both list it as a child, so a walk from the root loops forever;
// links in a cycle that does not touch the root are accepted as long as exactly one link has
// no parent, so a walk from the root never sees them. checkUrdfTree finds both before any
// walk and names the links and joints involved; the walk never recurses.
#pragma once

#include <urdf_model/model.h>

#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace dss {
namespace urdf_tree {

/// " (line N)" for a link or joint name, or "" when unknown.
using LineOf = std::function<std::string(const std::string& name)>;

namespace detail {

// "'a' (line 3), 'b' (line 4) and 2 more": at most `shown` names, so that a message about a
// huge file stays short.
inline std::string nameList(const std::vector<std::string>& names, const LineOf& line_of,
                            std::size_t shown = 8) {
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < shown; ++i) {
    if (i > 0) out += (i + 1 == names.size() ? " and " : ", ");
    out += "'" + names[i] + "'" + line_of(names[i]);
  }
  if (names.size() > shown) out += " and " + std::to_string(names.size() - shown) + " more";
  return out;
}

}  // namespace detail

/// An empty string when every link of `model` is reached exactly once from its root through
/// child joints; otherwise what is wrong, naming the links and joints (no file prefix).
inline std::string treeProblem(const urdf::ModelInterface& model, const LineOf& link_line,
                               const LineOf& joint_line) {
  // Parent joints of each link, as the joint elements declare them.
  std::map<std::string, std::vector<std::string>> parents;
  for (const auto& [name, joint] : model.joints_)
    if (joint) parents[joint->child_link_name].push_back(name);
  for (const auto& [link, joints] : parents)
    if (joints.size() > 1)
      return "link '" + link + "'" + link_line(link) + " is the child of " +
             std::to_string(joints.size()) + " joints, " + detail::nameList(joints, joint_line) +
             ": a URDF must be a tree, each link with at most one parent joint (this is a "
             "closed kinematic chain or a cycle)";

  const urdf::LinkConstSharedPtr root = model.getRoot();
  if (!root) return "no root link";
  std::set<std::string> reached{root->name};
  std::vector<urdf::LinkConstSharedPtr> stack{root};
  while (!stack.empty()) {
    const urdf::LinkConstSharedPtr link = stack.back();
    stack.pop_back();
    for (const auto& j : link->child_joints) {
      if (!j) continue;
      const urdf::LinkConstSharedPtr child = model.getLink(j->child_link_name);
      if (child && reached.insert(child->name).second) stack.push_back(child);
    }
  }
  std::vector<std::string> unreached;
  for (const auto& [name, link] : model.links_)
    if (!reached.count(name)) unreached.push_back(name);
  if (unreached.empty()) return std::string();

  // Only the root lacks a parent, so climbing from an unreached link ends in a cycle.
  std::vector<std::string> path;
  std::map<std::string, std::size_t> seen;
  std::string link = unreached.front();
  while (!seen.count(link) && path.size() <= model.links_.size()) {
    seen[link] = path.size();
    path.push_back(link);
    const auto p = parents.find(link);
    if (p == parents.end()) break;
    link = model.joints_.at(p->second.front())->parent_link_name;
  }
  std::string msg;
  if (seen.count(link)) {
    const std::vector<std::string> cycle(path.begin() + seen[link], path.end());
    std::vector<std::string> joints;
    for (const auto& l : cycle) joints.push_back(parents.at(l).front());
    msg = "links " + detail::nameList(cycle, link_line) + " and joints " +
          detail::nameList(joints, joint_line) +
          " form a cycle that is not connected to the root link '" + root->name + "'";
  } else {
    msg = "link '" + unreached.front() + "'" + link_line(unreached.front()) +
          " is not connected to the root link '" + root->name + "'";
  }
  return msg + "; " + std::to_string(unreached.size()) +
         " link(s) cannot be reached from the root: " + detail::nameList(unreached, link_line);
}

}  // namespace urdf_tree
}  // namespace dss
