// dss_check --motions: motions checked by OMPL motion validators on one model, and timed. The
// motions are a path (each row of a states file to the next) or random ones (a start the
// checker finds valid, towards a uniform state, cut to a random length of at most a fraction of
// the space's extent, as dss_bench tradeoff draws them). stdout: 1/0 per motion for the first
// validator (with --contacts, where its first colliding state lies and which pairs collide
// there); stderr: one JSON summary per validator (motions, valid, median microseconds per
// motion over repetitions, states checked per motion, disagreements with the first validator).
#pragma once

#include <string>
#include <vector>

#include "dss/planning/planning_problem.h"

namespace dss_check {

struct MotionCheckOptions {
  /// discrete | vector | continuous | ompl, the first one's verdicts on stdout.
  std::vector<std::string> validators;
  dss::CheckerConfig checker;  ///< the state checker every validator stands on
  double resolution = 0.01;    ///< OMPL's state validity checking resolution
  double motion_length = 0.2;  ///< random motions: at most this fraction of the extent
  /// continuous: the smallest sub-motion, a fraction of the motion (1: the whole motion is
  /// cleared at once or refused)
  double min_fraction = dss::kDefaultMinFraction;
  long random = 0;        ///< random motions (0: the path of `path`)
  int repeat = 0;         ///< timed repetitions (0: by the number of motions)
  bool contacts = false;  ///< explain each motion the first validator refuses
  std::string path_file;  ///< the states file, for messages
};

/// The names --motions accepts.
bool knownMotionValidator(const std::string& name);

/// Checks and times the motions; `path`: every active joint's value per state (the rows of
/// `path_file`, at file lines `lines`), used when `random` is 0. Throws std::runtime_error
/// naming the file and line for a path that motions cannot follow (fewer than two states, a
/// joint outside the group away from its held value: the caller holds them at the path's first
/// state), and for random motions whose start cannot be found.
void checkMotions(const dss::Problem& p, const std::vector<std::vector<double>>& path,
                  const std::vector<int>& lines, const MotionCheckOptions& options);

}  // namespace dss_check
