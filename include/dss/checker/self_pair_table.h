// Self-pair tables: decided cells of a self pair over the one or two group joint values its
// relative pose depends on.
//
// When the relative pose of two links depends on one or two group joint values only (e.g. the
// Panda's link5 and link7: joints 6 and 7; link5 and a finger: joints 6 and 7 with the finger
// joint held outside the group -- the table then answers only for the held value it was built
// with), the joint range is cut into cells and each cell is decided once, at build time, for
// every value inside it. Within a cell no point of one link moves more than L relative to the
// other (the joint's half-width times the distance of the geometry from the joint, from
// motion_bounds.h; a prismatic joint moves by its half-width).
//  - "Free": exact DSS proves the links at the cell centre farther apart than padding + L.
//  - "Colliding": the links at the centre still intersect when one is translated to each of
//    the six points at distance sqrt(3) L along the axes, so their Minkowski difference holds
//    the octahedron of those points and with it the ball of radius L: every pose in the cell
//    intersects (h_{A-B(q)}(d) >= h_{A-B(c)}(d) - L >= 0 for every unit d).
// Cells are decided coarse to fine (a decided block decides all its cells). At query time a
// decided cell answers the pair without a narrow phase; any other cell, or a value outside
// the range, takes the normal path. The tables never change an answer, only its cost.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "dss/core/simd_path.h"
#include "dss/robot/kinematics.h"
#include "dss/robot/robot_model.h"

namespace dss {

/// Decided cells of one self pair.
struct SelfPairTable {
  enum Cell : unsigned char { kUnknown = 0, kFree = 1, kColliding = 2 };
  int num_vars = 0;
  int var[2] = {-1, -1};  ///< active joint indices
  double lo[2] = {0, 0}, hi[2] = {0, 0}, inv_width[2] = {0, 0};
  bool wrap[2] = {false, false};  ///< continuous joint: the value is taken modulo 2 pi
  int cells[2] = {1, 1};
  /// Joints outside the group that the pair's relative pose depends on, at the held value the
  /// table was built with: any other value gets kUnknown.
  static constexpr int kMaxFixed = 4;
  int num_fixed = 0;
  int fixed_var[kMaxFixed] = {-1, -1, -1, -1};
  double fixed_value[kMaxFixed] = {0, 0, 0, 0};
  double padding = 0.0;
  std::vector<unsigned char> cell_state;  ///< Cell per cell, cells[0] x cells[1], row-major
  std::size_t num_free = 0;
  std::size_t num_colliding = 0;

  /// The decided state of the cell of q (kUnknown outside the range, or for NaN).
  Cell cell(const double* q) const {
    if (!heldMatch(q)) return kUnknown;
    const int idx = index(q);
    return idx < 0 ? kUnknown : static_cast<Cell>(cell_state[idx]);
  }
  /// The joints held outside the group are at the values the table was built with.
  bool heldMatch(const double* q) const {
    for (int k = 0; k < num_fixed; ++k)
      if (!(q[fixed_var[k]] == fixed_value[k])) return false;
    return true;
  }
  /// The cell index of q (row-major), or -1 outside the range or for NaN.
  int index(const double* q) const {
    double v[2];
    for (int k = 0; k < num_vars; ++k) v[k] = q[var[k]];
    return indexOf(v);
  }
  /// The same, from the variables' values (values[k]: active joint var[k]).
  int indexOf(const double* values) const {
    int idx = 0;
    for (int k = 0; k < num_vars; ++k) {
      double v = values[k];
      if (wrap[k]) v -= 6.283185307179586 * std::floor((v + 3.141592653589793) / 6.283185307179586);
      if (!(v >= lo[k] && v <= hi[k])) return -1;
      int i = static_cast<int>((v - lo[k]) * inv_width[k]);
      if (i >= cells[k]) i = cells[k] - 1;
      idx = idx * cells[k] + i;
    }
    return idx;
  }
  /// Same variables, ranges and cells: the same index for every q.
  bool sameGrid(const SelfPairTable& o) const {
    if (num_vars != o.num_vars) return false;
    for (int k = 0; k < num_vars; ++k)
      if (var[k] != o.var[k] || lo[k] != o.lo[k] || hi[k] != o.hi[k] || wrap[k] != o.wrap[k] ||
          cells[k] != o.cells[k])
        return false;
    return true;
  }
};

/// One side of a self pair for the table builder: its link, its elements, and a bound on the
/// distance of its geometry from the link's origin.
struct SelfPairSide {
  int link = -1;
  std::vector<const CollisionElement*> elements;
  double radius = 0.0;
};

/// The table of a self pair, when its relative pose depends on one or two group joints (and at
/// most SelfPairTable::kMaxFixed held ones) with finite ranges and some cell could be decided;
/// nullopt otherwise. `kin` computes the poses of both links; `in_group`: per active joint.
std::optional<SelfPairTable> buildSelfPairTable(const RobotModel& robot, const Kinematics& kin,
                                                const std::vector<double>& held,
                                                const std::vector<char>& in_group,
                                                const SelfPairSide& a, const SelfPairSide& b,
                                                int cells_1d, int cells_2d, double padding);

/// The tables of a model's self pairs, those on the same grid (e.g. the Panda's link5 against
/// link7, the hand and the two fingers: joints 6 and 7) packed together, two bits per table in
/// one byte per cell, so that a state reads one byte for all of them.
class SelfPairTables {
 public:
  SelfPairTables() = default;
  /// Takes the tables (all built at `padding`); new_index[i] receives table i's index.
  SelfPairTables(std::vector<SelfPairTable> tables, double padding, std::vector<int>* new_index);

