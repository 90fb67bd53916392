// Reader of moveit_msgs/PlanningScene YAML (MotionBenchMaker, robowflex).
#include "dss/scene/planning_scene_yaml.h"

#include <algorithm>
#include <array>
#include <initializer_list>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "attached_objects_yaml.h"
#include "dss/scene/scene_error.h"
#include "scene_util.h"
#include "yaml_util.h"

namespace dss {

namespace {

using scene_detail::YamlReader;

// Fields of the messages read (moveit_msgs as of ROS Noetic and ROS 2; a key outside these is
// what makes a ROS message fail to deserialize).
constexpr std::initializer_list<const char*> kPlanningSceneKeys = {"name",
                                                                   "robot_state",
                                                                   "robot_model_name",
                                                                   "fixed_frame_transforms",
                                                                   "allowed_collision_matrix",
                                                                   "link_padding",
                                                                   "link_scale",
                                                                   "object_colors",
                                                                   "world",
                                                                   "is_diff"};
constexpr std::initializer_list<const char*> kPlanningSceneOrWorldKeys = {
    "name",
    "robot_state",
    "robot_model_name",
    "fixed_frame_transforms",
    "allowed_collision_matrix",
    "link_padding",
    "link_scale",
    "object_colors",
    "world",
    "is_diff",
    "collision_objects",
    "octomap"};
constexpr std::initializer_list<const char*> kRobotStateKeys = {
    "joint_state", "multi_dof_joint_state", "attached_collision_objects", "is_diff"};
constexpr std::initializer_list<const char*> kAttachedObjectKeys = {
    "link_name", "object", "touch_links", "detach_posture", "weight"};
constexpr std::initializer_list<const char*> kJointStateKeys = {"header", "name", "position",
                                                                "velocity", "effort"};
constexpr std::initializer_list<const char*> kCollisionObjectKeys = {
    "header",          "pose",           "id",         "type",   "primitives",
    "primitive_poses", "meshes",         "mesh_poses", "planes", "plane_poses",
    "subframe_names",  "subframe_poses", "operation"};
constexpr std::initializer_list<const char*> kHeaderKeys = {"seq", "stamp", "frame_id"};

// shape_msgs/SolidPrimitive type numbers.
enum PrimitiveType { kBoxType = 1, kSphereType = 2, kCylinderType = 3, kConeType = 4 };

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

class SceneYamlReader {
 public:
  SceneYamlReader(const std::string& source, const SceneLoadOptions& options)
      : y_(source),
        options_(options),
        limits_(options.limits),
        base_dir_(scene_detail::parentDir(source)),
        mesh_budget_(limits_) {}

  // A robot state's attached objects alone (readAttachedObjectsYaml).
  Scene readAttachedOnly(const YAML::Node& list, const std::string& where) {
    Scene scene;
    scene.source = y_.file();
    y_.setUnknownKeyPolicy(options_.unknown_keys_are_warnings, &scene.warnings,
                           "SceneLoadOptions::unknown_keys_are_warnings");
    readAttached(list, where, scene);
    return scene;
  }

