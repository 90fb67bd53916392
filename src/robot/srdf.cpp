// SRDF reading with tinyxml and planning-group resolution (see dss/robot/srdf.h).
#include "dss/robot/srdf.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "xml_util.h"

namespace dss {
namespace {

std::string required(const TiXmlElement* e, const char* name, const std::string& file) {
  const char* v = e->Attribute(name);
  if (!v) xml::fail(file, e, std::string("<") + e->Value() + "> lacks attribute '" + name + "'");
  return v;
}

}  // namespace

const SrdfGroup* Srdf::group(const std::string& n) const {
  for (const auto& g : groups)
    if (g.name == n) return &g;
  return nullptr;
}

const SrdfGroupState* Srdf::groupState(const std::string& g, const std::string& n) const {
  for (const auto& s : group_states)
    if (s.group == g && s.name == n) return &s;
  return nullptr;
}

Srdf loadSrdf(const std::string& path, const RobotInputLimits& limits) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open SRDF file " + path);
  std::stringstream ss;
  ss << in.rdbuf();
  return parseSrdf(ss.str(), path, limits);
}

Srdf parseSrdf(const std::string& text, const std::string& file, const RobotInputLimits& limits) {
  // tinyxml parses recursively: bound the nesting before it sees the text.
  xml::checkDepth(text, file, limits.max_xml_depth,
                  "the limits argument of loadSrdf, parseSrdf or loadRobot");
  TiXmlDocument doc;
  xml::parse(doc, text, file);
  const TiXmlElement* robot = doc.RootElement();
  if (!robot || std::string(robot->Value()) != "robot")
    xml::fail(file, robot, "the root element is not <robot>");
  Srdf srdf;
  srdf.source = file;
  srdf.max_group_depth = limits.max_group_depth;
  if (const char* n = robot->Attribute("name")) srdf.name = n;
  for (const TiXmlElement* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Value();
    if (tag == "group") {
      SrdfGroup g;
      g.name = required(e, "name", file);
      for (const TiXmlElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
        const std::string ct = c->Value();
        if (ct == "joint")
          g.joints.push_back(required(c, "name", file));
        else if (ct == "link")
          g.links.push_back(required(c, "name", file));
        else if (ct == "group")
          g.subgroups.push_back(required(c, "name", file));
        else if (ct == "chain")
          g.chains.push_back({required(c, "base_link", file), required(c, "tip_link", file)});
      }
      srdf.groups.push_back(std::move(g));
    } else if (tag == "disable_collisions") {
      SrdfDisabledPair p{required(e, "link1", file), required(e, "link2", file), ""};
      if (const char* r = e->Attribute("reason")) p.reason = r;
      srdf.disabled_collisions.push_back(std::move(p));
    } else if (tag == "group_state") {
      SrdfGroupState s;
      s.name = required(e, "name", file);
      s.group = required(e, "group", file);
      for (const TiXmlElement* c = e->FirstChildElement("joint"); c;
           c = c->NextSiblingElement("joint")) {
        const std::string jn = required(c, "name", file);
        const char* v = c->Attribute("value");
        if (!v) {  // e.g. <joint name="panda_finger_joint1"/> in some files: no value given
          srdf.warnings.push_back(xml::where(file, c) + ": group_state '" + s.name + "' joint '" +
                                  jn + "' has no value: the joint keeps its other value");
          continue;
        }
        const auto vals =
            xml::numbers(v, -1, file, c, "group_state '" + s.name + "' joint '" + jn + "' value");
        if (vals.size() != 1)
          xml::fail(file, c,
                    "group_state '" + s.name + "' joint '" + jn +
                        "': expected one value (multi-DOF joints are not supported)");
        s.values.emplace_back(jn, vals[0]);
      }
      srdf.group_states.push_back(std::move(s));
    } else if (tag == "virtual_joint") {
      SrdfVirtualJoint v;
      v.name = required(e, "name", file);
      if (const char* t = e->Attribute("type")) v.type = t;
      if (const char* t = e->Attribute("parent_frame")) v.parent_frame = t;
      if (const char* t = e->Attribute("child_link")) v.child_link = t;
      srdf.virtual_joints.push_back(std::move(v));
    }
  }
  return srdf;
}

