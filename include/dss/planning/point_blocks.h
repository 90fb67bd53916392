// Points of one dimension in blocks of four, for nearest-neighbour scans four points at a time
// (each block holds, value by value, its four points' values side by side). The squared
// distance of a point to a query is summed value by value from the first, as OMPL's
// RealVectorStateSpace::distance sums it (whose square root is the distance), so every point
// gets the distance OMPL gives it, on every instruction set (dss/core/simd_path.h). The unused
// places of the last block hold NaN, which is never nearer than anything. From kTreeFrom points
// on, the queries go to a PointTree over the same points (point_tree.h), which finds the same
// points without a scan of every one.
#pragma once

#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "dss/core/simd_path.h"
#include "dss/planning/point_tree.h"

namespace dss {

class PointBlocks {
 public:
  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  /// The size from which the queries go to the tree by default (below it a scan costs no more).
  static constexpr std::size_t kTreeFrom = 512;
  /// (squared distance, index) of a point found by a query.
  using Found = std::pair<double, std::size_t>;

  /// Scans on activeSimdPath(), or on `path` (the best available when the CPU lacks it);
  /// the queries go to the tree from `tree_from` points on (SIZE_MAX: never).
  explicit PointBlocks(unsigned dimension);
  PointBlocks(unsigned dimension, SimdPath path, std::size_t tree_from = kTreeFrom);

  unsigned dimension() const { return dim_; }
  std::size_t size() const { return n_; }
  SimdPath path() const { return path_; }
  void clear() {
    data_.clear();
    n_ = 0;
    tree_.clear();
    tree_on_ = false;
  }
  /// Appends a point (dimension() values): its index is size() before the call.
  void push(const double* v);
  /// Moves the last point to index i (i < size()) and drops the last place.
  void swapRemove(std::size_t i);
  /// Point i's values into v.
  void get(std::size_t i, double* v) const;

  /// The index of the point nearest to q (the first of equally near ones); kNone when empty.
  /// When no point is at a finite distance below infinity (a NaN in q, say), point 0.
  std::size_t nearest(const double* q) const;
  /// The k nearest points, nearest first (ties: the lower index first). A NaN distance counts
  /// as infinite.
  void nearestK(const double* q, std::size_t k, std::vector<Found>& out) const;
  /// The points whose distance (the square root of the squared distance, as OMPL compares it)
  /// is <= radius, nearest first (ties: the lower index first).
  void withinRadius(const double* q, double radius, std::vector<Found>& out) const;

 private:
  double* place(std::size_t i) { return data_.data() + (i / 4) * dim_ * 4 + i % 4; }
  const double* place(std::size_t i) const { return data_.data() + (i / 4) * dim_ * 4 + i % 4; }
  /// Squared distances of every place (a multiple of four) to q, into a per-thread buffer.
  const double* allDistances(const double* q) const;

  unsigned dim_;
  SimdPath path_;
  std::size_t n_ = 0;
  std::vector<double> data_;  // block b, value d, lane l at (b * dim_ + d) * 4 + l
  std::size_t tree_from_;
  PointTree tree_;  // every point, from tree_from_ points on
  bool tree_on_ = false;
};

}  // namespace dss
