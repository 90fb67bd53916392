// A discrete motion check: the states of a motion at a resolution, each decided by a state
// checker, with no planner attached. The states are those OMPL's DiscreteMotionValidator
// checks: with n segments, the states at fractions j / n for j = 1 .. n - 1 and the end state
// (the start is assumed valid, as OMPL assumes it). A motion is free when all of them are free,
// whatever order they are checked in, so the order is chosen to find a collision early:
//
//  - kEndFirst, for a motion towards a new state: the end state first, then the rest in
//    bisection order (the middle of each remaining run of states, breadth first), as OMPL
//    orders them. Such a motion mostly collides near its far end, often at the end itself.
//  - kEndLast, for a motion from a new state towards a state the caller holds (the motions
//    RRTConnect grows from its goal tree run from the state it has just found valid back to a
//    tree node): the end is most likely free, so it comes last; the states three quarters and
//    nine tenths of the way come first, then bisection. A state the caller holds is mostly in a
//    tight spot (a goal inside a shelf, a tree grown out of one), so such a motion collides
//    close to its end. On the MotionBenchMaker problems this order finds the collision of such
//    a motion in 1.2 states instead of 3.6 (docs/design.md#discrete-motion-check).
//  - When the last valid state is wanted: in order from the start, stopping at the first
//    colliding state, as OMPL does.
//
// Every order gives the same verdict as checking every state. The checker is const and
// thread-safe; the orders are cached per thread.
#pragma once

#include <memory>
#include <vector>

#include "dss/checker/state_checker.h"

namespace dss {

enum class MotionOrder { kEndFirst, kEndLast };

/// The order of the states 1 .. n of a motion when only the verdict is wanted (see above):
/// every state exactly once. Written into `order` (resized to n).
void discreteCheckOrder(int n, MotionOrder kind, std::vector<int>& order);
/// The same order, n values, from a per-thread cache (motions of up to 256 segments; longer
/// ones are ordered into per-thread scratch). Valid until the thread's next call.
const int* cachedCheckOrder(int n, MotionOrder kind);

/// The states of discreteCheckOrder(n, kind) one at a time: from the per-thread cache for
/// motions of up to 256 segments, generated level by level of the bisection beyond, in memory
/// that does not grow with n (a motion at a very fine resolution would otherwise need n
/// integers before its first state is checked).
class CheckOrderCursor {
 public:
  CheckOrderCursor(int n, MotionOrder kind);
  /// The next state (1 .. n), 0 once every state has been given.
  int next() {
    if (cached_) return given_ < n_ ? cached_[given_++] : 0;
    return nextGenerated();
  }

 private:
  int nextGenerated();
  /// The bisection's next state at or after path_ on level depth_, 0 when the level has none.
  int nextOnLevel();

