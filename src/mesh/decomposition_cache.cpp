// The on-disk cache of convex decompositions (see decomposition_cache.h).
#include "dss/mesh/decomposition_cache.h"

#include <unistd.h>

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unordered_set>

#include "dss/core/any_shape_query.h"

namespace dss::mesh {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMagic = "dss-decomposition";
// A cache file larger than this is not ours (the largest real one is a few hundred KB).
constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t(256) << 20;

struct Fnv {
  std::uint64_t h = 14695981039346656037ull;
  void bytes(const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  }
  template <class T>
  void value(const T& v) {
    bytes(&v, sizeof v);
  }
};

// The most piece points a decomposition of this mesh can have: every triangle clipped to a
// cell gives at most a few more points than its cell has planes, and a cell has at most eight
// corners; generous, only to refuse absurd files before reserving memory.
std::size_t maxPoints(const TriangleMesh& mesh, const DecompositionOptions& options) {
  return 64 * (mesh.vertices.size() + mesh.triangles.size()) * std::size_t(options.max_pieces) +
         1024;
}

std::string fileName(const std::string& dir, std::uint64_t key) {
  char name[40];
  std::snprintf(name, sizeof name, "%016" PRIx64 ".dssdec", key);
  return (fs::path(dir) / name).string();
}

// Every mesh vertex in some piece: a piece point exactly, or inside a piece's hull (exact DSS).
bool coversVertices(const TriangleMesh& mesh, const Decomposition& d) {
  struct Hash {
    std::size_t operator()(const Eigen::Vector3d& p) const {
      Fnv f;
      f.value(p.x()), f.value(p.y()), f.value(p.z());
      return static_cast<std::size_t>(f.h);
    }
  };
  std::unordered_set<Eigen::Vector3d, Hash> points;
  for (const auto& piece : d.pieces) points.insert(piece.points.begin(), piece.points.end());
  std::vector<AnyShape> hulls;
  for (const auto& v : mesh.vertices) {
    if (points.count(v)) continue;
    if (hulls.empty())
      for (const auto& piece : d.pieces)
        hulls.emplace_back(convexHull(piece.points, "cached piece"));
    bool inside = false;
    const AnyShape point = ConvexHull(std::vector<Eigen::Vector3d>{v});
    for (const auto& h : hulls)
      if (intersect(point, Eigen::Isometry3d::Identity(), h, Eigen::Isometry3d::Identity())
              .intersect) {
        inside = true;
        break;
      }
    if (!inside) return false;
  }
  return true;
}

}  // namespace

std::uint64_t decompositionKey(const TriangleMesh& mesh, const DecompositionOptions& options) {
  Fnv f;
  f.value(kDecompositionVersion);
  f.value(static_cast<std::uint64_t>(mesh.vertices.size()));
  f.value(static_cast<std::uint64_t>(mesh.triangles.size()));
  for (const auto& v : mesh.vertices) f.value(v.x()), f.value(v.y()), f.value(v.z());
  for (const auto& t : mesh.triangles) f.value(t[0]), f.value(t[1]), f.value(t[2]);
  f.value(options.tolerance);
  f.value(options.max_pieces);
  return f.h;
}

std::string defaultDecompositionCacheDir() {
  if (const char* d = std::getenv("DSS_CACHE_DIR"); d && *d) return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return (fs::path(d) / "dss").string();
  if (const char* d = std::getenv("HOME"); d && *d)
    return (fs::path(d) / ".cache" / "dss").string();
  return "";
}

std::string formatDecomposition(std::uint64_t key, const TriangleMesh& mesh,
                                const DecompositionOptions& options, const Decomposition& d) {
  std::string out;
  char line[160];
  auto put = [&](const char* fmt, auto... args) {
    std::snprintf(line, sizeof line, fmt, args...);
    out += line;
  };
  put("%s %d\n", kMagic, kDecompositionVersion);
  put("key %016" PRIx64 "\n", key);
  put("mesh %zu %zu\n", mesh.vertices.size(), mesh.triangles.size());
  put("options %.17g %d\n", options.tolerance, options.max_pieces);
  put("closed %d\n", d.closed ? 1 : 0);
  put("hull_concavity %.17g\n", d.hull_concavity);
  put("pieces %zu\n", d.pieces.size());
  for (const auto& p : d.pieces) {
    put("piece %zu %.17g\n", p.points.size(), p.concavity);
    for (const auto& x : p.points) put("%.17g %.17g %.17g\n", x.x(), x.y(), x.z());
  }
  out += "end\n";
  return out;
}

