// Reader of a URDF used as a world: every link's collision geometry at its pose with all
// joints held still (see urdf_world.h for the decision on movable joints).
#include "dss/scene/urdf_world.h"

#include <console_bridge/console.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "../common/urdf_tree_check.h"
#include "../common/utf8_scan.h"
#include "dss/scene/scene_error.h"
#include "scene_util.h"

namespace dss {

namespace {

// Collects what urdfdom reports through console_bridge while it parses, so that its reason
// for refusing a file ends up in our exception instead of on stderr only.
class CapturingHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) messages.push_back(text);
  }
  std::vector<std::string> messages;
};

class CaptureGuard {
 public:
  explicit CaptureGuard(CapturingHandler* h) { console_bridge::useOutputHandler(h); }
  ~CaptureGuard() { console_bridge::restorePreviousOutputHandler(); }
};

Eigen::Isometry3d toIsometry(const urdf::Pose& p, const std::string& where) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() =
      scene_detail::checkedQuaternion(p.rotation.x, p.rotation.y, p.rotation.z, p.rotation.w, where)
          .toRotationMatrix();
  X.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  if (!X.translation().allFinite()) throw SceneError(where + ": non-finite position");
  return X;
}

// What the XML itself says: the number of <collision> children of each <link>, and the line
// of each link and joint element (for messages).
struct XmlFacts {
  std::map<std::string, int> collisions;
  std::map<std::string, int> link_lines, joint_lines;
  std::vector<std::string> links;                 // document order
  std::vector<urdf_tree::JointEdge> joint_edges;  // as the <parent>/<child> elements say
};

const char* linkOf(const TiXmlElement* joint, const char* tag) {
  const TiXmlElement* e = joint->FirstChildElement(tag);
  const char* link = e ? e->Attribute("link") : nullptr;
  return link ? link : "";
}

XmlFacts scanXml(const std::string& text, const std::string& path) {
  // tinyxml reads past the buffer on a truncated UTF-8 character (utf8_scan.h).
  const input_scan::Utf8Error bad = input_scan::firstInvalidUtf8(text);
  if (bad.found) throw SceneError(input_scan::utf8Message(path, bad));
  TiXmlDocument doc;
  doc.Parse(text.c_str());
  if (doc.Error()) {
    std::ostringstream s;
    s << path << ":" << doc.ErrorRow() << ":" << doc.ErrorCol()
      << ": malformed XML: " << doc.ErrorDesc();
    throw SceneError(s.str());
  }
  const TiXmlElement* robot = doc.FirstChildElement("robot");
  if (!robot) throw SceneError(path + ": no <robot> element");
  XmlFacts facts;
  for (const TiXmlElement* link = robot->FirstChildElement("link"); link;
       link = link->NextSiblingElement("link")) {
    const char* name = link->Attribute("name");
    int n = 0;
    for (const TiXmlElement* c = link->FirstChildElement("collision"); c;
         c = c->NextSiblingElement("collision"))
      ++n;
    facts.collisions[name ? name : ""] += n;
    if (name) {
      facts.link_lines.emplace(name, link->Row());
      facts.links.push_back(name);
    }
  }
  for (const TiXmlElement* joint = robot->FirstChildElement("joint"); joint;
       joint = joint->NextSiblingElement("joint"))
    if (const char* name = joint->Attribute("name")) {
      facts.joint_lines.emplace(name, joint->Row());
      facts.joint_edges.push_back({name, linkOf(joint, "parent"), linkOf(joint, "child")});
    }
  return facts;
}

// " (line N)" of a link or joint, or "" when the XML did not name it.
auto lineOf(const std::map<std::string, int>& lines) {
  return [&lines](const std::string& name) {
    const auto it = lines.find(name);
    return it == lines.end() ? std::string() : " (line " + std::to_string(it->second) + ")";
  };
}

class UrdfWorldReader {
 public:
  UrdfWorldReader(const std::string& path, const SceneLoadOptions& options)
      : path_(path),
        options_(options),
        base_dir_(scene_detail::parentDir(path)),
        mesh_budget_(options.limits) {}

