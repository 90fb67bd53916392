// A collision checker for robot states, with no planner attached: it owns a collision model
// and answers for one vector of active joint values at a time. DSS (dss_checker.h) and FCL
// (fcl_checker.h) implement it on the same model; the OMPL adapters
// (dss/planning/validity_checker.h) hold one.
//
// Checkers are const and thread-safe: any number of threads may ask one checker at once (the
// only state they change is their counters, and per-thread scratch that stops allocating once
// a thread has warmed up). A state with a non-finite value, or outside the model's bounds
// (CollisionModel::withinBounds), is invalid: never "free", never a crash.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "dss/checker/checker_counters.h"
#include "dss/checker/collision_model.h"

namespace dss {

enum class StateVerdict { kFree, kColliding, kInvalidInput };

class StateChecker {
 public:
  virtual ~StateChecker() = default;

  /// The verdict for one state: q holds one value per active joint of the robot (held joints
  /// included). Counted.
  StateVerdict check(const double* q) const {
    CounterSlots::Slot& c = counters_.local();
    c.add(c.checks);
    if (!timed_) return decide(q, c);
    const auto t0 = std::chrono::steady_clock::now();
    const StateVerdict v = decide(q, c);
    addTimeSince(t0, c);
    return v;
  }
  /// Up to kBatchLanes states at once (the states of a motion): bit l set when state q[l] is
  /// proven free by the checker's batched pass (check(q[l]) would answer kFree), each such
  /// state counted as one check (and in batch_free); the others are left to check(). A
  /// checker without a batched pass proves none.
  static constexpr int kBatchLanes = 8;
  unsigned freeStates(const double* const* q, int n) const;
  /// The same for states given value by value: value j of state l at lanes[kBatchLanes j + l]
  /// (all kBatchLanes lanes readable; those past n are ignored).
  unsigned freeLanes(const double* lanes, int n) const {
    CounterSlots::Slot& c = counters_.local();
    const auto t0 =
        timed_ ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
    const unsigned free = provenFree(lanes, n);
    if (timed_) addTimeSince(t0, c);
    if (free) {
      const auto k = static_cast<std::uint64_t>(__builtin_popcount(free));
      c.add(c.checks, k);
      c.add(c.batch_free, k);
    }
    return free;
  }
  /// Whether freeLanes' batches cost less than the exact checks they spare, so that a motion
  /// check should hand its states to them: a checker with an AVX2 batched pass. On the generic
  /// lanes (SSE2, or NEON elsewhere) a batch of eight states costs about as much as the exact
  /// checks of the six or seven it proves (docs/performance.md).
  virtual bool batchesPay() const { return false; }
  /// Colliding or invalid: what a planner must avoid.
  bool collides(const double* q) const { return check(q) != StateVerdict::kFree; }

  /// "dss", "fcl-hull", "fcl-mesh".
  virtual std::string name() const = 0;
  const CollisionModel& model() const { return *model_; }
  CheckerCounters counters() const { return counters_.sum(); }
  /// With `on`, every check adds its wall time to the counters (checking_ns): two clock reads
  /// per check. Set before the checker is shared (checker_setup.h: CheckerConfig::time_checks).
  void timeChecks(bool on) { timed_ = on; }
  bool timesChecks() const { return timed_; }

 protected:
  explicit StateChecker(std::shared_ptr<const CollisionModel> model) : model_(std::move(model)) {}
  /// Whether a state within the model's bounds collides; `counters` (this thread's slot) takes
  /// the narrow-phase tests and cap hits.
  virtual bool collidesWithinBounds(const double* q, CounterSlots::Slot& counters) const = 0;
  /// freeLanes' states proven free (none by default).
  virtual unsigned provenFree(const double* /*lanes*/, int /*n*/) const { return 0; }
  CounterSlots::Slot& counterSlot() const { return counters_.local(); }

 private:
  /// The wall time since t0 added to the counters' checking time.
  static void addTimeSince(std::chrono::steady_clock::time_point t0, CounterSlots::Slot& c) {
    const auto ns =
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0)
            .count();
    c.add(c.checking_ns, static_cast<std::uint64_t>(ns));
  }
  StateVerdict decide(const double* q, CounterSlots::Slot& c) const {
    if (!model_->withinBounds(q)) {
      c.add(c.invalid_input);
      return StateVerdict::kInvalidInput;
    }
    if (!collidesWithinBounds(q, c)) return StateVerdict::kFree;
    c.add(c.collisions);
    return StateVerdict::kColliding;
  }

  std::shared_ptr<const CollisionModel> model_;
  CounterSlots counters_;
  bool timed_ = false;
};

inline unsigned StateChecker::freeStates(const double* const* q, int n) const {
  if (n <= 0) return 0;
  n = n < kBatchLanes ? n : kBatchLanes;
  const std::size_t nq = model_->robot().numActiveJoints();
  thread_local std::vector<double> lanes;
  if (lanes.size() < nq * kBatchLanes) lanes.resize(nq * kBatchLanes);
  // Lanes past n repeat the first state.
  for (int l = 0; l < kBatchLanes; ++l) {
    const double* ql = q[l < n ? l : 0];
    for (std::size_t j = 0; j < nq; ++j) lanes[j * kBatchLanes + std::size_t(l)] = ql[j];
  }
  return freeLanes(lanes.data(), n);
}

}  // namespace dss
