// DiscreteMotionChecker and the orders of a motion's states.
#include "dss/checker/discrete_motion.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace dss {

namespace {
// Motions of up to this many segments have their orders cached per thread.
constexpr int kCachedSegments = 256;

// kEndLast's states taken out of the bisection and checked first: those three quarters and
// nine tenths of the way (rounded to the nearest state), each once, the end excluded. Their
// count (0 to 2) is returned, the states in first[0 .. count) and 0 in the rest.
int endLastLeaders(int n, int first[2]) {
  auto at = [n](double f) { return std::min(n, std::max(1, static_cast<int>(f * n + 0.5))); };
  int count = 0;
  first[0] = first[1] = 0;
  for (const int j : {at(0.75), at(0.9)})
    if (j != n && (count == 0 || first[0] != j)) first[count++] = j;
  return count;
}
}  // namespace

void discreteCheckOrder(int n, MotionOrder kind, std::vector<int>& order) {
  order.clear();
  if (n < 1) return;
  order.reserve(std::size_t(n));
  // The states taken out of the bisection: the end (first or last), and with kEndLast its
  // leaders.
  int first[2] = {0, 0};
  if (kind == MotionOrder::kEndFirst)
    order.push_back(n);
  else
    order.insert(order.end(), first, first + endLastLeaders(n, first));
  // The interior runs, breadth first: the middle of each run, then its two halves.
  thread_local std::vector<std::pair<int, int>> runs;
  runs.clear();
  if (n >= 2) runs.emplace_back(1, n - 1);
  for (std::size_t head = 0; head < runs.size(); ++head) {
    const auto [lo, hi] = runs[head];
    const int mid = (lo + hi) / 2;
    if (mid != first[0] && mid != first[1]) order.push_back(mid);
    if (lo < mid) runs.emplace_back(lo, mid - 1);
    if (hi > mid) runs.emplace_back(mid + 1, hi);
  }
  if (kind == MotionOrder::kEndLast) order.push_back(n);
}

const int* cachedCheckOrder(int n, MotionOrder kind) {
  constexpr int kCached = kCachedSegments;
  thread_local std::vector<std::vector<int>> cache[2] = {
      std::vector<std::vector<int>>(kCached + 1), std::vector<std::vector<int>>(kCached + 1)};
  thread_local std::vector<int> scratch;
  if (n < 1) return nullptr;
  if (n > kCached) {
    discreteCheckOrder(n, kind, scratch);
    return scratch.data();
  }
  std::vector<int>& order = cache[kind == MotionOrder::kEndLast][std::size_t(n)];
  if (order.empty()) discreteCheckOrder(n, kind, order);
  return order.data();
}

CheckOrderCursor::CheckOrderCursor(int n, MotionOrder kind) : n_(std::max(0, n)), kind_(kind) {
  if (n_ == 0) {
    phase_ = 2;
    return;
  }
  if (n_ <= kCachedSegments) {
    cached_ = cachedCheckOrder(n_, kind);
    return;
  }
  if (kind == MotionOrder::kEndLast) num_first_ = endLastLeaders(n_, first_);
}

int CheckOrderCursor::nextOnLevel() {
  // The runs of a level, left to right, are the paths of depth_ turns from the top run
  // [1, n - 1] (each run's middle, then its left and right halves, as discreteCheckOrder's
  // breadth-first queue takes them); a path whose run empties is skipped with every path
  // through it.
  const long long paths = 1LL << depth_;
  while (path_ < paths) {
    int lo = 1, hi = n_ - 1;
    int bit = depth_ - 1;
    for (; bit >= 0 && lo <= hi; --bit) {
      const int mid = lo + (hi - lo) / 2;
      if ((path_ >> bit) & 1)
        lo = mid + 1;
      else
        hi = mid - 1;
    }
    if (lo > hi) {  // emptied above the level: skip every path below that turn
      path_ = (path_ | ((1LL << (bit + 1)) - 1)) + 1;
      continue;
    }
    ++path_;
    return lo + (hi - lo) / 2;
  }
  return 0;
}

