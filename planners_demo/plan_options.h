// dss_plan's command line: the options, their parsing and checks, and the usage text.
#pragma once

#include <string>
#include <vector>

#include "dss/checker/checker_setup.h"
#include "dss/checker/continuous_motion.h"
#include "dss/scene/scene_load_options.h"
#include "planner_registry.h"

namespace dss_plan {

/// dss_plan's options (dss_plan --help describes each).
struct Args {
  std::string robot, srdf, scene, request, problems, planner = "RRTConnect", checker = "dss",
                                                     motion = "discrete", path, render,
                                                     nearest = "vector";
  double min_fraction = dss::kDefaultMinFraction;
  double time = 10.0, padding = 0.0, self_padding = 0.0, resolution = 0.0;
  unsigned long seed = 1;
  bool simplify = false;
  bool direct = false;      // --direct: the straight start-goal motion before the planner
  bool check_time = false;  // the checker times its checks (two clock reads per check)
  dss::MeshGeometryOptions meshes;
  bool demo = false;             // print the readable summary (no arguments, or --demo)
  bool default_problem = false;  // our dss_arm7 in its shelf scene (no robot given)
  dss::Options dss_options;      // --mode, --max-iterations
  bool benchmark = false;
  unsigned runs = 10;
  std::string log = "dss_plan_benchmark.log";
  std::vector<std::string> planner_list, checker_list;  // --benchmark: comma lists
  PlannerParams planner_params;                         // --param NAME=VALUE, in order
  long base_table_cells = -1;  // --base-table-cells (-1: the model's default)
  std::size_t scene_mesh_parts = dss::SceneLoadOptions{}.max_mesh_parts;  // --scene-mesh-parts
  long shard_k = 0, shard_n = 0;       // --shard K/N (0: every problem)
  std::vector<std::string> summarize;  // --summarize FILE...
  std::vector<double> workspace;  // --workspace: min x, y, z, max x, y, z (empty: the request's)
};

/// dss_plan's options from its arguments. A usage error (an unknown option, a bad value, a
/// missing file option) exits with status 2 and a message; --help prints the usage and exits.
/// With no robot given, the default problem: our dss_arm7 in its shelf scene.
Args parseArgs(int argc, char** argv);

/// The checker `name` (dss, fcl-hull, fcl-mesh) with the options' paddings and DSS settings;
/// timing its checks with --check-time and --benchmark.
dss::CheckerConfig checkerConfig(const Args& a, const std::string& name);

}  // namespace dss_plan
