// dss_check --motions (motion_checks.h).
#include "motion_checks.h"

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "dss/checker/contacts.h"
#include "dss/core/simd_path.h"
#include "timing.h"

namespace dss_check {
namespace {

namespace ob = ompl::base;

// Random motions: starts drawn until the checker finds one valid, at most this many times.
constexpr int kMaxStartDraws = 100000;

using dss::cli::median;
using dss::cli::threadCpuSeconds;

struct Motion {
  ob::ScopedState<> from, to;
  /// Both ends hold finite values only. A motion with NaN or Inf at an end is colliding for
  /// every validator, which is not asked (OMPL's segment count of such a motion is undefined).
  bool finite = true;
};

// The path's rows as the group's states: a joint outside the group must keep its held value
// (a motion moves the group alone).
std::vector<Motion> pathMotions(const dss::Problem& p, const std::vector<std::vector<double>>& path,
                                const std::vector<int>& lines, const std::string& file) {
  if (path.size() < 2)
    throw std::runtime_error(file + ": --motions needs a path of at least two states, got " +
                             std::to_string(path.size()));
  const dss::GroupStateMap& map = *p.map;
  const dss::RobotModel& robot = map.robot();
  std::vector<char> in_group(robot.numActiveJoints(), 0);
  for (int a : map.groupActive()) in_group[std::size_t(a)] = 1;
  std::vector<ob::ScopedState<>> states;
  std::vector<double> g(map.dimension());
  for (std::size_t i = 0; i < path.size(); ++i) {
    const std::vector<double>& q = path[i];
    const std::string at = file + ":" + std::to_string(i < lines.size() ? lines[i] : int(i) + 2);
    for (std::size_t a = 0; a < q.size(); ++a)
      if (!in_group[a] && !(q[a] == map.held()[a]))
        throw std::runtime_error(at + ": joint '" + robot.joints[robot.active_joints[a]].name +
                                 "' is not in group '" + p.group + "' and differs from its " +
                                 "value in the path's first state (" + std::to_string(q[a]) +
                                 " against " + std::to_string(map.held()[a]) +
                                 "): a motion moves the group's joints only");
    for (std::size_t k = 0; k < g.size(); ++k) g[k] = q[std::size_t(map.groupActive()[k])];
    ob::ScopedState<> s(p.si->getStateSpace());
    map.fromGroupValues(g.data(), s.get());
    states.push_back(s);
  }
  std::vector<char> finite(path.size());
  for (std::size_t i = 0; i < path.size(); ++i)
    finite[i] =
        std::all_of(path[i].begin(), path[i].end(), [](double v) { return std::isfinite(v); });
  std::vector<Motion> motions;
  for (std::size_t i = 0; i + 1 < states.size(); ++i)
    motions.push_back({states[i], states[i + 1], finite[i] && finite[i + 1]});
  return motions;
}

// Random motions as dss_bench tradeoff draws them: a start the validity checker finds valid,
// towards a uniform state, cut to a length uniform in [0, length * extent].
std::vector<Motion> randomMotions(const dss::Problem& p, long count, double length) {
  const ob::StateSpacePtr& space = p.si->getStateSpace();
  auto sampler = p.si->allocStateSampler();
  ompl::RNG rng;
  const double max_length = length * space->getMaximumExtent();
  std::vector<Motion> motions;
  motions.reserve(std::size_t(count));
  for (long i = 0; i < count; ++i) {
    ob::ScopedState<> from(space), to(space), far(space);
    int draws = 0;
    do {
      if (++draws > kMaxStartDraws)
        throw std::runtime_error("--motions: no valid start state in " +
                                 std::to_string(kMaxStartDraws) +
                                 " uniform samples of the group's space (is every state in "
                                 "collision?)");
      sampler->sampleUniform(from.get());
    } while (!p.si->isValid(from.get()));
    sampler->sampleUniform(far.get());
    const double d = space->distance(from.get(), far.get());
    const double l = rng.uniform01() * max_length;
    if (d > l)
      space->interpolate(from.get(), far.get(), l / d, to.get());
    else
      to = far;
    motions.push_back({from, to});
  }
  return motions;
}

// Where the first colliding state of a motion the first validator refused lies, and what
// collides there: the states the discrete validator checks, in order from the start (its
// lastValid, OMPL's).
std::string explain(const dss::Problem& p, const dss::ValidityChecker& vc,
                    const ob::MotionValidator& in_order, const Motion& m) {
  if (!m.finite) return "a state of the motion holds a value that is not finite";
  const ob::StateSpacePtr& space = p.si->getStateSpace();
  ob::ScopedState<> s(space);
  std::pair<ob::State*, double> last{s.get(), 0.0};
  if (in_order.checkMotion(m.from.get(), m.to.get(), last))
    return "no state of the motion at the space's resolution collides (the validator could not "
           "certify the motion between them)";
  const unsigned n = space->validSegmentCount(m.from.get(), m.to.get());
  const double t = std::min(1.0, last.second + 1.0 / double(std::max(1u, n)));
  space->interpolate(m.from.get(), m.to.get(), t, s.get());
  char head[64];
  std::snprintf(head, sizeof head, "at %.6g of the motion: ", t);
  const auto c = vc.contacts(s.get());
  std::string line = head;
  if (!c) return line + "invalid input (a value outside the model's bounds)";
  if (c->empty()) return line + "no pair collides under exact DSS";
  for (std::size_t k = 0; k < c->size(); ++k)
    line += (k ? "; " : "") + dss::describeContact(*p.model, (*c)[k]);
  return line;
}

}  // namespace

bool knownMotionValidator(const std::string& name) {
  return name == "discrete" || name == "vector" || name == "continuous" || name == "ompl";
}

void checkMotions(const dss::Problem& p, const std::vector<std::vector<double>>& path,
                  const std::vector<int>& lines, const MotionCheckOptions& o) {
  const std::shared_ptr<dss::ValidityChecker> vc = dss::makeValidityChecker(p, o.checker);
  p.si->setStateValidityChecker(vc);
  p.si->setStateValidityCheckingResolution(o.resolution);
  p.si->setup();
  const std::vector<Motion> motions = o.random > 0 ? randomMotions(p, o.random, o.motion_length)
                                                   : pathMotions(p, path, lines, o.path_file);
  if (o.random <= 0 && !p.si->isValid(motions.front().from.get()))
    std::cerr << "dss_check: warning: " << o.path_file << ":" << (lines.empty() ? 2 : lines.front())
              << ": the path's first state is invalid (a motion assumes its start valid)\n";

  std::vector<ob::MotionValidatorPtr> validators;
  for (const std::string& name : o.validators) {
    if (name == "continuous")
      validators.push_back(dss::makeContinuousMotionValidator(p, *vc, o.min_fraction));
    else if (name == "ompl")
      validators.push_back(std::make_shared<ob::DiscreteMotionValidator>(p.si));
    else
      validators.push_back(dss::makeDiscreteMotionValidator(p, *vc, name == "vector"));
  }
  const std::size_t nv = validators.size();
  const int repeat = o.repeat > 0              ? o.repeat
                     : motions.size() >= 10000 ? 5
                     : motions.size() >= 1000  ? 11
                                               : 31;
  // Interleaved repetitions after one untimed pass each (as dss_check's states): a slow phase of
  // a shared machine hits every validator alike. The untimed pass counts the states checked.
  std::vector<std::vector<char>> valid(nv, std::vector<char>(motions.size()));
  std::vector<std::vector<double>> us(nv), us_wall(nv);
  std::vector<double> states_per_motion(nv), batch_per_motion(nv), subs_per_motion(nv);
  const double n = double(std::max<std::size_t>(1, motions.size()));
  for (int rep = -1; rep < repeat; ++rep) {
    for (std::size_t k = 0; k < nv; ++k) {
      const ob::MotionValidator& mv = *validators[k];
      const dss::CheckerCounters before = vc->counters();
      const auto* cmv = dynamic_cast<const dss::ContinuousMotionValidator*>(&mv);
      const std::uint64_t subs0 = cmv ? cmv->motionChecker().subMotions() : 0;
      std::vector<char>& v = valid[k];
      const auto t0 = std::chrono::steady_clock::now();
      const double c0 = threadCpuSeconds();
      for (std::size_t i = 0; i < motions.size(); ++i)
        v[i] = motions[i].finite && mv.checkMotion(motions[i].from.get(), motions[i].to.get());
      const double c1 = threadCpuSeconds();
      const auto t1 = std::chrono::steady_clock::now();
      if (rep < 0) {
        const dss::CheckerCounters d = vc->counters() - before;
        states_per_motion[k] = double(d.checks) / n;
        batch_per_motion[k] = double(d.batch_free) / n;
        if (cmv) subs_per_motion[k] = double(cmv->motionChecker().subMotions() - subs0) / n;
        continue;
      }
      us[k].push_back((c1 - c0) * 1e6 / n);
      us_wall[k].push_back(std::chrono::duration<double, std::micro>(t1 - t0).count() / n);
    }
  }

  // The first validator's verdicts, and with --contacts where each refused motion collides.
  const std::shared_ptr<dss::DiscreteMotionValidator> in_order =
      dss::makeDiscreteMotionValidator(p, *vc);
  for (std::size_t i = 0; i < motions.size(); ++i) {
    std::cout << (valid[0][i] ? 1 : 0);
    if (o.contacts && !valid[0][i]) std::cout << '\t' << explain(p, *vc, *in_order, motions[i]);
    std::cout << "\n";
  }
  for (std::size_t k = 0; k < nv; ++k) {
    nlohmann::json j;
    j["motion_validator"] = o.validators[k];
    j["checker"] = o.checker.checker;
    j["motions"] = motions.size();
    j["source"] = o.random > 0 ? "random" : "path";
    if (o.random > 0) j["motion_length"] = o.motion_length;
    j["resolution"] = o.resolution;
    j["valid"] = std::count(valid[k].begin(), valid[k].end(), 1);
    j["us_per_motion"] = median(us[k]);
    j["us_per_motion_wall"] = median(us_wall[k]);
    j["us_per_motion_min"] = us[k].empty() ? 0.0 : *std::min_element(us[k].begin(), us[k].end());
    j["timer"] = "thread CPU time (wall time in us_per_motion_wall)";
    j["repetitions"] = repeat;
    j["states_per_motion"] = states_per_motion[k];  // state checks, the end state's included
    j["batch_free_states_per_motion"] = batch_per_motion[k];
    if (o.validators[k] == "continuous") {
      j["sub_motions_per_motion"] = subs_per_motion[k];
      j["min_fraction"] = o.min_fraction;
    }
    j["simd"] = dss::simdPathName(p.model->kinematics().simdPath());
    j["model"] = p.model->summary();
    if (k > 0) {
      std::size_t dis = 0;
      for (std::size_t i = 0; i < motions.size(); ++i) dis += valid[k][i] != valid[0][i];
      j["disagreements"] = dis;
      std::vector<double> r;
      for (std::size_t i = 0; i < us[k].size() && i < us[0].size(); ++i)
        if (us[0][i] > 0.0) r.push_back(us[k][i] / us[0][i]);
      j["paired_ratio_to_first"] = median(r);
    }
    std::cerr << j.dump() << "\n";
  }
}

}  // namespace dss_check
