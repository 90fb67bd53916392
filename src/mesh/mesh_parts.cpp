// Connected parts of a triangle mesh (see mesh_parts.h).
#include "dss/mesh/mesh_parts.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "dss/mesh/convex_decomposition.h"
#include "welded_ids.h"

namespace dss::mesh {

namespace {

int findRoot(std::vector<int>& parent, int a) {
  while (parent[a] != a) {
    parent[a] = parent[parent[a]];
    a = parent[a];
  }
  return a;
}

}  // namespace

namespace detail {

std::vector<int> weldedIds(const std::vector<Eigen::Vector3d>& v) {
  auto less = [&](int a, int b) {
    return std::lexicographical_compare(v[a].data(), v[a].data() + 3, v[b].data(), v[b].data() + 3);
  };
  std::vector<int> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return less(a, b) || (v[a] == v[b] && a < b); });
  std::vector<int> id(v.size());
  int next = -1;
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (i == 0 || v[order[i]] != v[order[i - 1]]) ++next;
    id[order[i]] = next;
  }
  return id;
}

}  // namespace detail

std::vector<std::vector<Eigen::Vector3d>> meshParts(const TriangleMesh& mesh, std::size_t max_parts,
                                                    const std::string& what) {
  const std::vector<Eigen::Vector3d>& v = mesh.vertices;
  if (v.empty()) throw std::runtime_error(what + ": mesh has no vertices");
  if (max_parts == 0) throw std::runtime_error(what + ": at most 0 mesh parts asked for");
  for (const auto& p : v)
    if (!p.allFinite()) throw std::runtime_error(what + ": non-finite mesh vertex");
  const int n = static_cast<int>(v.size());
  for (const auto& t : mesh.triangles)
    for (int i : t)
      if (i < 0 || i >= n)
        throw std::runtime_error(what + ": triangle index " + std::to_string(i) +
                                 " out of range (" + std::to_string(n) + " vertices)");

  // Vertices with equal coordinates become one point: `point[i]` for vertex i.
  const std::vector<int> point = detail::weldedIds(v);
  const int points = *std::max_element(point.begin(), point.end()) + 1;
  std::vector<int> first_vertex(points);  // point -> a vertex holding it
  for (int i = n - 1; i >= 0; --i) first_vertex[point[i]] = i;

  std::vector<int> parent(points);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<char> used(points, 0);
  for (const auto& t : mesh.triangles) {
    const int a = findRoot(parent, point[t[0]]);
    used[point[t[0]]] = used[point[t[1]]] = used[point[t[2]]] = 1;
    for (int k = 1; k < 3; ++k) {
      const int b = findRoot(parent, point[t[k]]);
      if (a != b) parent[b] = a;
    }
  }
  // Parts numbered in the order of their first triangle; unused points last.
  std::vector<int> part_of_root(points, -1);
  int parts = 0;
  for (const auto& t : mesh.triangles) {
    int& id = part_of_root[findRoot(parent, point[t[0]])];
    if (id < 0) id = parts++;
  }
  // Each point's set: its part, or `parts` for the unused points (one more set when any).
  std::vector<int> set_of(points);
  bool any_unused = false;
  for (int p = 0; p < points; ++p) {
    set_of[p] = used[p] ? part_of_root[findRoot(parent, p)] : parts;
    any_unused |= !used[p];
  }
  const std::size_t sets = std::size_t(parts) + (any_unused ? 1 : 0);

  // Beyond the cap, sets are joined in runs along the longest side of the bounding box, by
  // their centroids (per-set sums: no per-set storage for meshes of very many parts).
  std::vector<std::size_t> group(sets);
  std::size_t groups = sets;
  if (sets > max_parts) {
    Eigen::Vector3d lo = v[0], hi = v[0];
    for (const auto& p : v) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    int axis = 0;
    (hi - lo).maxCoeff(&axis);
    std::vector<double> sum(sets, 0.0);
    std::vector<std::size_t> count(sets, 0);
    for (int p = 0; p < points; ++p) {
      sum[set_of[p]] += v[first_vertex[p]][axis];
      ++count[set_of[p]];
    }
    std::vector<std::size_t> by_key(sets);
    std::iota(by_key.begin(), by_key.end(), std::size_t(0));
    std::stable_sort(by_key.begin(), by_key.end(), [&](std::size_t x, std::size_t y) {
      return sum[x] / double(count[x]) < sum[y] / double(count[y]);
    });
    for (std::size_t k = 0; k < sets; ++k) group[by_key[k]] = k * max_parts / sets;
    groups = max_parts;
  } else {
    std::iota(group.begin(), group.end(), std::size_t(0));
  }
  std::vector<std::vector<Eigen::Vector3d>> out(groups);
  for (int p = 0; p < points; ++p) out[group[set_of[p]]].push_back(v[first_vertex[p]]);
  return out;
}

double hullExcess(const TriangleMesh& mesh, const dss::ConvexHull& hull, std::size_t max_work) {
  const std::size_t per_sample = mesh.triangles.size() + mesh.vertices.size();
  if (mesh.triangles.empty() || per_sample > max_work) return 0.0;
  // Samples on the hull's surface: each facet triangle's centroid and edge midpoints.
  const TriangleMesh surface = tessellate(dss::AnyShape(hull));
  std::vector<Eigen::Vector3d> samples;
  samples.reserve(4 * surface.triangles.size());
  for (const auto& t : surface.triangles) {
    const Eigen::Vector3d& a = surface.vertices[t[0]];
    const Eigen::Vector3d& b = surface.vertices[t[1]];
    const Eigen::Vector3d& c = surface.vertices[t[2]];
    samples.push_back((a + b + c) / 3.0);
    samples.push_back(0.5 * (a + b));
    samples.push_back(0.5 * (b + c));
    samples.push_back(0.5 * (c + a));
  }
  const std::size_t budget = std::max<std::size_t>(1, max_work / per_sample);
  const std::size_t n = samples.size();
  const std::size_t stride = n > budget ? (n + budget - 1) / budget : 1;
  double excess = 0.0;
  for (std::size_t i = 0; i < n; i += stride)
    excess = std::max(excess, distanceToMesh(mesh, samples[i]));
  return excess;
}

}  // namespace dss::mesh
