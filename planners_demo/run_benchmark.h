// dss_plan --benchmark: one ompl::tools::Benchmark experiment per problem, one planner entry
// per planner and checker (PLANNER[CHECKER]), written to OMPL benchmark logs
// (benchmark_log.h), and one JSON line per entry on stdout.
#pragma once

#include <vector>

#include "dss/checker/checker_setup.h"
#include "plan_options.h"
#include "problem_files.h"

namespace dss_plan {

/// Runs the benchmark of every problem; 0 when done (throws on a bad file or an unwritable log).
int runBenchmark(const Args& a, const dss::LoadedRobot& robot,
                 const std::vector<ProblemFiles>& problems);

}  // namespace dss_plan
