// Kinematic-tree check of a URDF's links and joints, as its XML declares them (internal to
// the URDF readers: the robot loader and the URDF-as-world reader). It runs before urdfdom.
//
// urdfdom links its joints without checking that they form a tree. A link that is the child
// of two joints (a closed chain, or a cycle through links reachable from the root) keeps one
// of them as its parent while both list it as a child, so a walk from the root loops forever;
// links in a cycle that does not touch the root are accepted as long as exactly one link has
// no parent, so a walk from the root never sees them; and when no link or several links lack
// a parent urdfdom's message names no cycle or only two roots. treeProblem finds each case
// and names the links and joints involved, with their lines; the walks here never recurse.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace dss {
namespace urdf_tree {

/// One <joint>: its name and the links its <parent> and <child> name.
struct JointEdge {
  std::string name, parent, child;
};

namespace detail {

// "'a' (line 3), 'b' (line 4) and 2 more": at most `shown` names, so that a message about a
// huge file stays short.
template <class Line>
std::string nameList(const std::vector<std::string>& names, const Line& line_of,
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

/// An empty string when the joints connect the links into one tree (each link the child of
/// at most one joint, exactly one root, every link reached from it); otherwise what is wrong,
/// naming the links and joints (no file prefix). Joints that name a link not in `links`, or
/// lack a parent or child, are left to urdfdom to report. `link_line` and `joint_line` map a
/// name to " (line N)".
template <class LinkLine, class JointLine>
std::string treeProblem(const std::vector<std::string>& links, const std::vector<JointEdge>& joints,
                        const LinkLine& link_line, const JointLine& joint_line) {
  const std::set<std::string> known(links.begin(), links.end());
  std::map<std::string, std::vector<const JointEdge*>> parents, children;  // by link
  for (const JointEdge& j : joints) {
    if (!known.count(j.parent) || !known.count(j.child)) continue;
    parents[j.child].push_back(&j);
    children[j.parent].push_back(&j);
  }
  for (const auto& [link, list] : parents)
    if (list.size() > 1) {
      std::vector<std::string> names;
      for (const JointEdge* j : list) names.push_back(j->name);
      return "link '" + link + "'" + link_line(link) + " is the child of " +
             std::to_string(names.size()) + " joints, " + detail::nameList(names, joint_line) +
             ": a URDF must be a tree, each link with at most one parent joint (this is a "
             "closed kinematic chain or a cycle)";
    }

  // Climbing parents from a link that is not reached from a root ends in a cycle.
  auto cycleFrom = [&](const std::string& start, std::vector<std::string>& cycle_links,
                       std::vector<std::string>& cycle_joints) {
    std::vector<std::string> path;
    std::map<std::string, std::size_t> seen;
    std::string link = start;
    while (!seen.count(link) && parents.count(link)) {
      seen[link] = path.size();
      path.push_back(link);
      link = parents.at(link).front()->parent;
    }
    if (!seen.count(link)) return false;
    cycle_links.assign(path.begin() + static_cast<std::ptrdiff_t>(seen[link]), path.end());
    for (const auto& l : cycle_links) cycle_joints.push_back(parents.at(l).front()->name);
    return true;
  };
  const std::set<std::string> distinct(links.begin(), links.end());
  std::vector<std::string> roots;
  for (const auto& l : distinct)
    if (!parents.count(l)) roots.push_back(l);
  if (roots.empty()) {
    std::vector<std::string> cycle, cycle_joints;
    if (!distinct.empty() && cycleFrom(*distinct.begin(), cycle, cycle_joints))
      return "links " + detail::nameList(cycle, link_line) + " and joints " +
             detail::nameList(cycle_joints, joint_line) +
             " form a cycle, and every link has a parent joint: a URDF must be a tree with one "
             "root link";
    return std::string();  // no links at all: urdfdom says so
  }
  if (roots.size() > 1)
    return std::to_string(roots.size()) + " links have no parent joint, " +
           detail::nameList(roots, link_line) +
           ": a URDF must be one tree with one root link (the others are not connected to it)";

  const std::string& root = roots.front();
  std::set<std::string> reached{root};
  std::vector<std::string> stack{root};
  while (!stack.empty()) {
    const std::string link = stack.back();
    stack.pop_back();
    const auto c = children.find(link);
    if (c == children.end()) continue;
    for (const JointEdge* j : c->second)
      if (reached.insert(j->child).second) stack.push_back(j->child);
  }
  std::vector<std::string> unreached;
  for (const auto& l : distinct)
    if (!reached.count(l)) unreached.push_back(l);
  if (unreached.empty()) return std::string();
  std::vector<std::string> cycle, cycle_joints;
  std::string msg;
  if (cycleFrom(unreached.front(), cycle, cycle_joints))
    msg = "links " + detail::nameList(cycle, link_line) + " and joints " +
          detail::nameList(cycle_joints, joint_line) +
          " form a cycle that is not connected to the root link '" + root + "'";
  else  // cannot happen with one root, but say something true
    msg = "link '" + unreached.front() + "'" + link_line(unreached.front()) +
          " is not connected to the root link '" + root + "'";
  return msg + "; " + std::to_string(unreached.size()) +
         " link(s) cannot be reached from the root: " + detail::nameList(unreached, link_line);
}

}  // namespace urdf_tree
}  // namespace dss
