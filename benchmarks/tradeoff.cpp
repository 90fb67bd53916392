// `dss_bench tradeoff`: what each collision-checking setting costs in time, missed collisions
// and false alarms, on real robots in real MotionBenchMaker scenes.
//
// Per robot (Panda, UR5 + Robotiq gripper, KUKA iiwa 14) and per scene, the same seeded random
// states (uniform in the joint limits of the reference model) and the same random short motions
// are checked by every setting; every answer is scored against a ground truth:
//  - states: FCL 0.7 on the exact triangle meshes (fcl-mesh: BVHModel<OBBRSS>) with the scene's
//    exact primitives, no padding;
//  - motions: the same truth sampled along the straight joint-space motion so finely that no
//    point of the robot moves more than delta (--delta, 1 mm) between two samples (bound from the
//    joint-to-geometry radii, as in the continuous validator). A sample is free when DSS-exact
//    on the convex hulls certifies it (hulls contain the meshes; the state test checks that
//    claim) and otherwise decided by fcl-mesh. The truth can only miss a contact that never
//    gets deeper than delta/2 against the scene (delta between two links).
// Settings vary one axis at a time around the default (hull, exact, no padding, cap 64,
// discrete motion checks at 1 % of the space extent), plus a few combinations. Timing: thread
// CPU time, every setting in every repetition, median over repetitions.
#include <fcl/fcl.h>
#include <ompl/base/goals/GoalStates.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "dss/checker/continuous_motion.h"
#include "dss/checker/discrete_motion.h"
#include "dss/checker/fcl_checker.h"
#include "dss/checker/motion_bounds.h"
#include "dss/checker/sweep.h"
#include "dss/core/any_shape_query.h"
#include "dss/planning/planning_problem.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "subcommand.h"

#ifndef DSS_SHARED_DIR_DEFAULT
#define DSS_SHARED_DIR_DEFAULT "../shared"
#endif
#ifndef DSS_SOURCE_DIR_DEFAULT
#define DSS_SOURCE_DIR_DEFAULT "."
#endif

namespace dss {
namespace bench {
namespace {

namespace fs = std::filesystem;
namespace ob = ompl::base;
namespace og = ompl::geometric;

double cpuNow() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// ---------------------------------------------------------------------------------------------
// Command line

const char* kUsage =
    "usage: dss_bench tradeoff [options]\n"
    "  Speed/accuracy of collision-checking settings against exact-mesh ground truth.\n"
    "  --robots LIST        panda,ur5,iiwa (default: all three)\n"
    "  --states N           random states per robot, spread over its scenes (10000)\n"
    "  --motions N          random short motions per robot (2000)\n"
    "  --seed S             seed of states, motions and OMPL (1)\n"
    "  --csv FILE           one row per robot x setting\n"
    "  --reps R             timed repetitions, interleaved; medians reported (3)\n"
    "  --scenes-per-type K  MBM scenes per scene type (2; the iiwa takes 1 of 4 types)\n"
    "  --settings LIST      only these settings (names as in the table, e.g. default,continuous)\n"
    "  --delta M            motion truth: largest point displacement between samples (0.001 m)\n"
    "  --motion-length F    motions: from a truth-free start, a random direction, length uniform\n"
    "                       in (0, F] x the space's extent, clipped at the limits, to a "
    "truth-free\n"
    "                       end; F >= 1 (default): independent pairs of truth-free states\n"
    "  --plan-time S        RRTConnect time limit per problem (10 s)\n"
    "  --decompose-tolerance M  the decomposed geometry's concavity target (0.008 m)\n"
    "  --no-plan            skip the planning runs\n"
    "  --shared DIR         shared robots and scenes (default: the build's DSS_SHARED_DIR)\n"
    "  --quick              seconds-long run for CI (1 scene per robot, few states, 1 plan)\n"
    "  Exit status: 0; 1 on bad options or input; 3 when hull+exact (or decomposed+exact)\n"
    "  misses a collision of the\n"
    "  mesh truth that FCL's own gap does not explain; 77 when the shared robots are absent\n"
    "  (nothing measured).\n";

struct Args {
  std::vector<std::string> robots = {"panda", "ur5", "iiwa"};
  long states = 10000;
  long motions = 2000;
  std::uint64_t seed = 1;
  std::string csv;
  int reps = 3;
  int scenes_per_type = 2;
  std::set<std::string> only;
  double delta = 0.001;
  double motion_length = 1.0;
  double plan_time = 10.0;
  bool plan = true;
  std::string shared = DSS_SHARED_DIR_DEFAULT;
  bool quick = false;
  double decompose_tolerance = 0.008;  // the "decomposed" geometry's concavity target (m)
  std::string command;
};

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream is(s);
  std::string x;
  while (std::getline(is, x, ','))
    if (!x.empty()) out.push_back(x);
  return out;
}

double parseNumber(const std::string& opt, const std::string& v) {
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  if (v.empty() || *end != '\0' || !std::isfinite(x))
    throw std::invalid_argument(opt + ": '" + v + "' is not a number");
  return x;
}

// ---------------------------------------------------------------------------------------------
// Robots, variants and settings

enum class Geo { kHull, kSpheres, kCapsules, kMesh, kFclHull, kDecomposed };

const char* geoName(Geo g) {
  switch (g) {
    case Geo::kHull:
      return "hull";
    case Geo::kSpheres:
      return "spheres";
    case Geo::kCapsules:
      return "capsules";
    case Geo::kMesh:
      return "mesh";
    case Geo::kFclHull:
      return "fcl-hull";
    case Geo::kDecomposed:
      return "decomposed";
  }
  return "?";
}

struct VariantSpec {
  std::string urdf, srdf;  // relative to the shared robots folder (srdf may be absolute)
};

struct RobotSpec {
  std::string name;
  VariantSpec truth;  // hull (DSS), fcl-hull and mesh (FCL) read this model
  std::optional<VariantSpec> spheres, capsules;
  std::string scene_dir;  // under shared/scenes
  std::vector<std::string> types;
  bool requests = true;  // the scene folder's requests are this robot's (planning, held joints)
  int max_scenes_per_type = 1000;
};

std::vector<RobotSpec> robotSpecs() {
  const std::string iiwa_srdf =
      std::string(DSS_SOURCE_DIR_DEFAULT) + "/benchmarks/data/iiwa14.srdf";
  const std::vector<std::string> all = {
      "bookshelf_small", "bookshelf_tall",  "bookshelf_thin", "box", "cage",
      "table_pick",      "table_under_pick"};
  std::vector<RobotSpec> r;
  // Every Panda variant uses the MBM Panda's SRDF, so that the self pairs are the same ones.
  r.push_back({"panda",
               {"panda/panda.urdf", "panda/panda.srdf"},
               VariantSpec{"panda_vamp/panda_spherized.urdf", "panda/panda.srdf"},
               VariantSpec{"panda_description/panda_collision.urdf", "panda/panda.srdf"},
               "mbm_panda",
               all,
               true});
  r.push_back({"ur5",
               {"ur5_robotiq85/ur5.urdf", "ur5_robotiq85/ur5.srdf"},
               VariantSpec{"ur5_robotiq85/ur5_spherized.urdf", "ur5_robotiq85/ur5.srdf"},
               std::nullopt,
               "mbm_ur5",
               all,
               true});
  // The iiwa stands where the Panda stands: MBM Panda scenes place the robot's root at the world
  // origin (identity virtual joint), and so do we for the iiwa's root link `base`.
  r.push_back({"iiwa",
               {"iiwa_description/iiwa14_primitive_collision.urdf", iiwa_srdf},
               VariantSpec{"iiwa_description/iiwa14_spheres_collision.urdf", iiwa_srdf},
               std::nullopt,
               "mbm_panda",
               {"bookshelf_small", "box", "cage", "table_pick"},
               false,
               1});
  return r;
}

struct Setting {
  std::string name;
  std::string axis;
  Geo geo = Geo::kHull;
  Mode mode = Mode::kExact;
  int cap = 64;
  double pad = 0.0;
  double resolution = 0.01;  // 0: continuous validator
  bool plan = false;
  bool batched = false;  // the vector validator's batches (discrete_motion.h)

