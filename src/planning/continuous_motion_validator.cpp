// ContinuousMotionValidator: OMPL states to joint values, then the continuous motion check.
#include "dss/planning/continuous_motion_validator.h"

#include <ompl/base/SpaceInformation.h>

#include <cmath>
#include <vector>

#include "dss/planning/discrete_motion_validator.h"
#include "dss/planning/validity_checker.h"

namespace dss {

ContinuousMotionValidator::ContinuousMotionValidator(
    const ompl::base::SpaceInformationPtr& si,
    std::shared_ptr<const ContinuousMotionChecker> motion, std::shared_ptr<const GroupStateMap> map)
    : ompl::base::MotionValidator(si), motion_(std::move(motion)), map_(std::move(map)) {}

bool ContinuousMotionValidator::checkMotion(const ompl::base::State* s1,
                                            const ompl::base::State* s2) const {
  return check(s1, s2, nullptr);
}

bool ContinuousMotionValidator::checkMotion(
    const ompl::base::State* s1, const ompl::base::State* s2,
    std::pair<ompl::base::State*, double>& lastValid) const {
  double last = 0.0;
  if (check(s1, s2, &last)) return true;
  // At fraction 0 the start itself (which the space's interpolation may not take when it is
  // not finite).
  if (lastValid.first) {
    if (last == 0.0)
      si_->getStateSpace()->copyState(lastValid.first, s1);
    else
      si_->getStateSpace()->interpolate(s1, s2, last, lastValid.first);
  }
  lastValid.second = last;
  return false;
}

bool ContinuousMotionValidator::check(const ompl::base::State* s1, const ompl::base::State* s2,
                                      double* last) const {
  const RobotModel& robot = motion_->checker().model().robot();
  const std::size_t n = robot.numActiveJoints();
  thread_local std::vector<double> q0, q1;
  if (q0.size() < n) q0.resize(n), q1.resize(n);
  bool ok = map_->toJoints(s1, q0.data()) && map_->toJoints(s2, q1.data());
  if (ok) {
    // Continuous joints: move the short way, as OMPL's SO2 interpolation does.
    for (std::size_t i = 0; i < map_->dimension(); ++i) {
      const int a = map_->groupActive()[i];
      const RobotJoint& j = robot.joints[robot.active_joints[a]];
      if (j.type == JointType::kContinuous || !j.limits.has_position_limits)
        q1[a] = q0[a] + std::remainder(q1[a] - q0[a], 2.0 * M_PI);
    }
    const ValidityChecker* vc = decidingChecker(si_->getStateValidityChecker().get());
    ok = motion_->clear(q0.data(), q1.data(), last, motionOrderFrom(vc, s1));
  } else if (last) {
    *last = 0.0;
  }
  (ok ? valid_motions_ : invalid_motions_).fetch_add(1, std::memory_order_relaxed);
  return ok;
}

std::uint64_t motionChecks(const ompl::base::MotionValidator& validator) {
  if (const auto* c = dynamic_cast<const ContinuousMotionValidator*>(&validator))
    return c->validMotions() + c->invalidMotions();
  if (const auto* d = dynamic_cast<const DiscreteMotionValidator*>(&validator))
    return d->validMotions() + d->invalidMotions();
  return validator.getValidMotionCount() + validator.getInvalidMotionCount();
}

}  // namespace dss