  Scene read(const std::string& text) {
    Scene scene;
    scene.source = y_.file();
    y_.setUnknownKeyPolicy(options_.unknown_keys_are_warnings, &scene.warnings,
                           "SceneLoadOptions::unknown_keys_are_warnings");
    const YAML::Node root = y_.load(text);
    if (!root.IsMap()) y_.fail(root, "expected a PlanningScene mapping at the top level");
    const bool has_world = YamlReader::has(root, "world");
    if (has_world)
      y_.checkKeys(root, "planning scene", "moveit_msgs/PlanningScene", kPlanningSceneKeys);
    else  // a PlanningScene without `world`, or a bare PlanningSceneWorld
      y_.checkKeys(root, "planning scene", "moveit_msgs/PlanningScene (or PlanningSceneWorld)",
                   kPlanningSceneOrWorldKeys);

    if (YamlReader::has(root, "name")) scene.name = y_.string(root["name"], "name");
    if (YamlReader::has(root, "robot_model_name"))
      scene.robot_model_name = y_.string(root["robot_model_name"], "robot_model_name");
    if (YamlReader::has(root, "robot_state")) readRobotState(root["robot_state"], scene);
    if (YamlReader::has(root, "fixed_frame_transforms"))
      readFixedFrames(root["fixed_frame_transforms"], scene);
    if (YamlReader::has(root, "allowed_collision_matrix"))
      readAcm(root["allowed_collision_matrix"], scene);
    if (YamlReader::has(root, "link_padding") || YamlReader::has(root, "link_scale"))
      scene.warnings.push_back(y_.file() + ": link_padding/link_scale ignored");

    if (has_world || YamlReader::has(root, "collision_objects")) {
      const YAML::Node world = has_world ? root["world"] : root;  // or a bare World message
      if (!world.IsMap()) y_.fail(world, "world: expected a mapping");
      if (has_world)
        y_.checkKeys(world, "world", "moveit_msgs/PlanningSceneWorld",
                     {"collision_objects", "octomap"});
      if (YamlReader::has(world, "collision_objects")) {
        const YAML::Node objects =
            y_.sequence(world["collision_objects"], "world.collision_objects");
        // Aliases let a short text repeat long lists: count the obstacles (primitives and
        // meshes of all objects) before reading any, and refuse too many at once.
        std::size_t shapes = 0;
        for (std::size_t i = 0; i < objects.size(); ++i)
          for (const char* list : {"primitives", "meshes"}) {
            const YAML::Node l = YamlReader::optional(objects[i], list);
            if (l.IsDefined() && l.IsSequence()) shapes += l.size();
          }
        if (shapes > limits_.max_obstacles)
          y_.fail(objects,
                  scene_detail::overLimit("world.collision_objects: " + std::to_string(shapes) +
                                              " primitives and meshes in " +
                                              std::to_string(objects.size()) + " objects",
                                          limits_.max_obstacles, "max_obstacles"));
        for (std::size_t i = 0; i < objects.size(); ++i) readObject(objects[i], i, scene);
      }
      if (YamlReader::has(world, "octomap")) {
        const YAML::Node om = world["octomap"];
        const bool empty = om.IsMap() && YamlReader::has(om, "octomap") &&
                           YamlReader::has(om["octomap"], "data") &&
                           om["octomap"]["data"].IsSequence() && om["octomap"]["data"].size() == 0;
        if (!empty) scene.warnings.push_back(y_.at(om) + ": octomap not modelled (ignored)");
      }
    }
    // After the world's objects: an attached object's id must differ from theirs.
    if (YamlReader::has(root, "robot_state") &&
        YamlReader::has(root["robot_state"], "attached_collision_objects"))
      readAttached(root["robot_state"]["attached_collision_objects"],
                   "robot_state.attached_collision_objects", scene);

    // The file's own frames (world and fixed frames) are placed now; robot frames later.
    resolveFrames(scene, FrameMap{}, /*require_all=*/false);
    scene_detail::makeObstacleNamesUnique(scene);
    return scene;
  }

 private:
  void readRobotState(const YAML::Node& rs, Scene& scene) {
    if (!rs.IsMap()) y_.fail(rs, "robot_state: expected a mapping");
    y_.checkKeys(rs, "robot_state", "moveit_msgs/RobotState", kRobotStateKeys);
    if (YamlReader::has(rs, "joint_state")) {
      const YAML::Node js = rs["joint_state"];
      y_.checkKeys(js, "robot_state.joint_state", "sensor_msgs/JointState", kJointStateKeys);
      if (YamlReader::has(js, "name") || YamlReader::has(js, "position")) {
        const YAML::Node names =
            y_.sequence(y_.require(js, "name", "robot_state.joint_state"), "joint_state.name");
        const YAML::Node pos = y_.sequence(y_.require(js, "position", "robot_state.joint_state"),
                                           "joint_state.position");
        if (names.size() != pos.size())
          y_.fail(js, "robot_state.joint_state: " + std::to_string(names.size()) + " names but " +
                          std::to_string(pos.size()) + " positions");
        for (std::size_t i = 0; i < names.size(); ++i) {
          const std::string n = y_.string(names[i], "joint_state.name");
          scene.robot_state[n] = y_.number(pos[i], "joint_state.position of '" + n + "'");
        }
      }
    }
    if (YamlReader::has(rs, "multi_dof_joint_state"))
      scene.robot_multi_dof = y_.multiDofJointState(
          rs["multi_dof_joint_state"], "robot_state.multi_dof_joint_state",
          std::numeric_limits<std::size_t>::max(), [](std::size_t) { return std::string(); });
  }

