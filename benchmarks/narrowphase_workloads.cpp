// Generation of the section-6 workloads. Everything is drawn from one seeded std::mt19937_64
// per (workload, spread), so a run is reproducible on a given standard library.
#include "narrowphase_workloads.h"

#include <cmath>
#include <map>
#include <random>
#include <set>
#include <stdexcept>

#include "qhull_faces.h"

namespace dss {
namespace bench {

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Rng {
  std::mt19937_64 engine;
  explicit Rng(std::uint64_t seed) : engine(seed) {}
  double uniform(double lo, double hi) {
    // 53 random bits, exactly representable: independent of the library's distributions.
    const double u = double(engine() >> 11) * (1.0 / 9007199254740992.0);
    return lo + (hi - lo) * u;
  }
  Vec3d onSphere() {
    for (;;) {
      const Vec3d v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
      const double n2 = v.squaredNorm();
      if (n2 > 1e-6 && n2 <= 1.0) return v / std::sqrt(n2);
    }
  }
  Vec3d inBall(double radius) {
    for (;;) {
      const Vec3d v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
      if (v.squaredNorm() <= 1.0) return radius * v;
    }
  }
  Mat3d rotation() {  // uniform on SO(3) (Shoemake)
    const double u1 = uniform(0, 1), u2 = uniform(0, 2 * kPi), u3 = uniform(0, 2 * kPi);
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    const Eigen::Quaterniond q(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2),
                               b * std::sin(u3));
    return q.normalized().toRotationMatrix();
  }
};

double orient(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  return (b - a).cross(c - a).dot(d - a);
}

Polytope tetrahedron(Rng& rng, double shift) {
  std::vector<Vec3d> p(4);
  // The paper makes every tetrahedron contain the origin, so that sigma = 0 gives 100 %.
  for (;;) {
    for (auto& x : p) x = rng.onSphere();
    const Vec3d o = Vec3d::Zero();
    const double s = orient(p[0], p[1], p[2], p[3]);
    if (std::abs(s) < 1e-3) continue;
    if (orient(o, p[1], p[2], p[3]) * s > 0 && orient(p[0], o, p[2], p[3]) * s > 0 &&
        orient(p[0], p[1], o, p[3]) * s > 0 && orient(p[0], p[1], p[2], o) * s > 0)
      break;
  }
  Polytope t;
  for (auto& x : p) t.vertices.push_back(x + Vec3d(shift, 0, 0));
  t.triangles = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  const Vec3d c = 0.25 * (t.vertices[0] + t.vertices[1] + t.vertices[2] + t.vertices[3]);
  orientOutward(t.vertices, c, t.triangles);
  t.finishTopology();
  return t;
}

Polytope randomPolytope(Rng& rng, int vertices, double shift) {
  for (;;) {
    std::vector<Vec3d> p(vertices);
    for (auto& x : p) x = rng.onSphere();
    Polytope t;
    for (auto& x : p) t.vertices.push_back(x + Vec3d(shift, 0, 0));
    t.triangles = hullTriangles(t.vertices);
    // Every point must be a hull vertex (true with probability 1 on the sphere; checked so
    // that hill-climbing's precondition holds) and the unshifted hull must contain the origin.
    std::set<int> used;
    for (const auto& tri : t.triangles) used.insert(tri.begin(), tri.end());
    if (int(used.size()) != vertices) continue;
    bool contains_origin = true;
    for (const auto& tri : t.triangles)
      if (orient(p[tri[0]], p[tri[1]], p[tri[2]], Vec3d::Zero()) >= 0) contains_origin = false;
    if (!contains_origin) continue;
    t.finishTopology();
    return t;
  }
}

}  // namespace

void Polytope::finishTopology() {
  std::map<std::pair<int, int>, std::vector<int>> opposite;
  std::map<std::pair<int, int>, std::vector<Vec3d>> normals;
  for (const auto& t : triangles) {
    const Vec3d n =
        (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]).normalized();
    for (int k = 0; k < 3; ++k) {
      int a = t[k], b = t[(k + 1) % 3];
      if (a > b) std::swap(a, b);
      opposite[{a, b}].push_back(t[(k + 2) % 3]);
      normals[{a, b}].push_back(n);
    }
  }
  edges.clear();
  neighbours.assign(vertices.size(), {});
  for (const auto& [key, opp] : opposite) {
    if (opp.size() != 2)
      throw std::runtime_error("Polytope: hull edge not shared by two triangles");
    const auto& nrm = normals[key];
    edges.push_back(Edge{key.first, key.second, {opp[0], opp[1]}, {nrm[0], nrm[1]}});
    neighbours[key.first].push_back(key.second);
    neighbours[key.second].push_back(key.first);
  }
}

const char* workloadName(WorkloadKind kind) {
  switch (kind) {
    case WorkloadKind::kTetrahedra:
      return "tetra";
    case WorkloadKind::kBoxes:
      return "boxes";
    case WorkloadKind::kPolytopes:
      return "poly16";
    case WorkloadKind::kFrustumSpheres:
      return "frustum-spheres";
    case WorkloadKind::kFrustumBoxes:
      return "frustum-boxes";
  }
  return "?";
}

std::vector<double> defaultSigmas(WorkloadKind kind) {
  switch (kind) {
    case WorkloadKind::kTetrahedra:
      return {0.0, 0.8, 1.5, 2.5, 5.0, 15.0, 200.0};
    case WorkloadKind::kBoxes:
      return {0.2, 0.5, 1.0, 1.6, 2.5, 4.0, 10.0};
    case WorkloadKind::kPolytopes:
      return {0.0, 2.0, 3.0, 4.0, 8.0, 20.0, 150.0};
    case WorkloadKind::kFrustumSpheres:
    case WorkloadKind::kFrustumBoxes:
      return {1.0, 1.3, 1.7, 2.2, 3.0, 4.5, 6.5};
  }
  return {};
}

