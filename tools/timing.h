// Timing for the command-line tools: this thread's CPU time, and the median of timed
// repetitions (the mean of the two middle ones for an even count; 0 for none).
#pragma once

#include <algorithm>
#include <ctime>
#include <vector>

namespace dss::cli {

inline double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

}  // namespace dss::cli
