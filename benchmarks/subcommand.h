// Subcommands of dss_bench. Each subcommand is a function taking its own arguments (argv[0]
// is the subcommand name) and returning an exit code; it registers itself from its own file
// with DSS_BENCH_SUBCOMMAND, so the dispatcher in dss_bench.cpp never needs editing.
#pragma once

#include <functional>
#include <map>
#include <string>

namespace dss {
namespace bench {

struct Subcommand {
  std::string summary;
  std::function<int(int, char**)> run;
};

/// The registry (constructed on first use, so registration order across files is irrelevant).
inline std::map<std::string, Subcommand>& subcommands() {
  static std::map<std::string, Subcommand> registry;
  return registry;
}

struct SubcommandRegistration {
  SubcommandRegistration(const std::string& name, const std::string& summary,
                         std::function<int(int, char**)> run) {
    subcommands()[name] = Subcommand{summary, std::move(run)};
  }
};

}  // namespace bench
}  // namespace dss

#define DSS_BENCH_CONCAT_(a, b) a##b
#define DSS_BENCH_CONCAT(a, b) DSS_BENCH_CONCAT_(a, b)
/// DSS_BENCH_SUBCOMMAND("name", "one-line summary", function)
#define DSS_BENCH_SUBCOMMAND(name, summary, fn)                                                \
  static const ::dss::bench::SubcommandRegistration DSS_BENCH_CONCAT(kDssBenchSub_, __LINE__)( \
      name, summary, fn)