double sweepSigma() { return 5.0; }

void paperFrustum(std::vector<Vec3d>& vertices, Vec3d& inscribed_center, double& inscribed_radius) {
  const double near = 0.1, far = 100.0;
  const double tan_h = std::tan(40.0 * kPi / 180.0);  // half of the 80 degree horizontal FOV
  const double tan_v = tan_h * 9.0 / 16.0;            // 16:9
  vertices.clear();
  for (double z : {near, far})
    for (double sy : {-1.0, 1.0})
      for (double sx : {-1.0, 1.0}) vertices.emplace_back(sx * z * tan_h, sy * z * tan_v, z);
  // The largest inscribed sphere touches the top and bottom planes (the narrower pair) and the
  // far plane: centre (0, 0, c) with c sin(beta) = far - c; the near plane is then far away.
  const double sin_v = tan_v / std::sqrt(1 + tan_v * tan_v);
  const double c = far / (1 + sin_v);
  inscribed_center = Vec3d(0, 0, c);
  inscribed_radius = std::min({c * sin_v, far - c, c - near});
}

WorkloadSet makeWorkload(WorkloadKind kind, double sigma, int n, std::uint64_t seed, int vertices) {
  WorkloadSet w;
  w.kind = kind;
  w.name = workloadName(kind);
  w.sigma = sigma;
  // One stream per (workload, spread, vertex count).
  std::uint64_t s = seed * 0x9E3779B97F4A7C15ull + std::uint64_t(kind) * 1000003ull +
                    std::uint64_t(std::llround(sigma * 1e6)) * 7919ull + std::uint64_t(vertices);
  Rng rng(s);
  auto allPairs = [&](int count) {
    w.pairs.reserve(std::size_t(count) * (count - 1) / 2);
    for (int i = 0; i < count; ++i)
      for (int j = i + 1; j < count; ++j) w.pairs.emplace_back(i, j);
  };
  switch (kind) {
    case WorkloadKind::kTetrahedra:
    case WorkloadKind::kPolytopes: {
      w.a_kind = w.b_kind = SideKind::kPolytope;
      w.same_set = true;
      w.vertex_count = kind == WorkloadKind::kTetrahedra ? 4 : vertices;
      if (kind == WorkloadKind::kPolytopes && vertices != 16)
        w.name = "poly" + std::to_string(vertices);
      for (int i = 0; i < n; ++i) {
        const double shift = rng.uniform(0, sigma);
        w.a_polytopes.push_back(kind == WorkloadKind::kTetrahedra
                                    ? tetrahedron(rng, shift)
                                    : randomPolytope(rng, vertices, shift));
      }
      allPairs(n);
      break;
    }
    case WorkloadKind::kBoxes: {
      w.a_kind = w.b_kind = SideKind::kBox;
      w.same_set = true;
      for (int i = 0; i < n; ++i) {
        OrientedBox b;
        b.half = Vec3d(rng.uniform(0, 1), rng.uniform(0, 1), rng.uniform(0, 1));
        b.p_WB = Vec3d(rng.uniform(-sigma / 2, sigma / 2), rng.uniform(-sigma / 2, sigma / 2),
                       rng.uniform(-sigma / 2, sigma / 2));
        b.R_WB = rng.rotation();
        w.a_boxes.push_back(b);
      }
      allPairs(n);
      break;
    }
    case WorkloadKind::kFrustumSpheres:
    case WorkloadKind::kFrustumBoxes: {
      w.a_kind = SideKind::kPolytope;
      w.b_kind = kind == WorkloadKind::kFrustumSpheres ? SideKind::kBall : SideKind::kBox;
      const int m = std::max(2, int(std::lround(n / std::sqrt(2.0))));
      std::vector<Vec3d> local;
      Vec3d c;
      double rho;
      paperFrustum(local, c, rho);
      for (int i = 0; i < m; ++i) {
        const Mat3d R = rng.rotation();
        Polytope f;
        for (const auto& v : local) f.vertices.push_back(R * (v - c));
        // Quads near, far, left, right, bottom, top, each split into two triangles.
        // Vertex index = iz * 4 + iy * 2 + ix.
        const int quads[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 2, 6, 4},
                                 {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}};
        for (const auto& q : quads) {
          f.triangles.push_back({q[0], q[1], q[2]});
          f.triangles.push_back({q[0], q[2], q[3]});
        }
        Vec3d centroid = Vec3d::Zero();
        for (const auto& v : f.vertices) centroid += v / 8.0;
        orientOutward(f.vertices, centroid, f.triangles);
        f.finishTopology();
        w.a_polytopes.push_back(std::move(f));
      }
      for (int i = 0; i < m; ++i) {
        const Vec3d p = rng.inBall(sigma * rho);
        if (kind == WorkloadKind::kFrustumSpheres) {
          w.b_balls.push_back(Ball{rng.uniform(0, 1), p});
        } else {
          OrientedBox b;
          b.half = 0.5 * Vec3d(rng.uniform(0, 1), rng.uniform(0, 1), rng.uniform(0, 1));
          b.p_WB = p;
          w.b_boxes.push_back(b);
        }
      }
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) w.pairs.emplace_back(i, j);
      break;
    }
  }
  return w;
}

}  // namespace bench
}  // namespace dss
