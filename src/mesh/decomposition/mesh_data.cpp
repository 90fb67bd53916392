// The decomposition's mesh (see mesh_data.h).
#include "mesh_data.h"

#include <map>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "../welded_ids.h"

namespace dss::mesh::decomposition {

double MeshData::winding(const Vec3& p) const {
  double sum = 0.0;
  for (const auto& t : elements) {
    if (t[0] == t[1] && t[1] == t[2]) continue;
    sum += solidAngle(v[t[0]] - p, v[t[1]] - p, v[t[2]] - p);
  }
  return sum / (4.0 * kPi);
}

// The winding number of a closed mesh as the signed count of surface crossings along a ray.
// A hit near a triangle's edge, a ray running in a triangle's plane or an origin on the
// surface spoils a direction; the next one is tried, and the solid-angle sum settles the
// rare point that spoils them all.
double MeshData::crossings(const Vec3& p) const {
  // Unit directions far from the axes and from each other: meshes are full of faces and
  // edges aligned with the axes.
  constexpr double kDirections[4][3] = {
      {0.52554001318407206, 0.32180203584544953, 0.7875602480243713},
      {-0.6812727939142017, 0.52967884769756723, 0.50527982205320132},
      {0.21929088426740753, -0.88116337079999785, 0.4188825874127543},
      {-0.33308966438806864, -0.28569113514161276, -0.89857211773977319}};
  constexpr double kBary = 1e-9;
  for (const auto& dir : kDirections) {
    const Vec3 d(dir[0], dir[1], dir[2]);
    int sum = 0;
    const bool clear = tree.visitRay(p, d, near_eps, [&](int e) {
      if (normal[e].isZero()) return true;  // no interior to cross
      const auto& t = elements[e];
      const Vec3& a = v[t[0]];
      const Vec3 e1 = v[t[1]] - a, e2 = v[t[2]] - a, tv = p - a;
      const Vec3 pv = d.cross(e2);
      const double det = e1.dot(pv);
      if (std::abs(det) <= 1e-10 * e1.norm() * e2.norm())
        return std::abs(tv.dot(normal[e])) > near_eps;  // parallel: spoilt if in the plane
      const Vec3 qv = tv.cross(e1);
      const double b1 = tv.dot(pv) / det, b2 = d.dot(qv) / det, s = e2.dot(qv) / det;
      if (b1 < -kBary || b2 < -kBary || b1 + b2 > 1.0 + kBary || s < -near_eps) return true;
      if (b1 <= kBary || b2 <= kBary || b1 + b2 >= 1.0 - kBary || s <= near_eps) return false;
      sum += det < 0.0 ? 1 : -1;  // det < 0: the ray leaves through the triangle's front
      return true;
    });
    if (clear) return sum;
  }
  return winding(p);
}

bool closedManifold(const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& tris) {
  if (tris.empty()) return false;
  const std::vector<int> id = detail::weldedIds(v);
  std::vector<std::pair<int, int>> edges;
  edges.reserve(3 * tris.size());
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) {
      const int a = id[t[k]], b = id[t[(k + 1) % 3]];
      if (a == b) return false;
      edges.emplace_back(a, b);
    }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i + 1 < edges.size(); ++i)
    if (edges[i] == edges[i + 1]) return false;
  for (const auto& e : edges)
    if (!std::binary_search(edges.begin(), edges.end(), std::make_pair(e.second, e.first)))
      return false;
  return true;
}

namespace {

// Rounding of a coordinate is about 1e-16 of the largest magnitude (far offsets) and of the
// size (the geometry itself); every test keeps a margin several orders above both.
void setScales(MeshData& m) {
  const double d = m.size, r = m.reach;
  m.overlap = 1e-9 * d + 1e-13 * r;
  m.near_eps = 1e-9 * d + 1e-12 * r;
  // Float meshes (STL) store coplanar faces with vertices off their plane by ~1e-7 relative.
  m.on_eps = 1e-6 * d + 1e-12 * r;
  m.margin = 1e-12 * d + 1e-14 * r;
}

// An edge with exactly two triangles is reflex when the far vertex of one rises above the other's
// plane by more than a few degrees (seen from the edge): creases of tessellated round surfaces
// are convex and stay out.
void findReflexEdges(const std::vector<std::array<int, 3>>& tris, MeshData& m) {
  const std::vector<int> id = detail::weldedIds(m.v);
  struct Use {
    int a, b, tri, far;
  };
  std::vector<Use> uses;
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      int a = tris[i][k], b = tris[i][(k + 1) % 3];
      if (id[a] > id[b]) std::swap(a, b);
      uses.push_back({a, b, static_cast<int>(i), tris[i][(k + 2) % 3]});
    }
  std::sort(uses.begin(), uses.end(), [&](const Use& x, const Use& y) {
    return std::make_tuple(id[x.a], id[x.b], x.tri) < std::make_tuple(id[y.a], id[y.b], y.tri);
  });
  const double sin_min = std::sin(5.0 * kPi / 180.0);
  std::vector<std::vector<int>> per(m.elements.size());
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && id[uses[j].a] == id[uses[i].a] && id[uses[j].b] == id[uses[i].b]) ++j;
    if (j - i == 2) {
      const Use &u = uses[i], &w = uses[i + 1];
      const Vec3& a = m.v[u.a];
      const Vec3 far_w = m.v[w.far] - a, far_u = m.v[u.far] - a;
      const bool rises = m.normal[u.tri].dot(far_w) > sin_min * far_w.norm() &&
                         m.normal[w.tri].dot(far_u) > sin_min * far_u.norm();
      if (rises) {
        const int e = static_cast<int>(m.reflex.size());
        m.reflex.push_back({m.v[u.a], m.v[u.b]});
        per[u.tri].push_back(e);
        per[w.tri].push_back(e);
      }
    }
    i = j;
  }
  m.reflex_start.assign(1, 0);
  for (const auto& list : per) {
    m.reflex_ids.insert(m.reflex_ids.end(), list.begin(), list.end());
    m.reflex_start.push_back(static_cast<int>(m.reflex_ids.size()));
  }
}

}  // namespace

