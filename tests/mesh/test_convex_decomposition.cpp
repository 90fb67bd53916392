// Tests of dss/mesh/convex_decomposition.h: the pieces must cover every vertex, every triangle
// and (closed meshes) the solid, stay inside the mesh's hull, and report honest concavities;
// concave shapes must be split and the cap honoured. Coverage is decided exactly: a point is
// inside a piece when it is inside every facet plane of the piece's qhull hull by a margin far
// above rounding, or else when exact DSS finds the one-point hull touching the piece.
#include <boost/test/unit_test.hpp>
#include <chrono>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include "dss/core/any_shape_query.h"
#include "dss/mesh/convex_decomposition.h"
#include "support/shared_data.h"
#include "support/thrown_message.h"

using dss::mesh::ConvexPiece;
using dss::mesh::Decomposition;
using dss::mesh::DecompositionOptions;
using dss::mesh::TriangleMesh;
using Eigen::Vector3d;

namespace {

// The closed surface of a union of grid cells: cell (i, j, k) spans [x[i], x[i+1]] x
// [y[j], y[j+1]] x [z[k], z[k+1]]. Faces between two cells of the union are left out; grid
// vertices are shared, so the surface is closed and edge-manifold as long as no two cells
// meet along an edge only.
TriangleMesh cellUnion(const std::array<std::vector<double>, 3>& grid,
                       const std::vector<std::array<int, 3>>& cells) {
  const std::set<std::array<int, 3>> in(cells.begin(), cells.end());
  std::map<std::array<int, 3>, int> index;
  TriangleMesh m;
  auto vertex = [&](const std::array<int, 3>& g) {
    auto [it, fresh] = index.emplace(g, static_cast<int>(m.vertices.size()));
    if (fresh) m.vertices.emplace_back(grid[0][g[0]], grid[1][g[1]], grid[2][g[2]]);
    return it->second;
  };
  for (const auto& c : cells)
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side) {
        std::array<int, 3> nb = c;
        nb[a] += side ? 1 : -1;
        if (in.count(nb)) continue;
        const int b = (a + 1) % 3, d = (a + 2) % 3;
        int q[4];
        const int corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (int k = 0; k < 4; ++k) {
          std::array<int, 3> g = c;
          g[a] += side;
          g[b] += corner[k][0];
          g[d] += corner[k][1];
          q[k] = vertex(g);
        }
        // e_b x e_d = e_a: counter-clockwise in (b, d) faces +a.
        if (side) {
          m.triangles.push_back({q[0], q[1], q[2]});
          m.triangles.push_back({q[0], q[2], q[3]});
        } else {
          m.triangles.push_back({q[0], q[2], q[1]});
          m.triangles.push_back({q[0], q[3], q[2]});
        }
      }
  return m;
}

TriangleMesh cube(double side) {
  return cellUnion({{{0, side}, {0, side}, {0, side}}}, {{0, 0, 0}});
}