  void readAttached(const YAML::Node& list, const std::string& where, Scene& scene) {
    const YAML::Node att = y_.sequence(list, where);
    // Their shapes count against the obstacles' budget and their touch links against the
    // collision matrix's names, all before any is read (aliases repeat lists cheaply).
    std::size_t shapes = 0, touch = 0;
    for (std::size_t i = 0; i < att.size(); ++i) {
      if (!att[i].IsMap()) continue;
      const YAML::Node t = YamlReader::optional(att[i], "touch_links");
      if (t.IsDefined() && t.IsSequence()) touch += t.size();
      const YAML::Node obj = YamlReader::optional(att[i], "object");
      if (!obj.IsDefined() || !obj.IsMap()) continue;
      for (const char* l : {"primitives", "meshes"}) {
        const YAML::Node n = YamlReader::optional(obj, l);
        if (n.IsDefined() && n.IsSequence()) shapes += n.size();
      }
    }
    if (shapes > limits_.max_obstacles - std::min(scene.obstacles.size(), limits_.max_obstacles))
      y_.fail(att, scene_detail::overLimit(
                       where + ": " + std::to_string(shapes) + " primitives and meshes after " +
                           std::to_string(scene.obstacles.size()) + " obstacles",
                       limits_.max_obstacles, "max_obstacles"));
    if (touch > limits_.max_acm_entries)
      y_.fail(att, scene_detail::overLimit(where + ": " + std::to_string(touch) + " touch links",
                                           limits_.max_acm_entries, "max_acm_entries"));
    for (std::size_t i = 0; i < att.size(); ++i) {
      const YAML::Node a = att[i];
      const std::string elem = "attached collision object #" + std::to_string(i);
      if (!a.IsMap()) y_.fail(a, elem + ": expected a mapping");
      y_.checkKeys(a, elem, "moveit_msgs/AttachedCollisionObject", kAttachedObjectKeys);
      AttachedObject ao;
      ao.at = y_.at(a);
      ao.link = y_.string(y_.require(a, "link_name", elem), elem + " link_name");
      if (ao.link.empty()) y_.fail(a, elem + ": empty link_name");
      Scene parts;  // the object's shapes, read as a world object's
      readObject(y_.require(a, "object", elem), i, parts);
      ao.id = parts.obstacles.front().object_id;
      ao.parts = std::move(parts.obstacles);
      for (auto& w : parts.warnings) scene.warnings.push_back(std::move(w));
      if (YamlReader::has(a, "touch_links")) {
        const YAML::Node links = y_.sequence(a["touch_links"], elem + " touch_links");
        for (std::size_t k = 0; k < links.size(); ++k) {
          ao.touch_links.push_back(y_.string(links[k], elem + " touch_links"));
          if (ao.touch_links.back().empty()) y_.fail(links[k], elem + ": empty touch link");
        }
      }
      scene.attached.push_back(std::move(ao));
    }
  }

  void readFixedFrames(const YAML::Node& list, Scene& scene) {
    y_.sequence(list, "fixed_frame_transforms");
    for (const auto& t : list) {
      y_.checkKeys(t, "fixed_frame_transforms entry", "geometry_msgs/TransformStamped",
                   {"header", "child_frame_id", "transform"});
      const std::string child =
          y_.string(y_.require(t, "child_frame_id", "fixed_frame_transforms"), "child_frame_id");
      const Eigen::Isometry3d X = y_.transform(
          y_.require(t, "transform", "fixed frame '" + child + "'"), "fixed frame '" + child + "'");
      std::string key = (!child.empty() && child[0] == '/') ? child.substr(1) : child;
      scene.fixed_frames[key] = X;
    }
  }

