// dss_plan --benchmark: OMPL Benchmark experiments where each planner entry runs with its own
// validity checker ("RRTConnect[dss]", "RRTConnect[fcl-hull]", ...) on one shared
// SpaceInformation.
//
// How the checker follows the planner entry: the SpaceInformation holds one SwitchingChecker
// for the whole experiment; every planner entry is a CheckerBoundPlanner wrapping the OMPL
// planner and one checker. Its solve() makes its checker the active one, runs the wrapped
// planner and snapshots the difference of that checker's counters (checks, and the time in them:
// the benchmark's checkers time their checks) before returning. The motion validator checks a
// motion's states under the active checker as it would in a plan outside the benchmark.
// Benchmark then checks and simplifies the solution (with the same checker, still active) and
// calls the post-run event, which writes the snapshot: so the extra columns count the planner's
// own work only, not OMPL's path checks or simplification.
#pragma once

#include <ompl/base/Planner.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/tools/benchmark/Benchmark.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "dss/planning/validity_checker.h"

namespace dss_plan {

/// Forwards isValid/clearance to the active checker, switched only between planning runs; the
/// motion validators look through it to the active checker (dss::ForwardingValidityChecker).
class SwitchingChecker : public dss::ForwardingValidityChecker {
 public:
  explicit SwitchingChecker(const ompl::base::SpaceInformationPtr& si);
  void setActive(const dss::ValidityChecker* checker);
  bool isValid(const ompl::base::State* state) const override;
  double clearance(const ompl::base::State* state) const override;
  const dss::ValidityChecker* target() const override;

 private:
  std::atomic<const dss::ValidityChecker*> active_{nullptr};
};

/// What one planning run cost in collision checking (the planner's solve only).
struct RunRecord {
  dss::CheckerCounters counters;
  double checking_seconds = 0.0;
  std::uint64_t motion_checks = 0;
  long long sub_motions = -1;  ///< continuous validator's sub-motions (-1: discrete validator)
};

/// An OMPL planner bound to one validity checker; named "<planner>[<checker>]".
class CheckerBoundPlanner : public ompl::base::Planner {
 public:
  CheckerBoundPlanner(ompl::base::PlannerPtr inner, std::shared_ptr<dss::ValidityChecker> checker,
                      std::shared_ptr<SwitchingChecker> switching);

  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override;
  void clear() override;
  void setup() override;
  void setProblemDefinition(const ompl::base::ProblemDefinitionPtr& pdef) override;
  void getPlannerData(ompl::base::PlannerData& data) const override;

  const RunRecord& lastRun() const { return last_; }
  const dss::ValidityChecker& checker() const { return *checker_; }

 private:
  ompl::base::PlannerPtr inner_;
  std::shared_ptr<dss::ValidityChecker> checker_;
  std::shared_ptr<SwitchingChecker> switching_;
  RunRecord last_;
};

/// The post-run event: adds the last run's record to the run's properties, with OMPL's
/// "<name> <TYPE>" key convention (ompl_benchmark_statistics makes columns named with
/// underscores): validity checks, checking time (s), us per check, invalid states,
/// narrow phase tests, motion checks, cap hits for the DSS checker, and sub motions with the
/// continuous motion validator (whose swept-hull tests are not in "checking time", which
/// times state checks only).
void addRunProperties(const ompl::base::PlannerPtr& planner,
                      ompl::tools::Benchmark::RunProperties& run);

}  // namespace dss_plan
