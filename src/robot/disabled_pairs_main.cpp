// Writes an SRDF <disable_collisions> list for a URDF, as the MoveIt Setup Assistant does:
// adjacent pairs, pairs in collision at the default state, and pairs never or always in
// collision over random states.
// Usage: dss_disabled_pairs robot.urdf [samples=10000] [seed=1] [--package name=dir ...]
#include <cstdio>
#include <cstring>
#include <iostream>

#include "dss/robot/collision_pairs.h"
#include "dss/robot/urdf_loader.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s robot.urdf [samples] [seed] [--package name=dir ...]\n", argv[0]);
    return 2;
  }
  dss::LoadOptions load;
  dss::DisabledPairsOptions opt;
  int positional = 0;
  for (int i = 2; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--package") && i + 1 < argc) {
      const std::string kv = argv[++i];
      const auto eq = kv.find('=');
      if (eq == std::string::npos) {
        std::fprintf(stderr, "--package expects name=dir, got '%s'\n", kv.c_str());
        return 2;
      }
      load.mesh_paths.package_dirs[kv.substr(0, eq)] = kv.substr(eq + 1);
    } else if (positional == 0) {
      opt.samples = std::atoi(argv[i]);
      ++positional;
    } else {
      opt.seed = std::strtoull(argv[i], nullptr, 10);
      ++positional;
    }
  }
  try {
    const dss::RobotModel model = dss::loadUrdf(argv[1], load);
    const auto result = dss::computeDisabledPairs(model, opt);
    std::cout << "  <!-- dss_disabled_pairs: " << result.samples << " samples, seed " << opt.seed << ", "
              << result.pairs.size() << " pairs disabled -->\n"
              << result.toSrdf();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