  std::string stateKey() const {
    std::ostringstream os;
    os << geoName(geo) << "|" << int(mode) << "|" << cap << "|" << pad;
    return os.str();
  }
  std::string motionKey() const {
    std::ostringstream os;
    os << stateKey() << "|" << resolution << (batched ? "|vector" : "");
    return os.str();
  }
  bool isFcl() const { return geo == Geo::kMesh || geo == Geo::kFclHull; }
  std::string modeName() const { return isFcl() ? "fcl" : toString(mode); }
  std::string capName() const {
    return isFcl() ? "-" : cap == INT_MAX ? "none" : std::to_string(cap);
  }
  std::string motionName() const {
    if (resolution <= 0) return "continuous";
    std::ostringstream os;
    os << (batched ? "vector " : "discrete ") << resolution * 100 << "%";
    return os.str();
  }
};

std::vector<Setting> allSettings() {
  std::vector<Setting> s;
  auto add = [&](std::string name, std::string axis, Geo geo, Mode mode, int cap, double pad,
                 double res, bool plan) {
    s.push_back({name, axis, geo, mode, cap, pad, res, plan});
  };
  const Mode E = Mode::kExact;
  add("default", "default", Geo::kHull, E, 64, 0, 0.01, true);
  add("spheres", "geometry", Geo::kSpheres, E, 64, 0, 0.01, true);
  add("capsules", "geometry", Geo::kCapsules, E, 64, 0, 0.01, false);
  add("mesh", "geometry", Geo::kMesh, E, 64, 0, 0.01, true);
  add("fcl-hull", "geometry", Geo::kFclHull, E, 64, 0, 0.01, false);
  add("decomposed", "geometry", Geo::kDecomposed, E, 64, 0, 0.01, true);
  add("double", "arithmetic", Geo::kHull, Mode::kDouble, 64, 0, 0.01, false);
  add("float", "arithmetic", Geo::kHull, Mode::kFloat, 64, 0, 0.01, false);
  add("pad 5mm", "padding", Geo::kHull, E, 64, 0.005, 0.01, false);
  add("pad 1cm", "padding", Geo::kHull, E, 64, 0.01, 0.01, true);
  add("pad 2cm", "padding", Geo::kHull, E, 64, 0.02, 0.01, false);
  for (int cap : {8, 12, 20, 50})
    add("cap " + std::to_string(cap), "cap", Geo::kHull, E, cap, 0, 0.01, false);
  add("cap none", "cap", Geo::kHull, E, INT_MAX, 0, 0.01, false);
  add("discrete 0.5%", "motion", Geo::kHull, E, 64, 0, 0.005, false);
  add("discrete 0.1%", "motion", Geo::kHull, E, 64, 0, 0.001, false);
  add("continuous", "motion", Geo::kHull, E, 64, 0, 0.0, true);
  add("vector", "motion", Geo::kHull, E, 64, 0, 0.01, false);
  s.back().batched = true;
  add("spheres float", "combination", Geo::kSpheres, Mode::kFloat, 64, 0, 0.01, false);
  add("float cap 20", "combination", Geo::kHull, Mode::kFloat, 20, 0, 0.01, false);
  add("continuous pad 1cm", "combination", Geo::kHull, E, 64, 0.01, 0.0, false);
  return s;
}

// ---------------------------------------------------------------------------------------------
// Scenes, problems and the maps between reference and variant states

struct Loaded {
  LoadedRobot truth;
  std::optional<LoadedRobot> spheres, capsules;
  std::optional<LoadedRobot> decomposed;  // the reference URDF, meshes as convex pieces
  const LoadedRobot* get(Geo g) const {
    if (g == Geo::kSpheres) return spheres ? &*spheres : nullptr;
    if (g == Geo::kCapsules) return capsules ? &*capsules : nullptr;
    if (g == Geo::kDecomposed) return decomposed ? &*decomposed : nullptr;
    return &truth;
  }
};

/// A problem of one variant with the map from reference group values to its joint vector.
struct VariantProblem {
  Problem p;
  std::vector<int> from_truth;  // variant group index -> reference group index
  std::vector<double> held;     // full active-joint vector (held values)
  void toQ(const double* g, double* q) const {
    std::copy(held.begin(), held.end(), q);
    const auto& ga = p.map->groupActive();
    for (std::size_t i = 0; i < ga.size(); ++i) q[ga[i]] = g[from_truth[i]];
  }
  std::size_t nq() const { return held.size(); }
};

struct Motion {
  std::vector<double> g0, g1;  // reference group order
};

struct SceneCtx {
  std::string name, scene_path, request_path;
  std::map<std::string, double> start;
  std::string group;
  std::map<std::string, std::unique_ptr<VariantProblem>> problems;  // geo|margin
  std::vector<std::vector<double>> states;                          // reference group order
  std::vector<char> state_truth;                                    // 1: the truth collides
  std::vector<Motion> motions;
  std::vector<char> motion_truth;
};

std::string problemKey(Geo g, double margin) {
  std::ostringstream os;
  os << (g == Geo::kSpheres      ? "spheres"
         : g == Geo::kCapsules   ? "capsules"
         : g == Geo::kDecomposed ? "decomposed"
                                 : "truth")
     << "|" << margin;
  return os.str();
}

std::set<std::string>& seenWarnings() {
  static std::set<std::string> s;
  return s;
}

VariantProblem& problemFor(SceneCtx& ctx, const Loaded& L, Geo g, double margin,
                           const VariantProblem* ref) {
  const std::string key = problemKey(g, margin);
  auto it = ctx.problems.find(key);
  if (it != ctx.problems.end()) return *it->second;
  const LoadedRobot* robot = L.get(g);
  if (!robot) throw std::logic_error("no model for " + std::string(geoName(g)));
  Scene scene = loadScene(ctx.scene_path);
  auto vp = std::make_unique<VariantProblem>();
  vp->p = makeProblem(*robot, std::move(scene), ctx.group, ctx.start, margin);
  for (const auto& w : vp->p.warnings)
    if (seenWarnings().insert(robot->model->name + ": " + w).second)
      std::cerr << "tradeoff: note: " << robot->model->name << ": " << w << "\n";
  vp->held = vp->p.map->held();
  const auto& names = vp->p.map->jointNames();
  const auto& ref_names = ref ? ref->p.map->jointNames() : names;
  for (const auto& n : names) {
    auto f = std::find(ref_names.begin(), ref_names.end(), n);
    if (f == ref_names.end())
      throw std::runtime_error(robot->model->source + ": group joint '" + n +
                               "' is not a joint of the reference model");
    vp->from_truth.push_back(int(f - ref_names.begin()));
  }
  if (names.size() != ref_names.size())
    throw std::runtime_error(robot->model->source + ": group has " + std::to_string(names.size()) +
                             " joints, the reference model " + std::to_string(ref_names.size()));
  auto& out = *vp;
  ctx.problems[key] = std::move(vp);
  return out;
}

// ---------------------------------------------------------------------------------------------
// Motion truth: the reference geometry sampled with a bound on the displacement of every point.

/// For each moving slot: the joints above it with the bound on the distance of the slot's
/// geometry from each joint's origin (motion_bounds.h, as the continuous motion check).
std::vector<std::vector<ChainTerm>> chainBounds(const CollisionModel& m) {
  std::vector<std::vector<ChainTerm>> chains(m.slots().size());
  for (std::size_t k = 0; k < m.slots().size(); ++k) {
    const auto& s = m.slots()[k];
    if (s.moves)
      chains[k] = chainAbove(m.robot(), s.link, -1, s.center_L.norm() + s.radius, m.held());
  }
  return chains;
}

struct Truth {
  const VariantProblem* vp = nullptr;
  std::shared_ptr<const FclChecker> mesh;
  std::vector<std::vector<ChainTerm>> chains;
  double delta = 0.001;
  mutable std::uint64_t samples = 0;

