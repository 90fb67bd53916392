// dss_plan's summary line ("summary: solved S of N ...; planning time median ..., p95 ...")
// and --summarize, which merges the JSON lines of several runs into that line.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace dss_plan {

void printSummary(std::ostream& out, int solved, std::vector<double> times,
                  const std::string& planner, const std::string& checker, unsigned long seed);

/// The lines of `files` (one JSON object per problem, as dss_plan prints them), every one from
/// the same planner, checker and seed and naming each problem once, summarized on stdout: 0
/// when every problem was solved, 3 otherwise. Throws std::runtime_error naming the file and
/// line of a bad line.
int summarizeRuns(const std::vector<std::string>& files);

}  // namespace dss_plan
