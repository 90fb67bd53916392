// Conservative approximate convex decomposition: cells from plane splits, pieces from the
// triangles clipped to each cell plus the cell corners inside the solid, concavity certified by
// a branch-and-bound octree. See dss/mesh/convex_decomposition.h for the contract.
#include "dss/mesh/convex_decomposition.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "dss/core/any_shape.h"
#include "dss/core/convex_hull.h"
#include "welded_ids.h"

namespace dss::mesh {
namespace {

using Vec3 = Eigen::Vector3d;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

bool lexLess(const Vec3& a, const Vec3& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

void sortUnique(std::vector<Vec3>& pts) {
  std::sort(pts.begin(), pts.end(), lexLess);
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
}

struct Box {
  Vec3 lo = Vec3::Constant(kInf);
  Vec3 hi = Vec3::Constant(-kInf);
  void add(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void add(const Box& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  bool empty() const { return !(lo.array() <= hi.array()).all(); }
  double diagonal() const { return empty() ? 0.0 : (hi - lo).norm(); }
  double distanceSq(const Vec3& p) const {
    return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm();
  }
  bool overlaps(const Box& b) const {
    return (lo.array() <= b.hi.array()).all() && (b.lo.array() <= hi.array()).all();
  }
};

/// The half-space n·x <= o.
struct Plane {
  Vec3 n;
  double o;
};

Vec3 closestOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (!(len2 > 0.0)) return a;
  return a + std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) * ab;
}

// The projection onto the plane is used only when the triangle has an area well above rounding
// compared with its edges; slivers and repeated vertices take the nearest of the edges, which
// is then the exact answer up to the sliver's width.
Vec3 closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a;
  const Vec3 n = ab.cross(ac);
  const double n2 = n.squaredNorm();
  if (n2 > 1e-24 * ab.squaredNorm() * ac.squaredNorm()) {
    const Vec3 q = p - ((p - a).dot(n) / n2) * n;
    if (ab.cross(q - a).dot(n) >= 0.0 && (c - b).cross(q - b).dot(n) >= 0.0 &&
        (a - c).cross(q - c).dot(n) >= 0.0)
      return q;
  }
  Vec3 best = closestOnSegment(p, a, b);
  double best_d = (best - p).squaredNorm();
  for (const Vec3& q : {closestOnSegment(p, b, c), closestOnSegment(p, c, a)}) {
    const double d = (q - p).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = q;
    }
  }
  return best;
}

// Signed solid angle of triangle (a, b, c) seen from the origin (Van Oosterom and Strackee).
double solidAngle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double det = a.dot(b.cross(c));
  const double den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
  return 2.0 * std::atan2(det, den);
}

// An AABB tree over the mesh elements, for nearest-point and box-overlap queries.
class ElementTree {
 public:
  ElementTree() = default;
  ElementTree(const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& t) {
    const int n = static_cast<int>(t.size());
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0);
    corners_.resize(n);
    boxes_.resize(n);
    centres_.resize(n);
    for (int i = 0; i < n; ++i) {
      for (int k = 0; k < 3; ++k) {
        corners_[i][k] = v[t[i][k]];
        boxes_[i].add(corners_[i][k]);
      }
      centres_[i] = 0.5 * (boxes_[i].lo + boxes_[i].hi);
    }
    if (n > 0) build(0, n);
  }

  /// Distance from p to the nearest element, and that element's nearest point.
  double nearest(const Vec3& p, Vec3* point = nullptr) const {
    double best = kInf;
    Vec3 best_point = p;
    if (nodes_.empty()) return best;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (node.box.distanceSq(p) >= best) continue;
      if (node.count > 0) {
        for (int i = node.first; i < node.first + node.count; ++i) {
          if (boxes_[order_[i]].distanceSq(p) >= best) continue;
          const auto& t = corners_[order_[i]];
          const Vec3 q = closestOnTriangle(p, t[0], t[1], t[2]);
          const double d = (q - p).squaredNorm();
          if (d < best) {
            best = d;
            best_point = q;
          }
        }
        continue;
      }
      // The nearer child is searched first (pushed last).
      const double dl = nodes_[node.left].box.distanceSq(p);
      const double dr = nodes_[node.right].box.distanceSq(p);
      if (dl < dr) {
        stack[top++] = node.right;
        stack[top++] = node.left;
      } else {
        stack[top++] = node.left;
        stack[top++] = node.right;
      }
    }
    if (point) *point = best_point;
    return std::sqrt(best);
  }

  /// Calls f(element) for every element whose bounding box, grown by `pad`, the ray p + t d
  /// (t >= 0) meets, until f returns false; returns false when stopped. The padding absorbs the
  /// rounding of the slab test, so no box the ray touches is skipped.
  template <class F>
  bool visitRay(const Vec3& p, const Vec3& d, double pad, F&& f) const {
    if (nodes_.empty()) return true;
    const Vec3 inv = d.cwiseInverse();
    auto meets = [&](const Box& b) {
      double t0 = 0.0, t1 = kInf;
      for (int k = 0; k < 3; ++k) {
        double a = (b.lo[k] - pad - p[k]) * inv[k], c = (b.hi[k] + pad - p[k]) * inv[k];
        if (a > c) std::swap(a, c);
        t0 = std::max(t0, a);
        t1 = std::min(t1, c);
      }
      return t0 <= t1;
    };
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (!meets(node.box)) continue;
      if (node.count > 0) {
        for (int i = node.first; i < node.first + node.count; ++i)
          if (meets(boxes_[order_[i]]) && !f(order_[i])) return false;
        continue;
      }
      stack[top++] = node.right;
      stack[top++] = node.left;
    }
    return true;
  }

  /// Calls f(element) for every element whose bounding box overlaps `box` until f returns
  /// false; returns false when stopped.
  template <class F>
  bool visit(const Box& box, F&& f) const {
    if (nodes_.empty()) return true;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (!node.box.overlaps(box)) continue;
      if (node.count > 0) {
        for (int i = node.first; i < node.first + node.count; ++i)
          if (boxes_[order_[i]].overlaps(box) && !f(order_[i])) return false;
        continue;
      }
      stack[top++] = node.right;
      stack[top++] = node.left;
    }
    return true;
  }

 private:
  struct Node {
    Box box;
    int first = 0, count = 0;  // a leaf when count > 0
    int left = -1, right = -1;
  };

  // Median split along the longest axis of the centres: depth stays near log2(n), far below
  // the query stack's 128 entries.
  int build(int first, int last) {
    const int id = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Box box, centres;
    for (int i = first; i < last; ++i) {
      box.add(boxes_[order_[i]]);
      centres.add(centres_[order_[i]]);
    }
    nodes_[id].box = box;
    if (last - first <= 4) {
      nodes_[id].first = first;
      nodes_[id].count = last - first;
      return id;
    }
    int axis = 0;
    (centres.hi - centres.lo).maxCoeff(&axis);
    const int mid = (first + last) / 2;
    std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + last,
                     [&](int a, int b) {
                       const double ca = centres_[a][axis], cb = centres_[b][axis];
                       return ca < cb || (ca == cb && a < b);
                     });
    const int left = build(first, mid);
    const int right = build(mid, last);
    nodes_[id].left = left;
    nodes_[id].right = right;
    return id;
  }

  std::vector<std::array<Vec3, 3>> corners_;  // per element, in the mesh's order
  std::vector<int> order_;
  std::vector<Box> boxes_;
  std::vector<Vec3> centres_;
  std::vector<Node> nodes_;
};

