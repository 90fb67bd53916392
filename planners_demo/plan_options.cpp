// dss_plan's command line (see plan_options.h).
#include "plan_options.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "cli.h"
#include "mesh_cli.h"
#include "planner_registry.h"

namespace dss_plan {

namespace {

const char* kUsage =
    "usage: dss_plan                         (our dss_arm7 in its shelf scene)\n"
    "       dss_plan --robot R.urdf [--srdf S.srdf] --scene SCENE --request REQUEST.yaml\n"
    "       dss_plan --robot R.urdf [--srdf S.srdf] --problems DIR\n"
    "       dss_plan --benchmark [--runs N] [--log FILE] [any of the above]\n"
    "       dss_plan --summarize FILE...      (the JSON lines of several runs, one summary)\n"
    "  options: --planner NAME (RRTConnect) --checker dss|fcl-hull|fcl-mesh (dss)\n"
    "           --motion discrete|vector|continuous|ompl (discrete) --time SECONDS (10)\n"
    "           --seed N (1)\n"
    "           --param NAME=VALUE (repeatable): a parameter of the planner, as OMPL names\n"
    "           it (RRTConnect: range, intermediate_states); with a list of planners, each\n"
    "           must have it\n"
    "           --padding r --self-padding r --resolution f (OMPL's 0.01) --simplify\n"
    "           --check-time (report checking_time_s: two clock reads per state check)\n"
    "           --mode exact|double|float (dss arithmetic, exact) --max-iterations N (dss cap, "
    "64)\n"
    "           --motion: discrete checks OMPL's states at the resolution in an order that\n"
    "           finds collisions sooner (the same verdicts), vector the same states eight at\n"
    "           a time in float lanes where the checker proves them free (the same verdicts;\n"
    "           on the AVX2 path only, elsewhere as discrete), ompl with OMPL's own validator,\n"
    "           continuous certifies the whole motion\n"
    "           --motion-min-fraction f (continuous: smallest sub-motion, 1/1024)\n"
    "           --direct: try the straight motion from the start to each goal state first\n"
    "           (a free one is the solution, of two states); the planner runs only when none\n"
    "           is free. Off by default: OMPL's planners never try it themselves\n"
    "           --nearest vector|ompl (vector): the tree planners' nearest-neighbour search\n"
    "           on a joint-value space: vector scans the states' values four at a time, and\n"
    "           from 512 states on searches a k-d tree of them (the same distances, so the\n"
    "           same trees), ompl keeps the planner's default (GNAT)\n"
    "           --workspace XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (bounds of planar and floating\n"
    "           joints' translation; default: the request's workspace_parameters)\n"
    "           --base-table-cells N (a planar base's table against the scene: at most about\n"
    "           N cells, 0 for none; default 65536)\n"
    "           --scene-mesh-parts N (a scene mesh: the hulls of its connected parts, at\n"
    "           most N, in [1, 4096]; default 16; 1: one hull per mesh)\n"
    "           --shard K/N (with --problems: every N-th problem in name order, from the K-th)\n"
    "           --path FILE (CSV of the solution: every joint; several problems:\n"
    "           FILE.<problem>.csv)\n"
    "           --render FILE.html (one self-contained page: the robot's collision geometry\n"
    "           replaying the path, drag to orbit, wheel to zoom; obstacles the checker pruned\n"
    "           greyed, states found invalid red; with the problem not solved, the approximate\n"
    "           path or else the straight start-goal motion; with several problems\n"
    "           FILE.<problem>.html)\n"
    "  --benchmark: one ompl::tools::Benchmark experiment per problem, one planner entry per\n"
    "           planner and checker, named PLANNER[CHECKER]; --planner and --checker take\n"
    "           comma lists (checkers: dss,fcl-hull by default); --runs N per entry (10);\n"
    "           --log FILE (dss_plan_benchmark.log; with several problems FILE.<problem>.log).\n"
    "           Load with: ompl_benchmark_statistics FILE... -d results.db (package ompl-demos)\n"
    "  planners: RRTConnect RRT RRTstar LazyRRT BiTRRT pRRT PRM PRMstar LazyPRM KPIECE1\n"
    "            BKPIECE1 LBKPIECE1 EST SBL pSBL\n"
    "  exit codes: 0 every problem solved; 1 runtime error (files, model); 2 usage error;\n"
    "           3 a problem not solved (stdout then has \"solved\":false)\n"
    "  robot meshes:\n";

// A comma list of names; an empty or repeated name is a usage error.
std::vector<std::string> splitList(const dss::cli::ArgCursor& cli, const std::string& option,
                                   const std::string& v) {
  std::vector<std::string> out;
  std::stringstream ss(v);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item.empty()) cli.error(option + ": empty name in list '" + v + "'");
    if (std::find(out.begin(), out.end(), item) != out.end())
      cli.error(option + ": '" + item + "' listed twice");
    out.push_back(item);
  }
  if (out.empty() || v.back() == ',') cli.error(option + ": empty name in list '" + v + "'");
  return out;
}

}  // namespace

