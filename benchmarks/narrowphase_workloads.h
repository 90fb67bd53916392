// The narrow-phase workloads of Hornus 2017, section 6: random tetrahedra, oriented boxes,
// 16-vertex polytopes (and a vertex-count sweep), and a frustum against spheres and against
// axis-aligned boxes. Each workload at one spread sigma is generated once from a seed; the
// collision density falls as sigma grows.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "dss/core/types.h"

namespace dss {
namespace bench {

/// A convex polytope given by world vertices (the geometry every algorithm sees) and the
/// combinatorics of its hull: outward triangles, vertex adjacency, and each hull edge with the
/// two vertices opposite it in its adjacent triangles (for the exact separating-axis reference).
struct Polytope {
  struct Edge {
    int a, b;         // endpoints
    int opposite[2];  // third vertices of the two adjacent triangles
    Vec3d normal[2];  // unit outward normals of those triangles (rounded; a filter only)
  };
  std::vector<Vec3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::vector<int>> neighbours;
  std::vector<Edge> edges;

  /// Fills neighbours and edges from triangles. Throws if the triangles are not a closed
  /// two-manifold (every edge in exactly two triangles).
  void finishTopology();
};

struct OrientedBox {
  Vec3d half = Vec3d::Zero();
  Mat3d R_WB = Mat3d::Identity();
  Vec3d p_WB = Vec3d::Zero();
};

struct Ball {
  double radius = 0;
  Vec3d p_WC = Vec3d::Zero();
};

enum class WorkloadKind { kTetrahedra, kBoxes, kPolytopes, kFrustumSpheres, kFrustumBoxes };

/// What the A and B sides of each pair are.
enum class SideKind { kPolytope, kBox, kBall };

/// One workload at one spread. Pairs index `a_*` and `b_*`: for the all-pairs workloads both
/// sides refer to the same objects (stored once, in the A arrays, with `same_set` true).
struct WorkloadSet {
  WorkloadKind kind;
  std::string name;  // "tetra", "boxes", "poly16", "frustum-spheres", "frustum-boxes"
  double sigma = 0;
  int vertex_count = 0;  // polytope vertices (0 when not a polytope workload)
  SideKind a_kind, b_kind;
  bool same_set = false;
  std::vector<Polytope> a_polytopes, b_polytopes;
  std::vector<OrientedBox> a_boxes, b_boxes;
  std::vector<Ball> b_balls;
  std::vector<std::pair<int, int>> pairs;

  const std::vector<Polytope>& bPolytopes() const { return same_set ? a_polytopes : b_polytopes; }
  const std::vector<OrientedBox>& bBoxes() const { return same_set ? a_boxes : b_boxes; }
};

const char* workloadName(WorkloadKind kind);

/// The spreads used by default for each workload (chosen so that the densities run from about
/// 1 % to 100 %, with points near 60 % tetrahedra, 98 % boxes and 100 % polytopes, where the
/// absolute targets are set).
std::vector<double> defaultSigmas(WorkloadKind kind);

/// Spread giving about 50 % density for the vertex-count sweep.
double sweepSigma();

/// Generates the workload. `n` objects for the all-pairs workloads (n(n-1)/2 pairs); for the
/// frustum workloads round(n / sqrt 2) frusta and as many spheres or boxes, all pairs between
/// them (about the same pair count). Deterministic in (kind, sigma, n, vertices, seed).
WorkloadSet makeWorkload(WorkloadKind kind, double sigma, int n, std::uint64_t seed,
                         int vertices = 16);

/// The frustum of the paper in its camera frame (apex at the origin, looking along +z):
/// 80 degree horizontal field of view, 16:9, near 0.1, far 100. Returns the 8 vertices,
/// and the centre (on the axis) and radius of its largest inscribed sphere.
void paperFrustum(std::vector<Vec3d>& vertices, Vec3d& inscribed_center, double& inscribed_radius);

}  // namespace bench
}  // namespace dss