// Directed welded edges; closed and edge-manifold when each appears once and its reverse once.
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

// ---------------------------------------------------------------------------------------------
// The mesh as the decomposition sees it.

struct MeshData {
  std::vector<Vec3> v;
  // Triangles, then every vertex no triangle uses as a repeated-index element, so that it is
  // clipped, covered and measured like the rest.
  std::vector<std::array<int, 3>> elements;
  std::vector<Vec3> normal;  // unit, oriented out of the solid; zero for degenerate elements
  bool closed = false;
  // Closed, and every connected shell turns the same way as the whole: the winding number is
  // then >= 0 everywhere after orientation, which the face rule of the certificate relies on.
  bool face_rule = false;
  double size = 0.0;   // bounding-box diagonal
  double reach = 0.0;  // largest coordinate magnitude
  // Scales of rounding and of the tests built on it (see setScales).
  double overlap = 0.0;   // sibling cells overlap by this much
  double near_eps = 0.0;  // a corner this close to the surface is kept without a verdict
  double on_eps = 0.0;    // a triangle this close to a facet plane lies on it
  double margin = 0.0;    // plane tests for points and boxes
  ElementTree tree;
  // Reflex (concave) edges, as endpoint pairs, and the ones each element holds (CSR): cut
  // planes through them separate convex parts where they meet.
  std::vector<std::array<Vec3, 2>> reflex;
  std::vector<int> reflex_start, reflex_ids;

  double winding(const Vec3& p) const {
    double sum = 0.0;
    for (const auto& t : elements) {
      if (t[0] == t[1] && t[1] == t[2]) continue;
      sum += solidAngle(v[t[0]] - p, v[t[1]] - p, v[t[2]] - p);
    }
    return sum / (4.0 * kPi);
  }
  bool inside(const Vec3& p) const { return std::abs(crossings(p)) > 0.5; }

  // The winding number of a closed mesh as the signed count of surface crossings along a ray.
  // A hit near a triangle's edge, a ray running in a triangle's plane or an origin on the
  // surface spoils a direction; the next one is tried, and the solid-angle sum settles the
  // rare point that spoils them all.
  double crossings(const Vec3& p) const {
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
};

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

// ---------------------------------------------------------------------------------------------
// Cells and the triangles clipped to them.

// Clipped polygons, stored flat and in increasing element order.
struct Polygons {
  std::vector<int> element;
  std::vector<int> start{0};
  std::vector<Vec3> pts;
  std::size_t size() const { return element.size(); }
  void add(int e, const std::vector<Vec3>& poly) {
    element.push_back(e);
    pts.insert(pts.end(), poly.begin(), poly.end());
    start.push_back(static_cast<int>(pts.size()));
  }
};

// Keeps the part of polygon [first, last) where n·x <= o (Sutherland–Hodgman, one plane).
void clipPolygon(const Vec3* first, const Vec3* last, const Plane& plane, std::vector<Vec3>& out) {
  out.clear();
  const std::size_t k = static_cast<std::size_t>(last - first);
  double s_prev = plane.n.dot(first[k - 1]) - plane.o;
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3& a = first[(i + k - 1) % k];
    const Vec3& b = first[i];
    const double s = plane.n.dot(b) - plane.o;
    if ((s_prev <= 0.0) != (s <= 0.0)) out.push_back(a + (s_prev / (s_prev - s)) * (b - a));
    if (s <= 0.0) out.push_back(b);
    s_prev = s;
  }
}

struct Corner {
  Vec3 p;
  std::vector<int> planes;  // ids of the cell planes through it, sorted
  bool keep = false;        // inside the solid, or too near its surface to tell
};

struct Cell {
  std::vector<Corner> corners;
  Polygons polys;
};

Cell rootCell(const MeshData& m) {
  Box box;
  for (const Vec3& p : m.v) box.add(p);
  // The box must hold the mesh strictly inside: its corners are then outside the solid.
  const Vec3 grow = Vec3::Constant(1e-3 * m.size + 1e3 * m.near_eps + 1e-300);
  box.lo -= grow;
  box.hi += grow;
  Cell cell;
  for (int i = 0; i < 8; ++i) {
    Corner c;
    c.p = Vec3((i & 1) ? box.hi.x() : box.lo.x(), (i & 2) ? box.hi.y() : box.lo.y(),
               (i & 4) ? box.hi.z() : box.lo.z());
    c.planes = {(i & 1) ? 0 : 1, (i & 2) ? 2 : 3, (i & 4) ? 4 : 5};
    cell.corners.push_back(std::move(c));
  }
  std::vector<Vec3> tri(3);
  for (std::size_t e = 0; e < m.elements.size(); ++e) {
    for (int k = 0; k < 3; ++k) tri[k] = m.v[m.elements[e][k]];
    cell.polys.add(static_cast<int>(e), tri);
  }
  return cell;
}

