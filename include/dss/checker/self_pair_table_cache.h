// A process-wide cache of self-pair tables (self_pair_table.h). A table depends on the robot,
// the pair's two sides, the group, the held joint values and the table options, not on the
// scene: models of one robot in many scenes (a folder of MotionBenchMaker problems, a planning
// scene that changes between requests) build each table once. Only models built from the same
// RobotModel object (the same shared_ptr, still alive) share entries, and every part of the key
// must match exactly, so a cached table is the one buildSelfPairTable would return.
// Thread-safe; tables are built outside the lock. The cache holds at most 32 M cells (1 byte
// each) and 4096 entries, dropping the oldest first.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "dss/checker/self_pair_table.h"

namespace dss {

/// buildSelfPairTable, through the cache.
std::optional<SelfPairTable> cachedSelfPairTable(const std::shared_ptr<const RobotModel>& robot,
                                                 const Kinematics& kin,
                                                 const std::vector<double>& held,
                                                 const std::vector<char>& in_group,
                                                 const SelfPairSide& a, const SelfPairSide& b,
                                                 int cells_1d, int cells_2d, double padding);

struct SelfPairTableCacheStats {
  std::size_t hits = 0, misses = 0;  ///< lookups so far
  std::size_t entries = 0, cells = 0;
};
SelfPairTableCacheStats selfPairTableCacheStats();
/// Empties the cache (the counts stay).
void clearSelfPairTableCache();

}  // namespace dss