  Scene read() {
    const std::string text = scene_detail::readTextFile(path_);
    // tinyxml and urdfdom parse recursively: bound the nesting before either sees the text.
    scene_detail::checkXmlDepth(text, path_, options_.limits);
    const XmlFacts xml = scanXml(text, path_);
    const auto& xml_counts = xml.collisions;
    // The joints must form a tree before urdfdom links them (see urdf_tree_check.h).
    const std::string tree_problem = urdf_tree::treeProblem(
        xml.links, xml.joint_edges, lineOf(xml.link_lines), lineOf(xml.joint_lines));
    if (!tree_problem.empty()) throw SceneError(path_ + ": " + tree_problem);

    CapturingHandler capture;
    urdf::ModelInterfaceSharedPtr model;
    {
      CaptureGuard guard(&capture);
      model = urdf::parseURDF(text);
    }
    if (!model) {
      std::string msg = path_ + ": urdfdom refused the URDF";
      for (const auto& m : capture.messages) msg += "; " + m;
      throw SceneError(msg);
    }
    const std::size_t collision_count = [&] {
      std::size_t n = 0;
      for (const auto& [name, link] : model->links_) n += link->collision_array.size();
      return n;
    }();
    if (collision_count > options_.limits.max_obstacles)
      throw SceneError(
          path_ + ": " +
          scene_detail::overLimit(std::to_string(collision_count) + " <collision> elements",
                                  options_.limits.max_obstacles, "max_obstacles"));
    Scene scene;
    scene.source = path_;
    scene.name = model->getName();
    for (const auto& m : capture.messages) scene.warnings.push_back(path_ + ": urdfdom: " + m);

    // Joint values: given, else 0 (clamped into the limits); mimic joints follow.
    std::set<std::string> unused;
    for (const auto& kv : options_.joint_values) unused.insert(kv.first);
    std::function<double(const urdf::Joint&, int)> value = [&](const urdf::Joint& j,
                                                               int depth) -> double {
      const std::string where = path_ + ": joint '" + j.name + "'";
      if (depth > 64) throw SceneError(where + ": mimic chain too long (a cycle?)");
      if (j.mimic) {
        auto it = model->joints_.find(j.mimic->joint_name);
        if (it == model->joints_.end())
          throw SceneError(where + ": mimics unknown joint '" + j.mimic->joint_name + "'");
        return j.mimic->multiplier * value(*it->second, depth + 1) + j.mimic->offset;
      }
      double v = 0.0;
      auto given = options_.joint_values.find(j.name);
      if (given != options_.joint_values.end()) {
        v = given->second;
        unused.erase(j.name);
        if (!std::isfinite(v)) throw SceneError(where + ": non-finite value");
      }
      if (j.type != urdf::Joint::CONTINUOUS && j.limits && j.limits->lower <= j.limits->upper)
        v = std::min(std::max(v, j.limits->lower), j.limits->upper);
      return v;
    };

    // Link poses from the root, with an explicit stack (a chain of links may be long; the
    // tree check above guarantees that every link is reached once).
    std::map<std::string, Eigen::Isometry3d> X_WL;
    std::vector<std::pair<const urdf::Link*, Eigen::Isometry3d>> stack;
    auto visit = [&](const urdf::Link& link, const Eigen::Isometry3d& X) {
      stack.emplace_back(&link, X);
    };
    const auto root = model->getRoot();
    if (!root) throw SceneError(path_ + ": no root link");
    visit(*root, Eigen::Isometry3d::Identity());
    while (!stack.empty()) {
      const auto [link_ptr, X] = stack.back();
      stack.pop_back();
      const urdf::Link& link = *link_ptr;
      X_WL[link.name] = X;
      for (const auto& j : link.child_joints) {
        const std::string where = path_ + ": joint '" + j->name + "'";
        Eigen::Isometry3d X_PJ = toIsometry(j->parent_to_joint_origin_transform, where);
        Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
        switch (j->type) {
          case urdf::Joint::FIXED:
            break;
          case urdf::Joint::REVOLUTE:
          case urdf::Joint::CONTINUOUS:
          case urdf::Joint::PRISMATIC: {
            if (options_.urdf_require_fixed_joints)
              throw SceneError(where +
                               ": movable joint in a URDF world (only fixed joints "
                               "are accepted with urdf_require_fixed_joints)");
            const double q = value(*j, 0);
            Eigen::Vector3d axis(j->axis.x, j->axis.y, j->axis.z);
            if (!axis.allFinite() || axis.norm() < 1e-12)
              throw SceneError(where + ": zero or non-finite axis");
            axis.normalize();
            if (j->type == urdf::Joint::PRISMATIC)
              motion.translation() = q * axis;
            else
              motion.linear() = Eigen::AngleAxisd(q, axis).toRotationMatrix();
            std::ostringstream s;
            s << where << ": movable joint held at " << q << " in the world";
            scene.warnings.push_back(s.str());
            break;
          }
          default:
            throw SceneError(where +
                             ": floating and planar joints are not supported in a "
                             "URDF world");
        }
        auto child = model->getLink(j->child_link_name);
        if (!child) throw SceneError(where + ": missing child link '" + j->child_link_name + "'");
        visit(*child, X * X_PJ * motion);
      }
    }
    for (const auto& name : unused)
      throw SceneError(path_ + ": joint value given for '" + name + "', which the URDF lacks");

    // Links in file order would be nicer, but urdfdom keeps a map: sort by name for a
    // deterministic order.
    for (const auto& [name, link] : model->links_) {
      const int in_xml = xml_counts.count(name) ? xml_counts.at(name) : 0;
      if (static_cast<int>(link->collision_array.size()) != in_xml)
        throw SceneError(path_ + ": link '" + name + "' has " + std::to_string(in_xml) +
                         " <collision> elements but urdfdom read " +
                         std::to_string(link->collision_array.size()) +
                         " (an unsupported geometry tag?)");
      const auto& cols = link->collision_array;
      std::vector<Obstacle> link_obstacles;
      for (std::size_t k = 0; k < cols.size(); ++k) {
        const std::string where = path_ + ": link '" + name + "' collision " + std::to_string(k);
        const auto& c = cols[k];
        if (!c->geometry) throw SceneError(where + ": no geometry");
        std::vector<AnyShape> shapes = this->shapes(*c->geometry, where, scene.warnings);
        const Eigen::Isometry3d X_WS = X_WL.at(name) * toIsometry(c->origin, where + " origin");
        for (std::size_t h = 0; h < shapes.size(); ++h) {
          Obstacle o;
          o.object_id = name;
          o.name = name;  // numbered below when the link has several
          o.shape = std::move(shapes[h]);
          o.X_FO = X_WS;
          o.X_WO = o.X_FO;
          o.description =
              describeShape(o.shape) + " (" + scene_detail::partName(where, h, shapes.size()) + ")";
          link_obstacles.push_back(std::move(o));
        }
      }
      const std::string room =
          scene_detail::obstacleRoom(path_ + ": link '" + name + "'", link_obstacles.size(),
                                     scene.obstacles.size(), options_.limits);
      if (!room.empty()) throw SceneError(room);
      for (std::size_t k = 0; k < link_obstacles.size(); ++k) {
        if (link_obstacles.size() > 1) link_obstacles[k].name += "/" + std::to_string(k);
        scene.obstacles.push_back(std::move(link_obstacles[k]));
      }
    }
    scene_detail::makeObstacleNamesUnique(scene);
    return scene;
  }