// L of two 50 mm arms, 150 mm long overall, 50 mm thick.
TriangleMesh lShape() {
  return cellUnion({{{0, 0.05, 0.2}, {0, 0.05, 0.2}, {0, 0.05}}},
                   {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
}

// U: 40 mm prongs 110 mm long around a 40 mm gap.
TriangleMesh uShape() {
  return cellUnion({{{0, 0.04, 0.08, 0.12}, {0, 0.04, 0.15}, {0, 0.04}}},
                   {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {2, 1, 0}});
}

// A square frame (a ring with a hole through it): 40 mm bars around an 80 mm hole.
TriangleMesh frame() {
  std::vector<std::array<int, 3>> cells;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (i != 1 || j != 1) cells.push_back({i, j, 0});
  return cellUnion({{{0, 0.04, 0.12, 0.16}, {0, 0.04, 0.12, 0.16}, {0, 0.04}}}, cells);
}

// A block with a 2 mm slot, 70 mm deep: narrower than the 5 mm tolerance.
TriangleMesh slot() {
  return cellUnion({{{0, 0.05, 0.052, 0.102}, {0, 0.03, 0.1}, {0, 0.05}}},
                   {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {2, 1, 0}});
}

TriangleMesh plate() { return cellUnion({{{0, 0.2}, {0, 0.2}, {0, 0.001}}}, {{0, 0, 0}}); }

// A cube without its top face: an open surface.
TriangleMesh openBox() {
  TriangleMesh m = cube(0.1);
  std::vector<std::array<int, 3>> kept;
  for (const auto& t : m.triangles) {
    bool top = true;
    for (int k : t) top = top && m.vertices[k].z() == 0.1;
    if (!top) kept.push_back(t);
  }
  m.triangles = kept;
  return m;
}

TriangleMesh transformed(TriangleMesh m, double scale, const Vector3d& offset) {
  for (auto& v : m.vertices) v = scale * v + offset;
  return m;
}

// Every triangle with its own three vertices, as STL files load.
TriangleMesh unshared(const TriangleMesh& m) {
  TriangleMesh out;
  for (const auto& t : m.triangles) {
    const int base = static_cast<int>(out.vertices.size());
    for (int k : t) out.vertices.push_back(m.vertices[k]);
    out.triangles.push_back({base, base + 1, base + 2});
  }
  return out;
}

double meshSize(const TriangleMesh& m) {
  Vector3d lo = m.vertices[0], hi = lo;
  for (const auto& v : m.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return (hi - lo).norm();
}

double reach(const TriangleMesh& m) {
  double r = 0.0;
  for (const auto& v : m.vertices) r = std::max(r, v.cwiseAbs().maxCoeff());
  return r;
}

std::vector<Vector3d> surfaceSamples(const TriangleMesh& m, int n, std::mt19937_64& rng) {
  std::vector<double> area;
  for (const auto& t : m.triangles)
    area.push_back(
        (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).norm());
  std::discrete_distribution<int> pick(area.begin(), area.end());
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vector3d> out;
  for (int i = 0; i < n; ++i) {
    const auto& t = m.triangles[pick(rng)];
    double a = u(rng), b = u(rng);
    if (a + b > 1.0) {
      a = 1.0 - a;
      b = 1.0 - b;
    }
    out.push_back(m.vertices[t[0]] + a * (m.vertices[t[1]] - m.vertices[t[0]]) +
                  b * (m.vertices[t[2]] - m.vertices[t[0]]));
  }
  return out;
}

// Points of the solid of a closed mesh: lines along x through random (y, z) cross the surface
// at sorted abscissae, and the segments between the 1st and 2nd, 3rd and 4th, ... crossing are
// inside. A line passing within 1e-9 (barycentric) of a triangle edge is drawn again.
std::vector<Vector3d> solidSamples(const TriangleMesh& m, int n, std::mt19937_64& rng) {
  Vector3d lo = m.vertices[0], hi = lo;
  for (const auto& v : m.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  std::uniform_real_distribution<double> uy(lo.y(), hi.y()), uz(lo.z(), hi.z()), u(0.0, 1.0);
  std::vector<Vector3d> out;
  int lines = 0;
  while (static_cast<int>(out.size()) < n && lines < 100 * n) {
    ++lines;
    const double y = uy(rng), z = uz(rng);
    std::vector<double> xs;
    bool clean = true;
    for (const auto& t : m.triangles) {
      const Vector3d &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
      const double det = (b.y() - a.y()) * (c.z() - a.z()) - (c.y() - a.y()) * (b.z() - a.z());
      if (det == 0.0) continue;
      const double l1 = ((y - a.y()) * (c.z() - a.z()) - (c.y() - a.y()) * (z - a.z())) / det;
      const double l2 = ((b.y() - a.y()) * (z - a.z()) - (y - a.y()) * (b.z() - a.z())) / det;
      const double l0 = 1.0 - l1 - l2;
      if (l0 < -1e-9 || l1 < -1e-9 || l2 < -1e-9) continue;
      if (l0 < 1e-9 || l1 < 1e-9 || l2 < 1e-9) {
        clean = false;
        break;
      }
      xs.push_back(l0 * a.x() + l1 * b.x() + l2 * c.x());
    }
    if (!clean || xs.size() % 2 != 0 || xs.empty()) continue;
    std::sort(xs.begin(), xs.end());
    for (int k = 0; k < 20; ++k) {
      const std::size_t seg =
          2 * std::uniform_int_distribution<std::size_t>(0, xs.size() / 2 - 1)(rng);
      out.emplace_back(xs[seg] + u(rng) * (xs[seg + 1] - xs[seg]), y, z);
    }
  }
  return out;
}

struct Facet {
  Vector3d n, a;
};

std::vector<Facet> facetsOf(const std::vector<Vector3d>& points) {
  const TriangleMesh t =
      dss::mesh::tessellate(dss::AnyShape(dss::mesh::convexHull(points, "test hull")));
  std::vector<Facet> fs;
  for (const auto& tri : t.triangles) {
    const Vector3d& a = t.vertices[tri[0]];
    const Vector3d n = (t.vertices[tri[1]] - a).cross(t.vertices[tri[2]] - a);
    if (n.norm() > 0.0) fs.push_back({n.normalized(), a});
  }
  return fs;
}

// Point-in-piece decisions: a point strictly inside every facet plane of a piece's qhull hull,
// by a margin far above rounding, is inside it (the facets form a closed surface around it).
// Any other point asks exact DSS whether it is within `padding` of the piece.
class Coverage {
 public:
  explicit Coverage(const std::vector<ConvexPiece>& pieces) {
    for (const auto& p : pieces) {
      Entry e{dss::AnyShape(dss::mesh::convexHull(p.points, "piece")), facetsOf(p.points),
              p.points[0], p.points[0], 0.0};
      for (const auto& q : p.points) {
        e.lo = e.lo.cwiseMin(q);
        e.hi = e.hi.cwiseMax(q);
      }
      e.margin = 1e-9 * (e.hi - e.lo).norm();
      entries_.push_back(std::move(e));
    }
  }

  bool covers(const Vector3d& p, double padding) const {
    const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
    for (const Entry& e : entries_) {
      const double grow = padding + e.margin;
      if ((p.array() < e.lo.array() - grow).any() || (p.array() > e.hi.array() + grow).any())
        continue;
      const double margin = e.margin + 1e-13 * p.cwiseAbs().maxCoeff();
      bool strictly = !e.facets.empty();
      for (const Facet& f : e.facets)
        if (f.n.dot(p - f.a) >= -margin) {
          strictly = false;
          break;
        }
      if (strictly) return true;
      dss::Options opt;
      opt.max_iterations = 10000;
      const dss::Result r = dss::intersect(dss::AnyShape(dss::ConvexHull(std::vector<Vector3d>{p})),
                                           I, e.hull, I, opt, padding);
      BOOST_REQUIRE(r.status == dss::Status::kDecided);
      if (r.intersect) return true;
    }
    return false;
  }

 private:
  struct Entry {
    dss::AnyShape hull;
    std::vector<Facet> facets;
    Vector3d lo, hi;
    double margin;
  };
  std::vector<Entry> entries_;
};

// d(x): 0 inside the solid of a closed mesh, the distance to the surface otherwise.
double distanceToSolid(const TriangleMesh& m, bool closed, const Vector3d& x) {
  if (closed && dss::mesh::insideSolid(m, x)) return 0.0;
  return dss::mesh::distanceToMesh(m, x);
}

struct CheckCounts {
  int surface = 0, solid = 0;
};

// The properties every decomposition must have: vertices, surface and (closed) solid covered;
// piece points in the mesh's hull; each piece's concavity an upper bound of d over random points
// of it; the reported maxima consistent.
CheckCounts checkDecomposition(const TriangleMesh& m, const Decomposition& d, int samples,
                               int per_piece, std::uint64_t seed) {
  CheckCounts counts;
  BOOST_REQUIRE(!d.pieces.empty());
  const double size = meshSize(m);
  // Rounding of a sample point computed on a triangle or along a line: far below 1e-12.
  const double sample_pad = 1e-12 * (size + reach(m));
  const Coverage cover(d.pieces);
  int misses = 0;
  for (std::size_t i = 0; i < m.vertices.size(); ++i)
    if (!cover.covers(m.vertices[i], 0.0)) {
      ++misses;
      BOOST_TEST_MESSAGE("vertex " << i << " uncovered");
    }
  BOOST_TEST(misses == 0);
  std::mt19937_64 rng(seed);
  misses = 0;
  for (const Vector3d& p : surfaceSamples(m, samples, rng)) {
    ++counts.surface;
    if (!cover.covers(p, sample_pad)) ++misses;
  }
  BOOST_TEST(misses == 0);
  if (d.closed) {
    misses = 0;
    for (const Vector3d& p : solidSamples(m, samples, rng)) {
      ++counts.solid;
      if (!cover.covers(p, sample_pad)) ++misses;
    }
    BOOST_TEST(misses == 0);
    BOOST_TEST(counts.solid >= samples);
  }
  // Piece points lie in the mesh's hull, up to rounding of the cut points.
  const std::vector<Facet> mesh_hull = facetsOf(m.vertices);
  double outside = 0.0;
  for (const auto& piece : d.pieces)
    for (const auto& p : piece.points)
      for (const Facet& f : mesh_hull) outside = std::max(outside, f.n.dot(p - f.a));
  BOOST_TEST(outside <= 1e-9 * size + 1e-13 * reach(m));
  // Honest concavities: random convex combinations of 2, 3 and 4 piece points.
  double worst = 0.0;
  for (const auto& piece : d.pieces) {
    BOOST_TEST(piece.concavity >= 0.0);
    BOOST_TEST(piece.concavity <= d.max_concavity);
    worst = std::max(worst, piece.concavity);
    std::uniform_int_distribution<std::size_t> pick(0, piece.points.size() - 1);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double excess = 0.0;
    for (int s = 0; s < per_piece; ++s) {
      const int k = 2 + s % 3;
      Vector3d x = Vector3d::Zero();
      double total = 0.0;
      for (int j = 0; j < k; ++j) {
        const double w = -std::log(1.0 - u(rng));
        x += w * piece.points[pick(rng)];
        total += w;
      }
      x /= total;
      excess = std::max(excess, distanceToSolid(m, d.closed, x) - piece.concavity);
    }
    BOOST_TEST(excess <= 1e-9 * size);
  }
  BOOST_TEST(d.max_concavity == worst);
  return counts;
}

Decomposition decompose(const TriangleMesh& m, double tolerance = 0.005, int max_pieces = 8) {
  DecompositionOptions o;
  o.tolerance = tolerance;
  o.max_pieces = max_pieces;
  return dss::mesh::decomposeConvex(m, o, "test mesh");
}

constexpr int kSamples = 100000;
constexpr int kPerPiece = 400;

}  // namespace

BOOST_AUTO_TEST_SUITE(convex_decomposition)

BOOST_AUTO_TEST_CASE(helpers_on_a_cube) {
  const TriangleMesh m = cube(1.0);
  BOOST_TEST(dss::mesh::isClosedManifold(m));
  BOOST_TEST(dss::mesh::isClosedManifold(unshared(m)));  // welded by coordinates
  BOOST_TEST(!dss::mesh::isClosedManifold(openBox()));
  TriangleMesh flipped_one = m;
  std::swap(flipped_one.triangles[0][1], flipped_one.triangles[0][2]);
  BOOST_TEST(!dss::mesh::isClosedManifold(flipped_one));
  TriangleMesh inward = m;
  for (auto& t : inward.triangles) std::swap(t[1], t[2]);
  BOOST_TEST(dss::mesh::isClosedManifold(inward));

  const Vector3d centre(0.5, 0.5, 0.5), out(1.5, 0.5, 0.5);
  BOOST_TEST(std::abs(dss::mesh::windingNumber(m, centre) - 1.0) < 1e-12);
  BOOST_TEST(std::abs(dss::mesh::windingNumber(m, out)) < 1e-12);
  BOOST_TEST(std::abs(dss::mesh::windingNumber(inward, centre) + 1.0) < 1e-12);
  BOOST_TEST(dss::mesh::insideSolid(m, centre));
  BOOST_TEST(dss::mesh::insideSolid(inward, centre));
  BOOST_TEST(!dss::mesh::insideSolid(m, out));
  BOOST_TEST(dss::mesh::insideSolid(m, Vector3d(1.0 - 1e-9, 0.999, 1e-9)));
  BOOST_TEST(!dss::mesh::insideSolid(m, Vector3d(1.0 + 1e-9, 0.5, 0.5)));

  Vector3d nearest;
  BOOST_TEST(std::abs(dss::mesh::distanceToMesh(m, out, &nearest) - 0.5) < 1e-15);
  BOOST_TEST((nearest - Vector3d(1.0, 0.5, 0.5)).norm() < 1e-15);
  BOOST_TEST(std::abs(dss::mesh::distanceToMesh(m, Vector3d(2, 2, 2)) - std::sqrt(3.0)) < 1e-15);
  BOOST_TEST(std::abs(dss::mesh::distanceToMesh(m, centre) - 0.5) < 1e-15);
  // A vertex no triangle uses is part of the mesh.
  TriangleMesh extra = m;
  extra.vertices.emplace_back(3, 0, 0);
  BOOST_TEST(std::abs(dss::mesh::distanceToMesh(extra, Vector3d(3, 0, 1)) - 1.0) < 1e-15);
}

BOOST_AUTO_TEST_CASE(cube_is_one_piece) {
  const TriangleMesh m = cube(0.1);
  const Decomposition d = decompose(m);
  BOOST_TEST(d.closed);
  BOOST_TEST(d.pieces.size() == 1u);
  BOOST_TEST(d.max_concavity < 1e-6);
  BOOST_TEST(d.hull_concavity < 1e-6);
  checkDecomposition(m, d, kSamples, kPerPiece, 1);
}

BOOST_AUTO_TEST_CASE(l_shape_is_split_at_its_corner) {
  const TriangleMesh m = lShape();
  const Decomposition d = decompose(m);
  BOOST_TEST_MESSAGE("L: " << d.pieces.size() << " pieces, concavity " << d.max_concavity
                           << " (hull " << d.hull_concavity << ")");
  BOOST_TEST(d.closed);
  BOOST_TEST(d.hull_concavity > 0.05);  // the hull bridges the 150 mm notch
  BOOST_TEST(d.pieces.size() >= 2u);
  BOOST_TEST(d.pieces.size() <= 3u);
  BOOST_TEST(d.max_concavity <= 0.005);
  checkDecomposition(m, d, kSamples, kPerPiece, 2);
  // The checker can say no: the notch, inside the single hull, is in no piece.
  const Coverage cover(d.pieces);
  BOOST_TEST(!cover.covers(Vector3d(0.12, 0.12, 0.025), 0.0));
  BOOST_TEST(!cover.covers(Vector3d(0.06, 0.06, 0.025), 0.0));
  BOOST_TEST(cover.covers(Vector3d(0.04, 0.04, 0.025), 0.0));
}

BOOST_AUTO_TEST_CASE(u_shape_and_frame_meet_the_tolerance) {
  for (const bool ring : {false, true}) {
    const TriangleMesh m = ring ? frame() : uShape();
    const Decomposition d = decompose(m);
    BOOST_TEST_MESSAGE((ring ? "frame: " : "U: ")
                       << d.pieces.size() << " pieces, concavity " << d.max_concavity);
    BOOST_TEST(d.closed);
    BOOST_TEST(d.pieces.size() >= (ring ? 4u : 2u));
    BOOST_TEST(d.pieces.size() <= 8u);
    BOOST_TEST(d.max_concavity <= 0.005);
    checkDecomposition(m, d, kSamples, kPerPiece, ring ? 4 : 3);
    // The hole (the gap) is left open.
    const Coverage cover(d.pieces);
    BOOST_TEST(!cover.covers(ring ? Vector3d(0.08, 0.08, 0.02) : Vector3d(0.06, 0.1, 0.02), 0.0));
  }
}

BOOST_AUTO_TEST_CASE(narrow_slot_and_thin_plate_stay_whole) {
  // Nothing of the slot's hull is farther than 1 mm from the block: within the tolerance.
  const TriangleMesh s = slot();
  const Decomposition ds = decompose(s);
  BOOST_TEST(ds.pieces.size() == 1u);
  BOOST_TEST(ds.max_concavity <= 0.005);
  BOOST_TEST(ds.hull_concavity >= 0.001 - 1e-9);  // the slot's half-width, at least
  checkDecomposition(s, ds, kSamples, kPerPiece, 5);

  const TriangleMesh p = plate();
  const Decomposition dp = decompose(p);
  BOOST_TEST(dp.closed);
  BOOST_TEST(dp.pieces.size() == 1u);
  BOOST_TEST(dp.max_concavity < 1e-6);
  checkDecomposition(p, dp, kSamples, kPerPiece, 6);
}

BOOST_AUTO_TEST_CASE(open_mesh_covers_its_surface) {
  const TriangleMesh m = openBox();
  const Decomposition d = decompose(m);
  BOOST_TEST(!d.closed);
  BOOST_TEST(d.pieces.size() <= 8u);
  // Without a solid, the inside of the box is 50 mm from the nearest wall at its top centre.
  BOOST_TEST(d.hull_concavity >= 0.05 - 1e-9);
  BOOST_TEST(d.max_concavity < d.hull_concavity);
  const CheckCounts c = checkDecomposition(m, d, kSamples, kPerPiece, 7);
  BOOST_TEST(c.solid == 0);
}

BOOST_AUTO_TEST_CASE(cap_on_pieces_is_honoured) {
  const TriangleMesh m = frame();
  for (int cap : {1, 2, 3}) {
    const Decomposition d = decompose(m, 0.005, cap);
    BOOST_TEST(static_cast<int>(d.pieces.size()) <= cap);
    BOOST_TEST(d.max_concavity > 0.005);  // a frame needs four pieces
    checkDecomposition(m, d, kSamples / 10, kPerPiece, 10 + cap);
  }
}

BOOST_AUTO_TEST_CASE(offsets_and_scales_change_nothing_but_units) {
  const TriangleMesh base = lShape();
  const Decomposition d0 = decompose(base);
  struct Case {
    double scale;
    Vector3d offset;
  };
  for (const Case& c : {Case{1.0, Vector3d(1e3, -1e3, 1e3)}, Case{1e-3, Vector3d::Zero()},
                        Case{1e3, Vector3d::Zero()}, Case{1e-3, Vector3d(1.0, 2.0, -3.0)}}) {
    const TriangleMesh m = transformed(base, c.scale, c.offset);
    const Decomposition d = decompose(m, 0.005 * c.scale);
    BOOST_TEST_MESSAGE("scale " << c.scale << " offset " << c.offset.transpose() << ": "
                                << d.pieces.size() << " pieces, concavity " << d.max_concavity);
    BOOST_TEST(d.closed);
    BOOST_TEST(d.pieces.size() == d0.pieces.size());
    BOOST_TEST(d.max_concavity <= 0.005 * c.scale);
    checkDecomposition(m, d, kSamples / 4, kPerPiece, 20);
  }
}

BOOST_AUTO_TEST_CASE(stl_style_unshared_vertices_and_unused_vertices) {
  TriangleMesh m = unshared(uShape());
  m.vertices.emplace_back(0.3, 0.3, 0.3);  // used by no triangle: still covered
  const Decomposition d = decompose(m);
  BOOST_TEST(d.closed);
  checkDecomposition(m, d, kSamples / 4, kPerPiece, 30);
}

BOOST_AUTO_TEST_CASE(points_without_triangles) {
  std::mt19937_64 rng(50);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  TriangleMesh m;
  for (int i = 0; i < 40; ++i) m.vertices.emplace_back(u(rng), u(rng), u(rng));
  const Decomposition d = decompose(m);
  BOOST_TEST(!d.closed);
  BOOST_TEST(d.pieces.size() <= 8u);
  const Coverage cover(d.pieces);
  for (const auto& v : m.vertices) BOOST_TEST(cover.covers(v, 0.0));
  for (const auto& piece : d.pieces)
    for (int s = 0; s < 200; ++s) {
      // Random points of the piece are within its concavity of the nearest mesh point.
      Vector3d x = Vector3d::Zero();
      double total = 0.0;
      for (int j = 0; j < 3; ++j) {
        const double w = -std::log(1.0 - std::uniform_real_distribution<double>(0, 1)(rng));
        x += w * piece.points[std::uniform_int_distribution<std::size_t>(
                     0, piece.points.size() - 1)(rng)];
        total += w;
      }
      x /= total;
      BOOST_TEST(dss::mesh::distanceToMesh(m, x) <= piece.concavity + 1e-12);
    }
}

BOOST_AUTO_TEST_CASE(reruns_are_identical) {
  const TriangleMesh m = frame();
  const Decomposition a = decompose(m), b = decompose(m);
  BOOST_REQUIRE(a.pieces.size() == b.pieces.size());
  for (std::size_t i = 0; i < a.pieces.size(); ++i) {
    BOOST_TEST(a.pieces[i].concavity == b.pieces[i].concavity);
    BOOST_TEST(a.pieces[i].points == b.pieces[i].points);
  }
  BOOST_TEST(a.hull_concavity == b.hull_concavity);
}

BOOST_AUTO_TEST_CASE(bad_input_names_the_mesh) {
  DecompositionOptions o;
  auto message = [&](const TriangleMesh& m, const DecompositionOptions& opt) {
    return dss_test::thrownMessage([&] { dss::mesh::decomposeConvex(m, opt, "link7.stl"); });
  };
  BOOST_TEST(message(TriangleMesh{}, o).find("link7.stl") != std::string::npos);
  TriangleMesh nan = cube(1.0);
  nan.vertices[3].y() = std::nan("");
  BOOST_TEST(message(nan, o).find("link7.stl") != std::string::npos);
  TriangleMesh bad_index = cube(1.0);
  bad_index.triangles[2][1] = 8;
  BOOST_TEST(message(bad_index, o).find("triangle 2") != std::string::npos);
  for (double t : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    DecompositionOptions bad;
    bad.tolerance = t;
    const std::string msg = message(cube(1.0), bad);
    BOOST_TEST(msg.find("link7.stl") != std::string::npos);
    BOOST_TEST(msg.find("tolerance") != std::string::npos);
  }
  DecompositionOptions zero;
  zero.max_pieces = 0;
  BOOST_TEST(message(cube(1.0), zero).find("max_pieces") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(ur5_arm_links, DSS_NEEDS_SHARED) {
  for (const char* name : {"upperarm", "forearm"}) {
    const std::string path = dss_test::sharedPath(
        std::string("robots/ur_description/meshes/ur5/collision/") + name + ".stl");
    const TriangleMesh m = dss::mesh::loadMesh(path);
    const auto start = std::chrono::steady_clock::now();
    const Decomposition d = decompose(m);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::ostringstream pieces;
    for (const auto& p : d.pieces) pieces << " " << p.concavity * 1e3;
    BOOST_TEST_MESSAGE(name << ": " << m.triangles.size() << " triangles, " << d.pieces.size()
                            << " pieces, concavity " << d.max_concavity * 1e3 << " mm (hull "
                            << d.hull_concavity * 1e3 << " mm), pieces [mm]:" << pieces.str()
                            << ", " << seconds << " s");
    BOOST_TEST(d.closed);
    BOOST_TEST(d.pieces.size() <= 8u);
    // The single hull reaches about 40 mm over the neighbours; the pieces cut that several-fold.
    BOOST_TEST(d.hull_concavity > 0.03);
    BOOST_TEST(d.max_concavity < d.hull_concavity / 3);
    checkDecomposition(m, d, kSamples, kPerPiece / 2, 40);
  }
}

BOOST_AUTO_TEST_SUITE_END()