// The part of `cell` with n·x <= o. Without `polys_out` only the points of the clipped
// polygons are kept (in out.polys.pts), which is all a piece's hull needs.
Cell clipCell(const Cell& cell, const Plane& plane, int plane_id, const MeshData& m,
              bool polys_out = true) {
  Cell out;
  std::vector<Vec3> poly;
  for (std::size_t i = 0; i < cell.polys.size(); ++i) {
    const Vec3* first = cell.polys.pts.data() + cell.polys.start[i];
    const Vec3* last = cell.polys.pts.data() + cell.polys.start[i + 1];
    clipPolygon(first, last, plane, poly);
    if (poly.empty()) continue;
    if (polys_out)
      out.polys.add(cell.polys.element[i], poly);
    else
      out.polys.pts.insert(out.polys.pts.end(), poly.begin(), poly.end());
  }
  // Corners: those on the kept side, and where an edge of the cell (two corners sharing two
  // planes) crosses the plane. Labels are combinatorial, never re-derived from coordinates.
  std::vector<double> s(cell.corners.size());
  for (std::size_t i = 0; i < cell.corners.size(); ++i)
    s[i] = plane.n.dot(cell.corners[i].p) - plane.o;
  std::vector<int> common;
  for (std::size_t i = 0; i < cell.corners.size(); ++i) {
    if (s[i] > 0.0) continue;
    out.corners.push_back(cell.corners[i]);
    for (std::size_t j = 0; j < cell.corners.size(); ++j) {
      if (s[j] <= 0.0) continue;
      const Corner& a = cell.corners[i];
      const Corner& b = cell.corners[j];
      common.clear();
      std::set_intersection(a.planes.begin(), a.planes.end(), b.planes.begin(), b.planes.end(),
                            std::back_inserter(common));
      if (common.size() < 2) continue;
      Corner c;
      c.p = a.p + (s[i] / (s[i] - s[j])) * (b.p - a.p);
      c.planes = common;
      c.planes.push_back(plane_id);
      std::sort(c.planes.begin(), c.planes.end());
      if (m.closed) {
        // Any doubt keeps the corner: an extra point only enlarges the piece.
        c.keep = m.tree.nearest(c.p) <= m.near_eps || m.inside(c.p);
      }
      out.corners.push_back(std::move(c));
    }
  }
  return out;
}

// The piece points of a cell, with repeats (a vertex appears once per triangle using it).
std::vector<Vec3> cellPoints(const Cell& cell) {
  std::vector<Vec3> pts = cell.polys.pts;
  for (const Corner& c : cell.corners)
    if (c.keep) pts.push_back(c.p);
  return pts;
}

// ---------------------------------------------------------------------------------------------
// Piece hulls.

// Points of a rough hull, which only ranks candidate cuts.
constexpr std::size_t kRoughPoints = 2000;

struct Hull {
  std::vector<Vec3> points;   // the piece is conv(points)
  std::vector<Plane> planes;  // conv(points) lies in every half-space
  bool full = false;          // 3-D: the planes are the facets
  double volume = 0.0;
  Box box;
};

// Planes around a flat, collinear or tiny set: its bounding box, both sides of its best-fit
// plane and the edges of its 2-D hull in that plane. Every offset is the largest over the
// points, so each half-space holds the set whatever the rounding of its normal.
std::vector<Plane> flatPlanes(const std::vector<Vec3>& pts) {
  std::vector<Vec3> normals = {Vec3::UnitX(),  -Vec3::UnitX(), Vec3::UnitY(),
                               -Vec3::UnitY(), Vec3::UnitZ(),  -Vec3::UnitZ()};
  if (pts.size() >= 3) {
    Vec3 mean = Vec3::Zero();
    for (const Vec3& p : pts) mean += p;
    mean /= static_cast<double>(pts.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const Vec3& p : pts) cov += (p - mean) * (p - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    const Vec3 n = eig.eigenvectors().col(0), e1 = eig.eigenvectors().col(2),
               e2 = eig.eigenvectors().col(1);
    normals.push_back(n);
    normals.push_back(-n);
    // Andrew's monotone chain on the projections.
    std::vector<std::pair<double, double>> q;
    for (const Vec3& p : pts) q.emplace_back((p - mean).dot(e1), (p - mean).dot(e2));
    std::sort(q.begin(), q.end());
    q.erase(std::unique(q.begin(), q.end()), q.end());
    if (q.size() >= 3) {
      auto cross = [](const std::pair<double, double>& o, const std::pair<double, double>& a,
                      const std::pair<double, double>& b) {
        return (a.first - o.first) * (b.second - o.second) -
               (a.second - o.second) * (b.first - o.first);
      };
      std::vector<std::pair<double, double>> h(2 * q.size());
      std::size_t k = 0;
      for (std::size_t i = 0; i < q.size(); ++i) {
        while (k >= 2 && cross(h[k - 2], h[k - 1], q[i]) <= 0) --k;
        h[k++] = q[i];
      }
      for (std::size_t i = q.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross(h[k - 2], h[k - 1], q[i]) <= 0) --k;
        h[k++] = q[i];
      }
      h.resize(k - 1);
      for (std::size_t i = 0; i < h.size(); ++i) {
        const auto& a = h[i];
        const auto& b = h[(i + 1) % h.size()];
        const Vec3 outward = (b.second - a.second) * e1 - (b.first - a.first) * e2;
        if (outward.norm() > 0.0) normals.push_back(outward.normalized());
      }
    }
  }
  std::vector<Plane> planes;
  for (const Vec3& n : normals) {
    double o = -kInf;
    for (const Vec3& p : pts) o = std::max(o, n.dot(p));
    planes.push_back({n, o});
  }
  return planes;
}

enum class HullMode {
  kRough,     // for ranking cuts: from a subset of the points when they are many
  kVertices,  // qhull's vertices: within qhull's rounding of the points' hull
  kExact,     // qhull's vertices and every point not proved inside them
};