 private:
  // One shape, or the hulls of a mesh's parts.
  std::vector<AnyShape> shapes(const urdf::Geometry& g, const std::string& where,
                               std::vector<std::string>& warnings) {
    switch (g.type) {
      case urdf::Geometry::SPHERE: {
        const auto& s = static_cast<const urdf::Sphere&>(g);
        scene_detail::checkSize(s.radius, "radius", where);
        return {AnyShape(Sphere{s.radius})};
      }
      case urdf::Geometry::BOX: {
        const auto& b = static_cast<const urdf::Box&>(g);
        const Eigen::Vector3d size(b.dim.x, b.dim.y, b.dim.z);
        for (int i = 0; i < 3; ++i) scene_detail::checkSize(size[i], "box size", where);
        return {AnyShape(Box::fromSize(size))};
      }
      case urdf::Geometry::CYLINDER: {
        const auto& c = static_cast<const urdf::Cylinder&>(g);
        scene_detail::checkSize(c.radius, "radius", where);
        scene_detail::checkSize(c.length, "length", where);
        return {AnyShape(Cylinder::fromLength(c.radius, c.length))};
      }
      case urdf::Geometry::MESH: {
        const auto& m = static_cast<const urdf::Mesh&>(g);
        const Eigen::Vector3d scale(m.scale.x, m.scale.y, m.scale.z);
        scene_detail::checkMeshScale(scale, where);
        const std::string file =
            scene_detail::resolveMeshUri(m.filename, base_dir_, options_, where);
        std::vector<AnyShape> out;
        for (auto& h : scene_detail::meshFileHulls(file, scale, where, mesh_budget_,
                                                   options_.max_mesh_parts, warnings))
          out.emplace_back(std::move(h));
        return out;
      }
    }
    throw SceneError(where + ": unsupported geometry");
  }

  std::string path_;
  const SceneLoadOptions& options_;
  std::string base_dir_;
  scene_detail::MeshBudget mesh_budget_;
};

}  // namespace

Scene loadUrdfWorld(const std::string& path, const SceneLoadOptions& options) {
  return UrdfWorldReader(path, options).read();
}

}  // namespace dss
