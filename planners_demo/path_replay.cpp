// Sampling and checking a path for dss_plan --render (see path_replay.h).
#include "path_replay.h"

#include <ompl/base/ScopedState.h>

#include <algorithm>
#include <stdexcept>

namespace dss_plan {

namespace ob = ompl::base;

PathReplay replayPath(const dss::Problem& problem, const ob::StateValidityChecker& checker,
                      const ompl::geometric::PathGeometric& path, int max_frames_per_segment) {
  // PathGeometric::getStates() has no const overload in OMPL 1.5.
  std::vector<const ob::State*> states;
  for (std::size_t i = 0; i < path.getStateCount(); ++i) states.push_back(path.getState(i));
  if (states.empty()) throw std::invalid_argument("replayPath: the path has no state");
  if (max_frames_per_segment < 1)
    throw std::invalid_argument("replayPath: max_frames_per_segment must be >= 1");
  const dss::GroupStateMap& map = *problem.map;
  const ob::StateSpacePtr& space = problem.si->getStateSpace();
  PathReplay r;
  r.path_states = states.size();
  const double t_end = double(states.size() - 1);

  std::vector<double> group(map.dimension());
  auto joints = [&](const ob::State* s) {
    std::vector<double> q = map.held();
    map.toGroupValues(s, group.data());
    for (std::size_t i = 0; i < group.size(); ++i) q[map.groupActive()[i]] = group[i];
    return q;
  };
  auto check = [&](const ob::State* s, double t, double half) {
    ++r.samples_checked;
    if (checker.isValid(s)) return;
    ++r.samples_invalid;
    const double t0 = std::max(0.0, t - half), t1 = std::min(t_end, t + half);
    // Neighbouring samples' stretches meet (up to rounding): one stretch.
    if (!r.invalid_spans.empty() && t0 <= r.invalid_spans.back().second + 1e-9) {
      r.invalid_spans.back().second = std::max(r.invalid_spans.back().second, t1);
    } else {
      r.invalid_spans.emplace_back(t0, t1);
      r.span_first_q.push_back(joints(s));
    }
  };

  ob::ScopedState<> scoped(space);
  ob::State* between = scoped.get();
  double last_half = 0.5;
  for (std::size_t i = 0; i + 1 < states.size(); ++i) {
    const ob::State* a = states[i];
    const ob::State* b = states[i + 1];
    const int checks = std::max(1u, space->validSegmentCount(a, b));
    const int frames = std::min(checks, max_frames_per_segment);
    last_half = 0.5 / checks;
    for (int j = 0; j < checks; ++j) {
      if (j > 0) space->interpolate(a, b, double(j) / checks, between);
      check(j == 0 ? a : between, double(i) + double(j) / checks, last_half);
    }
    for (int j = 0; j < frames; ++j) {
      if (j > 0) space->interpolate(a, b, double(j) / frames, between);
      r.frame_t.push_back(double(i) + double(j) / frames);
      r.frame_q.push_back(joints(j == 0 ? a : between));
    }
  }
  check(states.back(), t_end, last_half);
  r.frame_t.push_back(t_end);
  r.frame_q.push_back(joints(states.back()));
  return r;
}

}  // namespace dss_plan
