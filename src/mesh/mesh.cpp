// Mesh files through assimp, convex hulls through qhull (reentrant API), tessellation of
// primitives. See dss/mesh/mesh.h for the contracts.
#include "dss/mesh/mesh.h"

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>

#include "mesh_file_check.h"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace dss::mesh {
namespace {

// Appends the vertices and triangles of every node's meshes, walking the node tree with an
// explicit stack (a file may nest nodes deeply). A node that instances a mesh again adds its
// vertices again, so the budget is checked before each mesh is copied. A scale with an odd
// number of negative components mirrors the mesh; the triangles are then flipped so that they
// stay outward.
void appendNodes(const aiScene* scene, const Eigen::Vector3d& scale, std::size_t max_vertices,
                 const std::string& path, TriangleMesh& out) {
  const bool mirrored = scale.x() * scale.y() * scale.z() < 0;
  std::vector<std::pair<const aiNode*, aiMatrix4x4>> stack{{scene->mRootNode, aiMatrix4x4()}};
  while (!stack.empty()) {
    const auto [node, X_parent] = stack.back();
    stack.pop_back();
    const aiMatrix4x4 X = X_parent * node->mTransformation;
    for (unsigned m = 0; m < node->mNumMeshes; ++m) {
      const aiMesh* mesh = scene->mMeshes[node->mMeshes[m]];
      if (mesh->mNumVertices > max_vertices - out.vertices.size())
        throw std::length_error("mesh " + path + " has more than " + std::to_string(max_vertices) +
                                " vertices");
      const int base = static_cast<int>(out.vertices.size());
      for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
        const aiVector3D p = X * mesh->mVertices[v];
        out.vertices.emplace_back(p.x * scale.x(), p.y * scale.y(), p.z * scale.z());
      }
      for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
        const aiFace& face = mesh->mFaces[f];
        if (face.mNumIndices != 3) continue;  // points and lines add vertices only
        const int a = base + int(face.mIndices[0]), b = base + int(face.mIndices[1]),
                  c = base + int(face.mIndices[2]);
        out.triangles.push_back(mirrored ? std::array<int, 3>{a, c, b}
                                         : std::array<int, 3>{a, b, c});
      }
    }
    // Children pushed in reverse so that they are visited in file order.
    for (unsigned c = node->mNumChildren; c-- > 0;) stack.push_back({node->mChildren[c], X});
  }
}

std::vector<Eigen::Vector3d> distinctPoints(std::vector<Eigen::Vector3d> pts) {
  auto less = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::sort(pts.begin(), pts.end(), less);
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  return pts;
}

// The result of one qhull run: hull vertices (input points, bit for bit), their adjacency
// and outward triangles. ok == false when qhull finds no 3-D hull (flat, collinear, ...).
struct QhullResult {
  bool ok = false;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::vector<int>> neighbours;
  std::vector<std::array<int, 3>> triangles;
};

