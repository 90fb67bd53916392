// Times scene loading: each file given (a directory stands for the scene*.yaml, *.scene and
// *.urdf files below it, *.orig.urdf excepted) is loaded `repeats` times; prints the median
// and minimum load time per file in milliseconds, and the mean of the medians.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli.h"
#include "dss/scene/scene_error.h"
#include "dss/scene/scene_loader.h"

namespace {

const char* const kUsage = R"(usage: dss_scene_timing [--repeats N] (scene_file | directory)...

Loads each scene file N times and prints the median and minimum load time per file, then
the mean of the medians. A directory stands for the scene*.yaml, *.scene and *.urdf files
below it (*.orig.urdf excepted). With more than 20 files only the summary is printed.

  --repeats N  loads per file, an integer >= 1 (default 20)
  --help       this text

Exit codes: 0 success; 1 a scene cannot be loaded; 2 usage error.
)";

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> files;
  int repeats = 20;
  dss::cli::ArgCursor cli(argc, argv, "dss_scene_timing", kUsage);
  while (cli.next()) {
    if (cli.option("--repeats")) {
      repeats = static_cast<int>(cli.integer(1, 1000000));
    } else if (cli.positional("scene_file")) {
      const std::string a = cli.value();
      if (!std::filesystem::is_directory(a)) {
        files.push_back(a);
        continue;
      }
      std::vector<std::string> found;
      for (const auto& e : std::filesystem::recursive_directory_iterator(a)) {
        const std::string name = e.path().filename().string();
        const std::string ext = e.path().extension().string();
        const bool orig = name.size() > 10 && name.substr(name.size() - 10) == ".orig.urdf";
        if (e.is_regular_file() && ((ext == ".yaml" && name.rfind("scene", 0) == 0) ||
                                    ext == ".scene" || (ext == ".urdf" && !orig)))
          found.push_back(e.path().string());
      }
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else {
      cli.unknown();
    }
  }
  if (files.empty()) cli.error("no scene file or directory given (or no scene files found in it)");
  double total_median = 0, worst_median = 0;
  const bool quiet = files.size() > 20;
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
    worst_median = std::max(worst_median, med);
    if (!quiet)
      std::printf("%-70s %3zu obstacles  median %.3f ms  min %.3f ms\n", f.c_str(), n, med, ms[0]);
  }
  std::printf("files %zu  mean of medians %.3f ms  worst median %.3f ms\n", files.size(),
              total_median / files.size(), worst_median);
  return 0;
}
