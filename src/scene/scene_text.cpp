// Reader of MoveIt's `.scene` text format, old and new versions.
#include "dss/scene/scene_text.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

#include "dss/scene/scene_error.h"
#include "scene_util.h"

namespace dss {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return std::string();
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> tokens(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> out;
  std::string t;
  while (in >> t) out.push_back(t);
  return out;
}

class SceneTextReader {
 public:
  SceneTextReader(const std::string& text, std::string source, const SceneInputLimits& limits,
                  std::size_t max_mesh_parts)
      : source_(std::move(source)),
        limits_(limits),
        max_mesh_parts_(max_mesh_parts),
        mesh_budget_(limits) {
    std::istringstream in(text);
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
      ++number;
      line = trim(line);
      if (!line.empty()) lines_.push_back({line, number});
    }
  }

  Scene read() {
    Scene scene;
    scene.source = source_;
    if (lines_.empty()) throw SceneError(source_ + ": empty .scene file");
    scene.name = lines_[0].text;
    // "(name)+" is how some writers mark the name; keep what is between the parentheses.
    if (scene.name.size() > 2 && scene.name.front() == '(') {
      const auto close = scene.name.find(')');
      if (close != std::string::npos) scene.name = scene.name.substr(1, close - 1);
    }
    next_ = 1;
    bool ended = false;
    while (next_ < lines_.size()) {
      const Line& l = lines_[next_++];
      if (l.text == ".") {
        ended = true;
        break;
      }
      if (l.text[0] != '*') fail(l, "expected '* <object id>' or '.', got '" + clip(l.text) + "'");
      readObject(trim(l.text.substr(1)), l, scene);
    }
    if (!ended) scene.warnings.push_back(source_ + ": no final '.' line");
    for (std::size_t i = next_; i < lines_.size(); ++i)
      scene.warnings.push_back(at(lines_[i]) + ": text after the final '.' ignored");
    scene_detail::makeObstacleNamesUnique(scene);
    return scene;
  }

 private:
  struct Line {
    std::string text;
    int number;
  };

  std::string at(const Line& l) const { return source_ + ":" + std::to_string(l.number); }
  [[noreturn]] void fail(const Line& l, const std::string& msg) const {
    throw SceneError(at(l) + ": " + msg);
  }

  const Line& nextLine(const std::string& what) {
    if (next_ >= lines_.size()) {
      const int last = lines_.empty() ? 0 : lines_.back().number;
      throw SceneError(source_ + ":" + std::to_string(last) + ": file ends before " + what);
    }
    return lines_[next_++];
  }

  double parseNumber(const std::string& tok, const Line& l, const std::string& what) const {
    char* end = nullptr;
    const double v = std::strtod(tok.c_str(), &end);
    if (end == tok.c_str() || *end != '\0')
      fail(l, what + ": expected a number, got '" + clip(tok) + "'");
    return v;
  }

  /// Exactly n numbers on the next line; finite unless `allow_nan` (quaternions check later).
  std::vector<double> numbers(std::size_t n, const std::string& what, const Line** where = nullptr,
                              bool allow_nan = false) {
    const Line& l = nextLine(what);
    if (where) *where = &l;
    const auto t = tokens(l.text);
    if (t.size() != n)
      fail(l, what + ": expected " + std::to_string(n) + " numbers, got '" + clip(l.text) + "'");
    std::vector<double> v;
    for (const auto& s : t) {
      v.push_back(parseNumber(s, l, what));
      if (!allow_nan && !std::isfinite(v.back())) fail(l, what + ": non-finite number");
    }
    return v;
  }

  /// A count of decimal digits (no sign), at most `limit` (`field` names the limit).
  std::size_t count(const Line& l, const std::string& what, std::size_t limit,
                    const char* field) const {
    const auto t = tokens(l.text);
    if (t.size() != 1) fail(l, what + ": expected a count, got '" + clip(l.text) + "'");
    return countToken(t[0], l, what, limit, field);
  }

  std::size_t countToken(const std::string& tok, const Line& l, const std::string& what,
                         std::size_t limit, const char* field) const {
    if (tok.empty() || tok.find_first_not_of("0123456789") != std::string::npos)
      fail(l, what + ": expected a count, got '" + clip(tok) + "'");
    // Digit by digit, stopping once over the limit: no overflow, whatever the length.
    std::size_t v = 0;
    for (char c : tok) {
      const std::size_t d = static_cast<std::size_t>(c - '0');
      if (d > limit || v > (limit - d) / 10)
        fail(l, scene_detail::overLimit(what + " " + clip(tok), limit, field));
      v = v * 10 + d;
    }
    return v;
  }