// The hull of `pts` (see HullMode).
Hull buildHull(std::vector<Vec3> pts, const MeshData& m, HullMode mode) {
  Hull h;
  // qhull's input is made distinct by tessellate(); the exact check wants few repeats.
  if (mode == HullMode::kExact) sortUnique(pts);
  if (mode == HullMode::kRough && pts.size() > kRoughPoints) {
    // Every k-th point, and the extreme ones along the axes so that the box is exact.
    std::vector<Vec3> sub;
    const std::size_t stride = (pts.size() + kRoughPoints - 1) / kRoughPoints;
    for (std::size_t i = 0; i < pts.size(); i += stride) sub.push_back(pts[i]);
    for (int k = 0; k < 3; ++k) {
      auto cmp = [k](const Vec3& a, const Vec3& b) { return a[k] < b[k]; };
      sub.push_back(*std::min_element(pts.begin(), pts.end(), cmp));
      sub.push_back(*std::max_element(pts.begin(), pts.end(), cmp));
    }
    pts.swap(sub);
    sortUnique(pts);
  }
  for (const Vec3& p : pts) h.box.add(p);
  TriangleMesh facets;
  if (pts.size() >= 4) facets = tessellate(dss::AnyShape(dss::ConvexHull(pts)));
  if (facets.triangles.empty()) {
    sortUnique(pts);
    h.points = std::move(pts);
    h.planes = flatPlanes(h.points);
    return h;
  }
  h.full = true;
  std::vector<Vec3> vertices = facets.vertices;
  sortUnique(vertices);
  struct Facet {
    Vec3 n, a;
  };
  std::vector<Facet> fs;
  std::vector<std::size_t> facet_of;  // the triangle of each facet
  const Vec3 g = 0.5 * (h.box.lo + h.box.hi);
  for (std::size_t i = 0; i < facets.triangles.size(); ++i) {
    const auto& t = facets.triangles[i];
    const Vec3 &a = facets.vertices[t[0]], &b = facets.vertices[t[1]], &c = facets.vertices[t[2]];
    h.volume += (a - g).dot((b - g).cross(c - g)) / 6.0;
    const Vec3 n = (b - a).cross(c - a);
    const double len = n.norm();
    if (len > 0.0 && std::isfinite(len)) {
      fs.push_back({n / len, a});
      facet_of.push_back(i);
    }
  }
  h.points = vertices;
  if (mode == HullMode::kExact) {
    // A point qhull left out is dropped only when it is inside every facet plane by a margin
    // far above rounding. The facets form a closed surface with vertices in `vertices`, so
    // such a point has winding number >= 1 about it and lies in their hull. Any other point
    // is kept. Points within the ball inside every facet plane (about the box centre) pass at
    // once.
    const double margin = 1e-9 * h.box.diagonal() + 16.0 * m.margin;
    double ball = kInf;
    for (const Facet& f : fs) ball = std::min(ball, -f.n.dot(g - f.a));
    ball -= 2.0 * margin;
    for (const Vec3& p : pts) {
      if ((p - g).norm() < ball) continue;
      if (std::binary_search(vertices.begin(), vertices.end(), p, lexLess)) continue;
      bool inside = true;
      for (const Facet& f : fs)
        if (f.n.dot(p - f.a) >= -margin) {
          inside = false;
          break;
        }
      if (!inside) h.points.push_back(p);
    }
  }
  if (mode == HullMode::kExact) {
    // Offsets as the largest over the points: each half-space holds them all, whatever the
    // rounding of its normal.
    for (const Facet& f : fs) {
      double o = -kInf;
      for (const Vec3& p : h.points) o = std::max(o, f.n.dot(p));
      h.planes.push_back({f.n, o});
    }
  } else {
    // qhull leaves every vertex below every facet up to its rounding, far below the margin.
    for (std::size_t i = 0; i < fs.size(); ++i) {
      const auto& t = facets.triangles[facet_of[i]];
      double o = -kInf;
      for (int k = 0; k < 3; ++k) o = std::max(o, fs[i].n.dot(facets.vertices[t[k]]));
      h.planes.push_back({fs[i].n, o + 16.0 * m.margin});
    }
  }
  return h;
}

// ---------------------------------------------------------------------------------------------
// Concavity certificate: h(P) = max over x in P of d(x), d the distance to the solid (closed
// meshes) or to the surface (open ones). d is 1-Lipschitz, so over a box of centre c and
// half-diagonal r, d <= d(c) + r; the distance to the surface u(c) bounds d(c). Boxes are
// refined, largest bound first, until the largest open bound meets the stopping rule; that
// bound is the certificate. A box is closed for good when
//  - it misses one of the piece's half-spaces;
//  - it holds no surface (u(c) > r) and its centre is inside the solid;
//  - (face rule) every triangle near it lies on a facet plane of the piece, with the solid on
//    the inner side, or outside a facet plane, and one of the piece's own triangle sections
//    lying on a facet crosses the box: the box's part of the piece's interior is then free of
//    surface, hence on one side of it, and it borders that section from the inside.

struct Limits {
  double good_enough = 0.0;  // stop once the bound is at most this
  double give_up = kInf;     // stop once a point of the piece is known to be farther
  double gap_abs = 0.0;      // stop once bound <= lower + max(gap_abs, gap_rel * lower)
  double gap_rel = 0.0;
  // ... but not while the bounds straddle this value: the caller needs to know which side of
  // it h is on (the tolerance).
  double decide = 0.0;
  int max_boxes = 0;
};

struct Certificate {
  double upper = kInf;  // certified bound of h
  double lower = 0.0;   // d(deepest) (a point of the piece, up to the facet rounding)
  Vec3 deepest = Vec3::Zero();
  int boxes = 0;
};

class Certifier {
 public:
  Certifier(const MeshData& m, const Hull& h, const Polygons& polys)
      : m_(m), h_(h), polys_(polys), cls_(m.elements.size(), kUnknown) {}

  Certificate run(const Limits& lim) {
    Certificate cert;
    cert.deepest = 0.5 * (h_.box.lo + h_.box.hi);
    if (h_.points.empty()) {
      cert.upper = 0.0;
      return cert;
    }
    good_enough_ = lim.good_enough;
    // The face rule accepts triangles within on_eps of a facet plane; the plane tests keep a
    // margin of their own. Every bound carries both.
    slack_ = 2.0 * m_.on_eps + 4.0 * m_.margin;
    std::vector<int> all(h_.planes.size());
    std::iota(all.begin(), all.end(), 0);
    const Vec3 grow = Vec3::Constant(m_.margin);
    double floor = 0.0;  // bounds of boxes too small to refine
    bool found = false;
    std::priority_queue<Item> heap;
    auto process = [&](const Vec3& lo, const Vec3& hi, bool outside, std::vector<int> active) {
      ++cert.boxes;
      Item item;
      if (!evaluate(lo, hi, outside, active, item, cert, found)) return;
      item.lo = lo;
      item.hi = hi;
      item.active = std::move(active);
      heap.push(std::move(item));
    };
    process(h_.box.lo - grow, h_.box.hi + grow, false, all);
    const double r_min = 1e-7 * m_.size + m_.on_eps;
    while (!heap.empty()) {
      const Item& top = heap.top();
      const double bound = top.ub + slack_;
      const double lower = found ? cert.lower : 0.0;
      const bool straddles = lower < lim.decide && bound > lim.decide;
      if (bound <= lim.good_enough || lower > lim.give_up ||
          (!straddles && bound <= lower + std::max(lim.gap_abs, lim.gap_rel * lower)) ||
          cert.boxes >= lim.max_boxes)
        break;
      Item box = top;
      heap.pop();
      const Vec3 ext = box.hi - box.lo;
      if (0.5 * ext.norm() <= r_min) {
        floor = std::max(floor, box.ub);
        continue;
      }
      // Halve every side longer than half the longest: boxes stay near cubes.
      const double longest = ext.maxCoeff();
      int split[3], ns = 0;
      for (int k = 0; k < 3; ++k)
        if (ext[k] >= 0.5 * longest) split[ns++] = k;
      for (int code = 0; code < (1 << ns); ++code) {
        Vec3 lo = box.lo, hi = box.hi;
        for (int j = 0; j < ns; ++j) {
          const int k = split[j];
          const double mid = 0.5 * (box.lo[k] + box.hi[k]);
          if (code & (1 << j))
            lo[k] = mid;
          else
            hi[k] = mid;
        }
        process(lo, hi, box.outside, box.active);
      }
    }
    cert.upper = std::max(floor, heap.empty() ? 0.0 : heap.top().ub) + slack_;
    if (!found) cert.lower = 0.0;
    if (!found && !heap.empty()) cert.deepest = 0.5 * (heap.top().lo + heap.top().hi);
    return cert;
  }