  /// Pair-level lazy truth: a pair goes to FCL on the meshes only when DSS-exact finds the
  /// hulls (which contain the meshes) intersecting; the model's filters are conservative.
  bool stateCollides(const double* q) const {
    const CollisionModel& m = *vp->p.model;
    thread_local std::vector<Eigen::Isometry3d> X;
    X.resize(m.robot().links.size());
    m.kinematics().computeLinkPoses(q, X.data());
    const FclChecker* fm = mesh.get();
    const Options exact;
    const auto& el = m.elements();
    fcl::CollisionRequestd req;
    auto fclHit = [&](const fcl::CollisionGeometryd* a, const Eigen::Isometry3d& XA,
                      const fcl::CollisionGeometryd* b, const Eigen::Isometry3d& XB) {
      fcl::CollisionResultd res;
      fcl::collide(a, fcl::Transform3d(XA.matrix()), b, fcl::Transform3d(XB.matrix()), req, res);
      return res.isCollision();
    };
    // No self-pair tables: a table certifies the hulls, not the meshes inside them.
    thread_local std::vector<unsigned char> no_tables;
    no_tables.assign(m.selfTables().size(), 0);
    return sweep<SweepPoses::kOwnLinks>(
        m, X.data(), no_tables.data(), SweepOptions{},
        [&](int e, const Eigen::Isometry3d& X_WS, int o) {
          const auto& ob = m.scene().obstacles[o];
          if (!intersect(el[e].source->shape, X_WS, ob.shape, ob.X_WO, exact).intersect)
            return false;
          return fclHit(fm->elementGeometry(e), X_WS, fm->obstacleGeometry(o), ob.X_WO);
        },
        [&](int ea, const Eigen::Isometry3d& XA, int eb, const Eigen::Isometry3d& XB) {
          if (!intersect(el[ea].source->shape, XA, el[eb].source->shape, XB, exact).intersect)
            return false;
          return fclHit(fm->elementGeometry(ea), XA, fm->elementGeometry(eb), XB);
        });
  }

  /// Largest displacement of any robot point along q0 -> q1 (bound).
  double sweepBound(const double* q0, const double* q1) const {
    double L = 0.0;
    for (const auto& c : chains) L = std::max(L, motionBound(c, q0, q1).length);
    return L;
  }