QhullResult runQhull(const std::vector<Eigen::Vector3d>& pts) {
  QhullResult res;
  if (pts.size() < 4) return res;
  // qhull computes with the coordinates as given: near 2^+-1000 its determinants overflow or
  // underflow (a zero-length facet normal crashes it). It sees the points scaled by a power of
  // two that brings the largest coordinate near 1, an exact change of every coordinate but the
  // subnormal ones; its answer names input points, which are kept bit for bit.
  double largest = 0.0;
  for (const auto& p : pts) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  if (!(largest > 0.0)) return res;  // every point at the origin
  int exponent = 0;
  std::frexp(largest, &exponent);
  std::vector<coordT> coords(pts.size() * 3);
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (int k = 0; k < 3; ++k) coords[3 * i + k] = std::ldexp(pts[i][k], -exponent);
  // qhull reports a degenerate input on errfile; it is an expected outcome here (flat meshes),
  // handled by the caller, so the text goes to /dev/null.
  FILE* devnull = std::fopen("/dev/null", "w");
  qhT qh_qh;
  qhT* qh = &qh_qh;
  qh_zero(qh, devnull);
  char flags[] = "qhull Qt";
  const int exitcode = qh_new_qhull(qh, 3, static_cast<int>(pts.size()), coords.data(), False,
                                    flags, nullptr, devnull);
  if (exitcode == 0) {
    std::vector<int> index(pts.size(), -1);  // input point id -> hull vertex index
    vertexT* vertex;
    FORALLvertices {
      const int id = qh_pointid(qh, vertex->point);
      index[id] = static_cast<int>(res.vertices.size());
      res.vertices.push_back(pts[id]);
    }
    std::vector<std::vector<int>> nb(res.vertices.size());
    facetT* facet;
    FORALLfacets {
      int tri[3];
      int n = 0;
      vertexT** vertexp;
      FOREACHvertex_(facet->vertices) {
        if (n < 3) tri[n] = index[qh_pointid(qh, vertex->point)];
        ++n;
      }
      if (n != 3) continue;  // with Qt every facet is a triangle
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          if (a != b) nb[tri[a]].push_back(tri[b]);
      const Eigen::Vector3d& p0 = res.vertices[tri[0]];
      const Eigen::Vector3d normal(facet->normal[0], facet->normal[1], facet->normal[2]);
      const Eigen::Vector3d c = (res.vertices[tri[1]] - p0).cross(res.vertices[tri[2]] - p0);
      if (c.dot(normal) < 0) std::swap(tri[1], tri[2]);
      res.triangles.push_back({tri[0], tri[1], tri[2]});
    }
    for (auto& list : nb) {
      std::sort(list.begin(), list.end());
      list.erase(std::unique(list.begin(), list.end()), list.end());
    }
    res.neighbours = std::move(nb);
    res.ok = res.vertices.size() >= 4;
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  if (devnull) std::fclose(devnull);
  return res;
}

void checkPoints(const std::vector<Eigen::Vector3d>& points, const std::string& what) {
  if (points.empty()) throw std::runtime_error("convex hull of " + what + ": no points");
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite())
      throw std::runtime_error("convex hull of " + what + ": point " + std::to_string(i) +
                               " is not finite");
}

}  // namespace

TriangleMesh loadMesh(const std::string& path, const Eigen::Vector3d& scale,
                      std::size_t max_vertices) {
  if (!scale.allFinite()) throw std::runtime_error("mesh " + path + ": non-finite scale");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw std::runtime_error("mesh file not found: " + path);
  checkMeshFile(path);  // mesh_file_check.h: format, counts and lists before assimp
  Assimp::Importer importer;
  // RViz and MoveIt ignore the Collada up-axis (a Z-up DAE is used as written); the <unit>
  // scale stays in the root transform and is applied below.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate);
  if (!scene || !scene->mRootNode)
    throw std::runtime_error("cannot read mesh " + path + ": " + importer.GetErrorString());
  TriangleMesh out;
  appendNodes(scene, scale, max_vertices, path, out);
  if (out.vertices.empty()) throw std::runtime_error("mesh " + path + " has no vertices");
  for (const auto& v : out.vertices)
    if (!v.allFinite()) throw std::runtime_error("mesh " + path + " has a non-finite vertex");
  return out;
}

dss::ConvexHull convexHull(const std::vector<Eigen::Vector3d>& points, const std::string& what,
                           HullInfo* info) {
  checkPoints(points, what);
  std::vector<Eigen::Vector3d> pts = distinctPoints(points);
  QhullResult q = runQhull(pts);
  if (info) {
    info->input_points = points.size();
    info->full_dimensional = q.ok;
    info->hull_vertices = q.ok ? q.vertices.size() : pts.size();
  }
  if (!q.ok) return dss::ConvexHull(std::move(pts));
  return dss::ConvexHull(std::move(q.vertices), q.neighbours);
}

dss::ConvexHull convexHull(const std::vector<Eigen::Vector3d>& points, const std::string& what) {
  return convexHull(points, what, nullptr);
}

namespace {

// A ring of n points at height z, radius r, starting at angle 0.
void addRing(TriangleMesh& m, int n, double r, double z) {
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    m.vertices.emplace_back(r * std::cos(a), r * std::sin(a), z);
  }
}

// Quads between ring a and ring b (each n points), outward for a below b.
void stitch(TriangleMesh& m, int a, int b, int n) {
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.push_back({a + i, a + j, b + j});
    m.triangles.push_back({a + i, b + j, b + i});
  }
}

// Fan from a pole vertex to a ring; `up` selects outward orientation for a top cap.
void fan(TriangleMesh& m, int pole, int ring, int n, bool up) {
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    if (up)
      m.triangles.push_back({pole, ring + i, ring + j});
    else
      m.triangles.push_back({pole, ring + j, ring + i});
  }
}