 private:
  enum : std::int8_t { kUnknown, kOnFacet, kApart, kBlocking };

  struct Item {
    double ub = 0.0;
    Vec3 lo, hi;
    bool outside = false;  // free of surface and outside the solid (inherited)
    std::vector<int> active;
    bool operator<(const Item& o) const { return ub < o.ub; }
  };

  // Fills item.ub; false when the box is closed for good.
  bool evaluate(const Vec3& lo, const Vec3& hi, bool outside, std::vector<int>& active, Item& item,
                Certificate& cert, bool& found) {
    const Vec3 c = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    const double r = half.norm();
    // Half-spaces: a box wholly inside one is done with it; wholly outside one, done for good.
    bool centre_in = true;
    std::size_t keep = 0;
    for (int i : active) {
      const Plane& p = h_.planes[i];
      const double mid = p.n.dot(c) - p.o;
      const double spread = p.n.cwiseAbs().dot(half);
      if (mid - spread > m_.margin) return false;
      if (mid > 0.0) centre_in = false;
      if (mid + spread > 0.0) active[keep++] = i;
    }
    active.resize(keep);
    const double u = m_.tree.nearest(c);
    item.outside = outside;
    // A box whose plain bound already meets the stopping level is never refined: the tests
    // below could only lower a bound that no longer matters.
    const double settled = std::max(good_enough_ - slack_, found ? cert.lower : 0.0);
    if (u + r <= settled) {
      item.ub = u + r;
      return true;
    }
    // d(c): u(c) outside the solid (and for open meshes), 0 inside, at most u(c) when unsure.
    bool known_out = outside || !m_.closed;
    double d = u;
    if (!known_out && u > m_.near_eps) {
      const bool in = m_.inside(c);
      if (u > r + m_.near_eps) {
        // No surface in the box: all of it is on the centre's side.
        if (in) return false;
        item.outside = true;
      }
      known_out = !in;
      if (in) d = 0.0;
    }
    // The face rule would close a box holding a point of the piece known to be outside the
    // solid only through the on_eps slack: such a box stays open.
    const bool witnessed_out = known_out && centre_in && u > 2.0 * m_.on_eps;
    if (!item.outside && !witnessed_out && m_.closed && faceRule(lo, hi)) return false;
    item.ub = d + r;
    if (centre_in && known_out && (!found || u > cert.lower)) {
      found = true;
      cert.lower = u;
      cert.deepest = c;
    }
    return true;
  }

  bool faceRule(const Vec3& lo, const Vec3& hi) {
    if (!m_.face_rule || !h_.full) return false;
    Box box{lo - Vec3::Constant(m_.on_eps), hi + Vec3::Constant(m_.on_eps)};
    bool witness = false;
    const bool clear = m_.tree.visit(box, [&](int e) {
      const std::int8_t k = classify(e);
      if (k == kBlocking) return false;
      if (k == kOnFacet && !witness) witness = crosses(e, lo, hi);
      return true;
    });
    return clear && witness;
  }

  std::int8_t classify(int e) {
    std::int8_t& k = cls_[e];
    if (k != kUnknown) return k;
    const auto& t = m_.elements[e];
    const Vec3 &a = m_.v[t[0]], &b = m_.v[t[1]], &c = m_.v[t[2]];
    const Vec3& n = m_.normal[e];
    k = kBlocking;
    for (const Plane& p : h_.planes) {
      const double sa = p.n.dot(a) - p.o, sb = p.n.dot(b) - p.o, sc = p.n.dot(c) - p.o;
      if (std::min({sa, sb, sc}) > m_.margin) {
        k = kApart;
        break;
      }
      if (std::max({std::abs(sa), std::abs(sb), std::abs(sc)}) <= m_.on_eps && n.dot(p.n) > 0.0)
        k = kOnFacet;
    }
    return k;
  }

  // Whether the piece's section of element e has area inside the box (shrunk by a margin).
  bool crosses(int e, const Vec3& lo, const Vec3& hi) {
    auto it = std::lower_bound(polys_.element.begin(), polys_.element.end(), e);
    for (; it != polys_.element.end() && *it == e; ++it) {
      const std::size_t i = static_cast<std::size_t>(it - polys_.element.begin());
      std::vector<Vec3> poly(polys_.pts.begin() + polys_.start[i],
                             polys_.pts.begin() + polys_.start[i + 1]);
      std::vector<Vec3> next;
      for (int k = 0; k < 3 && poly.size() >= 3; ++k) {
        const Vec3 axis = Vec3::Unit(k);
        clipPolygon(poly.data(), poly.data() + poly.size(), {axis, hi[k] - m_.margin}, next);
        poly.swap(next);
        if (poly.size() < 3) break;
        clipPolygon(poly.data(), poly.data() + poly.size(), {-axis, -lo[k] - m_.margin}, next);
        poly.swap(next);
      }
      if (poly.size() < 3) continue;
      Vec3 area = Vec3::Zero();
      for (std::size_t j = 1; j + 1 < poly.size(); ++j)
        area += (poly[j] - poly[0]).cross(poly[j + 1] - poly[0]);
      if (area.norm() > 1e-18 * m_.size * m_.size) return true;
    }
    return false;
  }

  const MeshData& m_;
  const Hull& h_;
  const Polygons& polys_;
  std::vector<std::int8_t> cls_;
  double good_enough_ = 0.0;
  double slack_ = 0.0;
};

Certificate certify(const MeshData& m, const Hull& h, const Polygons& polys, const Limits& lim) {
  return Certifier(m, h, polys).run(lim);
}

// ---------------------------------------------------------------------------------------------
// Splitting and merging.

struct Piece {
  Cell cell;          // a merged piece keeps its parts' polygons and kept corners
  bool done = false;  // meets the tolerance, too small, merged, or no cut helps
  Hull hull;
  Certificate cert;
};