  /// Interior samples only (the endpoints are checked by the caller). Coarse-to-fine order, so
  /// that colliding motions stop early.
  bool motionCollides(const double* q0, const double* q1, std::vector<double>& q) const {
    const std::size_t n = vp->nq();
    const long segs = std::max<long>(1, long(std::ceil(sweepBound(q0, q1) / delta)));
    long top = 1;
    while (top * 2 < segs) top *= 2;
    for (long step = top; step >= 1; step /= 2) {
      for (long i = step; i < segs; i += step) {
        if (step != top && (i / step) % 2 == 0) continue;  // done at a coarser level
        const double t = double(i) / double(segs);
        for (std::size_t a = 0; a < n; ++a) q[a] = q0[a] + t * (q1[a] - q0[a]);
        ++samples;
        if (stateCollides(q.data())) return true;
      }
    }
    return false;
  }
};

// ---------------------------------------------------------------------------------------------
// Diagnosis of a state where hull+exact says free and the mesh truth collides: per pair, what
// FCL says on the meshes and the gap DSS certifies between the hulls (bisection on an exact
// padded test: "padded(A, r) meets B" iff distance(A, B) <= r).

double certifiedGap(const AnyShape& a, const Eigen::Isometry3d& XA, const AnyShape& b,
                    const Eigen::Isometry3d& XB) {
  Options opt;
  opt.max_iterations = 1000;
  auto meets = [&](double r) { return intersect(a, XA, b, XB, opt, r).intersect; };
  if (meets(0.0)) return 0.0;
  double lo = 0.0, hi = 1e-6;
  while (!meets(hi) && hi < 10.0) lo = hi, hi *= 4.0;
  for (int i = 0; i < 50; ++i) {
    const double mid = 0.5 * (lo + hi);
    (meets(mid) ? hi : lo) = mid;
  }
  return lo;  // DSS certifies distance > lo
}

/// Names of the pairs (link vs obstacle, link vs link) that DSS-exact finds intersecting at q,
/// with the model's own pairs and no filters: what a setting's false alarms come from.
std::vector<std::string> collidingPairs(const CollisionModel& m, const double* q,
                                        double scene_padding = 0.0) {
  const RobotModel& r = m.robot();
  std::vector<Eigen::Isometry3d> X(r.links.size(), Eigen::Isometry3d::Identity());
  m.kinematics().computeLinkPoses(q, X.data());
  Options exact;
  std::vector<std::string> out;
  const auto& el = m.elements();
  for (const auto& s : m.slots()) {
    for (int o : s.obstacles) {
      bool hit = false;
      for (int e = s.first_element; e < s.first_element + s.num_elements && !hit; ++e) {
        const Eigen::Isometry3d XA = X[s.link] * el[e].source->X_LS;
        const auto& ob = m.scene().obstacles[o];
        hit = scene_padding > 0
                  ? certifiedGap(el[e].source->shape, XA, ob.shape, ob.X_WO) <= scene_padding
                  : intersect(el[e].source->shape, XA, ob.shape, ob.X_WO, exact).intersect;
      }
      if (hit) out.push_back(r.links[s.link].name + " vs scene");
    }
  }
  for (const auto& p : m.selfPairs()) {
    const auto& sa = m.slots()[p.a];
    const auto& sb = m.slots()[p.b];
    bool hit = false;
    for (int ea = sa.first_element; ea < sa.first_element + sa.num_elements && !hit; ++ea)
      for (int eb = sb.first_element; eb < sb.first_element + sb.num_elements && !hit; ++eb)
        hit = intersect(el[ea].source->shape, X[sa.link] * el[ea].source->X_LS,
                        el[eb].source->shape, X[sb.link] * el[eb].source->X_LS, exact)
                  .intersect;
    if (hit) {
      std::string a = r.links[sa.link].name, b = r.links[sb.link].name;
      if (b < a) std::swap(a, b);
      out.push_back(a + " vs " + b);
    }
  }
  return out;
}

/// The MoveIt Setup Assistant's "Default" rule for a variant model: self pairs that collide at
/// the model's default state are disabled. The reference SRDFs were made that way on the mesh
/// models; a sphere model given the same SRDF can have a pair in permanent collision (UR5:
/// wrist_2_link vs fts_robotside), which would make every state a false alarm.
std::vector<std::string> addDefaultCollidingPairs(LoadedRobot& robot) {
  if (!robot.srdf) return {};
  std::vector<int> all;
  for (std::size_t i = 0; i < robot.model->numActiveJoints(); ++i) all.push_back(int(i));
  const std::vector<double> q = robot.model->defaultState();
  CollisionModel m(robot.model, &*robot.srdf, Scene{}, all, q);
  std::vector<std::string> added;
  for (const auto& name : collidingPairs(m, q.data())) {
    const auto sep = name.find(" vs ");
    robot.srdf->disabled_collisions.push_back(
        {name.substr(0, sep), name.substr(sep + 4), "Default"});
    added.push_back(name);
  }
  return added;
}

struct Diagnosis {
  bool fcl_gap = false;  // every pair FCL calls colliding has a DSS-certified positive gap
  std::string text;
};

Diagnosis diagnose(const VariantProblem& vp, const FclChecker& fcl, const double* q) {
  const CollisionModel& m = *vp.p.model;
  const RobotModel& r = m.robot();
  std::vector<Eigen::Isometry3d> X(r.links.size(), Eigen::Isometry3d::Identity());
  m.kinematics().computeLinkPoses(q, X.data());
  fcl::CollisionRequestd req;
  Options exact;
  bool any_real = false, any = false;
  std::ostringstream os;
  auto pairTest = [&](const fcl::CollisionGeometryd* ga, const Eigen::Isometry3d& XA,
                      const AnyShape& sa, const fcl::CollisionGeometryd* gb,
                      const Eigen::Isometry3d& XB, const AnyShape& sb, const std::string& what) {
    fcl::CollisionResultd res;
    fcl::collide(ga, fcl::Transform3d(XA.matrix()), gb, fcl::Transform3d(XB.matrix()), req, res);
    if (!res.isCollision()) return;
    any = true;
    const bool dss_hit = intersect(sa, XA, sb, XB, exact).intersect;
    if (dss_hit) {
      any_real = true;
      os << "    " << what
         << ": FCL collides, DSS hull collides too (a filter or pair-set difference)\n";
      return;
    }
    const double gap = certifiedGap(sa, XA, sb, XB);
    os << "    " << what
       << ": FCL calls the meshes colliding; DSS certifies the hulls (which contain the meshes) "
       << (gap > 0 ? "apart by more than " : "apart (gap below bisection resolution) ")
       << std::setprecision(3) << gap * 1e6 << " um\n";
  };
  const auto& el = m.elements();
  for (const auto& s : m.slots()) {
    for (int o : s.obstacles)
      for (int e = s.first_element; e < s.first_element + s.num_elements; ++e)
        pairTest(fcl.elementGeometry(e), X[s.link] * el[e].source->X_LS, el[e].source->shape,
                 fcl.obstacleGeometry(o), m.scene().obstacles[o].X_WO, m.scene().obstacles[o].shape,
                 r.links[s.link].name + " vs " + m.scene().obstacles[o].name);
  }
  for (const auto& p : m.selfPairs()) {
    const auto& sa = m.slots()[p.a];
    const auto& sb = m.slots()[p.b];
    for (int ea = sa.first_element; ea < sa.first_element + sa.num_elements; ++ea)
      for (int eb = sb.first_element; eb < sb.first_element + sb.num_elements; ++eb)
        pairTest(fcl.elementGeometry(ea), X[sa.link] * el[ea].source->X_LS, el[ea].source->shape,
                 fcl.elementGeometry(eb), X[sb.link] * el[eb].source->X_LS, el[eb].source->shape,
                 r.links[sa.link].name + " vs " + r.links[sb.link].name);
  }
  Diagnosis d;
  d.fcl_gap = any && !any_real;
  d.text = os.str();
  return d;
}

// ---------------------------------------------------------------------------------------------
// One setting bound to one scene.

struct Instance {
  const VariantProblem* vp = nullptr;
  std::shared_ptr<const StateChecker> checker;
  std::shared_ptr<const ContinuousMotionChecker> cmv;
  std::shared_ptr<const DiscreteMotionChecker> vector;  // the batched discrete check
  std::vector<double> qs;                               // states, pre-mapped (n x nq)
  std::vector<double> m0, m1;                           // motion endpoints, pre-mapped
  std::vector<long> segs;                               // discrete segments per motion
};

std::shared_ptr<const StateChecker> makeSettingChecker(const VariantProblem& vp, const Setting& s) {
  CheckerConfig c;
  c.checker = s.geo == Geo::kMesh ? "fcl-mesh" : s.geo == Geo::kFclHull ? "fcl-hull" : "dss";
  c.scene_padding = s.pad;
  c.self_padding = 0.0;
  c.dss_options.mode = s.mode;
  c.dss_options.max_iterations = s.cap;
  return makeStateChecker(vp.p.model, c);
}

struct Row {
  std::string robot;
  Setting s;
  std::string model;
  int scenes = 0;
  long states = 0, truth_states = 0, missed = 0, false_alarms = 0, fcl_gap_claims = 0,
       unexplained = 0;
  std::uint64_t cap_hits = 0;
  double us_state = 0;
  long motions = 0, truth_motions = 0, m_missed = 0, m_false = 0;
  std::uint64_t m_cap_hits = 0;
  double us_motion = 0;
  int plan_problems = 0, plan_solved = 0, plan_truth_colliding = 0, plan_start_goal_invalid = 0;
  double plan_cpu_ms = 0, plan_wall_ms = 0;
  bool measured_states = false, measured_motions = false, measured_plan = false;
};

// ---------------------------------------------------------------------------------------------

struct RobotRun {
  const RobotSpec* spec;
  Loaded L;
  std::vector<std::unique_ptr<SceneCtx>> scenes;
  std::vector<std::unique_ptr<Truth>> truths;  // per scene
  double extent = 0;
  std::vector<double> lo, hi;
};

// Exit code when the shared robots are absent and nothing was measured (CTest: skipped).
constexpr int kExitNothingMeasured = 77;

bool fileExists(const std::string& p) { return fs::exists(p); }

std::string robotPath(const Args& a, const std::string& rel) {
  if (!rel.empty() && rel[0] == '/') return rel;
  return a.shared + "/robots/" + rel;
}

/// Kinematic consistency of a variant with the reference: largest offset of a same-named link's
/// origin over random states (the variant's held values, the reference's group values).
std::string kinematicsCheck(const VariantProblem& ref, const VariantProblem& var,
                            std::mt19937_64& rng, const std::vector<double>& lo,
                            const std::vector<double>& hi) {
  const RobotModel& ra = ref.p.model->robot();
  const RobotModel& rb = var.p.model->robot();
  std::vector<Eigen::Isometry3d> XA(ra.links.size()), XB(rb.links.size());
  std::vector<double> g(lo.size()), qa(ref.nq()), qb(var.nq());
  double worst = 0.0, worst_rot = 0.0;
  int compared = 0;
  for (int k = 0; k < 200; ++k) {
    for (std::size_t i = 0; i < g.size(); ++i)
      g[i] = std::uniform_real_distribution<double>(lo[i], hi[i])(rng);
    ref.toQ(g.data(), qa.data());
    var.toQ(g.data(), qb.data());
    // computeLinkPoses fills only links with geometry or leading to it: compare those with
    // geometry in both models.
    for (auto& x : XA) x.setIdentity();
    for (auto& x : XB) x.setIdentity();
    ref.p.model->kinematics().computeLinkPoses(qa.data(), XA.data());
    var.p.model->kinematics().computeLinkPoses(qb.data(), XB.data());
    compared = 0;
    for (std::size_t l = 0; l < ra.links.size(); ++l) {
      if (!ra.links[l].hasGeometry()) continue;
      const int m = rb.linkIndex(ra.links[l].name);
      if (m < 0 || !rb.links[m].hasGeometry()) continue;
      ++compared;
      worst = std::max(worst, (XA[l].translation() - XB[m].translation()).norm());
      worst_rot = std::max(worst_rot,
                           Eigen::AngleAxisd(XA[l].linear().transpose() * XB[m].linear()).angle());
    }
  }
  std::ostringstream os;
  os << compared << " links with geometry compared over 200 states: largest origin offset "
     << std::setprecision(3) << worst << " m, rotation " << worst_rot << " rad"
     << (worst > 1e-9 || worst_rot > 1e-9 ? "  ** kinematics differ from the reference **"
                                          : " (same kinematics)");
  return os.str();
}

std::vector<Row> runRobot(const Args& a, const RobotSpec& spec, int robot_index,
                          const std::vector<Setting>& settings, bool* bar_failed) {
  std::vector<Row> rows;
  // Files present?
  std::vector<std::string> need = {robotPath(a, spec.truth.urdf), robotPath(a, spec.truth.srdf)};
  for (const auto& p : need)
    if (!fileExists(p)) {
      std::cout << "tradeoff: skipping " << spec.name << ": " << p << " not found\n";
      return rows;
    }
  const std::string scene_root = a.shared + "/scenes/" + spec.scene_dir;
  if (!fs::is_directory(scene_root)) {
    std::cout << "tradeoff: skipping " << spec.name << ": " << scene_root << " not found\n";
    return rows;
  }
  RobotRun run;
  run.spec = &spec;
  const double t_load = cpuNow();
  run.L.truth = loadRobot(robotPath(a, spec.truth.urdf), robotPath(a, spec.truth.srdf));
  auto loadVariant = [&](const std::optional<VariantSpec>& v,
                         const char* what) -> std::optional<LoadedRobot> {
    if (!v) return std::nullopt;
    if (!fileExists(robotPath(a, v->urdf)) || !fileExists(robotPath(a, v->srdf))) {
      std::cout << "tradeoff: " << spec.name << ": no " << what << " model ("
                << robotPath(a, v->urdf) << " absent)\n";
      return std::nullopt;
    }
    LoadedRobot lr = loadRobot(robotPath(a, v->urdf), robotPath(a, v->srdf));
    for (const auto& p : addDefaultCollidingPairs(lr))
      std::cout
          << "  " << what << " model: self pair " << p
          << " collides at the default state: disabled (MoveIt Setup Assistant's 'Default' rule)\n";
    return lr;
  };
  run.L.spheres = loadVariant(spec.spheres, "sphere");
  run.L.capsules = loadVariant(spec.capsules, "capsule");
  // The reference URDF with every mesh decomposed (only when a setting needs it: the first
  // load of a robot computes its decompositions; later ones read them from the cache).
  if (std::any_of(settings.begin(), settings.end(),
                  [](const Setting& s) { return s.geo == Geo::kDecomposed; })) {
    LoadOptions lo;
    lo.meshes.geometry = MeshGeometry::kDecompose;
    lo.meshes.decomposition.tolerance = a.decompose_tolerance;
    const double t0 = cpuNow();
    run.L.decomposed = loadRobot(robotPath(a, spec.truth.urdf), robotPath(a, spec.truth.srdf), lo);
    // Its pieces are counted by the model summary printed with the other variants below.
    std::cout << "  decomposed model: tolerance " << a.decompose_tolerance * 1e3
              << " mm, loaded in " << std::setprecision(2) << cpuNow() - t0 << " s CPU\n";
  }

  // Scenes.
  const int per_type = std::min(a.quick ? 1 : a.scenes_per_type, spec.max_scenes_per_type);
  std::vector<std::string> types = spec.types;
  if (a.quick) types.resize(1);
  for (const auto& t : types) {
    for (int k = 1; k <= per_type; ++k) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%04d", k);
      const std::string sp = scene_root + "/" + t + "/scene" + buf + ".yaml";
      const std::string rp = scene_root + "/" + t + "/request" + buf + ".yaml";
      if (!fileExists(sp)) continue;
      auto ctx = std::make_unique<SceneCtx>();
      ctx->name = t + "/" + buf;
      ctx->scene_path = sp;
      if (spec.requests && fileExists(rp)) {
        ctx->request_path = rp;
        const PlanRequest req = loadPlanRequestYaml(rp);
        ctx->start = req.startState();
        ctx->group = req.group_name;
      }
      run.scenes.push_back(std::move(ctx));
    }
  }
  if (run.scenes.empty()) {
    std::cout << "tradeoff: skipping " << spec.name << ": no scenes under " << scene_root << "\n";
    return rows;
  }

