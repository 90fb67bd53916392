// Checks on random states and short motions drawn by OMPL's sampler in a problem's space,
// shared by the planning tests of our multi-DOF robots and of the Panda on its floating base:
// DSS against fcl-hull state by state, and the continuous validator against a dense check.
#pragma once

#include <ompl/base/ScopedState.h>

#include <boost/test/unit_test.hpp>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "dss/checker/checker_setup.h"
#include "dss/planning/continuous_motion_validator.h"
#include "dss/planning/planning_problem.h"

namespace dss_test {

/// A text file's contents (a model to rewrite before loading it).
inline std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Agreement {
  int states = 0, differ = 0, colliding = 0;
};

/// `n` states drawn uniformly in the problem's space, each checked by DSS and by fcl-hull.
inline Agreement dssAgainstFclHull(const dss::Problem& p, int n) {
  auto dss = dss::makeStateChecker(p.model, {"dss"});
  auto fcl = dss::makeStateChecker(p.model, {"fcl-hull"});
  ompl::base::StateSamplerPtr sampler = p.map->space()->allocStateSampler();
  ompl::base::ScopedState<> s(p.map->space());
  std::vector<double> q(p.model->robot().numActiveJoints());
  Agreement a;
  for (a.states = 0; a.states < n; ++a.states) {
    sampler->sampleUniform(s.get());
    BOOST_REQUIRE(p.map->toJoints(s.get(), q.data()));
    const dss::StateVerdict x = dss->check(q.data()), y = fcl->check(q.data());
    a.differ += x != y;
    a.colliding += x == dss::StateVerdict::kColliding;
  }
  return a;
}

struct MotionTally {
  int accepted = 0, rejected = 0, missed = 0;
};

/// `motions` short motions between free states (the end within `near` times the space's
/// extent of the start), each decided by the continuous validator; every accepted one is then
/// checked at 399 states between its ends (`missed` counts those where one collides).
inline MotionTally continuousAgainstDense(const dss::Problem& p, int motions, double near) {
  auto checker = dss::makeValidityChecker(p, {"dss"});
  auto motion = dss::makeContinuousMotionValidator(p, *checker);
  const auto& si = p.si;
  ompl::base::StateSamplerPtr sampler = si->allocStateSampler();
  ompl::base::ScopedState<> a(si->getStateSpace()), b(si->getStateSpace()),
      mid(si->getStateSpace());
  MotionTally t;
  for (int k = 0; k < motions; ++k) {
    do sampler->sampleUniform(a.get());
    while (!checker->isValid(a.get()));
    sampler->sampleUniformNear(b.get(), a.get(), near * si->getMaximumExtent());
    si->enforceBounds(b.get());
    if (!checker->isValid(b.get())) continue;
    const bool clear = motion->checkMotion(a.get(), b.get());
    (clear ? t.accepted : t.rejected) += 1;
    if (!clear) continue;
    for (int i = 1; i < 400; ++i) {
      si->getStateSpace()->interpolate(a.get(), b.get(), i / 400.0, mid.get());
      if (!checker->isValid(mid.get())) {
        ++t.missed;
        break;
      }
    }
  }
  return t;
}

}  // namespace dss_test