Polygons mergePolygons(const Polygons& a, const Polygons& b) {
  Polygons out;
  std::size_t i = 0, j = 0;
  std::vector<Vec3> poly;
  auto take = [&](const Polygons& p, std::size_t k) {
    poly.assign(p.pts.begin() + p.start[k], p.pts.begin() + p.start[k + 1]);
    out.add(p.element[k], poly);
  };
  while (i < a.size() || j < b.size()) {
    if (j >= b.size() || (i < a.size() && a.element[i] <= b.element[j]))
      take(a, i++);
    else
      take(b, j++);
  }
  return out;
}

// Search effort. Each split ranks up to about 80 planes (the three box normals and up to three
// principal axes, each with kSweep even offsets and three feature offsets tried on both sides)
// by a short certificate search of kScreenBoxes boxes per side, then certifies the best kExact
// in full.
constexpr int kSweep = 7;
constexpr int kScreenBoxes = 300;
constexpr std::size_t kExact = 6;
// Box budgets of a certificate while searching and for the reported bound.
constexpr int kSearchBoxes = 20000;
constexpr int kFinalBoxes = 50000;
// Pieces of many triangle sections (dense meshes) get a coarser sweep: each candidate clips
// them all.
constexpr std::size_t kDenseSections = 8000;
constexpr int kSweepDense = 3;
// Once the cap is reached: merges tried to free a slot for the worst piece, in all and in a
// row (cheapest first).
constexpr int kTrades = 4;
constexpr int kMergeAttempts = 2;

struct Decomposer {
  const MeshData& m;
  double tau;
  int max_pieces;
  int next_plane = 6;
  Limits scoring, final_limits;

  Decomposer(const MeshData& mesh, const DecompositionOptions& options)
      : m(mesh), tau(options.tolerance), max_pieces(options.max_pieces) {
    // The search needs to know on which side of the tolerance a piece is, and h to 10 %.
    scoring.good_enough = tau;
    scoring.gap_abs = 0.1 * tau;
    scoring.gap_rel = 0.1;
    scoring.decide = tau;
    scoring.max_boxes = kSearchBoxes;
    // The report: the same, and tighter bounds down to a twentieth of the tolerance.
    final_limits = scoring;
    final_limits.good_enough = 0.05 * tau;
    final_limits.max_boxes = kFinalBoxes;
  }

  Piece makePiece(Cell cell) const {
    Piece p;
    p.hull = buildHull(cellPoints(cell), m, HullMode::kVertices);
    p.cell = std::move(cell);
    return p;
  }

  void settle(Piece& p) const {
    const double diameter = p.hull.box.diagonal();
    // Every point of a piece is within its diameter of a piece point, and those lie on the
    // surface, inside the solid, or within near_eps of the surface.
    p.cert.upper = std::min(p.cert.upper, diameter + m.near_eps);
    p.done = p.done || p.cert.upper <= tau || diameter <= tau;
  }

  // Cut planes for piece p. Normals: the box axes and the piece's principal axes. Offsets:
  // through the mesh point nearest the piece's deepest point (the pocket's floor), through the
  // reflex edges of the piece (where convex parts meet; the offsets holding the most reflex
  // length), and an even sweep across the piece.
  std::vector<Plane> candidates(const Piece& p) const {
    Vec3 foot;
    m.tree.nearest(p.cert.deepest, &foot);
    std::vector<Vec3> normals = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
    const auto& pts = p.hull.points;
    Vec3 mean = Vec3::Zero();
    for (const Vec3& q : pts) mean += q;
    mean /= static_cast<double>(pts.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const Vec3& q : pts) cov += (q - mean) * (q - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    for (int k = 2; k >= 0; --k) {
      const Vec3 axis = eig.eigenvectors().col(k);
      if (!axis.allFinite()) continue;
      bool fresh = true;
      for (const Vec3& n : normals) fresh = fresh && std::abs(n.dot(axis)) < 0.99;
      if (fresh) normals.push_back(axis);
    }
    // Reflex edges of the piece's triangles, each once.
    std::vector<int> edges;
    for (int e : p.cell.polys.element)
      for (int k = m.reflex_start[e]; k < m.reflex_start[e + 1]; ++k)
        edges.push_back(m.reflex_ids[k]);
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());

    std::vector<Plane> planes;
    for (const Vec3& n : normals) {
      double lo = kInf, hi = -kInf;
      for (const Vec3& q : pts) {
        lo = std::min(lo, n.dot(q));
        hi = std::max(hi, n.dot(q));
      }
      const double extent = hi - lo;
      if (!(extent > 0.0)) continue;
      // Planes through mesh features often hold faces of the mesh: a side that keeps such a
      // face as a sliver spans the other side's whole width. Both sides of the feature are
      // tried, a hair away from it: well above the sibling overlap, and well below on_eps so
      // that the faces next to the cut still count as lying on the piece's facets.
      const double hair = std::max(1e-7 * extent, 10.0 * m.overlap);
      auto both = [&](double o) {
        planes.push_back({n, o - hair});
        planes.push_back({n, o + hair});
      };
      both(n.dot(foot));
      // Reflex offsets, clustered within 1% of the extent, weighted by edge length.
      std::vector<std::pair<double, double>> offsets;  // (offset, length)
      for (int e : edges) {
        const auto& ab = m.reflex[e];
        const double o = 0.5 * n.dot(ab[0] + ab[1]);
        if (o > lo + 0.02 * extent && o < hi - 0.02 * extent)
          offsets.emplace_back(o, (ab[1] - ab[0]).norm());
      }
      std::sort(offsets.begin(), offsets.end());
      std::vector<std::pair<double, double>> clusters;  // (weight, offset)
      for (std::size_t a = 0; a < offsets.size();) {
        std::size_t b = a;
        double weight = 0.0;
        while (b < offsets.size() && offsets[b].first - offsets[a].first <= 0.01 * extent)
          weight += offsets[b++].second;
        clusters.emplace_back(weight, offsets[(a + b) / 2].first);
        a = b;
      }
      std::stable_sort(clusters.begin(), clusters.end(),
                       [](const auto& x, const auto& y) { return x.first > y.first; });
      for (std::size_t k = 0; k < clusters.size() && k < 2; ++k) both(clusters[k].second);
      const int sweep = p.cell.polys.size() > kDenseSections ? kSweepDense : kSweep;
      for (int k = 1; k <= sweep; ++k) planes.push_back({n, lo + extent * k / (sweep + 1.0)});
    }
    return planes;
  }

  // Cut quality from the children's concavities: the worse side first, then the other, so that
  // a cut that frees a clean part beats one that halves a pocket (a later cut resolves the
  // rest); sides within the tolerance count as the tolerance.
  double score(double a, double b) const {
    a = std::max(a, tau);
    b = std::max(b, tau);
    return std::max(a, b) + std::min(a, b);
  }