int CheckOrderCursor::nextGenerated() {
  if (phase_ == 0) {
    if (kind_ == MotionOrder::kEndFirst && given_ == 0) return ++given_, n_;
    const int k = given_ - (kind_ == MotionOrder::kEndFirst ? 1 : 0);
    if (k < num_first_) return ++given_, first_[k];
    phase_ = 1;
  }
  while (phase_ == 1) {
    const int j = nextOnLevel();
    if (j != 0) {
      level_had_state_ = true;
      if (j == first_[0] || j == first_[1]) continue;
      return ++given_, j;
    }
    if (!level_had_state_ && depth_ > 0) {
      phase_ = 2;
      break;
    }
    if (depth_ >= 62) {
      phase_ = 2;
      break;
    }
    ++depth_, path_ = 0, level_had_state_ = false;
  }
  if (kind_ == MotionOrder::kEndLast && given_ < n_) return ++given_, n_;
  return 0;
}

unsigned freeInterpolated(const StateChecker& checker, const double* a, const double* b, int n,
                          const int* js, int m) {
  constexpr int kLanes = StateChecker::kBatchLanes;
  static_assert(kMotionBatch <= kLanes, "a batch fits the checker's lanes");
  const std::size_t nq = checker.model().robot().numActiveJoints();
  thread_local std::vector<double> lanes;
  if (lanes.size() < nq * kLanes) lanes.resize(nq * kLanes);
  m = std::min(m, kMotionBatch);
  if (m <= 0) return 0;
  // Value by value, each state's value as the one-by-one check computes it; lanes past m
  // repeat the first state. Two lanes per vector, a value's lanes in one pass (left to the
  // compiler, the loop ran over two values at a time and transposed them).
  using Two = double __attribute__((vector_size(16)));
  static_assert(kLanes % 2 == 0, "lanes in pairs");
  Two t[kLanes / 2];
  const double dn = double(n);
  for (int i = 0; i < kLanes / 2; ++i)
    t[i] = Two{double(js[2 * i < m ? 2 * i : 0]), double(js[2 * i + 1 < m ? 2 * i + 1 : 0])} / dn;
  double* const out = lanes.data();
  for (std::size_t k = 0; k < nq; ++k) {
    const double ak = a[k], dk = b[k] - a[k];
    const Two av = {ak, ak}, dv = {dk, dk};
    for (int i = 0; i < kLanes / 2; ++i) {
      const Two v = av + dv * t[i];
      std::memcpy(out + k * kLanes + 2 * i, &v, sizeof v);
    }
  }
  return checker.freeLanes(out, m);
}

DiscreteMotionChecker::DiscreteMotionChecker(std::shared_ptr<const StateChecker> checker,
                                             bool batched)
    : checker_(std::move(checker)) {
  if (!checker_) throw std::invalid_argument("DiscreteMotionChecker: no state checker");
  batched_ = batched && checker_->batchesPay();
}

bool DiscreteMotionChecker::clear(const double* q0, const double* q1, int segments,
                                  double* last_valid_fraction, MotionOrder kind) const {
  const StateChecker& checker = *checker_;
  // The start is assumed valid, but one outside the model's bounds (NaN, an infinity, a value
  // beyond a limit) is not: with few segments its motion's checked states could all be free.
  if (!checker.model().withinBounds(q0)) {
    if (last_valid_fraction) *last_valid_fraction = 0.0;
    return false;
  }
  const std::size_t nq = checker.model().robot().numActiveJoints();
  const int n = std::max(1, segments);
  thread_local std::vector<double> q;
  if (q.size() < nq) q.resize(nq);
  double* const qs = q.data();
  auto free = [&](int j) {
    if (j == n) return !checker.collides(q1);
    const double t = double(j) / double(n);
    for (std::size_t k = 0; k < nq; ++k) qs[k] = q0[k] + (q1[k] - q0[k]) * t;
    return !checker.collides(qs);
  };
  auto batch = [&](const int* js, int m) { return freeInterpolated(checker, q0, q1, n, js, m); };
  if (!last_valid_fraction)
    return batched_ ? motionStatesFreeBatched(n, free, batch, nullptr, kind)
                    : motionStatesFree(n, free, nullptr, kind);
  int first = 0;
  const bool ok = batched_ ? motionStatesFreeBatched(n, free, batch, &first)
                           : motionStatesFree(n, free, &first);
  if (!ok) *last_valid_fraction = double(first - 1) / double(n);
  return ok;
}

}  // namespace dss