  static std::string clip(const std::string& s) {
    return s.size() <= 64 ? s : s.substr(0, 64) + "...";
  }

  Eigen::Isometry3d pose(const std::string& what) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    const auto p = numbers(3, what + " position");
    const Line* ql = nullptr;
    const auto q = numbers(4, what + " orientation (x y z w)", &ql, true);
    X.linear() = scene_detail::checkedQuaternion(q[0], q[1], q[2], q[3], at(*ql) + ": " + what)
                     .toRotationMatrix();
    X.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
    return X;
  }

  void readObject(const std::string& id, const Line& header, Scene& scene) {
    if (id.empty()) fail(header, "object without an id");
    const std::string elem = "object '" + id + "'";
    // MoveIt adds the shapes of a repeated id to the first object (and moves the whole object
    // to the later pose): a file that repeats an id is ambiguous.
    const auto [first, inserted] = object_lines_.emplace(id, header.number);
    if (!inserted)
      fail(header, elem + " given twice (first at " + source_ + ":" +
                       std::to_string(first->second) + "); object ids must be unique");
    // MoveIt's rule: a line with spaces after "* id" is the object position (new format).
    const Line& probe = nextLine(elem + " shape count");
    Eigen::Isometry3d X_WObj = Eigen::Isometry3d::Identity();
    bool new_format = false;
    std::size_t n_shapes = 0;
    if (probe.text.find_first_of(" \t") != std::string::npos) {
      new_format = true;
      --next_;
      X_WObj = pose(elem + " pose");
      n_shapes = count(nextLine(elem + " shape count"), elem + " shape count",
                       limits_.max_shapes_per_object, "max_shapes_per_object");
    } else {
      n_shapes = count(probe, elem + " shape count", limits_.max_shapes_per_object,
                       "max_shapes_per_object");
    }
    if (n_shapes == 0) fail(probe, elem + ": no shapes (an empty object cannot be checked)");
    if (n_shapes > limits_.max_obstacles - std::min(scene.obstacles.size(), limits_.max_obstacles))
      fail(header,
           scene_detail::overLimit(elem + ": " + std::to_string(n_shapes) + " shapes after " +
                                       std::to_string(scene.obstacles.size()) + " obstacles",
                                   limits_.max_obstacles, "max_obstacles"));

    std::vector<Obstacle> parts;
    for (std::size_t k = 0; k < n_shapes; ++k) {
      const std::string se = elem + " shape " + std::to_string(k);
      const Line& tl = nextLine(se + " type");
      const std::string type = tl.text;
      AnyShape shape;
      std::vector<ConvexHull> mesh_hulls;  // a mesh: the hulls of its parts
      const Line* dl = nullptr;
      if (type == "box") {
        const auto d = numbers(3, se + " box size", &dl);
        for (int i = 0; i < 3; ++i) scene_detail::checkSize(d[i], "box size", at(*dl) + ": " + se);
        shape = Box::fromSize(Eigen::Vector3d(d[0], d[1], d[2]));
      } else if (type == "sphere") {
        const auto d = numbers(1, se + " sphere radius", &dl);
        scene_detail::checkSize(d[0], "radius", at(*dl) + ": " + se);
        shape = Sphere{d[0]};
      } else if (type == "cylinder" || type == "cone") {
        const auto d = numbers(2, se + " " + type + " radius and length", &dl);
        scene_detail::checkSize(d[0], "radius", at(*dl) + ": " + se);
        scene_detail::checkSize(d[1], "length", at(*dl) + ": " + se);
        if (type == "cylinder")
          shape = Cylinder::fromLength(d[0], d[1]);
        else
          shape = Cone::fromLength(d[0], d[1]);
      } else if (type == "mesh") {
        mesh_hulls = readMesh(se, tl, scene.warnings);
      } else if (type == "plane") {
        fail(tl, se + ": planes are unbounded and not supported as obstacles");
      } else {
        fail(tl, se + ": unknown shape type '" + clip(type) + "'");
      }
      const Eigen::Isometry3d X_ObjS = pose(se);
      numbers(4, se + " colour (r g b a)");
      auto add = [&](AnyShape part, const std::string& what) {
        Obstacle o;
        o.object_id = id;
        o.X_FO = X_WObj * X_ObjS;
        o.X_WO = o.X_FO;
        o.description = describeShape(part) + " (" + at(tl) + ", " + what + ")";
        o.shape = std::move(part);
        parts.push_back(std::move(o));
      };
      if (mesh_hulls.empty()) {
        add(std::move(shape), se);
      } else {
        for (std::size_t h = 0; h < mesh_hulls.size(); ++h)
          add(AnyShape(std::move(mesh_hulls[h])), scene_detail::partName(se, h, mesh_hulls.size()));
      }
    }
    const std::string room =
        scene_detail::obstacleRoom(elem, parts.size(), scene.obstacles.size(), limits_);
    if (!room.empty()) fail(header, room);
    if (new_format) {
      // Each subframe is read line by line, so the file's length bounds the work.
      const std::size_t n_sub = count(nextLine(elem + " subframe count"), elem + " subframe count",
                                      std::numeric_limits<std::size_t>::max(), "subframe count");
      for (std::size_t k = 0; k < n_sub; ++k) {
        nextLine(elem + " subframe name");
        pose(elem + " subframe");
      }
    }
    for (std::size_t k = 0; k < parts.size(); ++k) {
      parts[k].name = parts.size() == 1 ? id : id + "/" + std::to_string(k);
      scene.obstacles.push_back(std::move(parts[k]));
    }
  }

  // "v t" then v vertices and t triangles; MoveIt reads them as a token stream, so line
  // breaks inside the block are free. Triangles are checked and link the vertices into parts.
  // Both counts are bounded before any arithmetic on them (3 v + 3 t cannot wrap around).
  std::vector<ConvexHull> readMesh(const std::string& se, const Line& tl,
                                   std::vector<std::string>& warnings) {
    const Line& cl = nextLine(se + " mesh counts");
    const auto c = tokens(cl.text);
    if (c.size() != 2) fail(cl, se + ": expected 'vertex_count triangle_count'");
    const std::size_t nv =
        countToken(c[0], cl, se + " vertex count", limits_.max_mesh_vertices, "max_mesh_vertices");
    const std::size_t nt = countToken(c[1], cl, se + " triangle count", limits_.max_mesh_triangles,
                                      "max_mesh_triangles");
    if (nv == 0) fail(cl, se + ": mesh has no vertices");
    mesh_budget_.take(nv, at(cl) + ": " + se);
    std::vector<double> vals;
    const std::size_t want = 3 * nv + 3 * nt;
    const Line* last = &cl;
    while (vals.size() < want) {
      const Line& l = nextLine(se + " mesh data");
      last = &l;
      for (const auto& t : tokens(l.text)) vals.push_back(parseNumber(t, l, se + " mesh data"));
      if (vals.size() > want) fail(l, se + ": more mesh numbers than the counts announce");
    }
    mesh::TriangleMesh mesh;
    std::vector<Eigen::Vector3d>& pts = mesh.vertices;
    pts.resize(nv);
    for (std::size_t i = 0; i < nv; ++i) {
      pts[i] = Eigen::Vector3d(vals[3 * i], vals[3 * i + 1], vals[3 * i + 2]);
      if (!pts[i].allFinite()) fail(*last, se + ": non-finite mesh vertex " + std::to_string(i));
    }
    for (std::size_t i = 3 * nv; i < want; ++i)
      if (vals[i] < 0 || vals[i] >= double(nv) || vals[i] != std::floor(vals[i]))
        fail(*last, se + ": bad triangle index " + std::to_string(vals[i]));
    mesh.triangles.resize(nt);
    for (std::size_t t = 0; t < nt; ++t)
      for (std::size_t c = 0; c < 3; ++c)
        mesh.triangles[t][c] = static_cast<int>(vals[3 * nv + 3 * t + c]);
    return scene_detail::meshHulls(mesh, max_mesh_parts_, at(tl) + ": " + se, warnings);
  }

  std::string source_;
  const SceneInputLimits& limits_;
  std::size_t max_mesh_parts_;
  scene_detail::MeshBudget mesh_budget_;
  std::vector<Line> lines_;
  std::size_t next_ = 0;
  std::map<std::string, int> object_lines_;  // object id -> line of its "* id"
};

}  // namespace

Scene parseSceneText(const std::string& text, const std::string& source,
                     const SceneLoadOptions& options) {
  return SceneTextReader(text, source, options.limits, options.max_mesh_parts).read();
}

Scene loadSceneText(const std::string& path, const SceneLoadOptions& options) {
  return parseSceneText(scene_detail::readTextFile(path), path, options);
}

}  // namespace dss