  std::size_t size() const { return tables_.size(); }
  const std::vector<SelfPairTable>& tables() const { return tables_; }
  double padding() const { return padding_; }

  /// Reads every table once for state q: true when one certifies a collision at this self
  /// padding; otherwise skip[t] (one flag per table) is set when table t certifies its pair
  /// free at this padding. `held_match`: every joint held outside the group is at the value the
  /// tables were built with (the packed bytes are then read as masks). A narrow phase on
  /// geometry inside the elements' shapes (meshes inside their hulls) takes the free cells
  /// only (`colliding_cells` false): a collision of the hulls is not one of the meshes.
  bool read(const double* q, bool held_match, double self_padding, unsigned char* skip,
            bool colliding_cells = true) const;
  /// read() for the states of a batch, each at the held values, value j of state l at
  /// lanes[8 j + l], for the states l with bit l of `states` set: returns the states a table
  /// certifies colliding; for the others, bit l of skip[t] is set when table t certifies its
  /// pair free (skip[t] is only or-ed into). kAvx2 computes the cells' indices four lanes at a
  /// time where the CPU has it (the same operations, so the same cells); any other path lane
  /// by lane.
  unsigned readLanes(const double* lanes, unsigned states, double self_padding, unsigned* skip,
                     SimdPath path = SimdPath::kSse2) const;

  /// For every table, whether it certifies its pair free at this self padding at every state
  /// of the straight motion qa -> qb (active joint values): free_along[t] is set when the
  /// motion, cut into pieces that cross at most one cell boundary per variable, finds every cell
  /// of each piece's index rectangle (widened by a rounding margin) free. Unset for a
  /// continuous variable, a value outside the range, a held joint away from the table's value,
  /// or a motion of more than kMaxPieces pieces. Tables sharing a grid are walked together.
  void freeAlong(const double* qa, const double* qb, double self_padding,
                 unsigned char* free_along) const;
  static constexpr int kMaxPieces = 64;

 private:
  struct Group {
    int first = 0;  ///< its tables: tables_[first, first + count), on the grid of the first
    int count = 0;  ///< at most 4
    std::vector<std::uint8_t> packed;
    /// kBlock x kBlock cells per byte (kBlock per byte in 1D): the free bits of the tables
    /// free in every cell of the block, for freeAlong's first, coarse walk.
    int blocks[2] = {1, 1};
    std::vector<std::uint8_t> coarse;
  };
  static constexpr int kBlock = 8;
  /// The free bits of group g over motion qa -> qb walked on its grid (fine) or on its
  /// blocks, for the tables in `mask`.
  unsigned walkFree(const Group& g, const double* a, const double* b, bool fine,
                    unsigned mask) const;
  /// Of a packed byte: bit 2m + 1 set when table m's cell is kColliding (2), bit 2m when kFree.
  static unsigned colliding(unsigned byte) { return byte & 0xAAu & ~(byte << 1); }
  static unsigned free(unsigned byte) { return byte & 0x55u & ~(byte >> 1); }

  std::vector<SelfPairTable> tables_;
  std::vector<Group> groups_;
  double padding_ = 0.0;
};

}  // namespace dss
