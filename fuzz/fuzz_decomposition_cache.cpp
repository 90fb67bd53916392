// Fuzz target: the decomposition cache reader (dss::mesh::readCachedDecomposition), which
// reads files from a cache directory a user may share or tamper with. The mesh is an L-shaped
// closed block of our own (below); each input is written as the cache file of its key. Any
// bytes must end in "no usable file" or in a decomposition whose pieces are at most the cap,
// non-empty, finite, cover every mesh vertex (the reader checks it), and that formats and
// parses back to the same numbers, bit for bit. The seed in fuzz/seeds/ is this mesh's
// decomposition (tolerance 0.05, 4 pieces) at kDecompositionVersion 3; a file of another
// version is refused at its key line, so regenerate the seed when the version changes.
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "dss/mesh/decomposition_cache.h"
#include "fuzz_support.h"

namespace {

// An L of two boxes sharing a face: 12 vertices, 20 triangles, outward.
dss::mesh::TriangleMesh lShape() {
  dss::mesh::TriangleMesh m;
  const double ys[2] = {0, 1};
  // Profile in x-z: (0,0) (2,0) (2,1) (1,1) (1,2) (0,2), extruded along y.
  const double px[6] = {0, 2, 2, 1, 1, 0}, pz[6] = {0, 0, 1, 1, 2, 2};
  for (double y : ys)
    for (int i = 0; i < 6; ++i) m.vertices.emplace_back(px[i], y, pz[i]);
  auto v = [](int i, int side) { return side * 6 + i; };
  // Sides of the extrusion (quads as two triangles), outward.
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    m.triangles.push_back({v(i, 0), v(j, 1), v(j, 0)});
    m.triangles.push_back({v(i, 0), v(i, 1), v(j, 1)});
  }
  // Caps: the L split into triangles (0 1 2), (0 2 3), (0 3 4), (0 4 5); y = 0 faces -y.
  const int fan[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};
  for (const auto& f : fan) {
    m.triangles.push_back({v(f[0], 0), v(f[1], 0), v(f[2], 0)});
    m.triangles.push_back({v(f[0], 1), v(f[2], 1), v(f[1], 1)});
  }
  return m;
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const dss::mesh::TriangleMesh mesh = lShape();
  dss::mesh::DecompositionOptions options;
  options.tolerance = 0.05;
  options.max_pieces = 4;
  const std::uint64_t key = dss::mesh::decompositionKey(mesh, options);
  char name[40];
  std::snprintf(name, sizeof name, "%016" PRIx64 ".dssdec", key);
  dss_fuzz::writeTempFile(name, data, size);
  const auto d = dss::mesh::readCachedDecomposition(dss_fuzz::tempDir(), mesh, options);
  if (!d) return 0;
  if (d->pieces.empty() || d->pieces.size() > std::size_t(options.max_pieces))
    dss_fuzz::propertyFailed("piece count out of range");
  for (const auto& p : d->pieces) {
    if (p.points.empty() || !(p.concavity >= 0) || !std::isfinite(p.concavity))
      dss_fuzz::propertyFailed("empty piece or bad concavity");
    for (const auto& x : p.points)
      if (!x.allFinite()) dss_fuzz::propertyFailed("non-finite piece point");
  }
  const std::string text = dss::mesh::formatDecomposition(key, mesh, options, *d);
  const auto again = dss::mesh::parseDecomposition(text, key, mesh, options);
  if (!again || again->pieces.size() != d->pieces.size() || again->closed != d->closed ||
      !sameBits(again->hull_concavity, d->hull_concavity))
    dss_fuzz::propertyFailed("formatted decomposition does not parse back");
  for (std::size_t i = 0; i < d->pieces.size(); ++i) {
    const auto& a = d->pieces[i];
    const auto& b = again->pieces[i];
    if (a.points.size() != b.points.size() || !sameBits(a.concavity, b.concavity))
      dss_fuzz::propertyFailed("piece changed on the round trip");
    for (std::size_t k = 0; k < a.points.size(); ++k)
      for (int c = 0; c < 3; ++c)
        if (!sameBits(a.points[k][c], b.points[k][c])) dss_fuzz::propertyFailed("point changed");
  }
  return 0;
}
