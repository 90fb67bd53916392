// dss_plan's single solve of a problem: the validity checker and motion validator the options
// name, the plan, its JSON line on stdout (and the readable summary, the path file, the render
// page when asked).
#pragma once

#include "dss/checker/checker_setup.h"
#include "plan_options.h"
#include "problem_files.h"

namespace dss_plan {

struct Outcome {
  bool solved = false;
  double time = 0.0;
};

/// Solves one problem; `readable`: also print the summary for a person (the demo).
Outcome solveOne(const Args& a, const dss::LoadedRobot& robot, const ProblemFiles& files,
                 bool readable);

}  // namespace dss_plan
