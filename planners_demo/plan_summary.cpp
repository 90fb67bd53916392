// dss_plan's summary (see plan_summary.h).
#include "plan_summary.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

namespace dss_plan {

// "summary: solved S of N (planner, checker, seed); planning time median ..., p95 ...".
void printSummary(std::ostream& out, int solved, std::vector<double> times,
                  const std::string& planner, const std::string& checker, unsigned long seed) {
  std::sort(times.begin(), times.end());
  const double median = times[times.size() / 2];
  const double p95 =
      times[std::min(times.size() - 1, std::size_t(std::ceil(0.95 * times.size())) - 1)];
  const std::ios::fmtflags flags = out.flags();
  const std::streamsize precision = out.precision();
  out << "summary: solved " << solved << " of " << times.size() << " (" << planner << ", "
      << checker << ", seed " << seed << "); planning time median " << std::fixed
      << std::setprecision(3) << median * 1e3 << " ms, p95 " << p95 * 1e3 << " ms\n";
  out.flags(flags);
  out.precision(precision);
}

// --summarize: the JSON lines of several runs (shards of one problem folder, say) merged into
// the summary one run over all of them prints. Every line must come from the same planner,
// checker and seed, and name each problem once.
int summarizeRuns(const std::vector<std::string>& files) {
  std::vector<double> times;
  std::set<std::string> seen;
  int solved = 0;
  std::string planner, checker;
  unsigned long seed = 0;
  for (const std::string& file : files) {
    std::ifstream in(file);
    if (!in) throw std::runtime_error(file + ": cannot open");
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      const std::string where = file + ":" + std::to_string(n);
      nlohmann::json j;
      try {
        j = nlohmann::json::parse(line);
        const std::string problem = j.at("problem");
        const std::string p = j.at("planner"), c = j.at("checker");
        const unsigned long s = j.at("seed");
        if (seen.empty()) planner = p, checker = c, seed = s;
        if (p != planner || c != checker || s != seed)
          throw std::runtime_error("planner " + p + ", checker " + c + ", seed " +
                                   std::to_string(s) + " differ from the first line's (" + planner +
                                   ", " + checker + ", " + std::to_string(seed) + ")");
        if (!seen.insert(problem).second)
          throw std::runtime_error("problem '" + problem + "' appears twice");
        solved += j.at("solved").get<bool>();
        times.push_back(j.at("planning_time_s").get<double>());
      } catch (const std::exception& e) {
        throw std::runtime_error(where + ": " + e.what());
      }
    }
  }
  if (times.empty()) throw std::runtime_error("--summarize: no result lines in the files given");
  printSummary(std::cout, solved, times, planner, checker, seed);
  return solved == int(times.size()) ? 0 : 3;
}

}  // namespace dss_plan