namespace {

// Expands planning groups into joint indices, each group once (memoised): groups that share
// subgroups (a diamond) cost their size, not the number of paths through them. The expansion
// walks an explicit stack, so a long chain of subgroups cannot exhaust the call stack; a group
// that includes itself, directly or not, and nesting beyond Srdf::max_group_depth are errors
// naming the groups.
class GroupResolver {
 public:
  GroupResolver(const RobotModel& model, const Srdf& srdf) : model_(model), srdf_(srdf) {
    for (const auto& g : srdf.groups) index_.emplace(g.name, &g);  // the first of a name wins
    for (const auto& v : srdf.virtual_joints) virtual_joints_.insert(v.name);
  }

  const std::set<int>& joints(const std::string& name) {
    if (const auto done = memo_.find(name); done != memo_.end()) return done->second;
    // Depth-first over subgroups: a frame is expanded once all its subgroups are memoised.
    struct Frame {
      const SrdfGroup* group;
      std::size_t next_subgroup = 0;
    };
    std::vector<Frame> stack{{find(name, nullptr)}};
    std::set<std::string> on_stack{name};
    while (!stack.empty()) {
      Frame& f = stack.back();
      if (f.next_subgroup < f.group->subgroups.size()) {
        const std::string& sub = f.group->subgroups[f.next_subgroup++];
        if (memo_.count(sub)) continue;
        if (on_stack.count(sub)) throw std::runtime_error(cycleMessage(stack, sub));
        if (stack.size() >= srdf_.max_group_depth) throw std::runtime_error(depthMessage(stack));
        const SrdfGroup* g = find(sub, f.group);
        on_stack.insert(sub);
        stack.push_back({g});
        continue;
      }
      std::set<int> own = ownJoints(*f.group);
      for (const auto& sub : f.group->subgroups) {
        const std::set<int>& s = memo_.at(sub);
        own.insert(s.begin(), s.end());
      }
      on_stack.erase(f.group->name);
      memo_.emplace(f.group->name, std::move(own));
      stack.pop_back();
    }
    return memo_.at(name);
  }

 private:
  const SrdfGroup* find(const std::string& name, const SrdfGroup* parent) const {
    const auto it = index_.find(name);
    if (it == index_.end())
      throw std::runtime_error(srdf_.source + ": no group '" + name + "'" +
                               (parent ? " (a subgroup of group '" + parent->name + "')" : ""));
    return it->second;
  }

  template <class Frames>
  static std::string path(const Frames& stack, std::size_t shown = 8) {
    std::string out;
    const std::size_t n = stack.size();
    for (std::size_t i = 0; i < n; ++i) {
      if (n > shown && i == shown / 2) {
        out += " -> ... (" + std::to_string(n - shown) + " more)";
        i = n - shown / 2 - 1;
        continue;
      }
      out += (i ? " -> '" : "'") + stack[i].group->name + "'";
    }
    return out;
  }

  template <class Frames>
  std::string cycleMessage(const Frames& stack, const std::string& again) const {
    return srdf_.source + ": group '" + again +
           "' includes itself through its subgroups: " + path(stack) + " -> '" + again + "'";
  }

  template <class Frames>
  std::string depthMessage(const Frames& stack) const {
    return srdf_.source + ": group '" + stack.front().group->name +
           "': subgroups nest deeper than the limit of " + std::to_string(srdf_.max_group_depth) +
           " (" + path(stack) +
           "; RobotInputLimits::max_group_depth; raise it with the limits argument of "
           "loadSrdf, parseSrdf or loadRobot)";
  }