  // Reference problems, truth checkers, bounds.
  for (auto& ctx : run.scenes) {
    VariantProblem& ref = problemFor(*ctx, run.L, Geo::kHull, 0.0, nullptr);
    auto tr = std::make_unique<Truth>();
    tr->vp = &ref;
    CheckerConfig mc;
    mc.checker = "fcl-mesh";
    tr->mesh = std::dynamic_pointer_cast<const FclChecker>(makeStateChecker(ref.p.model, mc));
    tr->chains = chainBounds(*ref.p.model);
    tr->delta = a.delta;
    run.truths.push_back(std::move(tr));
  }
  {
    const GroupStateMap& map = *run.scenes[0]->problems.begin()->second->p.map;
    for (std::size_t i = 0; i < map.dimension(); ++i) {
      run.lo.push_back(map.lower(i));
      run.hi.push_back(map.upper(i));
      run.extent += (map.upper(i) - map.lower(i)) * (map.upper(i) - map.lower(i));
    }
    run.extent = std::sqrt(run.extent);
  }
  const VariantProblem& ref0 = *run.scenes[0]->problems.at(problemKey(Geo::kHull, 0.0));
  std::cout << "\n=== " << spec.name << ": " << run.L.truth.model->source << " ("
            << ref0.p.map->dimension() << " joints, group '" << ref0.p.group << "'), "
            << run.scenes.size() << " scene(s) of " << spec.scene_dir << "; loaded in "
            << std::fixed << std::setprecision(2) << cpuNow() - t_load << " s CPU\n";
  std::cout << "  reference (truth) model: " << ref0.p.model->summary() << "\n";
  {
    std::mt19937_64 krng(a.seed + 7);
    for (Geo g : {Geo::kSpheres, Geo::kCapsules, Geo::kDecomposed}) {
      if (!run.L.get(g)) continue;
      VariantProblem& vp = problemFor(*run.scenes[0], run.L, g, 0.0, &ref0);
      std::cout << "  " << geoName(g) << " model " << run.L.get(g)->model->source << ": "
                << vp.p.model->summary() << "\n    "
                << kinematicsCheck(ref0, vp, krng, run.lo, run.hi) << "\n";
    }
  }

  // States and motions, per scene (seeded by robot and scene).
  const long nsc = long(run.scenes.size());
  const long states_total = a.states, motions_total = a.motions;
  long t_states = 0, t_motions = 0;
  double truth_cpu = 0;
  std::uint64_t truth_samples = 0;
  std::vector<double> q, qa, qb;
  for (long si = 0; si < nsc; ++si) {
    SceneCtx& ctx = *run.scenes[si];
    const Truth& tr = *run.truths[si];
    const VariantProblem& ref = *tr.vp;
    const long ns = states_total / nsc + (si < states_total % nsc ? 1 : 0);
    const long nm = motions_total / nsc + (si < motions_total % nsc ? 1 : 0);
    std::mt19937_64 rng(a.seed * 1000003ULL + std::uint64_t(robot_index) * 1009ULL +
                        std::uint64_t(si));
    const std::size_t d = run.lo.size();
    auto uniform = [&](std::vector<double>& g) {
      g.resize(d);
      for (std::size_t i = 0; i < d; ++i)
        g[i] = std::uniform_real_distribution<double>(run.lo[i], run.hi[i])(rng);
    };
    q.resize(ref.nq());
    qa.resize(ref.nq());
    qb.resize(ref.nq());
    const double c0 = cpuNow();
    for (long i = 0; i < ns; ++i) {
      std::vector<double> g;
      uniform(g);
      ref.toQ(g.data(), q.data());
      ctx.state_truth.push_back(tr.mesh->collides(q.data()));
      ctx.states.push_back(std::move(g));
    }
    // Motions: a truth-free start and a truth-free end (an independent uniform state, or with
    // --motion-length F < 1 a random direction and a length uniform in (0, F] x extent, clipped
    // at the limits); the truth then decides the interior.
    long attempts = 0;
    while (long(ctx.motions.size()) < nm && attempts < 1000 * std::max(1L, nm)) {
      ++attempts;
      Motion mo;
      uniform(mo.g0);
      ref.toQ(mo.g0.data(), qa.data());
      if (tr.stateCollides(qa.data())) continue;
      std::vector<double> dir(d);
      double nn = 0;
      for (auto& x : dir) x = std::normal_distribution<double>()(rng), nn += x * x;
      const double len =
          (1.0 - std::uniform_real_distribution<double>()(rng)) * a.motion_length * run.extent;
      mo.g1.resize(d);
      double reach = len;  // clipped where the motion would leave the joint limits
      for (std::size_t i = 0; i < d; ++i) {
        const double v = dir[i] / std::sqrt(nn);
        if (v > 0) reach = std::min(reach, (run.hi[i] - mo.g0[i]) / v);
        if (v < 0) reach = std::min(reach, (run.lo[i] - mo.g0[i]) / v);
      }
      if (a.motion_length >= 1.0) {  // independent pairs of free states
        uniform(mo.g1);
      } else {
        for (std::size_t i = 0; i < d; ++i)
          mo.g1[i] = std::clamp(mo.g0[i] + reach * dir[i] / std::sqrt(nn), run.lo[i], run.hi[i]);
      }
      ref.toQ(mo.g1.data(), qb.data());
      if (tr.stateCollides(qb.data())) continue;
      ctx.motion_truth.push_back(tr.motionCollides(qa.data(), qb.data(), q));
      ctx.motions.push_back(std::move(mo));
    }
    if (long(ctx.motions.size()) < nm)
      std::cout << "  note: " << ctx.name << ": only " << ctx.motions.size() << " of " << nm
                << " motions found (free endpoints are rare here)\n";
    truth_cpu += cpuNow() - c0;
    truth_samples += tr.samples;
    t_states += std::count(ctx.state_truth.begin(), ctx.state_truth.end(), 1);
    t_motions += std::count(ctx.motion_truth.begin(), ctx.motion_truth.end(), 1);
  }
  long n_states = 0, n_motions = 0;
  for (auto& c : run.scenes)
    n_states += long(c->states.size()), n_motions += long(c->motions.size());
  std::cout << "  " << n_states << " states (" << t_states << " colliding in the truth), "
            << n_motions << " motions (" << t_motions
            << " colliding in the truth; motion truth: delta " << a.delta * 1e3 << " mm, "
            << truth_samples << " samples); truth computed in " << std::setprecision(1) << truth_cpu
            << " s CPU\n";