  void readAcm(const YAML::Node& acm, Scene& scene) {
    if (!acm.IsMap()) y_.fail(acm, "allowed_collision_matrix: expected a mapping");
    y_.checkKeys(acm, "allowed_collision_matrix", "moveit_msgs/AllowedCollisionMatrix",
                 {"entry_names", "entry_values", "default_entry_names", "default_entry_values"});
    if (YamlReader::has(acm, "entry_names") || YamlReader::has(acm, "entry_values")) {
      const YAML::Node names =
          y_.sequence(y_.require(acm, "entry_names", "allowed_collision_matrix"), "entry_names");
      // The matrix has names.size() squared values, however short the text (aliases).
      if (names.size() > limits_.max_acm_entries)
        y_.fail(names, scene_detail::overLimit("allowed_collision_matrix: " +
                                                   std::to_string(names.size()) + " entry_names",
                                               limits_.max_acm_entries, "max_acm_entries"));
      const YAML::Node values =
          y_.sequence(y_.require(acm, "entry_values", "allowed_collision_matrix"), "entry_values");
      const std::size_t n = names.size();
      if (values.size() != n)
        y_.fail(values, "allowed_collision_matrix: " + std::to_string(n) + " entry_names but " +
                            std::to_string(values.size()) + " rows of entry_values");
      std::vector<std::string> name(n);
      for (std::size_t i = 0; i < n; ++i) name[i] = y_.string(names[i], "entry_names");
      for (std::size_t i = 0; i < n; ++i) {
        // Rows are either plain lists of booleans or {enabled: [...]} (moveit_msgs).
        // (yaml-cpp's Node::operator= writes through to the tree, so no reassignment here.)
        y_.checkKeys(values[i], "allowed_collision_matrix row '" + name[i] + "'",
                     "moveit_msgs/AllowedCollisionEntry", {"enabled"});
        const YAML::Node row =
            values[i].IsMap() ? y_.require(values[i], "enabled", "allowed_collision_matrix row")
                              : YAML::Node(values[i]);
        y_.sequence(row, "allowed_collision_matrix row '" + name[i] + "'");
        if (row.size() != n)
          y_.fail(row, "allowed_collision_matrix row '" + name[i] +
                           "': " + std::to_string(row.size()) + " values for " + std::to_string(n) +
                           " names");
        for (std::size_t j = 0; j < n; ++j)
          if (boolean(row[j], "allowed_collision_matrix row '" + name[i] + "'") && i != j)
            scene.allowed_collisions.allow(name[i], name[j]);
      }
    }
    if (YamlReader::has(acm, "default_entry_names")) {
      const YAML::Node names = y_.sequence(acm["default_entry_names"], "default_entry_names");
      if (names.size() > limits_.max_acm_entries)
        y_.fail(names, scene_detail::overLimit(
                           "allowed_collision_matrix: " + std::to_string(names.size()) +
                               " default_entry_names",
                           limits_.max_acm_entries, "max_acm_entries"));
      const YAML::Node values =
          y_.sequence(y_.require(acm, "default_entry_values", "allowed_collision_matrix"),
                      "default_entry_values");
      if (values.size() != names.size())
        y_.fail(values,
                "allowed_collision_matrix: default_entry_names and default_entry_values "
                "differ in length");
      for (std::size_t i = 0; i < names.size(); ++i)
        if (boolean(values[i], "default_entry_values"))
          scene.allowed_collisions.allowAlways(y_.string(names[i], "default_entry_names"));
    }
  }

  bool boolean(const YAML::Node& n, const std::string& element) const {
    if (!n.IsScalar()) y_.fail(n, element + ": expected a boolean");
    try {
      return n.as<bool>();
    } catch (const YAML::Exception&) {
      y_.fail(n, element + ": expected a boolean, got '" + n.Scalar() + "'");
    }
  }

