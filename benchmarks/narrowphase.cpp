// `dss_bench narrowphase`: the paper's narrow-phase benchmark (Hornus 2017, section 6).
//
// For each workload and spread, every algorithm decides every pair; the algorithms run
// interleaved within each repetition (the order rotates between repetitions), and the
// reported time is the median over repetitions. Answers are scored against an independent
// reference (narrowphase_reference.h). Algorithms:
//   dss-exact, dss-double, dss-float   DSS in each mode (float: float copies of the shapes)
//   gjk, hybrid                        our decision GJK and the paper's Hybrid, in double
//   fcl-convex                         FCL 0.7 fcl::collide on fcl::Convex (boxes, spheres as
//                                      the other side where the workload has them as such)
//   fcl-box                            FCL with boxes as fcl::Box (its dedicated box-box test)
//   ccd-gjk, ccd-mpr                   libccd's ccdGJKIntersect / ccdMPRIntersect driven by the
//                                      same support functions as DSS, through callbacks
// FCL runs with its default solver (GST_LIBCCD: libccd MPR for convex pairs, 500 iterations,
// tolerance eps^(7/8)); libccd runs with the same iteration cap and tolerance.
#include <ccd/ccd.h>
#include <fcl/fcl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "dss/core/convex_hull.h"
#include "dss/core/dss.h"
#include "dss/core/gjk.h"
#include "dss/core/posed.h"
#include "dss/core/shapes.h"
#include "narrowphase_reference.h"
#include "narrowphase_workloads.h"
#include "subcommand.h"

