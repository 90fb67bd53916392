// URDF -> RobotModel: urdfdom for the kinematic tree, our own XML scan for the collision
// elements (so none is dropped silently) and for strict validation of every <origin>.
#include "dss/robot/urdf_loader.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <tuple>

#include "../common/urdf_tree_check.h"
#include "dss/mesh/mesh.h"
#include "dss/robot/multi_dof.h"
#include "xml_util.h"

namespace dss {
namespace {

namespace fs = std::filesystem;

// Collects urdfdom's console messages during one parse so that they end up in our exception.
class CaptureOutput : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) lines.push_back(text);
  }
  std::vector<std::string> lines;
};

struct CaptureScope {
  explicit CaptureScope(CaptureOutput* out) { console_bridge::useOutputHandler(out); }
  ~CaptureScope() { console_bridge::restorePreviousOutputHandler(); }
};

Eigen::Isometry3d toIsometry(const urdf::Pose& p) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  Eigen::Quaterniond q(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z);
  X.linear() = q.normalized().toRotationMatrix();
  return X;
}

struct ScannedCollision {
  const TiXmlElement* element;
  int index;  // among the link's <collision> elements
};

struct Scan {
  std::vector<std::string> joint_order;                             // document order
  std::map<std::string, std::vector<ScannedCollision>> collisions;  // per link
  std::map<std::string, const TiXmlElement*> link_elements;
  std::map<std::string, const TiXmlElement*> joint_elements;
  std::vector<std::string> link_order;            // document order
  std::vector<urdf_tree::JointEdge> joint_edges;  // as the <parent>/<child> elements say
};

const char* linkOf(const TiXmlElement* joint, const char* tag) {
  const TiXmlElement* e = joint->FirstChildElement(tag);
  const char* link = e ? e->Attribute("link") : nullptr;
  return link ? link : "";
}

Scan scanDocument(const TiXmlDocument& doc, const std::string& file) {
  Scan scan;
  const TiXmlElement* robot = doc.RootElement();
  if (!robot || std::string(robot->Value()) != "robot")
    xml::fail(file, robot, "the root element is not <robot>");
  for (const TiXmlElement* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Value();
    const char* name = e->Attribute("name");
    if (tag == "joint") {
      if (!name) xml::fail(file, e, "<joint> without a name");
      scan.joint_order.push_back(name);
      scan.joint_elements[name] = e;
      scan.joint_edges.push_back({name, linkOf(e, "parent"), linkOf(e, "child")});
      for (const char* child : {"origin", "axis"}) {
        const TiXmlElement* c = e->FirstChildElement(child);
        if (!c) continue;
        const std::string what = std::string("joint '") + name + "'";
        if (std::string(child) == "origin")
          xml::origin(c, file, what);
        else if (const char* xyz = c->Attribute("xyz"))
          xml::numbers(xyz, 3, file, c, what + " axis");
      }
    } else if (tag == "link") {
      if (!name) xml::fail(file, e, "<link> without a name");
      scan.link_elements[name] = e;
      scan.link_order.push_back(name);
      auto& list = scan.collisions[name];
      for (const TiXmlElement* c = e->FirstChildElement("collision"); c;
           c = c->NextSiblingElement("collision"))
        list.push_back({c, static_cast<int>(list.size())});
    }
  }
  return scan;
}

// One mesh file at one scale, as hull or as pieces: loaded (and decomposed) once per robot.
struct MeshPieces {
  std::vector<ConvexHull> hulls;
  std::vector<double> concavity;
};
struct MeshCache {
  std::map<std::tuple<std::string, std::array<double, 3>, bool>, MeshPieces> meshes;
};