  void readObject(const YAML::Node& obj, std::size_t index, Scene& scene) {
    const std::string fallback = "collision object #" + std::to_string(index);
    if (!obj.IsMap()) y_.fail(obj, fallback + ": expected a mapping");
    const std::string id = y_.string(y_.require(obj, "id", fallback), fallback + " id");
    const std::string elem = "object '" + id + "'";
    if (id.empty()) y_.fail(obj, fallback + ": empty id");
    // MoveIt's ADD replaces an object of the same id, so a repeated id would silently drop the
    // first object there: the file is ambiguous.
    const auto [first, inserted] = object_at_.emplace(id, y_.at(obj));
    if (!inserted)
      y_.fail(obj, elem + " given twice (first at " + first->second +
                       "); collision object ids must be unique");
    y_.checkKeys(obj, elem, "moveit_msgs/CollisionObject", kCollisionObjectKeys);

    if (YamlReader::has(obj, "operation")) {
      const YAML::Node op = obj["operation"];
      const std::string s = lower(y_.string(op, elem + " operation"));
      if (!(s == "0" || s == "add"))
        y_.fail(op, elem + ": operation '" + op.Scalar() +
                        "' not supported (only ADD; a scene file lists whole objects)");
    }
    std::string frame;
    if (YamlReader::has(obj, "header"))
      y_.checkKeys(obj["header"], elem + " header", "std_msgs/Header", kHeaderKeys);
    if (YamlReader::has(obj, "header") && YamlReader::has(obj["header"], "frame_id"))
      frame = y_.string(obj["header"]["frame_id"], elem + " header.frame_id");
    if (!frame.empty() && frame[0] == '/') frame = frame.substr(1);

    Eigen::Isometry3d X_FObj = Eigen::Isometry3d::Identity();
    if (YamlReader::has(obj, "pose")) X_FObj = y_.pose(obj["pose"], elem + " pose");

    struct Part {
      AnyShape shape;
      Eigen::Isometry3d X_ObjS;
      std::string description;
    };
    std::vector<Part> parts;

    // Shapes of this object (aliases can repeat a long list): bounded before any is read.
    std::size_t shapes = 0;
    for (const char* list : {"primitives", "meshes"})
      if (YamlReader::has(obj, list) && obj[list].IsSequence()) shapes += obj[list].size();
    if (shapes > limits_.max_shapes_per_object)
      y_.fail(obj, scene_detail::overLimit(
                       elem + ": " + std::to_string(shapes) + " primitives and meshes",
                       limits_.max_shapes_per_object, "max_shapes_per_object"));
    if (shapes > limits_.max_obstacles - std::min(scene.obstacles.size(), limits_.max_obstacles))
      y_.fail(obj,
              scene_detail::overLimit(elem + ": " + std::to_string(shapes) + " shapes after " +
                                          std::to_string(scene.obstacles.size()) + " obstacles",
                                      limits_.max_obstacles, "max_obstacles"));

    if (YamlReader::has(obj, "primitives")) {
      const YAML::Node prims = y_.sequence(obj["primitives"], elem + " primitives");
      const YAML::Node poses = YamlReader::optional(obj, "primitive_poses");
      if (prims.size() > 0 && (!poses.IsDefined() || poses.IsNull()))
        y_.fail(obj, elem + ": missing field 'primitive_poses'");
      if (prims.size() > 0) {
        y_.sequence(poses, elem + " primitive_poses");
        if (poses.size() != prims.size())
          y_.fail(poses, elem + ": " + std::to_string(prims.size()) + " primitives but " +
                             std::to_string(poses.size()) + " primitive_poses");
      }
      for (std::size_t k = 0; k < prims.size(); ++k) {
        const std::string pe = elem + " primitive " + std::to_string(k);
        AnyShape s = primitive(prims[k], pe);
        parts.push_back({std::move(s), y_.pose(poses[k], pe + " pose"), pe});
      }
    }
    if (YamlReader::has(obj, "meshes")) {
      const YAML::Node meshes = y_.sequence(obj["meshes"], elem + " meshes");
      const YAML::Node poses = YamlReader::optional(obj, "mesh_poses");
      if (meshes.size() > 0) {
        if (!poses.IsDefined() || poses.IsNull())
          y_.fail(obj, elem + ": missing field 'mesh_poses'");
        y_.sequence(poses, elem + " mesh_poses");
        if (poses.size() != meshes.size())
          y_.fail(poses, elem + ": " + std::to_string(meshes.size()) + " meshes but " +
                             std::to_string(poses.size()) + " mesh_poses");
      }
      for (std::size_t k = 0; k < meshes.size(); ++k) {
        const std::string me = elem + " mesh " + std::to_string(k);
        std::vector<ConvexHull> hulls = meshHulls(meshes[k], me, scene.warnings);
        const Eigen::Isometry3d X_ObjS = y_.pose(poses[k], me + " pose");
        for (std::size_t h = 0; h < hulls.size(); ++h)
          parts.push_back(
              {AnyShape(std::move(hulls[h])), X_ObjS, scene_detail::partName(me, h, hulls.size())});
      }
    }
    if (YamlReader::has(obj, "planes")) {
      const YAML::Node planes = obj["planes"];
      if (planes.IsSequence() && planes.size() > 0)
        y_.fail(planes, elem + ": planes are unbounded and not supported as obstacles");
    }
    if (parts.empty())
      y_.fail(obj, elem + ": no primitives or meshes (an empty object cannot be checked)");
    const std::string room =
        scene_detail::obstacleRoom(elem, parts.size(), scene.obstacles.size(), limits_);
    if (!room.empty()) y_.fail(obj, room);

    for (std::size_t k = 0; k < parts.size(); ++k) {
      Obstacle o;
      o.object_id = id;
      o.name = parts.size() == 1 ? id : id + "/" + std::to_string(k);
      o.frame_id = frame;
      o.X_FO = X_FObj * parts[k].X_ObjS;
      o.X_WO = o.X_FO;
      o.frame_resolved = false;
      o.description =
          describeShape(parts[k].shape) + " (" + y_.file() + ", " + parts[k].description + ")";
      o.shape = std::move(parts[k].shape);
      scene.obstacles.push_back(std::move(o));
    }
  }

