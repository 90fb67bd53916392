// SRDF reading with tinyxml and planning-group resolution (see dss/robot/srdf.h).
#include "dss/robot/srdf.h"

#include <algorithm>
#include <fstream>
#include <functional>
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

Srdf loadSrdf(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open SRDF file " + path);
  std::stringstream ss;
  ss << in.rdbuf();
  return parseSrdf(ss.str(), path);
}

Srdf parseSrdf(const std::string& text, const std::string& file) {
  TiXmlDocument doc;
  xml::parse(doc, text, file);
  const TiXmlElement* robot = doc.RootElement();
  if (!robot || std::string(robot->Value()) != "robot")
    xml::fail(file, robot, "the root element is not <robot>");
  Srdf srdf;
  srdf.source = file;
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
        if (!v) continue;  // e.g. <joint name="panda_finger_joint1"/> in some files: no value given
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

std::vector<int> groupActiveJoints(const RobotModel& model, const Srdf& srdf,
                                   const std::string& name) {
  std::set<int> joints;
  std::set<std::string> visiting;
  auto isVirtual = [&](const std::string& j) {
    return std::any_of(srdf.virtual_joints.begin(), srdf.virtual_joints.end(),
                       [&](const SrdfVirtualJoint& v) { return v.name == j; });
  };
  std::function<void(const std::string&)> add = [&](const std::string& gname) {
    const SrdfGroup* g = srdf.group(gname);
    const std::string where = srdf.source + ": group '" + gname + "'";
    if (!g) throw std::runtime_error(srdf.source + ": no group '" + gname + "'");
    if (!visiting.insert(gname).second) throw std::runtime_error(where + " includes itself");
    for (const auto& j : g->joints) {
      if (isVirtual(j)) continue;
      const int ji = model.jointIndex(j);
      if (ji < 0)
        throw std::runtime_error(where + " names joint '" + j + "' that robot '" + model.name +
                                 "' lacks");
      joints.insert(ji);
    }
    for (const auto& l : g->links) {
      const int li = model.linkIndex(l);
      if (li < 0)
        throw std::runtime_error(where + " names link '" + l + "' that robot '" + model.name +
                                 "' lacks");
      if (model.links[li].parent_joint >= 0) joints.insert(model.links[li].parent_joint);
    }
    for (const auto& c : g->chains) {
      const int base = model.linkIndex(c.base_link), tip = model.linkIndex(c.tip_link);
      if (base < 0 || tip < 0)
        throw std::runtime_error(where + " chain names a link that robot '" + model.name +
                                 "' lacks ('" + (base < 0 ? c.base_link : c.tip_link) + "')");
      int l = tip;
      std::vector<int> chain;
      while (l != base && l >= 0) {
        if (model.links[l].parent_joint >= 0) chain.push_back(model.links[l].parent_joint);
        l = model.links[l].parent_link;
      }
      if (l != base)
        throw std::runtime_error(where + " chain: '" + c.base_link + "' is not an ancestor of '" +
                                 c.tip_link + "'");
      joints.insert(chain.begin(), chain.end());
    }
    for (const auto& s : g->subgroups) add(s);
    visiting.erase(gname);
  };
  add(name);
  std::vector<int> out;
  for (int j : joints)  // std::set: increasing joint index = model order
    if (model.joints[j].active_index >= 0) out.push_back(model.joints[j].active_index);
  std::sort(out.begin(), out.end());
  return out;
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
  for (const auto& g : srdf.groups) {
    try {
      groupActiveJoints(model, srdf, g.name);
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