// One <collision> element -> its shapes (several for a decomposed mesh), or none with `why` set.
std::vector<CollisionElement> makeCollision(const ScannedCollision& sc, const std::string& link,
                                            const std::string& file, const std::string& base_dir,
                                            const LoadOptions& options, MeshCache& cache,
                                            std::string& why) {
  const TiXmlElement* c = sc.element;
  const std::string what = "link '" + link + "' collision[" + std::to_string(sc.index) + "]";
  CollisionElement out;
  out.X_LS = xml::origin(c->FirstChildElement("origin"), file, what);
  const TiXmlElement* geometry = c->FirstChildElement("geometry");
  const TiXmlElement* g = geometry ? geometry->FirstChildElement() : nullptr;
  if (!g) {
    why = xml::where(file, c) + ": " + what + " has no geometry";
    return {};
  }
  const std::string type = g->Value();
  auto positive = [&](const char* attribute, int count) {
    const char* text = g->Attribute(attribute);
    if (!text) xml::fail(file, g, what + " <" + type + "> lacks attribute '" + attribute + "'");
    auto v = xml::numbers(text, count, file, g, what + " <" + type + "> " + attribute);
    for (double x : v)
      if (x < 0)
        xml::fail(file, g, what + " <" + type + "> " + attribute + " '" + text + "' is negative");
    return v;
  };
  if (type == "box") {
    const auto s = positive("size", 3);
    out.shape = Box::fromSize(Eigen::Vector3d(s[0], s[1], s[2]));
    out.description = what + " box";
  } else if (type == "sphere") {
    out.shape = Sphere{positive("radius", 1)[0]};
    out.description = what + " sphere";
  } else if (type == "cylinder") {
    out.shape = Cylinder::fromLength(positive("radius", 1)[0], positive("length", 1)[0]);
    out.description = what + " cylinder";
  } else if (type == "capsule") {  // an extension (SDFormat, Drake); urdfdom drops it
    out.shape = Capsule::fromLength(positive("radius", 1)[0], positive("length", 1)[0]);
    out.description = what + " capsule";
  } else if (type == "mesh") {
    const char* uri = g->Attribute("filename");
    if (!uri) xml::fail(file, g, what + " <mesh> lacks attribute 'filename'");
    Eigen::Vector3d scale = Eigen::Vector3d::Ones();
    if (const char* s = g->Attribute("scale")) {
      const auto v = xml::numbers(s, -1, file, g, what + " <mesh> scale");
      if (v.size() == 1)
        scale.setConstant(v[0]);
      else if (v.size() == 3)
        scale = Eigen::Vector3d(v[0], v[1], v[2]);
      else
        xml::fail(file, g, what + " <mesh> scale '" + s + "': expected 1 or 3 numbers");
      // Zero flattens the mesh (to a plane, a line or a point); a negative component mirrors
      // it, which URDF allows: the hull is that of the mirrored vertices.
      for (int i = 0; i < 3; ++i)
        if (scale[i] == 0)
          xml::fail(file, g,
                    what + " <mesh> scale '" + s + "': component " + "xyz"[i] +
                        " is zero (the mesh would collapse); scales must be non-zero");
    }
    std::vector<std::string> tried;
    const auto path = resolveMeshUri(uri, base_dir, options.mesh_paths, &tried);
    if (!path) {
      std::string msg = what + ": cannot resolve mesh '" + std::string(uri) + "'";
      if (!tried.empty()) {
        msg += " (tried";
        for (const auto& t : tried) msg += " " + t;
        msg += ")";
      }
      xml::fail(file, g, msg);
    }
    out.description = what + " mesh " + *path;
    out.mesh_path = *path;
    out.mesh_scale = scale;
    const auto mode_it = options.meshes.links.find(link);
    const bool decompose =
        (mode_it != options.meshes.links.end() ? mode_it->second : options.meshes.geometry) ==
        MeshGeometry::kDecompose;
    const auto key =
        std::make_tuple(*path, std::array<double, 3>{scale.x(), scale.y(), scale.z()}, decompose);
    auto it = cache.meshes.find(key);
    if (it == cache.meshes.end()) {
      const std::size_t max_vertices = options.limits.max_mesh_vertices;
      try {
        const mesh::TriangleMesh m = mesh::loadMesh(*path, scale, max_vertices);
        MeshPieces pieces;
        if (!decompose) {
          pieces.hulls.push_back(mesh::convexHull(m.vertices, out.description));
          pieces.concavity.push_back(0.0);
        } else {
          const mesh::Decomposition d = mesh::decomposeCached(
              m, options.meshes.decomposition, out.description, options.meshes.cache_dir);
          for (std::size_t i = 0; i < d.pieces.size(); ++i) {
            pieces.hulls.push_back(mesh::convexHull(
                d.pieces[i].points, out.description + " piece " + std::to_string(i + 1)));
            pieces.concavity.push_back(d.pieces[i].concavity);
          }
        }
        it = cache.meshes.emplace(key, std::move(pieces)).first;
      } catch (const std::length_error& e) {
        xml::fail(file, g,
                  what + ": " + e.what() +
                      " (RobotInputLimits::max_mesh_vertices; raise it with "
                      "LoadOptions::limits.max_mesh_vertices)");
      } catch (const std::exception& e) {
        xml::fail(file, g, what + ": " + e.what());
      }
    }
    const MeshPieces& pieces = it->second;
    if (!decompose) {
      out.shape = pieces.hulls.front();
      return {out};
    }
    std::vector<CollisionElement> all;
    const int n = static_cast<int>(pieces.hulls.size());
    for (int i = 0; i < n; ++i) {
      CollisionElement piece = out;
      piece.shape = pieces.hulls[i];
      piece.piece = i;
      piece.pieces = n;
      piece.concavity = pieces.concavity[i];
      piece.description += " piece " + std::to_string(i + 1) + "/" + std::to_string(n);
      all.push_back(std::move(piece));
    }
    return all;
  } else {
    why = xml::where(file, g) + ": " + what + " has unsupported geometry <" + type + ">";
    return {};
  }
  return {out};
}

}  // namespace