  // Settings that this robot has a model for.
  std::vector<const Setting*> active;
  for (const auto& s : settings) {
    if (!run.L.get(s.geo)) {
      std::cout << "  setting '" << s.name << "': no " << geoName(s.geo) << " model for "
                << spec.name << " (not measured)\n";
      continue;
    }
    active.push_back(&s);
  }

  // Instances per setting and scene.
  std::map<std::string, std::vector<std::unique_ptr<Instance>>> inst;  // motionKey -> per scene
  std::map<std::string, const Setting*> by_state, by_motion;
  for (const Setting* s : active) {
    by_state.emplace(s->stateKey(), s);
    by_motion.emplace(s->motionKey(), s);
  }
  for (const auto& [key, s] : by_motion) {
    auto& v = inst[key];
    for (long si = 0; si < nsc; ++si) {
      SceneCtx& ctx = *run.scenes[si];
      const VariantProblem& ref = *run.truths[si]->vp;
      const Geo pg = s->isFcl() ? Geo::kHull : s->geo;
      const VariantProblem& vp = problemFor(ctx, run.L, pg, s->pad, &ref);
      auto in = std::make_unique<Instance>();
      in->vp = &vp;
      in->checker = makeSettingChecker(vp, *s);
      if (s->resolution <= 0) {
        in->cmv = std::make_shared<const ContinuousMotionChecker>(
            std::dynamic_pointer_cast<const DssChecker>(in->checker));
      }
      if (s->batched) in->vector = std::make_shared<const DiscreteMotionChecker>(in->checker, true);
      const std::size_t nq = vp.nq();
      in->qs.resize(ctx.states.size() * nq);
      for (std::size_t i = 0; i < ctx.states.size(); ++i)
        vp.toQ(ctx.states[i].data(), &in->qs[i * nq]);
      in->m0.resize(ctx.motions.size() * nq);
      in->m1.resize(ctx.motions.size() * nq);
      for (std::size_t i = 0; i < ctx.motions.size(); ++i) {
        vp.toQ(ctx.motions[i].g0.data(), &in->m0[i * nq]);
        vp.toQ(ctx.motions[i].g1.data(), &in->m1[i * nq]);
        double dist = 0;
        for (std::size_t k = 0; k < ctx.motions[i].g0.size(); ++k)
          dist += (ctx.motions[i].g1[k] - ctx.motions[i].g0[k]) *
                  (ctx.motions[i].g1[k] - ctx.motions[i].g0[k]);
        // OMPL's DiscreteMotionValidator: ceil(distance / (resolution x maximum extent)) segments.
        in->segs.push_back(
            s->resolution > 0
                ? std::max(1L, long(std::ceil(std::sqrt(dist) / (s->resolution * run.extent))))
                : 0);
      }
      v.push_back(std::move(in));
    }
  }

  // Timed runs: every state key, then every motion key, in each repetition.
  const int reps = a.quick ? 1 : std::max(1, a.reps);
  std::map<std::string, std::vector<double>> t_state, t_motion;
  std::map<std::string, std::vector<std::vector<char>>> ans_state, ans_motion;  // per scene
  std::map<std::string, std::uint64_t> caps_state, caps_motion;
  for (int rep = 0; rep < reps; ++rep) {
    for (const auto& [skey, s] : by_state) {
      auto& v = inst.at(s->motionKey());
      double cpu = 0;
      std::uint64_t caps = 0;
      for (long si = 0; si < nsc; ++si) {
        Instance& in = *v[si];
        const std::size_t n = run.scenes[si]->states.size(), nq = in.vp->nq();
        std::vector<char> ans(n);
        const std::uint64_t caps0 = in.checker->counters().cap_hits;
        const double c0 = cpuNow();
        for (std::size_t i = 0; i < n; ++i) ans[i] = in.checker->collides(&in.qs[i * nq]);
        cpu += cpuNow() - c0;
        caps += in.checker->counters().cap_hits - caps0;
        if (rep == 0) ans_state[skey].push_back(std::move(ans));
      }
      t_state[skey].push_back(cpu);
      if (rep == 0) caps_state[skey] = caps;
    }
    for (const auto& [mkey, s] : by_motion) {
      auto& v = inst.at(mkey);
      double cpu = 0;
      std::uint64_t caps = 0;
      for (long si = 0; si < nsc; ++si) {
        Instance& in = *v[si];
        const std::size_t n = run.scenes[si]->motions.size(), nq = in.vp->nq();
        std::vector<char> ans(n);
        std::vector<double> qq(nq);
        const std::uint64_t caps0 = in.checker->counters().cap_hits;
        const double c0 = cpuNow();
        for (std::size_t i = 0; i < n; ++i) {
          const double* q0 = &in.m0[i * nq];
          const double* q1 = &in.m1[i * nq];
          bool coll = in.checker->collides(q0);
          if (!coll && in.cmv) {
            coll = !in.cmv->clear(q0, q1);
          } else if (!coll && in.vector) {  // the same states, the end first, in batches
            coll = !in.vector->clear(q0, q1, int(in.segs[i]));
          } else if (!coll) {
            // OMPL order: the end state, then the interior states in order.
            coll = in.checker->collides(q1);
            const long segs = in.segs[i];
            for (long j = 1; !coll && j < segs; ++j) {
              const double t = double(j) / double(segs);
              for (std::size_t k = 0; k < nq; ++k) qq[k] = q0[k] + t * (q1[k] - q0[k]);
              coll = in.checker->collides(qq.data());
            }
          }
          ans[i] = coll;
        }
        cpu += cpuNow() - c0;
        caps += in.checker->counters().cap_hits - caps0;
        if (rep == 0) ans_motion[mkey].push_back(std::move(ans));
      }
      t_motion[mkey].push_back(cpu);
      if (rep == 0) caps_motion[mkey] = caps;
    }
  }

