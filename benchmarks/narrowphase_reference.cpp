// Exact and long-double reference answers (see narrowphase_reference.h for the contract).
#include "narrowphase_reference.h"

#include <algorithm>
#include <atomic>
#include <boost/multiprecision/cpp_int.hpp>
#include <cmath>
#include <limits>

namespace dss {
namespace bench {

namespace {

std::atomic<std::uint64_t> g_exact_fallbacks{0};

using Rational = boost::multiprecision::cpp_rational;

/// Sign of det(u, v, w) with u = u1 - u0, v = v1 - v0, w = w1 - w0 (all doubles), exactly.
int detSign(const Vec3d& u0, const Vec3d& u1, const Vec3d& v0, const Vec3d& v1, const Vec3d& w0,
            const Vec3d& w1) {
  const Vec3d u = u1 - u0, v = v1 - v0, w = w1 - w0;
  const double m0 = v.y() * w.z() - v.z() * w.y();
  const double m1 = v.z() * w.x() - v.x() * w.z();
  const double m2 = v.x() * w.y() - v.y() * w.x();
  const double det = u.x() * m0 + u.y() * m1 + u.z() * m2;
  const double perm = std::abs(u.x()) * (std::abs(v.y() * w.z()) + std::abs(v.z() * w.y())) +
                      std::abs(u.y()) * (std::abs(v.z() * w.x()) + std::abs(v.x() * w.z())) +
                      std::abs(u.z()) * (std::abs(v.x() * w.y()) + std::abs(v.y() * w.x()));
  // Rounding of the three differences and of the products and sums is below ~8 u * perm
  // (u = 2^-53); 1e-14 leaves a wide margin. Subnormal and zero cases fall through.
  const double bound = 1e-14 * perm;
  if (perm > 1e-290) {
    if (det > bound) return 1;
    if (det < -bound) return -1;
  }
  g_exact_fallbacks.fetch_add(1, std::memory_order_relaxed);
  Rational U[3], V[3], W[3];
  for (int k = 0; k < 3; ++k) {
    U[k] = Rational(u1[k]) - Rational(u0[k]);
    V[k] = Rational(v1[k]) - Rational(v0[k]);
    W[k] = Rational(w1[k]) - Rational(w0[k]);
  }
  const Rational d = U[0] * (V[1] * W[2] - V[2] * W[1]) + U[1] * (V[2] * W[0] - V[0] * W[2]) +
                     U[2] * (V[0] * W[1] - V[1] * W[0]);
  return d > 0 ? 1 : (d < 0 ? -1 : 0);
}

/// Does the plane through a face of `p` (outward normal) strictly separate `q` from it?
bool faceSeparates(const Polytope& p, const Polytope& q) {
  for (const auto& t : p.triangles) {
    const Vec3d &a = p.vertices[t[0]], &b = p.vertices[t[1]], &c = p.vertices[t[2]];
    bool ok = true;
    for (const auto& y : q.vertices)
      if (detSign(a, b, a, c, a, y) <= 0) {
        ok = false;
        break;
      }
    if (!ok) continue;
    // The face plane must also support p (it does for an exact hull; checked, so that a
    // "disjoint" answer never rests on qhull's rounding).
    for (std::size_t k = 0; k < p.vertices.size(); ++k) {
      if (int(k) == t[0] || int(k) == t[1] || int(k) == t[2]) continue;  // on the plane: sign 0
      if (detSign(a, b, a, c, a, p.vertices[k]) > 0) {
        ok = false;
        break;
      }
    }
    if (ok) return true;
  }
  return false;
}

/// Side (+1 / -1) on which the polytope lies locally around an edge, relative to the plane
/// through the edge with normal u x v; 0 when the plane cuts the edge's wedge (or degenerate).
int edgeSide(const Polytope& p, const Polytope::Edge& e, const Vec3d& u0, const Vec3d& u1,
             const Vec3d& v0, const Vec3d& v1) {
  const Vec3d& base = p.vertices[e.a];
  const int s0 = detSign(u0, u1, v0, v1, base, p.vertices[e.opposite[0]]);
  const int s1 = detSign(u0, u1, v0, v1, base, p.vertices[e.opposite[1]]);
  if (s0 >= 0 && s1 >= 0 && (s0 | s1)) return 1;
  if (s0 <= 0 && s1 <= 0 && (s0 | s1)) return -1;
  return 0;
}

/// Gauss-map filter (arcs of the two edges' normals must cross for the pair to give a face
/// of the Minkowski difference; Gregorius, GDC 2013). Evaluated in double on rounded normals,
/// it only skips pairs that miss by far more than any rounding (kMargin); every pair it keeps
/// goes through the exact tests below.
bool clearlyNotMinkowskiFace(const Polytope::Edge& ea, const Vec3d& bxa, const Polytope::Edge& eb,
                             const Vec3d& dxc) {
  constexpr double kMargin = 1e-9;
  const double cba = -eb.normal[0].dot(bxa), dba = -eb.normal[1].dot(bxa);
  const double adc = ea.normal[0].dot(dxc), bdc = ea.normal[1].dot(dxc);
  auto pos = [](double v) { return v > kMargin; };
  auto neg = [](double v) { return v < -kMargin; };
  if ((pos(cba) && pos(dba)) || (neg(cba) && neg(dba))) return true;
  if ((pos(adc) && pos(bdc)) || (neg(adc) && neg(bdc))) return true;
  if ((pos(cba) && neg(bdc)) || (neg(cba) && pos(bdc))) return true;
  return false;
}

bool edgesSeparate(const Polytope& a, const Polytope& b) {
  std::vector<Vec3d> dxc(b.edges.size());
  for (std::size_t k = 0; k < b.edges.size(); ++k)
    dxc[k] = b.edges[k].normal[1].cross(b.edges[k].normal[0]);  // (-n1) x (-n0)
  for (const auto& ea : a.edges) {
    const Vec3d &a0 = a.vertices[ea.a], &a1 = a.vertices[ea.b];
    const Vec3d bxa = ea.normal[1].cross(ea.normal[0]);
    for (std::size_t kb = 0; kb < b.edges.size(); ++kb) {
      const auto& eb = b.edges[kb];
      if (clearlyNotMinkowskiFace(ea, bxa, eb, dxc[kb])) continue;
      const Vec3d &b0 = b.vertices[eb.a], &b1 = b.vertices[eb.b];
      // Only pairs whose planes support both polytopes from opposite sides can realise a face
      // of the Minkowski difference; this local test is a necessary condition of the full one.
      const int sa = edgeSide(a, ea, a0, a1, b0, b1);
      if (sa == 0) continue;
      const int sb = edgeSide(b, eb, a0, a1, b0, b1);
      if (sb != -sa) continue;
      bool ok = true;
      for (const auto& y : b.vertices)
        if (detSign(a0, a1, b0, b1, a0, y) * sa >= 0) {
          ok = false;
          break;
        }
      if (!ok) continue;
      for (std::size_t k = 0; k < a.vertices.size(); ++k) {
        if (int(k) == ea.a || int(k) == ea.b) continue;  // on the plane: sign 0
        if (detSign(a0, a1, b0, b1, a0, a.vertices[k]) * sa < 0) {
          ok = false;
          break;
        }
      }
      if (ok) return true;
    }
  }
  return false;
}

using Vec3L = Eigen::Matrix<long double, 3, 1>;

Vec3L toL(const Vec3d& v) { return v.cast<long double>(); }

struct LdPolytope {
  std::vector<Vec3L> vertices, normals, edges;
};

LdPolytope fromBox(const OrientedBox& b) {
  LdPolytope p;
  const Eigen::Matrix<long double, 3, 3> R = b.R_WB.cast<long double>();
  const Vec3L h = toL(b.half), c = toL(b.p_WB);
  for (int k = 0; k < 8; ++k) {
    const Vec3L s((k & 1) ? h.x() : -h.x(), (k & 2) ? h.y() : -h.y(), (k & 4) ? h.z() : -h.z());
    p.vertices.push_back(R * s + c);
  }
  for (int k = 0; k < 3; ++k) {
    p.normals.push_back(R.col(k));
    p.edges.push_back(R.col(k));
  }
  return p;
}

LdPolytope fromPolytope(const Polytope& q) {
  LdPolytope p;
  for (const auto& v : q.vertices) p.vertices.push_back(toL(v));
  for (const auto& t : q.triangles)
    p.normals.push_back(
        (p.vertices[t[1]] - p.vertices[t[0]]).cross(p.vertices[t[2]] - p.vertices[t[0]]));
  for (const auto& e : q.edges) p.edges.push_back(p.vertices[e.b] - p.vertices[e.a]);
  return p;
}

/// Largest separation over the candidate axes (extra axes are harmless: a positive
/// separation along any axis is a certificate).
long double satGap(const LdPolytope& a, const LdPolytope& b) {
  long double best = -std::numeric_limits<long double>::infinity();
  auto test = [&](const Vec3L& n) {
    const long double len = n.norm();
    if (!(len > 1e-30L)) return;
    long double amin = INFINITY, amax = -INFINITY, bmin = INFINITY, bmax = -INFINITY;
    for (const auto& x : a.vertices) {
      const long double d = n.dot(x);
      amin = std::min(amin, d);
      amax = std::max(amax, d);
    }
    for (const auto& y : b.vertices) {
      const long double d = n.dot(y);
      bmin = std::min(bmin, d);
      bmax = std::max(bmax, d);
    }
    best = std::max(best, std::max(bmin - amax, amin - bmax) / len);
  };
  for (const auto& n : a.normals) test(n);
  for (const auto& n : b.normals) test(n);
  for (const auto& ea : a.edges) {
    const long double la = ea.norm();
    for (const auto& eb : b.edges) {
      const Vec3L n = ea.cross(eb);
      // Nearly parallel edges: the face normals already cover the directions that matter.
      if (n.norm() > 1e-12L * la * eb.norm()) test(n);
    }
  }
  return best;
}

long double pointTriangleDistance(const Vec3L& p, const Vec3L& a, const Vec3L& b, const Vec3L& c) {
  // Closest point by Voronoi regions of the triangle (Ericson, Real-Time Collision
  // Detection 5.1.5).
  const Vec3L ab = b - a, ac = c - a, ap = p - a;
  const long double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Vec3L bp = p - b;
  const long double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const long double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).norm();
  const Vec3L cp = p - c;
  const long double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const long double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).norm();
  const long double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
  const long double denom = 1 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

long double scaleOf(const Polytope& p) {
  long double s = 1;
  for (const auto& v : p.vertices) s = std::max<long double>(s, v.cwiseAbs().maxCoeff());
  return s;
}

}  // namespace

bool polytopesIntersectExact(const Polytope& a, const Polytope& b) {
  if (faceSeparates(a, b) || faceSeparates(b, a)) return false;
  return !edgesSeparate(a, b);
}

long double boxBoxGap(const OrientedBox& a, const OrientedBox& b) {
  return satGap(fromBox(a), fromBox(b));
}

long double polytopeBoxGap(const Polytope& a, const OrientedBox& b) {
  return satGap(fromPolytope(a), fromBox(b));
}

long double polytopeBallGap(const Polytope& a, const Ball& b) {
  const LdPolytope p = fromPolytope(a);
  const Vec3L c = toL(b.p_WC);
  long double max_plane = -INFINITY;
  for (std::size_t k = 0; k < a.triangles.size(); ++k) {
    const Vec3L n = p.normals[k].normalized();
    max_plane = std::max(max_plane, n.dot(c - p.vertices[a.triangles[k][0]]));
  }
  long double dist;
  if (max_plane <= 0) {
    dist = max_plane;  // inside: minus the distance to the nearest face plane
  } else {
    dist = INFINITY;
    for (const auto& t : a.triangles)
      dist = std::min(
          dist, pointTriangleDistance(c, p.vertices[t[0]], p.vertices[t[1]], p.vertices[t[2]]));
  }
  return dist - (long double)b.radius;
}

std::vector<RefAnswer> referenceAnswers(const WorkloadSet& w) {
  std::vector<RefAnswer> out(w.pairs.size());
  auto classify = [](long double gap, long double scale) {
    if (std::abs(gap) <= kTieTolerance * scale) return RefAnswer::kTie;
    return gap > 0 ? RefAnswer::kDisjoint : RefAnswer::kIntersect;
  };
  for (std::size_t k = 0; k < w.pairs.size(); ++k) {
    const auto [i, j] = w.pairs[k];
    if (w.a_kind == SideKind::kPolytope && w.b_kind == SideKind::kPolytope) {
      out[k] = polytopesIntersectExact(w.a_polytopes[i], w.bPolytopes()[j]) ? RefAnswer::kIntersect
                                                                            : RefAnswer::kDisjoint;
    } else if (w.a_kind == SideKind::kBox && w.b_kind == SideKind::kBox) {
      const auto &a = w.a_boxes[i], &b = w.bBoxes()[j];
      const long double scale =
          1 + std::max(a.p_WB.cwiseAbs().maxCoeff(), b.p_WB.cwiseAbs().maxCoeff()) + 2;
      out[k] = classify(boxBoxGap(a, b), scale);
    } else if (w.a_kind == SideKind::kPolytope && w.b_kind == SideKind::kBox) {
      const Polytope& a = w.a_polytopes[i];
      const OrientedBox& b = w.bBoxes()[j];
      out[k] = classify(polytopeBoxGap(a, b), scaleOf(a) + b.p_WB.cwiseAbs().maxCoeff());
    } else {
      const auto& a = w.a_polytopes[i];
      const auto& b = w.b_balls[j];
      out[k] = classify(polytopeBallGap(a, b), scaleOf(a) + b.p_WC.cwiseAbs().maxCoeff());
    }
  }
  return out;
}

std::uint64_t exactFallbackCount() { return g_exact_fallbacks.load(); }

}  // namespace bench
}  // namespace dss