RobotModel loadUrdf(const std::string& path, const LoadOptions& options) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open URDF file " + path);
  std::stringstream ss;
  ss << in.rdbuf();
  const fs::path dir = fs::absolute(fs::path(path)).parent_path();
  return loadUrdfString(ss.str(), path, dir.string(), options);
}

RobotModel loadUrdfString(const std::string& text, const std::string& file,
                          const std::string& base_dir, const LoadOptions& options) {
  // tinyxml and urdfdom parse recursively: bound the nesting before either sees the text.
  xml::checkDepth(text, file, options.limits.max_xml_depth, "LoadOptions::limits.max_xml_depth");
  TiXmlDocument doc;
  xml::parse(doc, text, file);
  const Scan scan = scanDocument(doc, file);
  // The joints must form a tree before urdfdom links them (see urdf_tree_check.h).
  {
    auto lineOf = [](const std::map<std::string, const TiXmlElement*>& elements) {
      return [&elements](const std::string& name) {
        const auto it = elements.find(name);
        return it == elements.end() ? std::string()
                                    : " (line " + std::to_string(it->second->Row()) + ")";
      };
    };
    const std::string problem = urdf_tree::treeProblem(
        scan.link_order, scan.joint_edges, lineOf(scan.link_elements), lineOf(scan.joint_elements));
    if (!problem.empty()) throw std::runtime_error(file + ": " + problem);
  }

  CaptureOutput capture;
  urdf::ModelInterfaceSharedPtr urdf;
  {
    CaptureScope scope(&capture);
    try {
      urdf = urdf::parseURDF(text);
    } catch (const std::exception& e) {
      capture.lines.push_back(e.what());
    }
  }
  if (!urdf) {
    std::string msg = file + ": urdfdom could not parse the robot";
    for (const auto& l : capture.lines) msg += "; " + l;
    throw std::runtime_error(msg);
  }

  RobotModel model;
  model.name = urdf->getName();
  model.source = file;
  for (const auto& l : capture.lines) {  // urdfdom repeats some messages
    const std::string w = file + ": urdfdom: " + l;
    if (std::find(model.warnings.begin(), model.warnings.end(), w) == model.warnings.end())
      model.warnings.push_back(w);
  }
  std::map<std::string, MultiDofType> multi_dof;  // planar and floating joints, by name
  std::map<std::string, int> joint_doc_index;
  for (std::size_t i = 0; i < scan.joint_order.size(); ++i)
    joint_doc_index[scan.joint_order[i]] = int(i);

  // Depth-first from the root, children in document order.
  const urdf::LinkConstSharedPtr root = urdf->getRoot();
  if (!root) throw std::runtime_error(file + ": no root link");
  struct Item {
    urdf::LinkConstSharedPtr link;
    int parent_joint;
  };
  std::vector<Item> stack{{root, -1}};
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    const int li = static_cast<int>(model.links.size());
    RobotLink link;
    link.name = item.link->name;
    link.parent_joint = item.parent_joint;
    if (item.parent_joint >= 0) {
      link.parent_link = model.joints[item.parent_joint].parent_link;
      model.joints[item.parent_joint].child_link = li;
      model.links[link.parent_link].child_joints.push_back(item.parent_joint);
    }
    model.links.push_back(link);
    std::vector<urdf::JointSharedPtr> children = item.link->child_joints;
    std::sort(children.begin(), children.end(), [&](const auto& a, const auto& b) {
      return joint_doc_index[a->name] < joint_doc_index[b->name];
    });
    // Joints are numbered when their child link is visited; push in reverse for document order.
    std::vector<Item> next;
    for (const auto& uj : children) {
      const TiXmlElement* je =
          scan.joint_elements.count(uj->name) ? scan.joint_elements.at(uj->name) : nullptr;
      const std::string what = "joint '" + uj->name + "'";
      RobotJoint j;
      j.name = uj->name;
      j.parent_link = li;
      j.X_PJ = toIsometry(uj->parent_to_joint_origin_transform);
      switch (uj->type) {
        case urdf::Joint::FIXED:
          j.type = JointType::kFixed;
          break;
        case urdf::Joint::REVOLUTE:
          j.type = JointType::kRevolute;
          break;
        case urdf::Joint::CONTINUOUS:
          j.type = JointType::kContinuous;
          break;
        case urdf::Joint::PRISMATIC:
          j.type = JointType::kPrismatic;
          break;
        case urdf::Joint::FLOATING:
        case urdf::Joint::PLANAR: {
          // A placeholder, expanded into one-variable joints below (multi_dof.h).
          j.type = JointType::kFixed;
          const bool planar = uj->type == urdf::Joint::PLANAR;
          multi_dof[uj->name] = planar ? MultiDofType::kPlanar : MultiDofType::kFloating;
          if (uj->mimic)
            xml::fail(file, je,
                      what + " is " + (planar ? "planar" : "floating") +
                          " and cannot mimic another joint");
          const Eigen::Vector3d a(uj->axis.x, uj->axis.y, uj->axis.z);
          if (planar && je && je->FirstChildElement("axis") &&
              !a.isApprox(Eigen::Vector3d::UnitZ(), 1e-12))
            model.warnings.push_back(xml::where(file, je) + ": " + what +
                                     " is planar: it moves in the x-y plane of its joint frame "
                                     "(MoveIt's convention); its <axis> is not used");
          break;
        }
        default:
          xml::fail(file, je, what + " has an unknown type");
      }
      if (j.isMoving()) {
        Eigen::Vector3d a(uj->axis.x, uj->axis.y, uj->axis.z);
        if (!a.allFinite() || a.norm() < 1e-12)
          xml::fail(file, je, what + " has a zero or invalid axis");
        j.axis = a.normalized();
        if (uj->limits) {
          j.limits.velocity = uj->limits->velocity;
          j.limits.effort = uj->limits->effort;
          if (j.type != JointType::kContinuous) {
            j.limits.has_position_limits = true;
            j.limits.lower = uj->limits->lower;
            j.limits.upper = uj->limits->upper;
            if (!(j.limits.lower <= j.limits.upper))
              xml::fail(file, je,
                        what + " has lower limit " + std::to_string(j.limits.lower) +
                            " above upper limit " + std::to_string(j.limits.upper));
          }
        } else if (j.type != JointType::kContinuous) {
          xml::fail(file, je, what + " has no <limit>");
        }
      }
      if (uj->mimic) {
        if (j.isMoving()) {
          j.mimic.leader = uj->mimic->joint_name;
          j.mimic.multiplier = uj->mimic->multiplier;
          j.mimic.offset = uj->mimic->offset;
          if (!std::isfinite(j.mimic.multiplier) || !std::isfinite(j.mimic.offset))
            xml::fail(file, je, what + " <mimic> multiplier/offset not finite");
        } else {
          model.warnings.push_back(xml::where(file, je) + ": " + what +
                                   " is fixed; its <mimic> tag is ignored");
        }
      }
      const int ji = static_cast<int>(model.joints.size());
      model.joints.push_back(j);
      const auto child = urdf->getLink(uj->child_link_name);
      if (!child)
        xml::fail(file, je, what + " names a missing child link '" + uj->child_link_name + "'");
      next.push_back({child, ji});
    }
    for (auto it = next.rbegin(); it != next.rend(); ++it) stack.push_back(*it);
  }
  // Joints were numbered breadth-wise per parent above; renumber so that joint order follows
  // the depth-first link order (joint of link i before joint of link i+1).
  {
    std::vector<int> new_index(model.joints.size(), -1);
    std::vector<RobotJoint> joints;
    for (auto& l : model.links)
      if (l.parent_joint >= 0) {
        new_index[l.parent_joint] = static_cast<int>(joints.size());
        joints.push_back(model.joints[l.parent_joint]);
      }
    for (auto& l : model.links) {
      if (l.parent_joint >= 0) l.parent_joint = new_index[l.parent_joint];
      for (int& c : l.child_joints) c = new_index[c];
    }
    model.joints = std::move(joints);
  }
  model.root_link = 0;
  model.rebuildIndex();

  // Active joints and mimic resolution.
  for (std::size_t ji = 0; ji < model.joints.size(); ++ji) {
    RobotJoint& j = model.joints[ji];
    if (j.isMoving() && j.mimic.leader.empty()) {
      j.active_index = static_cast<int>(model.active_joints.size());
      model.active_joints.push_back(static_cast<int>(ji));
    }
  }
  for (auto& j : model.joints) {
    if (j.mimic.leader.empty()) continue;
    const TiXmlElement* je = scan.joint_elements.at(j.name);
    const RobotJoint* cur = &j;
    for (std::size_t steps = 0;; ++steps) {
      if (steps > model.joints.size())
        xml::fail(file, je, "joint '" + j.name + "': cyclic <mimic> chain");
      const int li = model.jointIndex(cur->mimic.leader);
      if (li < 0)
        xml::fail(file, je,
                  "joint '" + j.name + "' mimics a missing joint '" + cur->mimic.leader + "'");
      const RobotJoint& leader = model.joints[li];
      if (multi_dof.count(leader.name))
        xml::fail(file, je,
                  "joint '" + j.name + "' mimics the multi-DOF joint '" + leader.name + "'");
      if (!leader.isMoving())
        xml::fail(file, je, "joint '" + j.name + "' mimics the fixed joint '" + leader.name + "'");
      if (leader.mimic.leader.empty()) break;
      cur = &leader;
    }
    // q_j = m_j * q_leader + o_j along the chain j -> ... -> an active joint, composed from
    // the active end.
    std::vector<const RobotJoint*> chain;
    for (const RobotJoint* c = &j; !c->mimic.leader.empty();
         c = &model.joints[model.jointIndex(c->mimic.leader)])
      chain.push_back(c);
    double mult = 1.0, off = 0.0;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      mult = (*it)->mimic.multiplier * mult;
      off = (*it)->mimic.multiplier * off + (*it)->mimic.offset;
    }
    j.mimic_active = model.joints[model.jointIndex(chain.back()->mimic.leader)].active_index;
    j.mimic_multiplier = mult;
    j.mimic_offset = off;
  }

  // Planar and floating joints become chains of one-variable joints.
  if (!multi_dof.empty()) {
    std::vector<std::pair<int, MultiDofType>> placeholders;
    for (const auto& [name, type] : multi_dof)
      placeholders.push_back({model.jointIndex(name), type});
    expandMultiDofJoints(model, placeholders, false, file);
  }

  // Collision elements, every one accounted for.
  for (const auto& [name, mode] : options.meshes.links)
    if (model.linkIndex(name) < 0)
      throw std::runtime_error(file + ": the mesh options name link '" + name + "', which robot '" +
                               model.name + "' does not have");
  if (options.load_collisions) {
    MeshCache cache;
    std::vector<std::string> dropped;
    for (auto& link : model.links) {
      const auto it = scan.collisions.find(link.name);
      if (it == scan.collisions.end()) continue;
      for (const auto& sc : it->second) {
        std::string why;
        auto c = makeCollision(sc, link.name, file, base_dir, options, cache, why);
        if (c.empty()) dropped.push_back(why);
        for (auto& e : c) link.collisions.push_back(std::move(e));
      }
    }
    if (!dropped.empty()) {
      std::string msg =
          std::to_string(dropped.size()) + " <collision> element(s) did not become a shape:";
      for (const auto& d : dropped) msg += "\n  " + d;
      if (!options.allow_dropped_collisions) throw std::runtime_error(file + ": " + msg);
      std::cerr << "WARNING: " << file << ": " << msg << "\n";
      for (const auto& d : dropped) model.warnings.push_back("dropped collision: " + d);
    }
  }
  return model;
}

}  // namespace dss