  // Score against the truth.
  for (const Setting* s : active) {
    Row r;
    r.robot = spec.name;
    r.s = *s;
    r.model = s->geo == Geo::kSpheres || s->geo == Geo::kCapsules ? run.L.get(s->geo)->model->source
                                                                  : run.L.truth.model->source;
    r.model = fs::path(r.model).lexically_relative(a.shared + "/robots").string();
    r.scenes = int(nsc);
    const auto& as = ans_state.at(s->stateKey());
    // Hulls and decomposed pieces contain the meshes: exact DSS on them must never miss.
    const bool hull_exact = (s->geo == Geo::kHull || s->geo == Geo::kDecomposed) &&
                            s->mode == Mode::kExact && s->pad == 0.0;
    const bool tally_fa = s->mode == Mode::kExact && s->pad == 0.0 && s->cap == 64 && !s->isFcl() &&
                          s->resolution == 0.01 && !s->batched;
    std::map<std::string, long> fa_pairs;
    for (long si = 0; si < nsc; ++si) {
      const SceneCtx& ctx = *run.scenes[si];
      for (std::size_t i = 0; i < ctx.states.size(); ++i) {
        const bool t = ctx.state_truth[i], x = as[si][i];
        ++r.states;
        r.truth_states += t;
        if (t && !x) {
          ++r.missed;
          if (hull_exact) {
            const Truth& tr = *run.truths[si];
            std::vector<double> qv(tr.vp->nq());
            tr.vp->toQ(ctx.states[i].data(), qv.data());
            const Diagnosis dg = diagnose(*tr.vp, *tr.mesh, qv.data());
            if (dg.fcl_gap)
              ++r.fcl_gap_claims;
            else
              ++r.unexplained;
            std::cout << "  "
                      << (dg.fcl_gap ? "FCL claims a collision at a DSS-certified gap"
                                     : "** MISS **")
                      << " (" << s->name << ", " << ctx.name << ", state " << i << "):\n"
                      << dg.text;
          }
        }
        r.false_alarms += !t && x;
        if (!t && x && tally_fa) {
          const VariantProblem& vp =
              problemFor(*run.scenes[si], run.L, s->geo, 0.0, run.truths[si]->vp);
          std::vector<double> qv(vp.nq());
          vp.toQ(ctx.states[i].data(), qv.data());
          for (const auto& pname : collidingPairs(*vp.p.model, qv.data())) ++fa_pairs[pname];
        }
      }
    }
    if (!fa_pairs.empty()) {
      std::vector<std::pair<long, std::string>> top;
      for (const auto& [k, v] : fa_pairs) top.push_back({v, k});
      std::sort(top.rbegin(), top.rend());
      std::cout << "  false alarms of '" << s->name << "' (" << r.false_alarms
                << " states), pairs most often involved:";
      for (std::size_t k = 0; k < top.size() && k < 4; ++k)
        std::cout << (k ? ";" : "") << " " << top[k].second << " (" << top[k].first << ")";
      std::cout << "\n";
    }
    r.cap_hits = caps_state.at(s->stateKey());
    r.us_state = r.states ? median(t_state.at(s->stateKey())) * 1e6 / double(r.states) : 0.0;
    r.measured_states = true;
    const auto& am = ans_motion.at(s->motionKey());
    for (long si = 0; si < nsc; ++si) {
      const SceneCtx& ctx = *run.scenes[si];
      for (std::size_t i = 0; i < ctx.motions.size(); ++i) {
        const bool t = ctx.motion_truth[i], x = am[si][i];
        ++r.motions;
        r.truth_motions += t;
        r.m_missed += t && !x;
        r.m_false += !t && x;
      }
    }
    r.m_cap_hits = caps_motion.at(s->motionKey());
    r.us_motion = r.motions ? median(t_motion.at(s->motionKey())) * 1e6 / double(r.motions) : 0.0;
    r.measured_motions = r.motions > 0;
    if (hull_exact && r.unexplained > 0) *bar_failed = true;
    rows.push_back(r);
  }

  // Planning: RRTConnect (OMPL defaults) on the scenes' requests.
  if (a.plan && spec.requests) {
    for (auto& r : rows) {
      if (!r.s.plan) continue;
      if (a.quick && r.s.name != "default" && r.s.name != "continuous") continue;
      std::vector<double> cpu_ms, wall_ms;
      for (long si = 0; si < nsc; ++si) {
        if (a.quick && si > 0) break;
        SceneCtx& ctx = *run.scenes[si];
        if (ctx.request_path.empty()) continue;
        const PlanRequest req = loadPlanRequestYaml(ctx.request_path);
        const Geo pg = r.s.isFcl() ? Geo::kHull : r.s.geo;
        const LoadedRobot* robot = run.L.get(pg);
        Problem p = makeProblem(*robot, loadScene(ctx.scene_path), ctx.group, ctx.start, r.s.pad);
        VariantProblem vp;  // only for the map back to reference joint order
        vp.p = p;
        vp.held = p.map->held();
        const auto& ref = *run.truths[si]->vp;
        for (const auto& n : p.map->jointNames()) {
          const auto& rn = ref.p.map->jointNames();
          vp.from_truth.push_back(int(std::find(rn.begin(), rn.end(), n) - rn.begin()));
        }
        auto checker = std::make_shared<ValidityChecker>(p.si, makeSettingChecker(vp, r.s), p.map);
        og::SimpleSetup ss(p.si);
        ss.setStateValidityChecker(checker);
        if (r.s.resolution > 0) {  // the discrete validator, as dss_plan's default
          p.si->setStateValidityCheckingResolution(r.s.resolution);
          p.si->setMotionValidator(makeDiscreteMotionValidator(p, *checker));
        } else {
          p.si->setMotionValidator(makeContinuousMotionValidator(p, *checker));
        }
        ss.setPlanner(std::make_shared<og::RRTConnect>(p.si));
        ob::ScopedState<> s0(p.si->getStateSpace());
        const std::vector<double> g0 = p.map->groupValues(ctx.start);
        p.map->fromGroupValues(g0.data(), s0.get());
        ss.setStartState(s0);
        auto goal = std::make_shared<ob::GoalStates>(p.si);
        for (const auto& gc : req.goals) {
          std::map<std::string, double> by_name = ctx.start;
          for (const auto& jc : gc.joint_constraints) by_name[jc.joint_name] = jc.position;
          ob::ScopedState<> gs(p.si->getStateSpace());
          const std::vector<double> gv = p.map->groupValues(by_name);
          p.map->fromGroupValues(gv.data(), gs.get());
          goal->addState(gs);
        }
        ss.setGoal(goal);
        ss.setup();
        if (!checker->isValid(s0.get()) || !checker->isValid(goal->getState(0)))
          ++r.plan_start_goal_invalid;
        ++r.plan_problems;
        const double c0 = cpuNow();
        const auto w0 = std::chrono::steady_clock::now();
        const ob::PlannerStatus st = ss.solve(a.quick ? std::min(a.plan_time, 2.0) : a.plan_time);
        const double cpu = cpuNow() - c0;
        const double wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
        const bool solved = st == ob::PlannerStatus::EXACT_SOLUTION;
        cpu_ms.push_back(solved ? cpu * 1e3 : INFINITY);
        wall_ms.push_back(solved ? wall * 1e3 : INFINITY);
        if (!solved) continue;
        ++r.plan_solved;
        // The solution path against the truth: states and the motions between them.
        const Truth& tr = *run.truths[si];
        const auto& states = ss.getSolutionPath().getStates();
        const std::size_t dim = p.map->dimension();
        std::vector<double> gv(dim), gref(dim), qa2(tr.vp->nq()), qb2(tr.vp->nq()), qt(tr.vp->nq());
        bool coll = false;
        for (std::size_t k = 0; k < states.size() && !coll; ++k) {
          p.map->toGroupValues(states[k], gv.data());
          for (std::size_t i = 0; i < dim; ++i) gref[vp.from_truth[i]] = gv[i];
          tr.vp->toQ(gref.data(), qb2.data());
          coll = tr.stateCollides(qb2.data());
          if (!coll && k > 0) coll = tr.motionCollides(qa2.data(), qb2.data(), qt);
          qa2.swap(qb2);
        }
        r.plan_truth_colliding += coll;
      }
      // Median over problems, failures counted as infinitely slow.
      r.plan_cpu_ms = median(cpu_ms);
      r.plan_wall_ms = median(wall_ms);
      r.measured_plan = r.plan_problems > 0;
    }
  }
  return rows;
}

// ---------------------------------------------------------------------------------------------
// Output

std::string pct(long k, long n) {
  if (n <= 0) return "-";
  std::ostringstream os;
  os << std::fixed
     << std::setprecision(k == 0                ? 0
                          : 100.0 * k / n < 0.1 ? 3
                                                : 2)
     << 100.0 * double(k) / double(n) << "%";
  return os.str();
}

void printTable(const std::vector<Row>& rows) {
  std::string robot;
  for (const auto& r : rows) {
    if (r.robot != robot) {
      robot = r.robot;
      std::printf("\n%s: %ld states (%ld colliding in the truth), %ld motions (%ld colliding)\n",
                  robot.c_str(), r.states, r.truth_states, r.motions, r.truth_motions);
      std::printf("%-19s %9s %8s %8s %9s %9s %5s | %9s %8s %8s %9s | %6s %10s %6s\n", "setting",
                  "us/state", "missed", "(rate)", "false al.", "(rate)", "caps", "us/motion",
                  "missed", "(rate)", "false al.", "solved", "median ms", "bad");
    }
    std::printf("%-19s %9.3f %8ld %8s %9ld %9s %5llu | %9.2f %8ld %8s %9ld |", r.s.name.c_str(),
                r.us_state, r.missed, pct(r.missed, r.truth_states).c_str(), r.false_alarms,
                pct(r.false_alarms, r.states - r.truth_states).c_str(),
                (unsigned long long)r.cap_hits, r.us_motion, r.m_missed,
                pct(r.m_missed, r.truth_motions).c_str(), r.m_false);
    if (r.measured_plan)
      std::printf(" %2d/%-3d %10.1f %6d\n", r.plan_solved, r.plan_problems, r.plan_cpu_ms,
                  r.plan_truth_colliding);
    else
      std::printf(" %6s %10s %6s\n", "-", "-", "-");
    if (r.fcl_gap_claims)
      std::printf(
          "    (of the %ld missed: %ld are FCL collisions at a DSS-certified gap, %ld "
          "unexplained)\n",
          r.missed, r.fcl_gap_claims, r.unexplained);
  }
  std::printf(
      "\nmissed rate = missed / truth-colliding; false-alarm rate = false alarms / truth-free; "
      "caps = answers at the "
      "iteration cap (state checks);\nplanning: solved/problems, median thread-CPU ms over "
      "problems (failures count "
      "as slowest), bad = solution paths the truth finds colliding\n");
}

void writeCsv(const std::string& path, const std::vector<Row>& rows, const Args& a) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  out << "robot,setting,axis,geometry,model,mode,cap,padding_m,motion_check,scenes,states,truth_"
         "colliding_states,"
         "us_per_state,state_missed,state_false_alarms,state_cap_hits,fcl_gap_claims,unexplained_"
         "misses,motions,"
         "truth_colliding_motions,us_per_motion,motion_missed,motion_false_alarms,motion_cap_hits,"
         "plan_problems,"
         "plan_solved,plan_median_cpu_ms,plan_median_wall_ms,plan_paths_truth_colliding,plan_start_"
         "or_goal_invalid,"
         "delta_m,motion_length,reps,seed,command\n";
  out << std::setprecision(6);
  for (const auto& r : rows) {
    out << r.robot << "," << r.s.name << "," << r.s.axis << "," << geoName(r.s.geo) << ","
        << r.model << "," << r.s.modeName() << "," << r.s.capName() << "," << r.s.pad << ","
        << r.s.motionName() << "," << r.scenes << "," << r.states << "," << r.truth_states << ","
        << r.us_state << "," << r.missed << "," << r.false_alarms << "," << r.cap_hits << ","
        << r.fcl_gap_claims << "," << r.unexplained << "," << r.motions << "," << r.truth_motions
        << "," << r.us_motion << "," << r.m_missed << "," << r.m_false << "," << r.m_cap_hits
        << ",";
    if (r.measured_plan)
      out << r.plan_problems << "," << r.plan_solved << "," << r.plan_cpu_ms << ","
          << r.plan_wall_ms << "," << r.plan_truth_colliding << "," << r.plan_start_goal_invalid;
    else
      out << ",,,,,";
    out << "," << a.delta << "," << a.motion_length << "," << (a.quick ? 1 : a.reps) << ","
        << a.seed << ",\"" << a.command << "\"\n";
  }
}