  std::set<int> ownJoints(const SrdfGroup& g) const {
    const std::string where = srdf_.source + ": group '" + g.name + "'";
    std::set<int> joints;
    for (const auto& j : g.joints) {
      // A planar or floating joint (URDF or SRDF virtual): its one-variable parts.
      if (const int md = model_.multiDofIndex(j); md >= 0) {
        for (int part : model_.multi_dof_joints[md].joints) joints.insert(part);
        continue;
      }
      if (virtual_joints_.count(j)) continue;  // a fixed virtual joint
      const int ji = model_.jointIndex(j);
      if (ji < 0)
        throw std::runtime_error(where + " names joint '" + j + "' that robot '" + model_.name +
                                 "' lacks");
      joints.insert(ji);
    }
    for (const auto& l : g.links) {
      const int li = model_.linkIndex(l);
      if (li < 0)
        throw std::runtime_error(where + " names link '" + l + "' that robot '" + model_.name +
                                 "' lacks");
      if (model_.links[li].parent_joint >= 0) joints.insert(model_.links[li].parent_joint);
    }
    for (const auto& c : g.chains) {
      const int base = model_.linkIndex(c.base_link), tip = model_.linkIndex(c.tip_link);
      if (base < 0 || tip < 0)
        throw std::runtime_error(where + " chain names a link that robot '" + model_.name +
                                 "' lacks ('" + (base < 0 ? c.base_link : c.tip_link) + "')");
      int l = tip;
      std::vector<int> chain;
      while (l != base && l >= 0) {
        if (model_.links[l].parent_joint >= 0) chain.push_back(model_.links[l].parent_joint);
        l = model_.links[l].parent_link;
      }
      if (l != base)
        throw std::runtime_error(where + " chain: '" + c.base_link + "' is not an ancestor of '" +
                                 c.tip_link + "'");
      joints.insert(chain.begin(), chain.end());
    }
    // A part of a multi-DOF joint (a link's parent joint, a chain through it) brings the
    // others: the joint moves as a whole, as in MoveIt.
    std::set<int> whole = joints;
    for (int j : joints)
      if (const int md = model_.joints[j].multi_dof; md >= 0)
        for (int part : model_.multi_dof_joints[md].joints) whole.insert(part);
    return whole;
  }

  const RobotModel& model_;
  const Srdf& srdf_;
  std::map<std::string, const SrdfGroup*> index_;
  std::set<std::string> virtual_joints_;
  std::map<std::string, std::set<int>> memo_;
};

std::vector<int> activeIndices(const RobotModel& model, const std::set<int>& joints) {
  std::vector<int> out;
  for (int j : joints)  // std::set: increasing joint index = model order
    for (int k = 0; k < model.joints[j].numVariables(); ++k)
      out.push_back(model.joints[j].active_index + k);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

std::vector<int> groupActiveJoints(const RobotModel& model, const Srdf& srdf,
                                   const std::string& name) {
  GroupResolver resolver(model, srdf);
  return activeIndices(model, resolver.joints(name));
}

std::vector<std::string> checkSrdfAgainstModel(const RobotModel& model, const Srdf& srdf) {
  std::vector<std::string> out;
  auto link = [&](const std::string& l, const std::string& ctx) {
    if (model.linkIndex(l) < 0)
      out.push_back(srdf.source + ": " + ctx + " names missing link '" + l + "'");
  };
  for (const auto& p : srdf.disabled_collisions) {
    link(p.link1, "disable_collisions");
    link(p.link2, "disable_collisions");
  }
  GroupResolver resolver(model, srdf);  // one memo for all groups
  for (const auto& g : srdf.groups) {
    try {
      resolver.joints(g.name);
    } catch (const std::exception& e) {
      out.push_back(e.what());
    }
  }
  for (const auto& s : srdf.group_states)
    for (const auto& [j, v] : s.values)
      if (model.jointIndex(j) < 0)
        out.push_back(srdf.source + ": group_state '" + s.name + "' names missing joint '" + j +
                      "'");
  return out;
}

}  // namespace dss