std::optional<Decomposition> parseDecomposition(const std::string& text, std::uint64_t key,
                                                const TriangleMesh& mesh,
                                                const DecompositionOptions& options) {
  std::istringstream in(text);
  std::string word;
  auto expect = [&](const char* w) { return static_cast<bool>(in >> word) && word == w; };
  auto count = [&](std::size_t limit, std::size_t* n) {
    // Digits only: ">>" into an unsigned type would accept "-1" as a huge count.
    if (!(in >> word) || word.empty() || word.size() > 19 ||
        word.find_first_not_of("0123456789") != std::string::npos)
      return false;
    *n = std::stoull(word);
    return *n <= limit;
  };
  auto number = [&](double* x) {
    if (!(in >> word) || word.size() > 40) return false;
    char* end = nullptr;
    *x = std::strtod(word.c_str(), &end);
    return end == word.c_str() + word.size() && std::isfinite(*x);
  };
  std::size_t version = 0, nv = 0, nt = 0, pieces = 0, max_pieces = 0, closed = 0;
  double tolerance = 0.0, hull_concavity = 0.0;
  char key_text[20];
  std::snprintf(key_text, sizeof key_text, "%016" PRIx64, key);
  if (!expect(kMagic) || !count(1000, &version) || version != std::size_t(kDecompositionVersion))
    return std::nullopt;
  if (!expect("key") || !(in >> word) || word != key_text) return std::nullopt;
  if (!expect("mesh") || !count(SIZE_MAX / 2, &nv) || !count(SIZE_MAX / 2, &nt) ||
      nv != mesh.vertices.size() || nt != mesh.triangles.size())
    return std::nullopt;
  if (!expect("options") || !number(&tolerance) || !count(1u << 20, &max_pieces) ||
      tolerance != options.tolerance || max_pieces != std::size_t(options.max_pieces))
    return std::nullopt;
  if (!expect("closed") || !count(1, &closed)) return std::nullopt;
  if (!expect("hull_concavity") || !number(&hull_concavity) || hull_concavity < 0)
    return std::nullopt;
  if (!expect("pieces") || !count(std::size_t(options.max_pieces), &pieces) || pieces == 0)
    return std::nullopt;
  Decomposition d;
  d.closed = closed == 1;
  d.hull_concavity = hull_concavity;
  std::size_t total = 0;
  const std::size_t limit = maxPoints(mesh, options);
  for (std::size_t i = 0; i < pieces; ++i) {
    ConvexPiece p;
    std::size_t np = 0;
    if (!expect("piece") || !count(limit - total, &np) || np == 0 || !number(&p.concavity) ||
        p.concavity < 0)
      return std::nullopt;
    total += np;
    p.points.resize(np);
    for (auto& x : p.points)
      if (!number(&x.x()) || !number(&x.y()) || !number(&x.z())) return std::nullopt;
    d.max_concavity = std::max(d.max_concavity, p.concavity);
    d.pieces.push_back(std::move(p));
  }
  if (!expect("end") || (in >> word)) return std::nullopt;
  return d;
}

std::optional<Decomposition> readCachedDecomposition(const std::string& dir,
                                                     const TriangleMesh& mesh,
                                                     const DecompositionOptions& options) {
  if (dir.empty()) return std::nullopt;
  const std::uint64_t key = decompositionKey(mesh, options);
  const std::string path = fileName(dir, key);
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec || size > kMaxFileBytes) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::string text(static_cast<std::size_t>(size), '\0');
  if (!in.read(text.data(), static_cast<std::streamsize>(size))) return std::nullopt;
  try {
    std::optional<Decomposition> d = parseDecomposition(text, key, mesh, options);
    if (!d || !coversVertices(mesh, *d)) return std::nullopt;
    return d;
  } catch (const std::exception&) {  // a hull qhull refuses: the file is not ours
    return std::nullopt;
  }
}

bool writeCachedDecomposition(const std::string& dir, const TriangleMesh& mesh,
                              const DecompositionOptions& options, const Decomposition& d) {
  if (dir.empty()) return false;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return false;
  const std::uint64_t key = decompositionKey(mesh, options);
  const std::string path = fileName(dir, key);
  // A name no other process writes: the rename then replaces the file in one step.
  const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." +
                          std::to_string(reinterpret_cast<std::uintptr_t>(&d));
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return false;
    const std::string text = formatDecomposition(key, mesh, options, d);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!out.flush()) {
      fs::remove(tmp, ec);
      return false;
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    return false;
  }
  return true;
}

Decomposition decomposeCached(const TriangleMesh& mesh, const DecompositionOptions& options,
                              const std::string& what, const std::string& dir, bool* from_cache) {
  if (from_cache) *from_cache = false;
  if (auto d = readCachedDecomposition(dir, mesh, options)) {
    if (from_cache) *from_cache = true;
    return *d;
  }
  Decomposition d = decomposeConvex(mesh, options, what);
  writeCachedDecomposition(dir, mesh, options, d);
  return d;
}

}  // namespace dss::mesh