  // Splits piece p; false when no candidate plane leaves points on both sides.
  bool split(const Piece& p, Piece& left_out, Piece& right_out) {
    struct Candidate {
      Plane plane;
      int id_left, id_right;
      double estimate = kInf, proxy = 0.0;
    };
    // Screening: rough hulls of both sides and a short search of each for its deepest pocket
    // (the lower bound); sections of the parent stand in for the sides' own.
    std::vector<Candidate> cands;
    const double side_margin = 1e-6 * p.hull.box.diagonal();
    Limits quick = scoring;
    quick.max_boxes = kScreenBoxes;
    auto estimate = [&](const Certificate& x) { return x.upper <= tau ? x.upper : x.lower; };
    for (const Plane& pl : candidates(p)) {
      // Both sides must hold points of the piece away from the plane: a plane along a face
      // only shaves off that face.
      bool below = false, above = false;
      for (const Vec3& q : p.hull.points) {
        const double s = pl.n.dot(q) - pl.o;
        below = below || s < -side_margin;
        above = above || s > side_margin;
      }
      if (!below || !above) continue;
      Candidate c{pl, next_plane, next_plane + 1};
      next_plane += 2;
      std::vector<Vec3> left = cellPoints(clipCell(p.cell, leftPlane(pl), c.id_left, m, false));
      std::vector<Vec3> right = cellPoints(clipCell(p.cell, rightPlane(pl), c.id_right, m, false));
      if (left.empty() || right.empty()) continue;
      const Hull hl = buildHull(std::move(left), m, HullMode::kRough);
      const Hull hr = buildHull(std::move(right), m, HullMode::kRough);
      c.proxy = hl.volume + hr.volume;
      c.estimate = score(estimate(certify(m, hl, p.cell.polys, quick)),
                         estimate(certify(m, hr, p.cell.polys, quick)));
      cands.push_back(c);
    }
    if (cands.empty()) return false;
    std::stable_sort(cands.begin(), cands.end(), [](const Candidate& a, const Candidate& b) {
      return a.estimate < b.estimate || (a.estimate == b.estimate && a.proxy < b.proxy);
    });
    // The best few by estimate are built in full and certified; the worse side first, so that
    // a candidate already beaten stops early.
    int best = -1;
    double best_score = kInf, best_proxy = kInf;
    for (std::size_t k = 0; k < std::min(kExact, cands.size()); ++k) {
      const Candidate& c = cands[k];
      Piece left = makePiece(clipCell(p.cell, leftPlane(c.plane), c.id_left, m));
      Piece right = makePiece(clipCell(p.cell, rightPlane(c.plane), c.id_right, m));
      if (left.hull.points.empty() || right.hull.points.empty()) continue;
      Limits lim = scoring;
      lim.give_up = best_score;
      Piece* first = &left;
      Piece* second = &right;
      if (second->hull.volume > first->hull.volume) std::swap(first, second);
      first->cert = certify(m, first->hull, first->cell.polys, lim);
      if (first->cert.lower > best_score) continue;
      second->cert = certify(m, second->hull, second->cell.polys, lim);
      if (second->cert.lower > best_score) continue;
      settle(left);
      settle(right);
      const double s = score(left.cert.upper, right.cert.upper);
      const double proxy = left.hull.volume + right.hull.volume;
      if (s < best_score || (s == best_score && proxy < best_proxy)) {
        best_score = s;
        best_proxy = proxy;
        best = static_cast<int>(k);
        left_out = std::move(left);
        right_out = std::move(right);
      }
    }
    return best >= 0;
  }

  // The two sides of a cut, overlapping by m.overlap so that rounding leaves no gap.
  Plane leftPlane(const Plane& p) const { return {p.n, p.o + m.overlap}; }
  Plane rightPlane(const Plane& p) const { return {-p.n, -p.o + m.overlap}; }

  // Merges the pair of pieces, other than `keep`, that grows the hulls least while its joint
  // hull stays certified below `limit`, passing over the first `skip` such pairs.
  bool mergeOnce(std::vector<Piece>& pieces, double limit, int keep, int skip = 0) {
    struct Pair {
      int i, j;
      double cost;
      Hull hull;
    };
    std::vector<Pair> pairs;
    for (std::size_t i = 0; i < pieces.size(); ++i)
      for (std::size_t j = i + 1; j < pieces.size(); ++j) {
        const Piece &a = pieces[i], &b = pieces[j];
        if (static_cast<int>(i) == keep || static_cast<int>(j) == keep) continue;
        if (a.cert.upper > limit || b.cert.upper > limit) continue;
        // Pieces farther apart than the limit are not tried: their joint hull spans the gap.
        const Box &ba = a.hull.box, &bb = b.hull.box;
        Box grown{ba.lo - Vec3::Constant(limit), ba.hi + Vec3::Constant(limit)};
        if (!grown.overlaps(bb)) continue;
        std::vector<Vec3> pts = a.hull.points;
        pts.insert(pts.end(), b.hull.points.begin(), b.hull.points.end());
        Hull h = buildHull(std::move(pts), m, HullMode::kVertices);
        const double cost = h.volume - a.hull.volume - b.hull.volume;
        pairs.push_back({static_cast<int>(i), static_cast<int>(j), cost, std::move(h)});
      }
    std::stable_sort(pairs.begin(), pairs.end(),
                     [](const Pair& a, const Pair& b) { return a.cost < b.cost; });
    Limits lim = scoring;
    lim.give_up = limit;
    for (Pair& pr : pairs) {
      Polygons polys = mergePolygons(pieces[pr.i].cell.polys, pieces[pr.j].cell.polys);
      Certificate cert = certify(m, pr.hull, polys, lim);
      if (cert.upper > limit) continue;
      if (skip-- > 0) continue;
      Piece merged;
      merged.cell.polys = std::move(polys);
      // The corners kept inside the solid, for the final hull (merged pieces are not split).
      for (const Piece* part : {&pieces[pr.i], &pieces[pr.j]})
        for (const Corner& c : part->cell.corners)
          if (c.keep) merged.cell.corners.push_back(c);
      merged.done = true;
      merged.hull = std::move(pr.hull);
      merged.cert = cert;
      pieces[pr.i] = std::move(merged);
      pieces.erase(pieces.begin() + pr.j);
      return true;
    }
    return false;
  }

