// Times scene loading: each file given (or the MotionBenchMaker scenes under the shared
// folder) is loaded `repeats` times; prints the median load time per file in milliseconds.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "dss/scene/scene_error.h"
#include "dss/scene/scene_loader.h"

int main(int argc, char** argv) {
  std::vector<std::string> files;
  int repeats = 20;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--repeats" && i + 1 < argc) repeats = std::max(1, std::atoi(argv[++i]));
    else files.push_back(a);
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: dss_scene_timing [--repeats N] scene_file...\n");
    return 2;
  }
  double total_median = 0;
  for (const auto& f : files) {
    std::vector<double> ms;
    std::size_t n = 0;
    try {
      for (int r = 0; r < repeats; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        const dss::Scene s = dss::loadScene(f);
        const auto t1 = std::chrono::steady_clock::now();
        n = s.obstacles.size();
        ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return 1;
    }
    std::sort(ms.begin(), ms.end());
    const double med = ms[ms.size() / 2];
    total_median += med;
    std::printf("%-70s %3zu obstacles  median %.3f ms  min %.3f ms\n", f.c_str(), n, med, ms[0]);
  }
  std::printf("files %zu  mean of medians %.3f ms\n", files.size(), total_median / files.size());
  return 0;
}
