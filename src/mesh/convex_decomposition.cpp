// Conservative approximate convex decomposition: cells from plane splits, pieces from the
// triangles clipped to each cell plus the cell corners inside the solid, concavity certified by
// a branch-and-bound octree. See dss/mesh/convex_decomposition.h for the contract; this file
// splits and merges the pieces, decomposition/ holds the mesh, the cells, the hulls and the
// certificate.
#include "dss/mesh/convex_decomposition.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "decomposition/cells.h"
#include "decomposition/concavity_certificate.h"
#include "decomposition/geometry.h"
#include "decomposition/mesh_data.h"
#include "decomposition/piece_hull.h"

namespace dss::mesh {
namespace decomposition {
namespace {

struct Piece {
  Cell cell;          // a merged piece keeps its parts' polygons and kept corners
  bool done = false;  // meets the tolerance, too small, merged, or no cut helps
  Hull hull;
  Certificate cert;
};

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
    const Eigen::Matrix3d axes = principalAxes(pts);
    for (int k = 2; k >= 0; --k) {
      const Vec3 axis = axes.col(k);
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
}  // namespace decomposition

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
  return indicesValid(mesh) && decomposition::closedManifold(mesh.vertices, mesh.triangles);
}

double windingNumber(const TriangleMesh& mesh, const Eigen::Vector3d& p) {
  requireIndices(mesh, "windingNumber");
  double sum = 0.0;
  for (const auto& t : mesh.triangles)
    sum += decomposition::solidAngle(mesh.vertices[t[0]] - p, mesh.vertices[t[1]] - p,
                                     mesh.vertices[t[2]] - p);
  return sum / (4.0 * decomposition::kPi);
}

bool insideSolid(const TriangleMesh& mesh, const Eigen::Vector3d& p) {
  return std::abs(windingNumber(mesh, p)) > 0.5;
}

double distanceToMesh(const TriangleMesh& mesh, const Eigen::Vector3d& p,
                      Eigen::Vector3d* nearest) {
  if (mesh.vertices.empty()) throw std::runtime_error("distanceToMesh: the mesh has no vertices");
  requireIndices(mesh, "distanceToMesh");
  std::vector<char> used(mesh.vertices.size(), 0);
  double best = decomposition::kInf;
  Eigen::Vector3d best_point = mesh.vertices[0];
  auto consider = [&](const Eigen::Vector3d& q) {
    const double d = (q - p).squaredNorm();
    if (d < best) {
      best = d;
      best_point = q;
    }
  };
  for (const auto& t : mesh.triangles) {
    consider(decomposition::closestOnTriangle(p, mesh.vertices[t[0]], mesh.vertices[t[1]],
                                              mesh.vertices[t[2]]));
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
  using namespace decomposition;
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
