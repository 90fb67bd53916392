// The process-wide cache of self-pair tables (see dss/checker/self_pair_table_cache.h).
#include "dss/checker/self_pair_table_cache.h"

#include <cstring>
#include <deque>
#include <mutex>

namespace dss {

namespace {

constexpr std::size_t kMaxCells = std::size_t(32) << 20;
// Pairs without a table hold no cells but still an entry (a held value that changes with every
// request would otherwise grow the list, and the lookups with it).
constexpr std::size_t kMaxEntries = 4096;

struct Key {
  std::weak_ptr<const RobotModel> robot;
  const RobotModel* robot_ptr = nullptr;
  int link_a = -1, link_b = -1;
  std::vector<const CollisionElement*> elements_a, elements_b;
  double radius_a = 0.0, radius_b = 0.0;
  std::vector<double> held;
  std::vector<char> in_group;
  int cells_1d = 0, cells_2d = 0;
  double padding = 0.0;

  // Doubles compared by their bits: the same inputs, not merely equal values.
  static bool sameBits(double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; }
  bool matches(const Key& o) const {
    if (robot_ptr != o.robot_ptr || link_a != o.link_a || link_b != o.link_b ||
        cells_1d != o.cells_1d || cells_2d != o.cells_2d || !sameBits(padding, o.padding) ||
        !sameBits(radius_a, o.radius_a) || !sameBits(radius_b, o.radius_b) ||
        elements_a != o.elements_a || elements_b != o.elements_b || in_group != o.in_group ||
        held.size() != o.held.size())
      return false;
    for (std::size_t i = 0; i < held.size(); ++i)
      if (!sameBits(held[i], o.held[i])) return false;
    // The same address may hold another robot once the first is gone: an entry counts only
    // while its robot lives.
    const std::shared_ptr<const RobotModel> alive = robot.lock();
    return alive && alive.get() == o.robot_ptr;
  }
};

struct Entry {
  Key key;
  std::optional<SelfPairTable> table;
  std::size_t cells = 0;
};

struct Cache {
  std::mutex mutex;
  std::deque<Entry> entries;  // oldest first
  std::size_t cells = 0, hits = 0, misses = 0;
};

Cache& cache() {
  static Cache c;
  return c;
}

}  // namespace

std::optional<SelfPairTable> cachedSelfPairTable(const std::shared_ptr<const RobotModel>& robot,
                                                 const Kinematics& kin,
                                                 const std::vector<double>& held,
                                                 const std::vector<char>& in_group,
                                                 const SelfPairSide& a, const SelfPairSide& b,
                                                 int cells_1d, int cells_2d, double padding) {
  Key key{robot,    robot.get(), a.link,   b.link,   a.elements, b.elements, a.radius,
          b.radius, held,        in_group, cells_1d, cells_2d,   padding};
  Cache& c = cache();
  {
    std::lock_guard<std::mutex> lock(c.mutex);
    for (const Entry& e : c.entries)
      if (e.key.matches(key)) {
        ++c.hits;
        return e.table;
      }
    ++c.misses;
  }
  std::optional<SelfPairTable> table =
      buildSelfPairTable(*robot, kin, held, in_group, a, b, cells_1d, cells_2d, padding);
  Entry entry{std::move(key), table, table ? table->cell_state.size() : 0};
  std::lock_guard<std::mutex> lock(c.mutex);
  // Entries of robots that are gone first, then the oldest, until the new one fits.
  for (auto it = c.entries.begin(); it != c.entries.end();)
    if (it->key.robot.expired()) {
      c.cells -= it->cells;
      it = c.entries.erase(it);
    } else {
      ++it;
    }
  while (!c.entries.empty() &&
         (c.cells + entry.cells > kMaxCells || c.entries.size() >= kMaxEntries)) {
    c.cells -= c.entries.front().cells;
    c.entries.pop_front();
  }
  if (entry.cells <= kMaxCells) {
    c.cells += entry.cells;
    c.entries.push_back(std::move(entry));
  }
  return table;
}

SelfPairTableCacheStats selfPairTableCacheStats() {
  Cache& c = cache();
  std::lock_guard<std::mutex> lock(c.mutex);
  SelfPairTableCacheStats s;
  s.hits = c.hits;
  s.misses = c.misses;
  s.entries = c.entries.size();
  s.cells = c.cells;
  return s;
}

void clearSelfPairTableCache() {
  Cache& c = cache();
  std::lock_guard<std::mutex> lock(c.mutex);
  c.entries.clear();
  c.cells = 0;
}

}  // namespace dss