  static int worstOf(const std::vector<Piece>& pieces, bool open_only) {
    int worst = -1;
    for (std::size_t i = 0; i < pieces.size(); ++i)
      if ((!open_only || !pieces[i].done) &&
          (worst < 0 || pieces[i].cert.upper > pieces[worst].cert.upper))
        worst = static_cast<int>(i);
    return worst;
  }

  // Splits the worst open piece while slots and the split budget last.
  void splitWorst(std::vector<Piece>& pieces, int& splits_left) {
    while (static_cast<int>(pieces.size()) < max_pieces && splits_left > 0) {
      const int worst = worstOf(pieces, true);
      if (worst < 0) break;
      --splits_left;
      Piece left, right;
      if (!split(pieces[worst], left, right)) {
        pieces[worst].done = true;
        continue;
      }
      pieces[worst] = std::move(left);
      pieces.insert(pieces.begin() + worst + 1, std::move(right));
    }
  }

  static double worstConcavity(const std::vector<Piece>& pieces) {
    double h = 0.0;
    for (const Piece& p : pieces) h = std::max(h, p.cert.upper);
    return h;
  }

  std::vector<Piece> run(Piece root) {
    std::vector<Piece> pieces;
    root.cert = certify(m, root.hull, root.cell.polys, scoring);
    settle(root);
    pieces.push_back(std::move(root));
    int splits_left = 4 * max_pieces;
    splitWorst(pieces, splits_left);
    // Pieces whose joint hull meets the tolerance become one, and the freed slots go to
    // the pieces still above it.
    while (pieces.size() > 1 && mergeOnce(pieces, tau, -1)) {
    }
    splitWorst(pieces, splits_left);
    // With the cap reached above the tolerance: trade a merge of two better pieces (kept below
    // the worst) for a split of the worst, while that lowers the worst; the few cheapest
    // merges are tried in turn.
    bool improved = true;
    int trades = kTrades;
    while (improved && splits_left > 0) {
      improved = false;
      const int worst = worstOf(pieces, false);
      const double current = pieces[worst].cert.upper;
      if (current <= tau || pieces[worst].done || static_cast<int>(pieces.size()) < max_pieces)
        break;
      for (int attempt = 0; attempt < kMergeAttempts && splits_left > 0 && trades > 0; ++attempt) {
        --trades;
        std::vector<Piece> trial = pieces;
        if (!mergeOnce(trial, current, worst, attempt)) break;
        splitWorst(trial, splits_left);
        if (worstConcavity(trial) < current) {
          pieces = std::move(trial);
          improved = true;
          break;
        }
      }
    }
    return pieces;
  }
};

}  // namespace

namespace {

bool indicesValid(const TriangleMesh& mesh) {
  for (const auto& t : mesh.triangles)
    for (int k : t)
      if (k < 0 || static_cast<std::size_t>(k) >= mesh.vertices.size()) return false;
  return true;
}

void requireIndices(const TriangleMesh& mesh, const char* who) {
  if (!indicesValid(mesh))
    throw std::runtime_error(std::string(who) + ": a triangle has a vertex index out of range");
}

}  // namespace

bool isClosedManifold(const TriangleMesh& mesh) {
  return indicesValid(mesh) && closedManifold(mesh.vertices, mesh.triangles);
}

double windingNumber(const TriangleMesh& mesh, const Eigen::Vector3d& p) {
  requireIndices(mesh, "windingNumber");
  double sum = 0.0;
  for (const auto& t : mesh.triangles)
    sum += solidAngle(mesh.vertices[t[0]] - p, mesh.vertices[t[1]] - p, mesh.vertices[t[2]] - p);
  return sum / (4.0 * kPi);
}

bool insideSolid(const TriangleMesh& mesh, const Eigen::Vector3d& p) {
  return std::abs(windingNumber(mesh, p)) > 0.5;
}

double distanceToMesh(const TriangleMesh& mesh, const Eigen::Vector3d& p,
                      Eigen::Vector3d* nearest) {
  if (mesh.vertices.empty()) throw std::runtime_error("distanceToMesh: the mesh has no vertices");
  requireIndices(mesh, "distanceToMesh");
  std::vector<char> used(mesh.vertices.size(), 0);
  double best = kInf;
  Vec3 best_point = mesh.vertices[0];
  auto consider = [&](const Vec3& q) {
    const double d = (q - p).squaredNorm();
    if (d < best) {
      best = d;
      best_point = q;
    }
  };
  for (const auto& t : mesh.triangles) {
    consider(closestOnTriangle(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]));
    for (int k : t) used[k] = 1;
  }
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    if (!used[i]) consider(mesh.vertices[i]);
  if (nearest) *nearest = best_point;
  return std::sqrt(best);
}

Decomposition decomposeConvex(const TriangleMesh& mesh, const DecompositionOptions& options,
                              const std::string& what) {
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance))
    throw std::runtime_error("convex decomposition of " + what +
                             ": the tolerance must be positive and finite");
  if (options.max_pieces < 1)
    throw std::runtime_error("convex decomposition of " + what + ": max_pieces must be >= 1");
  const MeshData m = prepare(mesh, what);
  Decomposer dec(m, options);

  // The search works on qhull's vertices; each final piece gets its exact hull (every point
  // qhull dropped without proof put back) and a certificate of that hull.
  auto finish = [&](const Piece& p, double search_bound) {
    const Hull exact = buildHull(cellPoints(p.cell), m, HullMode::kExact);
    double h = std::min(certify(m, exact, p.cell.polys, dec.final_limits).upper,
                        exact.box.diagonal() + m.near_eps);
    // The search's certificate is for the same hull when qhull dropped nothing unproved.
    if (exact.points.size() == p.hull.points.size()) h = std::min(h, search_bound);
    return std::make_pair(exact.points, h);
  };
  Piece root = dec.makePiece(rootCell(m));
  Decomposition out;
  out.closed = m.closed;
  ConvexPiece whole;
  std::tie(whole.points, whole.concavity) = finish(root, kInf);
  out.hull_concavity = whole.concavity;
  for (Piece& p : dec.run(std::move(root))) {
    ConvexPiece piece;
    std::tie(piece.points, piece.concavity) = finish(p, p.cert.upper);
    out.max_concavity = std::max(out.max_concavity, piece.concavity);
    out.pieces.push_back(std::move(piece));
  }
  // Pieces that do not cut the single hull's concavity by at least a fifth are not worth
  // their cost: every piece is one more element per check (an open shell, whose inside counts
  // as concave, ends here).
  if (out.pieces.size() > 1 && !(out.max_concavity <= 0.8 * out.hull_concavity)) {
    out.pieces.assign(1, std::move(whole));
    out.max_concavity = out.hull_concavity;
  }
  return out;
}

}  // namespace dss::mesh