  AnyShape primitive(const YAML::Node& p, const std::string& pe) const {
    if (!p.IsMap()) y_.fail(p, pe + ": expected a mapping {type, dimensions}");
    y_.checkKeys(p, pe, "shape_msgs/SolidPrimitive", {"type", "dimensions", "polygon"});
    const YAML::Node t = y_.require(p, "type", pe);
    const std::string ts = lower(y_.string(t, pe + " type"));
    int type = 0;
    if (ts == "box" || ts == "1")
      type = kBoxType;
    else if (ts == "sphere" || ts == "2")
      type = kSphereType;
    else if (ts == "cylinder" || ts == "3")
      type = kCylinderType;
    else if (ts == "cone" || ts == "4")
      type = kConeType;
    else
      y_.fail(t, pe + ": unknown primitive type '" + t.Scalar() + "'");
    const YAML::Node dims = y_.sequence(y_.require(p, "dimensions", pe), pe + " dimensions");
    const std::size_t want = type == kBoxType ? 3 : type == kSphereType ? 1 : 2;
    if (dims.size() != want)
      y_.fail(dims, pe + ": " + t.Scalar() + " needs " + std::to_string(want) +
                        " dimensions, got " + std::to_string(dims.size()));
    double d[3] = {0, 0, 0};
    for (std::size_t i = 0; i < want; ++i) {
      d[i] = y_.number(dims[i], pe + " dimensions");
      scene_detail::checkSize(d[i], "dimension " + std::to_string(i), y_.at(dims) + ": " + pe);
    }
    switch (type) {
      case kBoxType:
        return Box::fromSize(Eigen::Vector3d(d[0], d[1], d[2]));
      case kSphereType:
        return Sphere{d[0]};
      case kCylinderType:
        return Cylinder::fromLength(d[1], d[0]);  // [height, radius]
      default:
        return Cone::fromLength(d[1], d[0]);  // [height, radius]
    }
  }

