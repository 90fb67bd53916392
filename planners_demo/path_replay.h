// A planned path as dss_plan --render replays it: the robot's joint values at frames along the
// path (for drawing) and what the validity checker says about the states along it (for marking
// collisions). The path is sampled as OMPL's discrete motion validator samples it: each segment
// at the state space's validSegmentCount states, the last state once more; every sample is
// checked, and an invalid sample marks the stretch of path nearer to it than to its neighbours.
// Frames are a subset of the same interpolation (at most a few per segment): enough for smooth
// playback without one frame per check. Positions along the path are a parameter t in
// [0, states - 1]: path state k at t = k, linear in the state space's interpolation in between.
#pragma once

#include <ompl/base/StateValidityChecker.h>
#include <ompl/geometric/PathGeometric.h>

#include <cstddef>
#include <utility>
#include <vector>

#include "dss/planning/planning_problem.h"

namespace dss_plan {

struct PathReplay {
  std::size_t path_states = 0;  ///< states of the path (frame t = k is path state k)
  /// Path parameter of each frame, increasing from 0 to path_states - 1.
  std::vector<double> frame_t;
  /// Every active joint value of the robot (RobotModel::active_joints order) at each frame.
  std::vector<std::vector<double>> frame_q;
  std::size_t samples_checked = 0;
  std::size_t samples_invalid = 0;
  /// Stretches [t0, t1] of the path nearest to an invalid sample (merged, increasing).
  std::vector<std::pair<double, double>> invalid_spans;
  /// For each stretch, every active joint value of its first invalid sample.
  std::vector<std::vector<double>> span_first_q;
};

/// Samples `path` (at least one state) of `problem` and checks every sample with `checker`.
/// `max_frames_per_segment` (>= 1) bounds the frames kept per segment.
PathReplay replayPath(const dss::Problem& problem, const ompl::base::StateValidityChecker& checker,
                      const ompl::geometric::PathGeometric& path, int max_frames_per_segment = 24);

}  // namespace dss_plan