// Sphere-like surface: two hemispheres of radius r centred at z = +-h (h = 0: a sphere).
TriangleMesh roundSurface(double r, double h, int n) {
  TriangleMesh m;
  // An even band count puts a ring on the equator, where a capsule's two caps meet its side.
  int bands = std::max(2, n / 2);
  if (bands % 2) ++bands;
  m.vertices.emplace_back(0, 0, -r - h);  // south pole
  std::vector<int> rings;
  for (int k = 1; k < bands; ++k) {
    const double lat = -M_PI / 2 + M_PI * k / bands;
    const double z = r * std::sin(lat);
    const double rr = r * std::cos(lat);
    if (2 * k == bands) {
      rings.push_back(static_cast<int>(m.vertices.size()));
      addRing(m, n, rr, -h);
      if (h > 0) {
        rings.push_back(static_cast<int>(m.vertices.size()));
        addRing(m, n, rr, h);
      }
      continue;
    }
    rings.push_back(static_cast<int>(m.vertices.size()));
    addRing(m, n, rr, z + (lat < 0 ? -h : h));
  }
  m.vertices.emplace_back(0, 0, r + h);  // north pole
  const int north = static_cast<int>(m.vertices.size()) - 1;
  fan(m, 0, rings.front(), n, false);
  for (std::size_t i = 0; i + 1 < rings.size(); ++i) stitch(m, rings[i], rings[i + 1], n);
  fan(m, north, rings.back(), n, true);
  return m;
}

TriangleMesh prism(double r_bottom, double r_top, double h, int n) {
  TriangleMesh m;
  m.vertices.emplace_back(0, 0, -h);
  const int bottom = 1;
  addRing(m, n, r_bottom, -h);
  int top = -1;
  if (r_top > 0) {
    top = static_cast<int>(m.vertices.size());
    addRing(m, n, r_top, h);
    m.vertices.emplace_back(0, 0, h);
    fan(m, 0, bottom, n, false);
    stitch(m, bottom, top, n);
    fan(m, static_cast<int>(m.vertices.size()) - 1, top, n, true);
  } else {  // cone: apex
    m.vertices.emplace_back(0, 0, h);
    fan(m, 0, bottom, n, false);
    fan(m, static_cast<int>(m.vertices.size()) - 1, bottom, n, true);
  }
  return m;
}

}  // namespace

TriangleMesh tessellate(const dss::AnyShape& shape, int resolution) {
  if (resolution < 3) throw std::invalid_argument("tessellate: resolution must be >= 3");
  const int n = resolution;
  if (const auto* s = std::get_if<dss::Sphere>(&shape)) return roundSurface(s->radius, 0, n);
  if (const auto* e = std::get_if<dss::Ellipsoid>(&shape)) {
    TriangleMesh m = roundSurface(1.0, 0, n);
    for (auto& v : m.vertices) v = v.cwiseProduct(e->radii);
    return m;
  }
  if (const auto* c = std::get_if<dss::Capsule>(&shape))
    return roundSurface(c->radius, c->half_length, n);
  if (const auto* c = std::get_if<dss::Cylinder>(&shape))
    return prism(c->radius, c->radius, c->half_length, n);
  if (const auto* c = std::get_if<dss::Cone>(&shape)) return prism(c->radius, 0, c->half_length, n);
  if (const auto* b = std::get_if<dss::Box>(&shape)) {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i)
      m.vertices.emplace_back((i & 1) ? b->half.x() : -b->half.x(),
                              (i & 2) ? b->half.y() : -b->half.y(),
                              (i & 4) ? b->half.z() : -b->half.z());
    // faces as quads (outward), two triangles each
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
      m.triangles.push_back({q[0], q[1], q[2]});
      m.triangles.push_back({q[0], q[2], q[3]});
    }
    return m;
  }
  const auto& hull = std::get<dss::ConvexHull>(shape);
  QhullResult q = runQhull(distinctPoints(hull.points()));
  TriangleMesh m;
  if (!q.ok) {
    m.vertices = hull.points();
    return m;
  }
  m.vertices = std::move(q.vertices);
  m.triangles = std::move(q.triangles);
  return m;
}

}  // namespace dss::mesh
