// dss_check: validity of robot states (CSV, or uniform random ones) against a scene with one
// or several checkers. stdout: 1/0 per state for the first checker; stderr: one JSON summary
// per checker (states, valid, median microseconds per state over repetitions, disagreements
// against the first checker). --describe prints the model as JSON instead; --motions checks
// the motions between the states instead (motion_checks.h).
#include <ompl/base/ScopedState.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "cli.h"
#include "dss/checker/contacts.h"
#include "dss/checker/fcl_checker.h"
#include "dss/core/simd_path.h"
#include "dss/planning/planning_problem.h"
#include "dss/robot/joint_states_csv.h"
#include "dss/scene/scene_loader.h"
#include "mesh_cli.h"
#include "motion_checks.h"
#include "timing.h"

namespace {

// Option ranges (as dss_plan's): paddings in metres, seeds for OMPL's 32-bit seed generator.
constexpr double kMaxPadding = 1e3;
constexpr long long kMaxCount = 1000000000;
constexpr long long kMaxSeed = 4294967295;  // OMPL seeds are 32-bit
constexpr long long kMaxThreads = 1024;
constexpr long long kMaxMotions = 10000000;  // --motions --random: two OMPL states each

const char* kUsage =
    "usage: dss_check --robot R.urdf [--srdf S.srdf] [--scene FILE] [--group G]\n"
    "                 (--states FILE.csv | --random N [--seed S])\n"
    "                 [--checker dss|fcl-hull|fcl-mesh[:sweep][,...]] [--padding r] "
    "[--self-padding r]\n"
    "                 [--repeat K] [--describe] [--contacts]\n"
    "                 [--mode exact|double|float] [--no-obb-stage] [--threads N]\n"
    "                 [--workspace XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX]  (bounds of planar and\n"
    "                 floating joints' translation; needed when the group moves one)\n"
    "                 [--base-table-cells N]  (a planar base's table against the scene: at\n"
    "                 most about N cells, 0 for none; default 65536)\n"
    "                 [--scene-mesh-parts N]  (a scene mesh: the hulls of its connected\n"
    "                 parts, at most N, in [1, 4096]; default 16; 1: one hull per mesh)\n"
    "                 [--motions discrete|vector|continuous|ompl[,...]] [--resolution f]\n"
    "                 [--motion-length f] [--motion-min-fraction f]\n"
    "  --padding r, --self-padding r  in [0, 1000]; --random N >= 1; --seed S in [0, 2^32-1];\n"
    "  --repeat K: 0 (default) picks 5, 11 or 31 by the number of states; --threads N >= 1\n"
    "  --contacts: each line of a state the first checker calls colliding also names the\n"
    "  pairs that collide there (exact DSS with the same paddings), after a tab\n"
    "  --motions: check motions instead of states, each listed motion validator on the one\n"
    "  --checker: the path from each row of --states to the next, or --random N motions\n"
    "  (N <= 10^7: a valid start towards a uniform state, cut to a length uniform up to\n"
    "  --motion-length times the space's extent, in (0, 1], default 0.2); stdout: 1/0 per\n"
    "  motion for the first validator (with --contacts, its first colliding state and pairs);\n"
    "  --resolution f in (0, 1]: OMPL's state validity checking resolution (0.01)\n"
    "  --motion-min-fraction f in [1e-12, 1]: the continuous validator's smallest sub-motion\n"
    "  (1/1024); 1: a motion is cleared whole or refused\n"
    "exit codes: 0 success; 1 runtime error (files, model); 2 usage error\n"
    "robot meshes:\n";

using dss::cli::threadCpuSeconds;

nlohmann::json describe(const dss::Problem& p) {
  using nlohmann::json;
  const dss::CollisionModel& m = *p.model;
  const dss::RobotModel& r = m.robot();
  json j;
  j["robot"] = r.name;
  j["group"] = p.group;
  j["group_joints"] = p.map->jointNames();
  json links = json::array();
  for (const auto& s : m.slots()) {
    json l;
    l["name"] = r.links[s.link].name;
    l["moves"] = s.moves;
    l["pose_link"] = r.links[s.pose_link].name;  // the link whose pose places it in a query
    l["bounding_radius"] = s.radius;
    if (s.moves) {
      l["reach_radius"] = s.reach_radius;
      if (s.reach_half_W.any())
        l["reach_box_half"] = {s.reach_half_W.x(), s.reach_half_W.y(), s.reach_half_W.z()};
    }
    json els = json::array();
    for (int e = s.first_element; e < s.first_element + s.num_elements; ++e) {
      const auto& ce = *m.elements()[e].source;
      json x;
      x["shape"] = dss::shapeTypeName(ce.shape);
      x["description"] = ce.description;
      if (const auto* h = std::get_if<dss::ConvexHull>(&ce.shape)) x["hull_vertices"] = h->size();
      if (ce.piece >= 0) {  // a piece of a decomposed mesh
        x["piece"] = ce.piece + 1;
        x["pieces"] = ce.pieces;
        x["concavity"] = ce.concavity;
      }
      const auto& el = m.elements()[e];
      json balls = json::array();  // inner balls (shape frame): x, y, z, radius
      for (int k = 0; k < el.num_inner; ++k)
        balls.push_back(
            {el.inner_S[k].x(), el.inner_S[k].y(), el.inner_S[k].z(), el.inner_S[k].w()});
      x["inner_balls"] = balls;
      if (el.has_inner_box)  // inner box (shape frame): centre, half extents
        x["inner_box"] = {{"center", {el.inner_box_c.x(), el.inner_box_c.y(), el.inner_box_c.z()}},
                          {"half", {el.inner_box_h.x(), el.inner_box_h.y(), el.inner_box_h.z()}}};
      els.push_back(x);
    }
    l["elements"] = els;
    l["obstacles_checked"] = s.obstacles.size();
    links.push_back(l);
  }
  j["links"] = links;
  json joints = json::array();
  for (const auto& jt : r.joints) {
    json x;
    x["name"] = jt.name;
    x["type"] = dss::toString(jt.type);
    if (jt.limits.has_position_limits) x["limits"] = {jt.limits.lower, jt.limits.upper};
    joints.push_back(x);
  }
  j["joints"] = joints;
  json multi = json::array();  // planar and floating joints and the joints they became
  for (const auto& md : r.multi_dof_joints) {
    json x;
    x["name"] = md.name;
    x["type"] = md.type == dss::MultiDofType::kPlanar ? "planar" : "floating";
    x["from"] = md.from_srdf ? "srdf virtual joint" : "urdf joint";
    json parts = json::array();
    for (int ji : md.joints) parts.push_back(r.joints[ji].name);
    x["joints"] = parts;
    multi.push_back(x);
  }
  j["multi_dof_joints"] = multi;
  json obs = json::array();
  for (const auto& o : m.scene().obstacles)
    obs.push_back({{"name", o.name}, {"shape", dss::describeShape(o.shape)}});
  j["obstacles_kept"] = obs;
  j["obstacles_total"] = m.obstaclesBefore();
  json pairs = json::array();
  for (const auto& sp : m.selfPairs())
    pairs.push_back({r.links[m.slots()[sp.a].link].name, r.links[m.slots()[sp.b].link].name});
  j["self_pairs"] = pairs;
  const dss::ClearanceGrid& grid = m.clearanceGrid();
  j["clearance_grid"] = {{"voxels", grid.voxels()},
                         {"voxel_size", grid.voxelSize()},
                         {"origin", {grid.origin().x(), grid.origin().y(), grid.origin().z()}}};
  // The links that keep a sphere chain (sphere_chain.h) and its points: outer and inner radii.
  json chains = json::array();
  for (const auto& slot : m.slots()) {
    if (slot.num_chain == 0) continue;
    json points = json::array();
    for (int k = slot.first_chain; k < slot.first_chain + slot.num_chain; ++k) {
      const auto& cp = m.chainPoints()[std::size_t(k)];
      points.push_back({{"outer", cp.outer}, {"inner", cp.inner > 0.0 ? cp.inner : 0.0}});
    }
    chains.push_back({{"link", r.links[slot.link].name}, {"points", points}});
  }
  j["sphere_chains"] = chains;
  j["clearance_grid"]["upper_bounds"] = grid.hasCells();
  j["robot_scene_pairs"] = m.scenePairs();
  j["robot_scene_pairs_total"] = m.scenePairsBefore();
  j["summary"] = m.summary();
  j["warnings"] = p.warnings;
  return j;
}

int run(int argc, char** argv) {
  std::string robot, srdf, scene_path, group, states, checkers = "dss";
  double padding = 0.0, self_padding = 0.0;
  long base_table_cells = -1;  // -1: the model's default
  dss::SceneLoadOptions scene_options;
  long random_n = 0;
  unsigned long seed = 1;
  int repeat = 0;
  bool do_describe = false;
  bool contacts = false;
  std::string mode = "exact";
  bool box_stage = true;
  int threads = 1;
  std::vector<double> workspace;
  std::string motions;  // --motions: the motion validators
  double resolution = 0.01, motion_length = 0.2;
  bool motion_option = false;  // --resolution or --motion-length given
  double min_fraction = dss::kDefaultMinFraction;
  bool min_fraction_given = false;
  const std::string usage = std::string(kUsage) + dss::cli::kMeshOptionsUsage;
  dss::cli::ArgCursor cli(argc, argv, "dss_check", usage.c_str());
  dss::MeshGeometryOptions meshes;
  while (cli.next()) {
    if (dss::cli::meshOption(cli, &meshes)) continue;
    if (cli.option("--robot"))
      robot = cli.value();
    else if (cli.option("--srdf"))
      srdf = cli.value();
    else if (cli.option("--scene"))
      scene_path = cli.value();
    else if (cli.option("--group"))
      group = cli.value();
    else if (cli.option("--states"))
      states = cli.value();
    else if (cli.option("--checker"))
      checkers = cli.value();
    else if (cli.option("--padding"))
      padding = cli.number(0, kMaxPadding);
    else if (cli.option("--self-padding"))
      self_padding = cli.number(0, kMaxPadding);
    else if (cli.option("--base-table-cells"))
      base_table_cells = static_cast<long>(cli.integer(0, 1 << 24));
    else if (cli.option("--scene-mesh-parts"))
      scene_options.max_mesh_parts = static_cast<std::size_t>(cli.integer(1, 4096));
    else if (cli.option("--random"))
      random_n = cli.integer(1, kMaxCount);
    else if (cli.option("--seed"))
      seed = static_cast<unsigned long>(cli.integer(0, kMaxSeed));
    else if (cli.option("--repeat"))
      repeat = static_cast<int>(cli.integer(0, kMaxCount));
    else if (cli.flag("--describe"))
      do_describe = true;
    else if (cli.flag("--contacts"))
      contacts = true;
    else if (cli.option("--mode")) {
      mode = cli.value();
      if (mode != "exact" && mode != "double" && mode != "float")
        cli.error("--mode: expected exact, double or float, got '" + mode + "'");
    } else if (cli.flag("--no-obb-stage"))
      box_stage = false;
    else if (cli.option("--workspace"))
      workspace = cli.numbers(6);
    else if (cli.option("--threads"))
      threads = static_cast<int>(cli.integer(1, kMaxThreads));
    else if (cli.option("--motions"))
      motions = cli.value();
    else if (cli.option("--resolution"))
      resolution = cli.number(0, 1), motion_option = true;
    else if (cli.option("--motion-length"))
      motion_length = cli.number(0, 1), motion_option = true;
    else if (cli.option("--motion-min-fraction"))
      min_fraction = cli.number(1e-12, 1.0), min_fraction_given = true;
    else
      cli.unknown();
  }
  if (robot.empty()) cli.error("--robot is required");
  if (!do_describe && states.empty() && random_n <= 0)
    cli.error("--states or --random is required");
  std::vector<std::string> validators;
  if (motion_option && motions.empty())
    cli.error("--resolution and --motion-length apply to --motions only");
  if (!motions.empty()) {
    std::istringstream is(motions);
    std::string v;
    while (std::getline(is, v, ','))
      if (!dss_check::knownMotionValidator(v))
        cli.error("--motions: expected discrete, vector, continuous or ompl, got '" + v + "'");
      else
        validators.push_back(v);
    if (validators.empty() || motions.back() == ',')
      cli.error("--motions: expected a comma list of motion validators, got '" + motions + "'");
    if (checkers.find(',') != std::string::npos)
      cli.error("--motions: every motion validator stands on one --checker, got '" + checkers +
                "'");
    if (threads > 1)
      cli.error("--motions: one thread only (--threads " + std::to_string(threads) + ")");
    if (checkers != "dss" &&
        std::find(validators.begin(), validators.end(), "continuous") != validators.end())
      cli.error("--motions: the continuous validator needs --checker dss, got '" + checkers + "'");
    if (random_n > kMaxMotions)
      cli.error("--motions: --random takes at most " + std::to_string(kMaxMotions) +
                " motions (each holds two states), got " + std::to_string(random_n));
    if (resolution <= 0) cli.error("--resolution: expected a number in (0, 1]");
    if (motion_length <= 0) cli.error("--motion-length: expected a number in (0, 1]");
  }
  if (min_fraction_given &&
      std::find(validators.begin(), validators.end(), "continuous") == validators.end())
    cli.error("--motion-min-fraction applies to --motions continuous only");
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  ompl::RNG::setSeed(seed);

  dss::LoadOptions load;
  load.meshes = meshes;
  dss::LoadedRobot r = dss::loadRobot(robot, srdf, load);
  if (!workspace.empty())
    r = dss::withWorkspace(r, Eigen::Vector3d(workspace[0], workspace[1], workspace[2]),
                           Eigen::Vector3d(workspace[3], workspace[4], workspace[5]));
  // Every stored warning reaches the user: the robot's and the SRDF's here, the scene's
  // through the problem's warnings below.
  for (const auto& w : r.warnings()) std::cerr << "dss_check: warning: " << w << "\n";
  std::map<std::string, double> path_start;  // --motions on a path: its first state by name
  if (!states.empty()) {
    // A CSV may hold joint values outside the URDF limits (MotionBenchMaker's Panda fingers at
    // 0.065 against 0.04). The model is built with those limits widened to cover them, so that
    // its bounds (prismatic travel, the reach of every link) hold for every row; each widened
    // joint is reported.
    const dss::JointStatesCsv csv =
        dss::readJointStatesCsv(states, *r.model, r.model->defaultState());
    // A path's motions move the group alone: the joints outside it are held at the values of
    // the path's first state (motion_checks.h refuses a row that moves them).
    if (!validators.empty() && !csv.states.empty())
      for (std::size_t a = 0; a < r.model->numActiveJoints(); ++a) {
        const std::string& name = r.model->joints[r.model->active_joints[a]].name;
        if (std::find(csv.columns.begin(), csv.columns.end(), name) != csv.columns.end())
          path_start[name] = csv.states.front()[a];
      }
    auto widened = std::make_shared<dss::RobotModel>(*r.model);
    for (std::size_t a = 0; a < widened->numActiveJoints(); ++a) {
      dss::RobotJoint& j = widened->joints[widened->active_joints[a]];
      if (!j.limits.has_position_limits) continue;
      double lo = j.limits.lower, hi = j.limits.upper;
      for (const auto& q : csv.states)
        if (std::isfinite(q[a])) lo = std::min(lo, q[a]), hi = std::max(hi, q[a]);
      if (lo == j.limits.lower && hi == j.limits.upper) continue;
      std::cerr << "dss_check: warning: " << states << ": joint " << j.name << " has values in ["
                << lo << ", " << hi << "], outside its limits [" << j.limits.lower << ", "
                << j.limits.upper << "]: checked with the limits widened to cover them\n";
      j.limits.lower = lo;
      j.limits.upper = hi;
    }
    r.model = widened;
  }
  dss::Scene scene;
  if (!scene_path.empty()) scene = dss::loadScene(scene_path, scene_options);
  dss::CollisionModelOptions options;
  options.prune_margin = padding;
  if (base_table_cells >= 0) options.base_table_cells = std::size_t(base_table_cells);
  const dss::Problem p = dss::makeProblem(r, std::move(scene), group, path_start, options);
  for (const auto& w : p.warnings) std::cerr << "dss_check: warning: " << w << "\n";
  if (do_describe) {
    std::cout << describe(p).dump(2) << "\n";
    return 0;
  }

  // A checker's configuration by name. "fcl-hull:sweep": FCL behind the DSS checker's own
  // sphere/oriented-box sweep instead of FCL's world AABBs.
  auto configFor = [&](const std::string& name) {
    dss::CheckerConfig cfg;
    cfg.checker = name;
    if (cfg.checker.size() > 6 && cfg.checker.compare(cfg.checker.size() - 6, 6, ":sweep") == 0 &&
        cfg.checker.rfind("fcl-", 0) == 0) {
      cfg.checker.resize(cfg.checker.size() - 6);
      cfg.fcl_prefilter = "shared";
    }
    cfg.scene_padding = padding;
    cfg.self_padding = self_padding;
    if (mode == "exact")
      cfg.dss_options.mode = dss::Mode::kExact;
    else if (mode == "double")
      cfg.dss_options.mode = dss::Mode::kDouble;
    else
      cfg.dss_options.mode = dss::Mode::kFloat;  // checked when parsed
    cfg.obb_stage = box_stage;
    return cfg;
  };

  // States as vectors of every active joint's value. A CSV sets the joints it names (joints
  // outside the group too: such a state takes the full kinematics), the others keep their held
  // values; it must name every joint of the group. Random states are uniform in the group's
  // space.
  const std::size_t nq = r.model->numActiveJoints();
  std::vector<std::vector<double>> st;
  std::vector<int> lines;  // of the CSV's rows
  if (!states.empty()) {
    dss::JointStatesCsv csv = dss::readJointStatesCsv(states, *r.model, p.map->held());
    for (const std::string& name : p.map->jointNames())
      if (std::find(csv.columns.begin(), csv.columns.end(), name) == csv.columns.end())
        throw std::runtime_error(states + ": the header lacks joint '" + name + "' of group '" +
                                 p.group + "'");
    st = std::move(csv.states);
    lines = std::move(csv.lines);
  } else if (validators.empty()) {
    auto sampler = p.si->allocStateSampler();
    ompl::base::ScopedState<> s(p.si->getStateSpace());
    std::vector<double> q(nq);
    for (long i = 0; i < random_n; ++i) {
      sampler->sampleUniform(s.get());
      p.map->toJoints(s.get(), q.data());
      st.push_back(q);
    }
  }

  if (!validators.empty()) {
    dss_check::MotionCheckOptions mo;
    mo.validators = validators;
    mo.checker = configFor(checkers);
    mo.resolution = resolution;
    mo.motion_length = motion_length;
    mo.min_fraction = min_fraction;
    mo.random = states.empty() ? random_n : 0;
    mo.repeat = repeat;
    mo.contacts = contacts;
    mo.path_file = states;
    dss_check::checkMotions(p, st, lines, mo);
    return 0;
  }

  std::vector<std::string> names_list;
  {
    std::istringstream is(checkers);
    std::string c;
    while (std::getline(is, c, ',')) names_list.push_back(c);
  }
  if (repeat <= 0) repeat = st.size() >= 10000 ? 5 : st.size() >= 1000 ? 11 : 31;
  // Every checker is built first; then the repetitions run interleaved (checker 1, 2, ...,
  // then again), after one untimed warm-up pass each, so that a slow phase of a shared machine
  // hits every checker alike and the ratios of medians stay meaningful.
  std::vector<std::shared_ptr<const dss::StateChecker>> built;
  for (std::size_t k = 0; k < names_list.size(); ++k) {
    const dss::CheckerConfig cfg = configFor(names_list[k]);
    auto checker = dss::makeStateChecker(p.model, cfg);
    built.push_back(checker);
  }
  const std::size_t nc = built.size();
  std::vector<std::vector<char>> valid(nc, std::vector<char>(st.size()));
  std::vector<std::vector<double>> per_state(nc), per_state_wall(nc);
  const double n = double(std::max<std::size_t>(1, st.size()));
  for (int rep = -1; rep < repeat; ++rep) {
    for (std::size_t k = 0; k < nc; ++k) {
      const dss::StateChecker& checker = *built[k];
      std::vector<char>& v = valid[k];
      const auto t0 = std::chrono::steady_clock::now();
      const double c0 = threadCpuSeconds();
      if (threads <= 1) {
        for (std::size_t i = 0; i < st.size(); ++i) v[i] = !checker.collides(st[i].data());
      } else {
        // Contiguous blocks per thread (no false sharing on `valid` except at block edges).
        std::vector<std::thread> pool;
        const std::size_t block = (st.size() + threads - 1) / threads;
        for (int t = 0; t < threads; ++t)
          pool.emplace_back([&, t] {
            const std::size_t b = std::min(st.size(), t * block),
                              e = std::min(st.size(), b + block);
            for (std::size_t i = b; i < e; ++i) v[i] = !checker.collides(st[i].data());
          });
        for (auto& th : pool) th.join();
      }
      const double c1 = threadCpuSeconds();
      const auto t1 = std::chrono::steady_clock::now();
      if (rep < 0) continue;  // warm-up
      // With threads, only wall time means anything.
      per_state[k].push_back(threads <= 1
                                 ? (c1 - c0) * 1e6 / n
                                 : std::chrono::duration<double, std::micro>(t1 - t0).count() / n);
      per_state_wall[k].push_back(std::chrono::duration<double, std::micro>(t1 - t0).count() / n);
    }
  }
  // Per repetition, each checker's time over the first checker's, taken in the same
  // repetition a few milliseconds apart: the median of these paired ratios follows the speed
  // ratio even when the machine changes speed between repetitions.
  std::vector<double> paired_ratio(nc, 0.0);
  for (std::size_t k = 1; k < nc; ++k) {
    std::vector<double> r;
    for (std::size_t i = 0; i < per_state[k].size() && i < per_state[0].size(); ++i)
      if (per_state[0][i] > 0.0) r.push_back(per_state[k][i] / per_state[0][i]);
    paired_ratio[k] = dss::cli::median(r);
  }
  for (std::size_t k = 0; k < nc; ++k) {
    const auto& checker = built[k];
    std::sort(per_state[k].begin(), per_state[k].end());
    std::sort(per_state_wall[k].begin(), per_state_wall[k].end());
    const auto c = checker->counters();
    nlohmann::json j;
    j["checker"] = names_list[k];
    if (checker->name() == "dss") j["mode"] = mode;
    j["states"] = st.size();
    j["valid"] = std::count(valid[k].begin(), valid[k].end(), 1);
    j["us_per_state"] = per_state[k].empty() ? 0.0 : per_state[k][per_state[k].size() / 2];
    j["us_per_state_wall"] =
        per_state_wall[k].empty() ? 0.0 : per_state_wall[k][per_state_wall[k].size() / 2];
    j["us_per_state_min"] = per_state[k].empty() ? 0.0 : per_state[k].front();
    j["timer"] = threads <= 1 ? "thread CPU time (wall time in us_per_state_wall)" : "wall time";
    j["threads"] = threads;
    j["simd"] = dss::simdPathName(p.model->kinematics().simdPath());
    j["repetitions"] = repeat;
    j["pair_tests_per_state"] = st.empty() ? 0.0 : double(c.pair_tests) / double(c.checks);
    j["cap_hits"] = c.cap_hits;
    j["model"] = p.model->summary();
    if (const auto* f = dynamic_cast<const dss::FclChecker*>(checker.get())) {
      j["solver"] = dss::FclChecker::solverDescription();
      j["prefilter"] = f->prefilterName();
    }
    if (k == 0) {
      // --contacts: the colliding pairs by exact DSS at the same paddings.
      dss::DssCheckerSettings set;
      set.scene_padding = padding;
      set.self_padding = self_padding;
      const dss::DssChecker explain(p.model, set);
      for (std::size_t i = 0; i < st.size(); ++i) {
        std::cout << (valid[0][i] ? 1 : 0);
        if (contacts && !valid[0][i]) {
          const auto c = dss::contactsAt(explain, st[i].data());
          std::string line;
          if (!c)
            line = "invalid input (a value outside the model's bounds)";
          else if (c->empty())
            line = "no pair collides under exact DSS";
          for (std::size_t n = 0; c && n < c->size(); ++n)
            line += (n ? "; " : "") + dss::describeContact(*p.model, (*c)[n]);
          std::cout << '\t' << line;
        }
        std::cout << "\n";
      }
    } else {
      std::size_t dis = 0;
      for (std::size_t i = 0; i < valid[k].size(); ++i) dis += valid[k][i] != valid[0][i];
      j["disagreements"] = dis;
      j["paired_ratio_to_first"] = paired_ratio[k];
    }
    std::cerr << j.dump() << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "dss_check: " << e.what() << "\n";
    return 1;
  }
}