  int n_;
  MotionOrder kind_;
  const int* cached_ = nullptr;
  int given_ = 0;
  int first_[2] = {0, 0};  ///< kEndLast: the states taken out of the bisection
  int num_first_ = 0;
  int phase_ = 0;  ///< 0: the states before the bisection, 1: the bisection, 2: done
  int depth_ = 0;
  long long path_ = 0;  ///< on level depth_, the runs' left (0) and right (1) turns from the top
  bool level_had_state_ = false;
};

/// Whether the states 1 .. n of a motion are all free, by `free(j)` (true: state j is free).
/// With `first_colliding` null, in discreteCheckOrder(n, kind) order; otherwise in order from
/// state 1, and *first_colliding receives the first colliding state (n + 1 when none).
template <class Free>
bool motionStatesFree(int n, Free&& free, int* first_colliding = nullptr,
                      MotionOrder kind = MotionOrder::kEndFirst) {
  if (first_colliding) {
    for (int j = 1; j <= n; ++j)
      if (!free(j)) {
        *first_colliding = j;
        return false;
      }
    *first_colliding = n + 1;
    return true;
  }
  CheckOrderCursor order(n, kind);
  for (int j = order.next(); j != 0; j = order.next())
    if (!free(j)) return false;
  return true;
}

/// The same verdict (and first colliding state) as motionStatesFree, with states decided in
/// batches: `batch(js, m)` returns bit i set for each state js[i] (m <= kMotionBatch states)
/// proven free (StateChecker::freeLanes); the states it leaves are decided by `free`, in the
/// same order as the batch lists them, and so is state n (the end state, which OMPL decides
/// with the space information's validity checker). Without `first_colliding`: the first states
/// of the order one by one (a colliding motion mostly ends there: kMotionProbesEndFirst of a
/// motion towards a new state, the end itself; kMotionProbesEndLast of a motion towards a held
/// state, the two states near its end), then the rest of the order in batches; with it, in
/// order from state 1, batch after batch. Runs of fewer than kMotionMinBatch states go one by
/// one.
constexpr int kMotionBatch = 8;
constexpr int kMotionProbesEndFirst = 1;
constexpr int kMotionProbesEndLast = 2;
constexpr int kMotionMinBatch = 3;
template <class Free, class Batch>
bool motionStatesFreeBatched(int n, Free&& free, Batch&& batch, int* first_colliding = nullptr,
                             MotionOrder kind = MotionOrder::kEndFirst) {
  int js[kMotionBatch];
  // The states next() gives until it gives 0, batch by batch except n (those a batch leaves
  // decided in batch order), n where it comes: the first colliding one in *at.
  auto run = [&](auto&& next, int* at) {
    int j = next();
    while (j != 0) {
      int m = 0;
      while (j != 0 && j != n && m < kMotionBatch) js[m++] = j, j = next();
      if (m >= kMotionMinBatch) {
        const unsigned proven = batch(js, m);
        for (int i = 0; i < m; ++i)
          if (!((proven >> i) & 1u) && !free(js[i])) return *at = js[i], false;
      } else {
        for (int i = 0; i < m; ++i)
          if (!free(js[i])) return *at = js[i], false;
      }
      if (j == n) {
        if (!free(n)) return *at = n, false;
        j = next();
      }
    }
    return true;
  };
  int at = 0;
  if (first_colliding) {  // in order from state 1
    int k = 0;
    const bool ok = run([&k, n] { return k < n ? ++k : 0; }, &at);
    *first_colliding = ok ? n + 1 : at;
    return ok;
  }
  CheckOrderCursor order(n, kind);
  const int probes = kind == MotionOrder::kEndFirst ? kMotionProbesEndFirst : kMotionProbesEndLast;
  for (int k = 0; k < probes; ++k) {
    const int j = order.next();
    if (j == 0) return true;
    if (!free(j)) return false;
  }
  return run([&order] { return order.next(); }, &at);
}

/// A batch for motionStatesFreeBatched: states js[0 .. m) (m <= kMotionBatch) of the motion
/// a -> b at n segments, each value interpolated as OMPL's real vector spaces do (a + (b - a)
/// j / n), handed to checker.freeLanes value by value (per-thread scratch).
unsigned freeInterpolated(const StateChecker& checker, const double* a, const double* b, int n,
                          const int* js, int m);

class DiscreteMotionChecker {
 public:
  /// Throws std::invalid_argument for a null checker. `batched`: states decided in batches
  /// where the checker proves them free (motionStatesFreeBatched), the same verdicts, when
  /// its batches pay (StateChecker::batchesPay); otherwise one by one, as without it.
  explicit DiscreteMotionChecker(std::shared_ptr<const StateChecker> checker, bool batched = false);

  /// True when the straight joint-space motion from q0 to q1 (active joint values) is free at
  /// `segments` segments: the states q0 + (q1 - q0) j / segments for j = 1 .. segments - 1
  /// (each value computed as OMPL's real vector spaces interpolate) and q1 itself, checked in
  /// `kind` order. Otherwise `last_valid_fraction` (optional; it makes the check run in order
  /// from the start) receives (j - 1) / segments for the first colliding state j, as OMPL's
  /// lastValid. A state outside the model's bounds or with a non-finite value counts as
  /// colliding; so does such a start (fraction 0), which is not checked otherwise. segments < 1
  /// counts as 1.
  bool clear(const double* q0, const double* q1, int segments,
             double* last_valid_fraction = nullptr,
             MotionOrder kind = MotionOrder::kEndFirst) const;

  const StateChecker& checker() const { return *checker_; }
  /// Whether states go in batches: asked for, and the checker's batches pay.
  bool batched() const { return batched_; }

 private:
  std::shared_ptr<const StateChecker> checker_;
  bool batched_ = false;
};

}  // namespace dss
