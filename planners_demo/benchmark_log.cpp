#include "benchmark_log.h"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/PlannerData.h>
#include <ompl/base/SpaceInformation.h>

#include <sstream>
#include <stdexcept>

#include "dss/planning/continuous_motion_validator.h"

namespace ob = ompl::base;

namespace dss_plan {

SwitchingChecker::SwitchingChecker(const ob::SpaceInformationPtr& si)
    : dss::ForwardingValidityChecker(si) {}

void SwitchingChecker::setActive(const dss::ValidityChecker* checker) {
  active_.store(checker);
  if (checker) specs_ = checker->getSpecs();
}

bool SwitchingChecker::isValid(const ob::State* state) const {
  const dss::ValidityChecker* c = active_.load(std::memory_order_relaxed);
  if (!c)
    throw std::logic_error(
        "dss_plan: no active validity checker (a planner ran outside its wrapper)");
  return c->isValid(state);
}

const dss::ValidityChecker* SwitchingChecker::target() const {
  return active_.load(std::memory_order_relaxed);
}

double SwitchingChecker::clearance(const ob::State* state) const {
  const dss::ValidityChecker* c = active_.load(std::memory_order_relaxed);
  return c ? c->clearance(state) : 0.0;
}

CheckerBoundPlanner::CheckerBoundPlanner(ob::PlannerPtr inner,
                                         std::shared_ptr<dss::ValidityChecker> checker,
                                         std::shared_ptr<SwitchingChecker> switching)
    : ob::Planner(inner->getSpaceInformation(),
                  inner->getName() + "[" + checker->checker().name() + "]"),
      inner_(std::move(inner)),
      checker_(std::move(checker)),
      switching_(std::move(switching)) {
  specs_ = inner_->getSpecs();
  params_.include(inner_->params());
  plannerProgressProperties_ = inner_->getPlannerProgressProperties();
}

ob::PlannerStatus CheckerBoundPlanner::solve(const ob::PlannerTerminationCondition& ptc) {
  switching_->setActive(checker_.get());
  const dss::CheckerCounters counters0 = checker_->counters();
  const auto& mv = si_->getMotionValidator();
  const std::uint64_t motions0 = dss::motionChecks(*mv);
  const auto* cmv = dynamic_cast<const dss::ContinuousMotionValidator*>(mv.get());
  const std::uint64_t sub0 = cmv ? cmv->motionChecker().subMotions() : 0;
  const ob::PlannerStatus status = inner_->solve(ptc);
  last_.sub_motions = cmv ? static_cast<long long>(cmv->motionChecker().subMotions() - sub0) : -1;
  last_.counters = checker_->counters() - counters0;
  last_.checking_seconds = double(last_.counters.checking_ns) * 1e-9;
  last_.motion_checks = dss::motionChecks(*mv) - motions0;
  return status;
}

void CheckerBoundPlanner::clear() {
  ob::Planner::clear();
  inner_->clear();
  last_ = RunRecord{};
}

void CheckerBoundPlanner::setup() {
  ob::Planner::setup();
  if (!inner_->isSetup()) inner_->setup();
}

void CheckerBoundPlanner::setProblemDefinition(const ob::ProblemDefinitionPtr& pdef) {
  ob::Planner::setProblemDefinition(pdef);
  inner_->setProblemDefinition(pdef);
}

void CheckerBoundPlanner::getPlannerData(ob::PlannerData& data) const {
  inner_->getPlannerData(data);
}

void addRunProperties(const ob::PlannerPtr& planner, ompl::tools::Benchmark::RunProperties& run) {
  const auto* bound = dynamic_cast<const CheckerBoundPlanner*>(planner.get());
  if (!bound)
    throw std::runtime_error("dss_plan: benchmark planner " + planner->getName() +
                             " has no checker");
  const RunRecord& r = bound->lastRun();
  auto put = [&](const std::string& key, auto value) {
    std::ostringstream s;
    s.precision(17);
    s << value;
    run[key] = s.str();
  };
  put("validity checks INTEGER", r.counters.checks);
  put("checking time REAL", r.checking_seconds);
  put("us per check REAL",
      r.counters.checks ? r.checking_seconds * 1e6 / double(r.counters.checks) : 0.0);
  put("invalid states INTEGER", r.counters.collisions + r.counters.invalid_input);
  put("narrow phase tests INTEGER", r.counters.pair_tests);
  put("motion checks INTEGER", r.motion_checks);
  if (bound->checker().checker().name() == "dss") put("cap hits INTEGER", r.counters.cap_hits);
  if (r.sub_motions >= 0) put("sub motions INTEGER", r.sub_motions);
}

}  // namespace dss_plan