MeshData prepare(const TriangleMesh& mesh, const std::string& what) {
  const std::string head = "convex decomposition of " + what + ": ";
  if (mesh.vertices.empty()) throw std::runtime_error(head + "the mesh has no vertices");
  MeshData m;
  m.v = mesh.vertices;
  Box box;
  for (std::size_t i = 0; i < m.v.size(); ++i) {
    if (!m.v[i].allFinite())
      throw std::runtime_error(head + "vertex " + std::to_string(i) + " is not finite");
    box.add(m.v[i]);
    m.reach = std::max(m.reach, m.v[i].cwiseAbs().maxCoeff());
  }
  const int nv = static_cast<int>(m.v.size());
  std::vector<char> used(m.v.size(), 0);
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    for (int k : mesh.triangles[i])
      if (k < 0 || k >= nv)
        throw std::runtime_error(head + "triangle " + std::to_string(i) +
                                 " has a vertex index out of range");
    for (int k : mesh.triangles[i]) used[k] = 1;
  }
  m.elements = mesh.triangles;
  for (int i = 0; i < nv; ++i)
    if (!used[i]) m.elements.push_back({i, i, i});
  m.size = box.diagonal();
  setScales(m);
  m.closed = closedManifold(mesh.vertices, mesh.triangles);

  // Orientation: the solid's signed volume decides the outward sense of the normals.
  const Vec3 centre = 0.5 * (box.lo + box.hi);
  const std::size_t nt = mesh.triangles.size();
  std::vector<double> volume(nt);
  double total = 0.0;
  for (std::size_t i = 0; i < nt; ++i) {
    const auto& t = mesh.triangles[i];
    volume[i] = (m.v[t[0]] - centre).dot((m.v[t[1]] - centre).cross(m.v[t[2]] - centre));
    total += volume[i];
  }
  const double sign = total < 0.0 ? -1.0 : 1.0;
  m.normal.assign(m.elements.size(), Vec3::Zero());
  for (std::size_t i = 0; i < nt; ++i) {
    const auto& t = mesh.triangles[i];
    const Vec3 n = (m.v[t[1]] - m.v[t[0]]).cross(m.v[t[2]] - m.v[t[0]]);
    const double len = n.norm();
    if (len > 0.0 && std::isfinite(len)) m.normal[i] = sign * n / len;
  }
  if (m.closed) {
    // Shells: triangles joined by welded edges (union-find); each must turn like the whole.
    const std::vector<int> id = detail::weldedIds(mesh.vertices);
    std::vector<int> parent(nt);
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    std::map<std::pair<int, int>, int> first_use;
    for (std::size_t i = 0; i < nt; ++i)
      for (int k = 0; k < 3; ++k) {
        int a = id[mesh.triangles[i][k]], b = id[mesh.triangles[i][(k + 1) % 3]];
        if (a > b) std::swap(a, b);
        auto [it, fresh] = first_use.emplace(std::make_pair(a, b), static_cast<int>(i));
        if (!fresh) parent[find(static_cast<int>(i))] = find(it->second);
      }
    std::map<int, double> shell_volume;
    for (std::size_t i = 0; i < nt; ++i) shell_volume[find(static_cast<int>(i))] += volume[i];
    m.face_rule = true;
    for (const auto& [root, vol] : shell_volume)
      if (!(vol * sign > 0.0)) m.face_rule = false;
  }
  findReflexEdges(mesh.triangles, m);
  m.tree = ElementTree(m.v, m.elements);
  return m;
}

}  // namespace dss::mesh::decomposition