dss::CheckerConfig checkerConfig(const Args& a, const std::string& name) {
  dss::CheckerConfig cfg;
  cfg.checker = name;
  cfg.scene_padding = a.padding;
  cfg.self_padding = a.self_padding;
  cfg.dss_options = a.dss_options;
  cfg.time_checks = a.check_time || a.benchmark;
  return cfg;
}

Args parseArgs(int argc, char** argv) {
  Args a;
  a.demo = argc == 1;
  bool checker_given = false, runs_given = false, log_given = false;
  const std::string usage = std::string(kUsage) + dss::cli::kMeshOptionsUsage;
  dss::cli::ArgCursor cli(argc, argv, "dss_plan", usage.c_str());
  while (cli.next()) {
    if (dss::cli::meshOption(cli, &a.meshes)) continue;
    if (cli.option("--robot"))
      a.robot = cli.value();
    else if (cli.option("--srdf"))
      a.srdf = cli.value();
    else if (cli.option("--scene"))
      a.scene = cli.value();
    else if (cli.option("--request"))
      a.request = cli.value();
    else if (cli.option("--problems"))
      a.problems = cli.value();
    else if (cli.option("--planner"))
      a.planner = cli.value();
    else if (cli.option("--checker"))
      a.checker = cli.value(), checker_given = true;
    else if (cli.option("--motion"))
      a.motion = cli.value();
    else if (cli.option("--direct"))
      a.direct = true;
    else if (cli.option("--nearest"))
      a.nearest = cli.value();
    else if (cli.option("--time"))
      a.time = cli.number(1e-6, 1e6);
    else if (cli.option("--param")) {
      const std::string v = cli.value();
      const auto eq = v.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == v.size())
        cli.error("--param: expected NAME=VALUE, got '" + v + "'");
      const std::string name = v.substr(0, eq);
      for (const auto& pv : a.planner_params)
        if (pv.first == name) cli.error("--param: '" + name + "' given twice");
      a.planner_params.emplace_back(name, v.substr(eq + 1));
    } else if (cli.option("--seed"))
      a.seed = static_cast<unsigned long>(cli.integer(0, 4294967295));
    else if (cli.option("--padding"))
      a.padding = cli.number(0.0, 1e3);
    else if (cli.option("--self-padding"))
      a.self_padding = cli.number(0.0, 1e3);
    else if (cli.option("--workspace"))
      a.workspace = cli.numbers(6);
    else if (cli.option("--base-table-cells"))
      a.base_table_cells = static_cast<long>(cli.integer(0, 1 << 24));
    else if (cli.option("--scene-mesh-parts"))
      a.scene_mesh_parts = static_cast<std::size_t>(cli.integer(1, 4096));
    else if (cli.option("--resolution"))
      a.resolution = cli.number(0.0, 1.0);
    else if (cli.option("--path"))
      a.path = cli.value();
    else if (cli.option("--render")) {
      a.render = cli.value();
      if (a.render.empty()) cli.error("--render: empty file name");
    } else if (cli.flag("--simplify"))
      a.simplify = true;
    else if (cli.flag("--check-time"))
      a.check_time = true;
    else if (cli.option("--motion-min-fraction"))
      a.min_fraction = cli.number(1e-12, 1.0);
    else if (cli.option("--mode")) {
      const std::string m = cli.value();
      if (m == "exact")
        a.dss_options.mode = dss::Mode::kExact;
      else if (m == "double")
        a.dss_options.mode = dss::Mode::kDouble;
      else if (m == "float")
        a.dss_options.mode = dss::Mode::kFloat;
      else
        cli.error("--mode: expected exact, double or float, got '" + m + "'");
    } else if (cli.option("--max-iterations"))
      a.dss_options.max_iterations = static_cast<int>(cli.integer(1, 1000000));
    else if (cli.flag("--benchmark"))
      a.benchmark = true;
    else if (cli.option("--runs"))
      a.runs = static_cast<unsigned>(cli.integer(1, 1000000)), runs_given = true;
    else if (cli.option("--log"))
      a.log = cli.value(), log_given = true;
    else if (cli.flag("--demo"))
      a.demo = true;
    else if (cli.option("--shard")) {
      const std::string v = cli.value();
      const auto slash = v.find('/');
      const auto k = dss::cli::parseInteger(v.substr(0, slash).c_str(), 1, 1000000);
      const auto n = slash == std::string::npos
                         ? std::nullopt
                         : dss::cli::parseInteger(v.substr(slash + 1).c_str(), 1, 1000000);
      if (!k || !n || *k > *n) cli.error("--shard: expected K/N with 1 <= K <= N, got '" + v + "'");
      a.shard_k = *k, a.shard_n = *n;
    } else if (cli.flag("--summarize"))
      a.summarize.push_back("");  // files follow as positionals
    else if (!a.summarize.empty() && cli.positional("FILE"))
      a.summarize.push_back(cli.value());
    else
      cli.unknown();
  }
  if (!a.summarize.empty()) {
    a.summarize.erase(a.summarize.begin());
    if (a.summarize.empty()) cli.error("--summarize needs the JSON-lines files of the runs");
    return a;
  }
  if (a.shard_n > 0 && a.problems.empty()) cli.error("--shard needs --problems");
  if (a.benchmark && !checker_given) a.checker = "dss,fcl-hull";
  a.planner_list = splitList(cli, "--planner", a.planner);
  a.checker_list = splitList(cli, "--checker", a.checker);
  for (const auto& pl : a.planner_list)
    if (planners().find(pl) == planners().end())
      cli.error("--planner: unknown planner '" + pl + "' (dss_plan --help lists them)");
  for (const auto& pl : a.planner_list) try {
      checkPlannerParams(pl, a.planner_params);
    } catch (const std::invalid_argument& e) {
      cli.error(std::string("--param: ") + e.what());
    }
  for (const auto& c : a.checker_list)
    if (c != "dss" && c != "fcl-hull" && c != "fcl-mesh")
      cli.error("--checker: unknown checker '" + c + "' (dss, fcl-hull, fcl-mesh)");
  if (a.motion != "discrete" && a.motion != "vector" && a.motion != "continuous" &&
      a.motion != "ompl")
    cli.error("--motion: expected discrete, vector, continuous or ompl, got '" + a.motion + "'");
  if (a.nearest != "vector" && a.nearest != "ompl")
    cli.error("--nearest: expected vector or ompl, got '" + a.nearest + "'");
  if (a.motion == "continuous" && a.checker_list != std::vector<std::string>{"dss"})
    cli.error("--motion continuous needs --checker dss (the continuous validator is DSS's)");
  if (!a.benchmark) {
    if (a.planner_list.size() > 1) cli.error("--planner: a list of planners needs --benchmark");
    if (a.checker_list.size() > 1) cli.error("--checker: a list of checkers needs --benchmark");
    if (runs_given) cli.error("--runs needs --benchmark");
    if (log_given) cli.error("--log needs --benchmark");
  } else {
    if (!a.path.empty()) cli.error("--path is not available with --benchmark");
    if (!a.render.empty()) cli.error("--render is not available with --benchmark");
    if (a.log.empty()) cli.error("--log: empty file name");
  }

  if (a.robot.empty() && a.request.empty() && a.problems.empty()) a.demo = true;  // options only
  if (a.demo && a.robot.empty()) {
    const std::string root = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
    a.robot = root + "/dss_arm7.urdf";
    a.srdf = root + "/dss_arm7.srdf";
    a.scene = root + "/scenes/shelf.yaml";
    a.request = root + "/scenes/shelf_request.yaml";
    a.default_problem = true;
  } else {
    if (a.robot.empty()) cli.error("--robot is required");
    if (a.problems.empty() && a.request.empty()) cli.error("--request or --problems is required");
  }
  return a;
}

}  // namespace dss_plan
