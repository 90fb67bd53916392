// dss_bench: one executable, several benchmarks. `dss_bench <subcommand> [options]`; each
// subcommand registers itself in its own file (subcommand.h), this file only dispatches.
#include <cstdio>
#include <cstring>
#include <exception>

#include "subcommand.h"

namespace {

void printUsage(std::FILE* out) {
  std::fprintf(out,
               "usage: dss_bench <subcommand> [options]   (dss_bench <subcommand> "
               "--help)\n\nsubcommands:\n");
  for (const auto& [name, sub] : dss::bench::subcommands())
    std::fprintf(out, "  %-14s %s\n", name.c_str(), sub.summary.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    printUsage(stderr);
    return 2;
  }
  if (!std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") ||
      !std::strcmp(argv[1], "help")) {
    printUsage(stdout);
    return 0;
  }
  const auto& subs = dss::bench::subcommands();
  const auto it = subs.find(argv[1]);
  if (it == subs.end()) {
    std::fprintf(stderr, "dss_bench: unknown subcommand '%s'\n", argv[1]);
    printUsage(stderr);
    return 2;
  }
  try {
    return it->second.run(argc - 1, argv + 1);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dss_bench %s: %s\n", argv[1], e.what());
    return 1;
  }
}