  // The hulls of a mesh's connected parts (one hull for vertices without triangles).
  std::vector<ConvexHull> meshHulls(const YAML::Node& m, const std::string& me,
                                    std::vector<std::string>& warnings) {
    if (!m.IsMap()) y_.fail(m, me + ": expected a mapping");
    y_.checkKeys(m, me, "shape_msgs/Mesh (with our resource, dimensions and scale)",
                 {"vertices", "triangles", "resource", "dimensions", "scale"});
    if (YamlReader::has(m, "resource")) {
      const std::string uri = y_.string(m["resource"], me + " resource");
      Eigen::Vector3d scale = Eigen::Vector3d::Ones();
      const char* skey = YamlReader::has(m, "dimensions") ? "dimensions"
                         : YamlReader::has(m, "scale")    ? "scale"
                                                          : nullptr;
      if (skey) {
        scale = y_.vector3(m[skey], me + " " + skey);
        for (int i = 0; i < 3; ++i)
          if (!(scale[i] > 0)) y_.fail(m[skey], me + ": mesh scale must be positive");
      }
      const std::string where = y_.at(m) + ": " + me;
      const std::string file = scene_detail::resolveMeshUri(uri, base_dir_, options_, where);
      return scene_detail::meshFileHulls(file, scale, where, mesh_budget_, options_.max_mesh_parts,
                                         warnings);
    }
    const YAML::Node verts = y_.sequence(y_.require(m, "vertices", me), me + " vertices");
    mesh_budget_.take(verts.size(), y_.at(verts) + ": " + me);
    mesh::TriangleMesh mesh;
    std::vector<Eigen::Vector3d>& pts = mesh.vertices;
    pts.reserve(verts.size());
    for (const auto& v : verts) pts.push_back(y_.vector3(v, me + " vertex"));
    if (pts.empty()) y_.fail(verts, me + ": mesh has no vertices");
    if (YamlReader::has(m, "triangles")) {
      const YAML::Node tris = y_.sequence(m["triangles"], me + " triangles");
      if (tris.size() > limits_.max_mesh_triangles)
        y_.fail(tris,
                scene_detail::overLimit(me + ": " + std::to_string(tris.size()) + " triangles",
                                        limits_.max_mesh_triangles, "max_mesh_triangles"));
      for (const auto& t : tris) {
        y_.checkKeys(t, me + " triangle", "shape_msgs/MeshTriangle", {"vertex_indices"});
        const YAML::Node idx =
            t.IsMap() ? y_.require(t, "vertex_indices", me + " triangle") : YAML::Node(t);
        y_.sequence(idx, me + " triangle");
        if (idx.size() != 3) y_.fail(idx, me + ": a triangle needs 3 vertex indices");
        std::array<int, 3> tri{};
        for (std::size_t c = 0; c < 3; ++c) {
          const YAML::Node i = idx[c];
          const int k = y_.integer(i, me + " triangle index");
          if (k < 0 || static_cast<std::size_t>(k) >= pts.size())
            y_.fail(i, me + ": triangle index " + std::to_string(k) + " out of range (" +
                           std::to_string(pts.size()) + " vertices)");
          tri[c] = k;
        }
        mesh.triangles.push_back(tri);
      }
    }
    return scene_detail::meshHulls(mesh, options_.max_mesh_parts, y_.at(m) + ": " + me, warnings);
  }

  YamlReader y_;
  const SceneLoadOptions& options_;
  const SceneInputLimits& limits_;
  std::string base_dir_;
  scene_detail::MeshBudget mesh_budget_;
  std::map<std::string, std::string> object_at_;  // collision object id -> "file:line"
};

}  // namespace

std::vector<AttachedObject> scene_detail::readAttachedObjectsYaml(
    const YAML::Node& list, const std::string& source, const std::string& where,
    const SceneLoadOptions& options, std::vector<std::string>& warnings) {
  Scene s = SceneYamlReader(source, options).readAttachedOnly(list, where);
  warnings.insert(warnings.end(), s.warnings.begin(), s.warnings.end());
  return std::move(s.attached);
}

Scene parsePlanningSceneYaml(const std::string& text, const std::string& source,
                             const SceneLoadOptions& options) {
  return SceneYamlReader(source, options).read(text);
}

Scene loadPlanningSceneYaml(const std::string& path, const SceneLoadOptions& options) {
  return parsePlanningSceneYaml(scene_detail::readTextFile(path), path, options);
}

}  // namespace dss