namespace dss {
namespace bench {
namespace {

using Clock = std::chrono::steady_clock;

// ---------------------------------------------------------------------------------------------
// Command line

struct Config {
  int n = 300;
  int reps = 5;
  std::uint64_t seed = 20170601;
  int max_iterations = Options{}.max_iterations;
  bool quick = false;
  bool sweep = false;
  bool only_sweep = false;
  std::vector<WorkloadKind> workloads = {WorkloadKind::kTetrahedra, WorkloadKind::kBoxes,
                                         WorkloadKind::kPolytopes, WorkloadKind::kFrustumSpheres,
                                         WorkloadKind::kFrustumBoxes};
  std::vector<double> sigmas;  // overrides the per-workload defaults when given
  std::vector<int> sweep_vertices = {4, 8, 12, 16, 24, 32, 48, 64, 128, 256};
  std::string csv, json;
};

const char* kUsage =
    "usage: dss_bench narrowphase [options]\n"
    "  --n N               objects per workload (default 300: 44850 pairs; frustum workloads\n"
    "                      use round(N/sqrt 2) frusta x as many objects)\n"
    "  --reps R            timed repetitions, interleaved (default 5); medians are reported\n"
    "  --quick             tiny run for CI (N=40, 2 repetitions)\n"
    "  --workloads LIST    comma list of tetra,boxes,poly16,frustum-spheres,frustum-boxes\n"
    "  --sigmas LIST       comma list of spreads (default: per workload, densities ~1..100 %)\n"
    "  --sweep             add the vertex-count sweep at ~50 % density\n"
    "  --only-sweep        run only the sweep\n"
    "  --sweep-vertices L  comma list of vertex counts for the sweep\n"
    "  --max-iterations K  iteration cap of DSS, GJK and Hybrid (default dss::Options)\n"
    "  --seed S            generator seed\n"
    "  --csv FILE          write one row per workload x spread x algorithm\n"
    "  --json FILE         the same rows plus the target ratios, as JSON\n";

std::vector<std::string> splitComma(const std::string& s) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t end = s.find(',', start);
    out.push_back(s.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

Config parseArgs(int argc, char** argv) {
  Config c;
  bool n_given = false, reps_given = false;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    auto value = [&]() -> std::string {
      if (k + 1 >= argc) throw std::runtime_error("option " + a + " needs a value");
      return argv[++k];
    };
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (a == "--n") {
      c.n = std::stoi(value());
      n_given = true;
    } else if (a == "--reps") {
      c.reps = std::stoi(value());
      reps_given = true;
    } else if (a == "--quick") {
      c.quick = true;
    } else if (a == "--sweep") {
      c.sweep = true;
    } else if (a == "--only-sweep") {
      c.sweep = c.only_sweep = true;
    } else if (a == "--seed") {
      c.seed = std::stoull(value());
    } else if (a == "--max-iterations") {
      c.max_iterations = std::stoi(value());
    } else if (a == "--csv") {
      c.csv = value();
    } else if (a == "--json") {
      c.json = value();
    } else if (a == "--sigmas") {
      c.sigmas.clear();
      for (const auto& s : splitComma(value())) c.sigmas.push_back(std::stod(s));
    } else if (a == "--sweep-vertices") {
      c.sweep_vertices.clear();
      for (const auto& s : splitComma(value())) c.sweep_vertices.push_back(std::stoi(s));
    } else if (a == "--workloads") {
      c.workloads.clear();
      for (const auto& s : splitComma(value())) {
        bool found = false;
        for (auto kind : {WorkloadKind::kTetrahedra, WorkloadKind::kBoxes, WorkloadKind::kPolytopes,
                          WorkloadKind::kFrustumSpheres, WorkloadKind::kFrustumBoxes})
          if (s == workloadName(kind)) {
            c.workloads.push_back(kind);
            found = true;
          }
        if (!found) throw std::runtime_error("unknown workload '" + s + "'");
      }
    } else {
      throw std::runtime_error("unknown option '" + a + "'\n" + kUsage);
    }
  }
  if (c.quick) {
    if (!n_given) c.n = 40;
    if (!reps_given) c.reps = 2;
    c.sweep_vertices = {8, 16, 32, 64};
  }
  if (c.n < 2 || c.reps < 1 || c.max_iterations < 1)
    throw std::runtime_error("--n >= 2, --reps >= 1, --max-iterations >= 1");
  return c;
}

// ---------------------------------------------------------------------------------------------
// Algorithms

struct PassStats {
  long long iterations = 0;
  int max_iterations = 0;
  long long cap_hits = 0;
};

struct Algorithm {
  std::string name;
  bool reports_iterations = false;
  /// Decides pairs [begin, end), writing 1 (intersect) or 0 into answers[begin, end).
  std::function<PassStats(std::size_t begin, std::size_t end, std::uint8_t* answers)> pass;
};

using Pairs = std::vector<std::pair<int, int>>;

template <class F>
PassStats decisionPass(const Pairs& pairs, std::size_t begin, std::size_t end,
                       std::uint8_t* answers, F&& decide) {
  PassStats s;
  for (std::size_t k = begin; k < end; ++k) {
    const Result r = decide(pairs[k].first, pairs[k].second);
    answers[k] = r.intersect;
    s.iterations += r.iterations;
    s.max_iterations = std::max(s.max_iterations, r.iterations);
    s.cap_hits += r.status == Status::kIterationLimit;
  }
  return s;
}

template <class F>
PassStats boolPass(const Pairs& pairs, std::size_t begin, std::size_t end, std::uint8_t* answers,
                   F&& decide) {
  for (std::size_t k = begin; k < end; ++k) answers[k] = decide(pairs[k].first, pairs[k].second);
  return {};
}

template <class S>
void ccdSupport(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const S& s = *static_cast<const S*>(obj);
  const Vec3d p = s.support(Vec3d(dir->v[0], dir->v[1], dir->v[2]), Vec3d::Zero());
  out->v[0] = p.x();
  out->v[1] = p.y();
  out->v[2] = p.z();
}

template <class S>
void ccdCenter(const void* obj, ccd_vec3_t* out) {
  const Vec3d p = static_cast<const S*>(obj)->center();
  out->v[0] = p.x();
  out->v[1] = p.y();
  out->v[2] = p.z();
}

// FCL's libccd defaults (gjk_solver_libccd: 500 iterations, tolerance eps^(7/8)).
constexpr unsigned long kCcdMaxIterations = 500;
const double kCcdTolerance = std::pow(std::numeric_limits<double>::epsilon(), 7.0 / 8.0);

/// DSS (three modes), GJK, Hybrid and libccd on shapes A, B (double) and Af, Bf (float).
template <class A, class B, class Af, class Bf>
void addSupportAlgorithms(std::vector<Algorithm>& algos, const Pairs& pairs,
                          const std::vector<A>& a, const std::vector<B>& b,
                          const std::vector<Af>& af, const std::vector<Bf>& bf, int max_iterations,
                          const std::string& suffix = "") {
  auto dss = [&, max_iterations](Mode mode) {
    return
        [&pairs, &a, &b, mode, max_iterations](std::size_t k0, std::size_t k1, std::uint8_t* ans) {
          Options opt;
          opt.mode = mode;
          opt.max_iterations = max_iterations;
          return decisionPass(pairs, k0, k1, ans,
                              [&](int i, int j) { return intersect(a[i], b[j], opt); });
        };
  };
  algos.push_back({"dss-exact" + suffix, true, dss(Mode::kExact)});
  algos.push_back({"dss-double" + suffix, true, dss(Mode::kDouble)});
  if (!suffix.empty()) return;  // variants (e.g. the sweep's linear scan) only time DSS
  algos.push_back(
      {"dss-float", true,
       [&pairs, &af, &bf, max_iterations](std::size_t k0, std::size_t k1, std::uint8_t* ans) {
         Options opt;
         opt.mode = Mode::kFloat;
         opt.max_iterations = max_iterations;
         return decisionPass(pairs, k0, k1, ans,
                             [&](int i, int j) { return intersect(af[i], bf[j], opt); });
       }});
  algos.push_back(
      {"gjk", true,
       [&pairs, &a, &b, max_iterations](std::size_t k0, std::size_t k1, std::uint8_t* ans) {
         Options opt;
         opt.mode = Mode::kDouble;
         opt.max_iterations = max_iterations;
         return decisionPass(pairs, k0, k1, ans,
                             [&](int i, int j) { return intersectGjk(a[i], b[j], opt); });
       }});
  algos.push_back(
      {"hybrid", true,
       [&pairs, &a, &b, max_iterations](std::size_t k0, std::size_t k1, std::uint8_t* ans) {
         Options opt;
         opt.mode = Mode::kDouble;
         opt.max_iterations = max_iterations;
         return decisionPass(pairs, k0, k1, ans,
                             [&](int i, int j) { return intersectHybrid(a[i], b[j], opt); });
       }});
  auto ccd = [&](bool mpr) {
    return [&pairs, &a, &b, mpr](std::size_t k0, std::size_t k1, std::uint8_t* ans) {
      ccd_t c;
      CCD_INIT(&c);
      c.support1 = ccdSupport<A>;
      c.support2 = ccdSupport<B>;
      c.center1 = ccdCenter<A>;
      c.center2 = ccdCenter<B>;
      c.max_iterations = kCcdMaxIterations;
      c.mpr_tolerance = kCcdTolerance;
      if (mpr)
        return boolPass(pairs, k0, k1, ans,
                        [&](int i, int j) { return ccdMPRIntersect(&a[i], &b[j], &c) == 1; });
      return boolPass(pairs, k0, k1, ans,
                      [&](int i, int j) { return ccdGJKIntersect(&a[i], &b[j], &c) == 1; });
    };
  };
  algos.push_back({"ccd-gjk", false, ccd(false)});
  algos.push_back({"ccd-mpr", false, ccd(true)});
}

struct FclObject {
  std::shared_ptr<fcl::CollisionGeometryd> geometry;
  fcl::Transform3d X_WG = fcl::Transform3d::Identity();
};

void addFclAlgorithm(std::vector<Algorithm>& algos, const std::string& name, const Pairs& pairs,
                     const std::vector<FclObject>& a, const std::vector<FclObject>& b) {
  algos.push_back(
      {name, false, [&pairs, &a, &b](std::size_t k0, std::size_t k1, std::uint8_t* ans) {
         fcl::CollisionRequestd request;  // default: GST_LIBCCD, one contact, no contact data
         return boolPass(pairs, k0, k1, ans, [&](int i, int j) {
           fcl::CollisionResultd result;
           fcl::collide(a[i].geometry.get(), a[i].X_WG, b[j].geometry.get(), b[j].X_WG, request,
                        result);
           return result.isCollision();
         });
       }});
}

// ---------------------------------------------------------------------------------------------
// Shape representations of one workload

FclObject fclConvex(const std::vector<Vec3d>& vertices, const std::vector<std::vector<int>>& faces,
                    const fcl::Transform3d& X = fcl::Transform3d::Identity()) {
  auto v = std::make_shared<std::vector<fcl::Vector3d>>(vertices.begin(), vertices.end());
  auto f = std::make_shared<std::vector<int>>();
  for (const auto& face : faces) {
    f->push_back(int(face.size()));
    f->insert(f->end(), face.begin(), face.end());
  }
  return FclObject{std::make_shared<fcl::Convexd>(v, int(faces.size()), f), X};
}

FclObject fclConvex(const Polytope& p) {
  std::vector<std::vector<int>> faces;
  for (const auto& t : p.triangles) faces.push_back({t[0], t[1], t[2]});
  return fclConvex(p.vertices, faces);
}

fcl::Transform3d transformOf(const Mat3d& R, const Vec3d& p) {
  fcl::Transform3d X = fcl::Transform3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

FclObject fclBoxAsConvex(const OrientedBox& b) {
  std::vector<Vec3d> v;
  for (int k = 0; k < 8; ++k)
    v.emplace_back((k & 1) ? b.half.x() : -b.half.x(), (k & 2) ? b.half.y() : -b.half.y(),
                   (k & 4) ? b.half.z() : -b.half.z());
  // Faces counter-clockwise seen from outside (vertex index bits: x=1, y=2, z=4).
  const std::vector<std::vector<int>> faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                               {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return fclConvex(v, faces, transformOf(b.R_WB, b.p_WB));
}

FclObject fclBox(const OrientedBox& b) {
  return FclObject{std::make_shared<fcl::Boxd>(2 * b.half), transformOf(b.R_WB, b.p_WB)};
}

struct Representations {
  std::vector<ConvexHull> a_hulls, b_hulls;
  std::vector<ConvexHull> a_scan_hulls, b_scan_hulls;  // without adjacency (sweep only)
  std::vector<ConvexHullT<float>> a_hulls_f, b_hulls_f;
  std::vector<Posed<Box>> a_boxes, b_boxes;
  std::vector<Posed<BoxT<float>>> a_boxes_f, b_boxes_f;
  std::vector<Posed<Sphere>> b_balls;
  std::vector<Posed<SphereT<float>>> b_balls_f;
  std::vector<FclObject> a_fcl_convex, b_fcl_convex, a_fcl_prim, b_fcl_prim;
};

void buildPolytopes(const std::vector<Polytope>& in, std::vector<ConvexHull>& hulls,
                    std::vector<ConvexHull>& scan_hulls, std::vector<ConvexHullT<float>>& hulls_f,
                    std::vector<FclObject>& fcl_convex, bool scan_variant) {
  for (const auto& p : in) {
    hulls.emplace_back(p.vertices, p.neighbours);
    if (scan_variant) scan_hulls.emplace_back(p.vertices);
    hulls_f.push_back(hulls.back().cast<float>());
    fcl_convex.push_back(fclConvex(p));
  }
}

void buildBoxes(const std::vector<OrientedBox>& in, std::vector<Posed<Box>>& boxes,
                std::vector<Posed<BoxT<float>>>& boxes_f, std::vector<FclObject>& fcl_convex,
                std::vector<FclObject>& fcl_prim) {
  for (const auto& b : in) {
    boxes.emplace_back(Box{b.half}, b.R_WB, b.p_WB);
    boxes_f.emplace_back(BoxT<float>{b.half.cast<float>()}, b.R_WB.cast<float>(),
                         b.p_WB.cast<float>());
    fcl_convex.push_back(fclBoxAsConvex(b));
    fcl_prim.push_back(fclBox(b));
  }
}

/// The algorithms for one workload (the representations must outlive them).
std::vector<Algorithm> makeAlgorithms(const WorkloadSet& w, Representations& r, int max_iterations,
                                      bool scan_variant) {
  std::vector<Algorithm> algos;
  const Pairs& pairs = w.pairs;
  if (w.a_kind == SideKind::kPolytope) {
    buildPolytopes(w.a_polytopes, r.a_hulls, r.a_scan_hulls, r.a_hulls_f, r.a_fcl_convex,
                   scan_variant);
  } else {
    buildBoxes(w.a_boxes, r.a_boxes, r.a_boxes_f, r.a_fcl_convex, r.a_fcl_prim);
  }
  if (!w.same_set) {
    if (w.b_kind == SideKind::kPolytope) {
      buildPolytopes(w.b_polytopes, r.b_hulls, r.b_scan_hulls, r.b_hulls_f, r.b_fcl_convex,
                     scan_variant);
    } else if (w.b_kind == SideKind::kBox) {
      buildBoxes(w.b_boxes, r.b_boxes, r.b_boxes_f, r.b_fcl_convex, r.b_fcl_prim);
    } else {
      for (const auto& s : w.b_balls) {
        r.b_balls.emplace_back(Sphere{s.radius}, Mat3d::Identity(), s.p_WC);
        r.b_balls_f.emplace_back(SphereT<float>{float(s.radius)}, Mat3<float>::Identity(),
                                 s.p_WC.cast<float>());
        r.b_fcl_prim.push_back(FclObject{std::make_shared<fcl::Sphered>(s.radius),
                                         transformOf(Mat3d::Identity(), s.p_WC)});
      }
    }
  }
  const auto& bh = w.same_set ? r.a_hulls : r.b_hulls;
  const auto& bh_scan = w.same_set ? r.a_scan_hulls : r.b_scan_hulls;
  const auto& bhf = w.same_set ? r.a_hulls_f : r.b_hulls_f;
  const auto& bb = w.same_set ? r.a_boxes : r.b_boxes;
  const auto& bbf = w.same_set ? r.a_boxes_f : r.b_boxes_f;
  const auto& b_fcl_convex = w.same_set ? r.a_fcl_convex : r.b_fcl_convex;
  const auto& b_fcl_prim = w.same_set ? r.a_fcl_prim : r.b_fcl_prim;

  if (w.a_kind == SideKind::kPolytope && w.b_kind == SideKind::kPolytope) {
    addSupportAlgorithms(algos, pairs, r.a_hulls, bh, r.a_hulls_f, bhf, max_iterations);
    if (scan_variant)
      addSupportAlgorithms(algos, pairs, r.a_scan_hulls, bh_scan, r.a_hulls_f, bhf, max_iterations,
                           "-scan");
    addFclAlgorithm(algos, "fcl-convex", pairs, r.a_fcl_convex, b_fcl_convex);
  } else if (w.a_kind == SideKind::kBox && w.b_kind == SideKind::kBox) {
    addSupportAlgorithms(algos, pairs, r.a_boxes, bb, r.a_boxes_f, bbf, max_iterations);
    addFclAlgorithm(algos, "fcl-convex", pairs, r.a_fcl_convex, b_fcl_convex);
    addFclAlgorithm(algos, "fcl-box", pairs, r.a_fcl_prim, b_fcl_prim);
  } else if (w.a_kind == SideKind::kPolytope && w.b_kind == SideKind::kBox) {
    addSupportAlgorithms(algos, pairs, r.a_hulls, bb, r.a_hulls_f, bbf, max_iterations);
    addFclAlgorithm(algos, "fcl-convex", pairs, r.a_fcl_convex, b_fcl_convex);
    addFclAlgorithm(algos, "fcl-box", pairs, r.a_fcl_convex, b_fcl_prim);
  } else {
    addSupportAlgorithms(algos, pairs, r.a_hulls, r.b_balls, r.a_hulls_f, r.b_balls_f,
                         max_iterations);
    addFclAlgorithm(algos, "fcl-convex", pairs, r.a_fcl_convex, b_fcl_prim);
  }
  return algos;
}

// ---------------------------------------------------------------------------------------------
// Running and reporting

struct Row {
  std::string workload;
  double sigma = 0;
  int vertices = 0;
  std::size_t pairs = 0;
  double density = 0;  // reference intersecting fraction (ties excluded from both counts)
  std::size_t ties = 0;
  std::string reference;
  std::string algo;
  double ns_median = 0, ns_min = 0, ns_max = 0;
  bool has_iterations = false;
  double mean_iterations = 0;
  int max_iterations = 0;
  long long cap_hits = 0;
  long long wrong = 0;
  long long wrong_intersect = 0;  // answered intersect, reference disjoint
  double mpairsPerSecond() const { return ns_median > 0 ? 1e3 / ns_median : 0; }
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size();
  return m % 2 ? v[m / 2] : 0.5 * (v[m / 2 - 1] + v[m / 2]);
}

std::vector<Row> runWorkload(const WorkloadSet& w, const Config& cfg, bool scan_variant,
                             bool exact_reference_feasible) {
  const auto t0 = Clock::now();
  Representations reps;
  std::vector<Algorithm> algos = makeAlgorithms(w, reps, cfg.max_iterations, scan_variant);
  const std::size_t m = w.pairs.size();

  std::vector<RefAnswer> ref;
  std::string ref_name;
  if (exact_reference_feasible) {
    ref = referenceAnswers(w);
    ref_name = (w.a_kind == SideKind::kPolytope && w.b_kind == SideKind::kPolytope) ? "exact-sat"
                                                                                    : "longdouble";
  }
  const double ref_seconds = std::chrono::duration<double>(Clock::now() - t0).count();

  std::vector<std::vector<std::uint8_t>> answers(algos.size(), std::vector<std::uint8_t>(m));
  std::vector<std::vector<double>> ns(algos.size());
  std::vector<PassStats> stats(algos.size());
  // Each repetition walks the pairs in blocks; within a block every algorithm runs once, in
  // an order that rotates. Load from other processes then hits all algorithms alike.
  constexpr std::size_t kBlock = 1500;
  const std::size_t na = algos.size();
  const std::size_t nblocks = (m + kBlock - 1) / kBlock;
  // block_seconds[k][b * reps + rep]: the time of algorithm k on block b in repetition rep.
  std::vector<std::vector<double>> block_seconds(na, std::vector<double>(nblocks * cfg.reps, 0.0));
  for (int rep = 0; rep < cfg.reps; ++rep) {
    std::vector<double> seconds(na, 0.0);
    std::vector<PassStats> rep_stats(na);
    std::size_t block_index = 0;
    for (std::size_t k0 = 0; k0 < m; k0 += kBlock, ++block_index) {
      const std::size_t k1 = std::min(m, k0 + kBlock);
      for (std::size_t q = 0; q < na; ++q) {
        const std::size_t k = (q + block_index + std::size_t(rep)) % na;
        const auto start = Clock::now();
        const PassStats s = algos[k].pass(k0, k1, answers[k].data());
        const double dt = std::chrono::duration<double>(Clock::now() - start).count();
        seconds[k] += dt;
        block_seconds[k][block_index * cfg.reps + rep] = dt;
        rep_stats[k].iterations += s.iterations;
        rep_stats[k].max_iterations = std::max(rep_stats[k].max_iterations, s.max_iterations);
        rep_stats[k].cap_hits += s.cap_hits;
      }
    }
    for (std::size_t k = 0; k < na; ++k) ns[k].push_back(seconds[k] * 1e9 / double(m));
    stats = rep_stats;
  }
  if (!exact_reference_feasible) {
    // Reference = DSS exact (the sweep's large polytopes, where the exact SAT is too slow).
    ref.resize(m);
    for (std::size_t k = 0; k < algos.size(); ++k)
      if (algos[k].name == "dss-exact")
        for (std::size_t p = 0; p < m; ++p)
          ref[p] = answers[k][p] ? RefAnswer::kIntersect : RefAnswer::kDisjoint;
    ref_name = "dss-exact";
  }
  std::size_t intersecting = 0, ties = 0;
  for (auto r : ref) {
    intersecting += r == RefAnswer::kIntersect;
    ties += r == RefAnswer::kTie;
  }
  std::vector<Row> rows;
  for (std::size_t k = 0; k < algos.size(); ++k) {
    Row row;
    row.workload = w.name;
    row.sigma = w.sigma;
    row.vertices = w.vertex_count;
    row.pairs = m;
    row.density = m > ties ? double(intersecting) / double(m - ties) : 0;
    row.ties = ties;
    row.reference = ref_name;
    row.algo = algos[k].name;
    // Median per block over the repetitions, summed over blocks: a preemption by another
    // process spoils one block of one repetition and is discarded by that block's median.
    double sum_of_medians = 0;
    for (std::size_t blk = 0; blk < nblocks; ++blk)
      sum_of_medians +=
          median(std::vector<double>(block_seconds[k].begin() + blk * cfg.reps,
                                     block_seconds[k].begin() + (blk + 1) * cfg.reps));
    row.ns_median = sum_of_medians * 1e9 / double(m);
    row.ns_min = *std::min_element(ns[k].begin(), ns[k].end());
    row.ns_max = *std::max_element(ns[k].begin(), ns[k].end());
    row.has_iterations = algos[k].reports_iterations;
    row.mean_iterations = double(stats[k].iterations) / double(m);
    row.max_iterations = stats[k].max_iterations;
    row.cap_hits = stats[k].cap_hits;
    for (std::size_t p = 0; p < m; ++p) {
      if (ref[p] == RefAnswer::kTie) continue;
      const bool want = ref[p] == RefAnswer::kIntersect;
      if (bool(answers[k][p]) != want) {
        ++row.wrong;
        row.wrong_intersect += answers[k][p];
      }
    }
    rows.push_back(row);
  }
  std::fprintf(stderr,
               "  %-16s sigma %-6g pairs %zu density %5.1f%% (reference %s %.1fs, total %.1fs)\n",
               w.name.c_str(), w.sigma, m, 100 * rows[0].density, ref_name.c_str(), ref_seconds,
               std::chrono::duration<double>(Clock::now() - t0).count());
  return rows;
}

void printRows(const std::vector<Row>& rows) {
  std::printf("%-16s %6s %4s %6s %7s %5s  %-17s %9s %8s %7s %6s %5s %6s\n", "workload", "sigma",
              "verts", "pairs", "density", "ties", "algo", "Mpairs/s", "ns/pair", "mean_it",
              "max_it", "caps", "wrong");
  std::string last;
  for (const auto& r : rows) {
    char key[128];
    std::snprintf(key, sizeof key, "%s/%g/%d", r.workload.c_str(), r.sigma, r.vertices);
    if (!last.empty() && last != key) std::printf("\n");
    last = key;
    char it_mean[32] = "-", it_max[32] = "-", caps[32] = "-";
    if (r.has_iterations) {
      std::snprintf(it_mean, sizeof it_mean, "%.2f", r.mean_iterations);
      std::snprintf(it_max, sizeof it_max, "%d", r.max_iterations);
      std::snprintf(caps, sizeof caps, "%lld", r.cap_hits);
    }
    std::printf("%-16s %6g %4d %6zu %6.1f%% %5zu  %-17s %9.3f %8.1f %7s %6s %5s %6lld\n",
                r.workload.c_str(), r.sigma, r.vertices, r.pairs, 100 * r.density, r.ties,
                r.algo.c_str(), r.mpairsPerSecond(), r.ns_median, it_mean, it_max, caps, r.wrong);
  }
}

// Speed targets: ratios of pairs/s taken in the same run.
struct Ratio {
  std::string workload;
  double sigma, density;
  int vertices;
  std::string what;
  double value, target;
  bool ok;
};

std::vector<Ratio> targetRatios(const std::vector<Row>& rows) {
  std::map<std::string, std::map<std::string, const Row*>> groups;
  std::vector<std::string> order;
  for (const auto& r : rows) {
    char key[128];
    std::snprintf(key, sizeof key, "%s/%g/%d", r.workload.c_str(), r.sigma, r.vertices);
    if (!groups.count(key)) order.push_back(key);
    groups[key][r.algo] = &r;
  }
  std::vector<Ratio> out;
  for (const auto& key : order) {
    const auto& g = groups[key];
    if (!g.count("dss-double")) continue;
    const Row& d = *g.at("dss-double");
    if (d.workload == "sweep") continue;  // the targets name the five workloads, not the sweep
    const bool boxes = d.workload == "boxes";
    auto speedup = [&](const std::string& other, const std::string& what, double target) {
      if (!g.count(other)) return;
      const double v = g.at(other)->ns_median / d.ns_median;
      out.push_back({d.workload, d.sigma, d.density, d.vertices, what, v, target, v >= target});
    };
    if (!boxes) speedup("fcl-convex", "dss-double / fcl-convex", 4.0);
    if (boxes) speedup("fcl-box", "dss-double / fcl-box", 1.5);
    speedup("ccd-mpr", "dss-double / ccd-mpr", boxes ? 1.0 : 1.5);
    if (d.density >= 0.2) speedup("gjk", "dss-double / gjk", 1.05);
    if (g.count("dss-exact")) {
      const Row& e = *g.at("dss-exact");
      const double v = e.ns_median / d.ns_median;
      out.push_back({d.workload, d.sigma, d.density, d.vertices, "dss-exact cost / dss-double", v,
                     1.25, v <= 1.25});
      out.push_back({d.workload, d.sigma, d.density, d.vertices, "dss-exact wrong answers",
                     double(e.wrong), 0, e.wrong == 0});
    }
  }
  // Absolute rates of a careful plain implementation: tetrahedra at 60 %,
  // 16-vertex polytopes at 100 %, boxes at 98 %; the spread whose density is nearest.
  auto absolute = [&](const std::string& workload, double density, double mpairs) {
    const Row* best = nullptr;
    for (const auto& r : rows)
      if (r.workload == workload && r.algo == "dss-double" &&
          (!best || std::abs(r.density - density) < std::abs(best->density - density)))
        best = &r;
    if (!best) return;
    char what[96];
    std::snprintf(what, sizeof what, "dss-double Mpairs/s (target at %.0f%%)", 100 * density);
    out.push_back({workload, best->sigma, best->density, best->vertices, what,
                   best->mpairsPerSecond(), mpairs, best->mpairsPerSecond() >= mpairs});
  };
  absolute("tetra", 0.60, 7.0);
  absolute("poly16", 1.00, 5.0);
  absolute("boxes", 0.98, 3.9);
  return out;
}

void printRatios(const std::vector<Ratio>& ratios) {
  std::printf(
      "\nTargets (ratios of medians in this run; >= target unless the target is a cost):\n");
  std::printf("%-16s %6s %4s %7s  %-38s %9s %7s  %s\n", "workload", "sigma", "verts", "density",
              "measure", "value", "target", "");
  int met = 0;
  for (const auto& r : ratios) {
    std::printf("%-16s %6g %4d %6.1f%%  %-38s %9.3f %7.2f  %s\n", r.workload.c_str(), r.sigma,
                r.vertices, 100 * r.density, r.what.c_str(), r.value, r.target,
                r.ok ? "ok" : "MISSED");
    met += r.ok;
  }
  std::printf("targets: %d of %zu met\n", met, ratios.size());
  // Per measure and workload: how many spreads meet it.
  std::map<std::string, std::pair<int, int>> summary;
  std::vector<std::string> order;
  for (const auto& r : ratios) {
    const std::string key = r.what + " | " + r.workload;
    if (!summary.count(key)) order.push_back(key);
    summary[key].first += r.ok;
    summary[key].second += 1;
  }
  std::printf("\nsummary (spreads meeting the target / spreads measured):\n");
  for (const auto& key : order)
    std::printf("  %-60s %d/%d\n", key.c_str(), summary[key].first, summary[key].second);
}

void writeCsv(const std::string& path, const std::vector<Row>& rows) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f << "workload,sigma,vertices,pairs,density,ties,reference,algo,mpairs_per_s,ns_per_pair_median,"
       "ns_per_pair_min,ns_per_pair_max,mean_iterations,max_iterations,cap_hits,wrong,wrong_"
       "intersect\n";
  for (const auto& r : rows) {
    f << r.workload << ',' << r.sigma << ',' << r.vertices << ',' << r.pairs << ',' << r.density
      << ',' << r.ties << ',' << r.reference << ',' << r.algo << ',' << r.mpairsPerSecond() << ','
      << r.ns_median << ',' << r.ns_min << ',' << r.ns_max << ',';
    if (r.has_iterations)
      f << r.mean_iterations << ',' << r.max_iterations << ',' << r.cap_hits;
    else
      f << ",,";
    f << ',' << r.wrong << ',' << r.wrong_intersect << '\n';
  }
}

void writeJson(const std::string& path, const Config& cfg, const std::vector<Row>& rows,
               const std::vector<Ratio>& ratios) {
  nlohmann::json j;
  j["benchmark"] = "narrowphase";
  j["n"] = cfg.n;
  j["reps"] = cfg.reps;
  j["seed"] = cfg.seed;
  j["max_iterations"] = cfg.max_iterations;
  j["fcl_solver"] = "GST_LIBCCD (FCL 0.7 default)";
  j["ccd"] = {{"max_iterations", kCcdMaxIterations}, {"mpr_tolerance", kCcdTolerance}};
  for (const auto& r : rows) {
    nlohmann::json x = {{"workload", r.workload},
                        {"sigma", r.sigma},
                        {"vertices", r.vertices},
                        {"pairs", r.pairs},
                        {"density", r.density},
                        {"ties", r.ties},
                        {"reference", r.reference},
                        {"algo", r.algo},
                        {"mpairs_per_s", r.mpairsPerSecond()},
                        {"ns_per_pair_median", r.ns_median},
                        {"ns_per_pair_min", r.ns_min},
                        {"ns_per_pair_max", r.ns_max},
                        {"wrong", r.wrong},
                        {"wrong_intersect", r.wrong_intersect}};
    if (r.has_iterations) {
      x["mean_iterations"] = r.mean_iterations;
      x["max_iterations"] = r.max_iterations;
      x["cap_hits"] = r.cap_hits;
    }
    j["rows"].push_back(x);
  }
  for (const auto& r : ratios)
    j["targets"].push_back({{"workload", r.workload},
                            {"sigma", r.sigma},
                            {"vertices", r.vertices},
                            {"density", r.density},
                            {"measure", r.what},
                            {"value", r.value},
                            {"target", r.target},
                            {"ok", r.ok}});
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f << j.dump(1) << '\n';
}

int runNarrowphase(int argc, char** argv) {
  const Config cfg = parseArgs(argc, argv);
  const auto start = Clock::now();
  std::printf(
      "dss_bench narrowphase: N=%d, %d repetitions (interleaved, medians), seed %llu, "
      "max_iterations %d\n",
      cfg.n, cfg.reps, (unsigned long long)cfg.seed, cfg.max_iterations);
  std::printf(
      "FCL %s with its default solver GST_LIBCCD (libccd MPR for convex pairs, box-box by its "
      "dedicated test); libccd GJK/MPR through our support functions, %lu iterations, tolerance "
      "%.2g\n",
      FCL_VERSION, kCcdMaxIterations, kCcdTolerance);
  std::vector<Row> rows;
  if (!cfg.only_sweep) {
    for (auto kind : cfg.workloads) {
      const auto sigmas = cfg.sigmas.empty() ? defaultSigmas(kind) : cfg.sigmas;
      for (double sigma : sigmas) {
        const WorkloadSet w = makeWorkload(kind, sigma, cfg.n, cfg.seed);
        const auto r = runWorkload(w, cfg, false, true);
        rows.insert(rows.end(), r.begin(), r.end());
      }
    }
  }
  if (cfg.sweep) {
    // Fewer objects: the polytopes get large. The exact reference runs up to 128 vertices;
    // above, answers are scored against DSS exact (named in the reference column).
    const int n = std::max(10, cfg.n / 3);
    for (int v : cfg.sweep_vertices) {
      const WorkloadSet w = makeWorkload(WorkloadKind::kPolytopes, sweepSigma(), n, cfg.seed, v);
      WorkloadSet ws = w;
      ws.name = "sweep";
      const auto r = runWorkload(ws, cfg, true, v <= 128);
      rows.insert(rows.end(), r.begin(), r.end());
    }
  }
  printRows(rows);
  const auto ratios = targetRatios(rows);
  printRatios(ratios);
  long long exact_wrong = 0;
  for (const auto& r : rows)
    if (r.algo == "dss-exact" && r.reference != "dss-exact") exact_wrong += r.wrong;
  if (exact_wrong)
    std::printf("WARNING: dss-exact and the reference disagree on %lld pairs\n", exact_wrong);
  std::printf("exact reference: %llu determinant signs needed the rational fallback\n",
              (unsigned long long)exactFallbackCount());
  std::printf("total %.1f s\n", std::chrono::duration<double>(Clock::now() - start).count());
  if (!cfg.csv.empty()) writeCsv(cfg.csv, rows);
  if (!cfg.json.empty()) writeJson(cfg.json, cfg, rows, ratios);
  return 0;
}

}  // namespace

DSS_BENCH_SUBCOMMAND("narrowphase", "DSS vs GJK, Hybrid, FCL and libccd on the paper's workloads",
                     runNarrowphase);

}  // namespace bench
}  // namespace dss