int runTradeoff(int argc, char** argv) {
  Args a;
  std::ostringstream cmd;
  cmd << "dss_bench tradeoff";
  bool states_set = false, motions_set = false;
  for (int i = 1; i < argc; ++i) {
    const std::string o = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(o + " needs a value\n" + kUsage);
      return argv[++i];
    };
    if (o != "--csv" && o != "--shared") cmd << " " << o;
    if (o == "--robots") {
      a.robots = splitList(value());
      cmd << " " << argv[i];
      const std::set<std::string> known = {"panda", "ur5", "iiwa"};
      if (a.robots.empty()) throw std::invalid_argument("--robots: empty list");
      for (const auto& r : a.robots)
        if (!known.count(r))
          throw std::invalid_argument("--robots: unknown robot '" + r + "' (panda, ur5, iiwa)");
    } else if (o == "--states" || o == "--motions" || o == "--seed" || o == "--reps" ||
               o == "--scenes-per-type") {
      const std::string v = value();
      cmd << " " << v;
      const double x = parseNumber(o, v);
      if (x < 0 || x != std::floor(x) || x > 1e9)
        throw std::invalid_argument(o + ": '" + v + "' is not a count");
      if (o == "--states")
        a.states = long(x), states_set = true;
      else if (o == "--motions")
        a.motions = long(x), motions_set = true;
      else if (o == "--seed")
        a.seed = std::uint64_t(x);
      else if (o == "--reps") {
        if (x < 1) throw std::invalid_argument("--reps must be at least 1");
        a.reps = int(x);
      } else {
        if (x < 1) throw std::invalid_argument("--scenes-per-type must be at least 1");
        a.scenes_per_type = int(x);
      }
    } else if (o == "--csv")
      a.csv = value();
    else if (o == "--shared")
      a.shared = value();
    else if (o == "--settings") {
      const std::string v = value();
      cmd << " " << v;
      std::set<std::string> names;
      for (const auto& s : allSettings()) names.insert(s.name);
      for (const auto& s : splitList(v)) {
        if (!names.count(s)) {
          std::string all;
          for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
          throw std::invalid_argument("--settings: unknown setting '" + s + "' (" + all + ")");
        }
        a.only.insert(s);
      }
    } else if (o == "--delta" || o == "--motion-length" || o == "--plan-time" ||
               o == "--decompose-tolerance") {
      const std::string v = value();
      cmd << " " << v;
      const double x = parseNumber(o, v);
      if (x <= 0) throw std::invalid_argument(o + " must be positive");
      if (o == "--delta")
        a.delta = x;
      else if (o == "--motion-length")
        a.motion_length = x;
      else if (o == "--decompose-tolerance")
        a.decompose_tolerance = x;
      else
        a.plan_time = x;
    } else if (o == "--no-plan")
      a.plan = false;
    else if (o == "--quick")
      a.quick = true;
    else if (o == "-h" || o == "--help") {
      std::cout << kUsage;
      return 0;
    } else
      throw std::invalid_argument("unknown option '" + o + "'\n" + kUsage);
  }
  if (a.quick) {
    if (!states_set) a.states = 300;
    if (!motions_set) a.motions = 40;
  }
  if (!a.csv.empty()) cmd << " --csv " << a.csv;
  a.command = cmd.str();
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  ompl::RNG::setSeed(std::uint_fast32_t(a.seed));

  if (!fs::is_directory(a.shared + "/robots")) {
    std::cout << "tradeoff: skipping every robot: " << a.shared
              << "/robots not found (set --shared)\n";
    if (!a.csv.empty()) writeCsv(a.csv, {}, a);
    return kExitNothingMeasured;
  }
  std::vector<Setting> settings;
  for (const auto& s : allSettings())
    if (a.only.empty() || a.only.count(s.name)) settings.push_back(s);
  std::cout << a.command << "\n";
  std::vector<Row> rows;
  bool bar_failed = false;
  const auto specs = robotSpecs();
  for (const auto& name : a.robots) {
    for (std::size_t k = 0; k < specs.size(); ++k) {
      if (specs[k].name != name) continue;
      auto r = runRobot(a, specs[k], int(k), settings, &bar_failed);
      rows.insert(rows.end(), r.begin(), r.end());
    }
  }
  printTable(rows);
  if (!a.csv.empty()) {
    writeCsv(a.csv, rows, a);
    std::cout << "wrote " << a.csv << "\n";
  }
  // Hulls contain the meshes, so hull+exact must never miss a mesh collision.
  long unexplained = 0, gaps = 0;
  for (const auto& r : rows)
    if (r.s.geo == Geo::kHull && r.s.mode == Mode::kExact && r.s.pad == 0.0)
      unexplained += r.unexplained, gaps += r.fcl_gap_claims;
  if (gaps)
    std::cout << "note: FCL called " << gaps
              << " hull+exact-free state(s) colliding at a DSS-certified gap (listed above)\n";
  if (bar_failed) {
    std::cout << "FAIL: hull+exact missed " << unexplained
              << " collision(s) of the mesh truth (listed above)\n";
    return 3;
  }
  return 0;
}

}  // namespace

DSS_BENCH_SUBCOMMAND(
    "tradeoff", "speed vs missed collisions and false alarms of checking settings on real robots",
    runTradeoff);

}  // namespace bench
}  // namespace dss
