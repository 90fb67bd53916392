// Writes an SRDF <disable_collisions> list for a URDF, as the MoveIt Setup Assistant does:
// adjacent pairs, pairs in collision at the default state, and pairs never or always in
// collision over random states.
// Usage: dss_disabled_pairs robot.urdf [samples=10000] [seed=1] [--package name=dir ...]
#include <cstdio>
#include <iostream>
#include <limits>
#include <string>

#include "cli.h"
#include "dss/robot/collision_pairs.h"
#include "dss/robot/urdf_loader.h"

namespace {

const char* const kUsage =
    R"(usage: dss_disabled_pairs robot.urdf [samples] [seed] [--package name=dir ...]

Prints SRDF <disable_collisions> lines for the URDF, as the MoveIt Setup Assistant does:
adjacent pairs, pairs in collision at the default state, and pairs never or always in
collision over `samples` random states.

  samples            random states to sample, an integer >= 1 (default 10000)
  seed               random seed, an integer >= 0 (default 1)
  --package name=dir resolve package://name/ mesh paths to dir (repeatable)
  --help             this text

Exit codes: 0 success; 1 the robot cannot be loaded or sampled; 2 usage error.
)";

}  // namespace

int main(int argc, char** argv) {
  dss::LoadOptions load;
  dss::DisabledPairsOptions opt;
  std::string urdf;
  int positional = 0;
  dss::cli::ArgCursor cli(argc, argv, "dss_disabled_pairs", kUsage);
  while (cli.next()) {
    if (cli.option("--package")) {
      const std::string kv = cli.value();
      const auto eq = kv.find('=');
      if (eq == std::string::npos || eq == 0)
        cli.error("--package: expected name=dir, got '" + kv + "'");
      load.mesh_paths.package_dirs[kv.substr(0, eq)] = kv.substr(eq + 1);
    } else if (positional == 0 && cli.positional("robot.urdf")) {
      urdf = cli.value();
      ++positional;
    } else if (positional == 1 && cli.positional("samples")) {
      opt.samples = static_cast<int>(cli.integer(1, std::numeric_limits<int>::max()));
      ++positional;
    } else if (positional == 2 && cli.positional("seed")) {
      opt.seed = static_cast<std::uint64_t>(cli.integer(0, std::numeric_limits<long long>::max()));
      ++positional;
    } else {
      cli.unknown();
    }
  }
  if (urdf.empty()) cli.error("no robot.urdf given");
  try {
    const dss::RobotModel model = dss::loadUrdf(urdf, load);
    const auto result = dss::computeDisabledPairs(model, opt);
    std::cout << "  <!-- dss_disabled_pairs: " << result.samples << " samples, seed " << opt.seed
              << ", " << result.pairs.size() << " pairs disabled -->\n"
              << result.toSrdf();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
