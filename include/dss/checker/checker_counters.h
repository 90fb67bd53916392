// Counters of a checker: what it was asked and what it found. They are the only state a
// checker changes while it answers, kept in per-thread slots (a cache line each, a thread's
// slot chosen once) so that threads checking in parallel never write to the same line, and a
// count costs no locked instruction.
#pragma once

#include <atomic>
#include <cstdint>

namespace dss {

struct CheckerCounters {
  std::uint64_t checks = 0;         ///< states checked
  std::uint64_t invalid_input = 0;  ///< of them: non-finite, or outside the model's bounds
  std::uint64_t collisions = 0;     ///< of them: found in collision
  std::uint64_t pair_tests = 0;     ///< narrow-phase calls
  std::uint64_t cap_hits = 0;       ///< states with a DSS answer at the iteration cap (colliding)
  /// Wall time in the checks, nanoseconds (0 unless the checker times its checks:
  /// StateChecker::timeChecks).
  std::uint64_t checking_ns = 0;
  /// Checks answered free by a batched pass (StateChecker::freeLanes), counted in `checks`.
  std::uint64_t batch_free = 0;

  /// The counts between two snapshots.
  CheckerCounters operator-(const CheckerCounters& o) const {
    return {checks - o.checks,         invalid_input - o.invalid_input, collisions - o.collisions,
            pair_tests - o.pair_tests, cap_hits - o.cap_hits,           checking_ns - o.checking_ns,
            batch_free - o.batch_free};
  }
};

/// Per-thread slots: the first kOwnedSlots threads that ask each own one slot index for good,
/// the same in every slot array; every later thread shares the overflow index kOwnedSlots.
/// A thread adds to an owned slot with a plain read and write (no locked instruction: no
/// other thread writes it), to the overflow slot atomically.
constexpr int kOwnedSlots = 16;
inline int threadSlotIndex() {
  static std::atomic<int> next{0};
  thread_local const int index = [] {
    int i = next.load(std::memory_order_relaxed);
    while (i < kOwnedSlots && !next.compare_exchange_weak(i, i + 1, std::memory_order_relaxed)) {
    }
    return i < kOwnedSlots ? i : kOwnedSlots;
  }();
  return index;
}
/// n added to counter c of slot `index` (threadSlotIndex()).
inline void addToSlot(std::atomic<std::uint64_t>& c, std::uint64_t n, int index) {
  if (index < kOwnedSlots)
    c.store(c.load(std::memory_order_relaxed) + n, std::memory_order_relaxed);
  else
    c.fetch_add(n, std::memory_order_relaxed);
}

class CounterSlots {
 public:
  struct alignas(64) Slot {
    std::atomic<std::uint64_t> checks{0}, invalid_input{0}, collisions{0}, pair_tests{0},
        cap_hits{0}, checking_ns{0}, batch_free{0};
    int index = 0;  ///< this slot's index (threadSlotIndex())
    void add(std::atomic<std::uint64_t>& c, std::uint64_t n = 1) { addToSlot(c, n, index); }
  };
  CounterSlots() {
    for (int i = 0; i <= kOwnedSlots; ++i) slots_[i].index = i;
  }
  /// This thread's slot.
  Slot& local() const { return slots_[threadSlotIndex()]; }
  CheckerCounters sum() const {
    CheckerCounters c;
    for (const Slot& s : slots_) {
      c.checks += s.checks.load(std::memory_order_relaxed);
      c.invalid_input += s.invalid_input.load(std::memory_order_relaxed);
      c.collisions += s.collisions.load(std::memory_order_relaxed);
      c.pair_tests += s.pair_tests.load(std::memory_order_relaxed);
      c.cap_hits += s.cap_hits.load(std::memory_order_relaxed);
      c.checking_ns += s.checking_ns.load(std::memory_order_relaxed);
      c.batch_free += s.batch_free.load(std::memory_order_relaxed);
    }
    return c;
  }

 private:
  mutable Slot slots_[kOwnedSlots + 1];
};

}  // namespace dss
