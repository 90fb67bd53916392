// Points of one dimension in a k-d tree of small buckets, for the point nearest to a query
// without a scan of every point. Each node keeps the box of its points; the search visits the
// nearer child first and passes over a node whose box lies farther from the query than the
// nearest point found. The bound (the squared distance from the query to the box) is summed
// value by value from the first, as a point's squared distance is (PointBlocks, OMPL's
// RealVectorStateSpace::distance), and rounding is monotone, so it never exceeds the computed
// distance of a point inside the box: the search returns exactly the point a scan of every
// point returns, the least squared distance below infinity and, among equal ones, the lowest
// index, on every instruction set. A bucket holds its points in blocks of four, scanned four
// at a time as PointBlocks scans.
//
// Points come one at a time: a point goes down to its bucket, and a bucket that outgrows
// kBucket points splits at the median of its widest value. A tree grown lopsided (points added
// in sorted order) is built again balanced once its depth exceeds twice a balanced tree's.
// Values may be NaN or infinite: a box takes only the values it can order, and a point with a
// NaN distance is never nearest.
#pragma once

#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "dss/core/simd_path.h"

namespace dss {

class PointTree {
 public:
  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  /// (squared distance, index) of a point found by a query.
  using Found = std::pair<double, std::size_t>;
  /// Points a bucket holds before it splits (more only where its points cannot be told apart).
  static constexpr std::size_t kBucket = 128;

  /// Scans on `path` (the best available when the CPU lacks it).
  PointTree(unsigned dimension, SimdPath path);

  unsigned dimension() const { return dim_; }
  std::size_t size() const { return size_; }
  void clear();
  /// Adds the point of index `index` (distinct from every index held) with values v
  /// (dimension() values).
  void insert(std::size_t index, const double* v);
  /// Drops the point of index `index`; then, unless `moved` is kNone or `index`, the point of
  /// index `moved` takes index `index` (as PointBlocks::swapRemove moves its last point).
  void swapRemove(std::size_t index, std::size_t moved);
  /// The index of the point nearest to q: the least squared distance below infinity, the lowest
  /// index among equal ones; kNone when no point is at such a distance (none held, a NaN in q).
  std::size_t nearest(const double* q) const;
  /// The k nearest points, nearest first (ties: the lower index first); a NaN distance counts
  /// as infinite. As PointBlocks::nearestK.
  void nearestK(const double* q, std::size_t k, std::vector<Found>& out) const;
  /// The points whose distance (the square root of the squared distance, as OMPL compares it)
  /// is <= radius, nearest first (ties: the lower index first). As PointBlocks::withinRadius.
  void withinRadius(const double* q, double radius, std::vector<Found>& out) const;
  /// The deepest bucket's depth (the root's is 0).
  int depth() const { return depth_; }

 private:
  struct Node {
    int dim = -1;        ///< the split value's coordinate; -1: a bucket
    double split = 0.0;  ///< values below go to child 0, the others to child 1
    int child[2] = {-1, -1};
    int bucket = -1;
  };
  struct Bucket {
    std::vector<double>
        data;  ///< blocks of four: block b, value d, lane l at (b * dim + d) * 4 + l
    std::vector<std::size_t> index;  ///< per place (kNone past the points)
    std::size_t count = 0;
    /// It splits past this many points: kBucket, or twice the count at which its points could
    /// not be told apart (so that copies of one point do not make every addition a split).
    std::size_t split_past = kBucket;
  };
  struct Where {
    int bucket = -1;
    std::size_t place = 0;
  };

  int newNode();
  int newBucket();
  double* lower(int node) { return boxes_.data() + std::size_t(node) * 2 * dim_; }
  double* upper(int node) { return lower(node) + dim_; }
  const double* lower(int node) const { return boxes_.data() + std::size_t(node) * 2 * dim_; }
  const double* upper(int node) const { return lower(node) + dim_; }
  /// The first value of a bucket's place p (the others every fourth double after it).
  double* placeIn(Bucket& b, std::size_t p) const {
    return b.data.data() + (p / 4) * dim_ * 4 + p % 4;
  }
  const double* placeIn(const Bucket& b, std::size_t p) const {
    return b.data.data() + (p / 4) * dim_ * 4 + p % 4;
  }
  void grow(int node, const double* v);
  void append(int bucket, std::size_t index, const double* v);
  void values(const Bucket& b, std::size_t place, double* v) const;
  /// Splits the bucket of `node` when it holds more than kBucket points that it can tell apart.
  void split(int node, int depth);
  void rebuild();
  /// A subtree over the points pts[begin, end) (values in vals, dim_ per point), into `node`.
  void build(int node, std::vector<std::size_t>& pts, std::size_t begin, std::size_t end,
             std::vector<double>& vals, int depth);
  /// The squared distance from q to the node's box (a lower bound of its points' distances).
  double boxBound(int node, const double* q) const;
  /// The bucket's points handed to the visitor: four at a time (kQuad) or one at a time.
  template <bool kQuad, class Visitor>
  void scanBucket(const Bucket& b, const double* q, Visitor& v) const;
  /// The nodes the visitor cannot prune, nearer child first.
  template <bool kQuad, class Visitor>
  void search(const double* q, Visitor& v) const;
  // What the searches collect (point_tree.cpp), and each search on each instruction set.
  struct Nearest;
  struct NearestK;
  struct WithinRadius;
#define DSS_POINT_TREE_PATHS(Name, Visitor)             \
  void Name##Avx2(const double* q, Visitor& v) const;   \
  void Name##Sse2(const double* q, Visitor& v) const;   \
  void Name##Scalar(const double* q, Visitor& v) const; \
  void Name##On(const double* q, Visitor& v) const;
  DSS_POINT_TREE_PATHS(nearest, Nearest)
  DSS_POINT_TREE_PATHS(nearestK, NearestK)
  DSS_POINT_TREE_PATHS(withinRadius, WithinRadius)
#undef DSS_POINT_TREE_PATHS

  unsigned dim_;
  SimdPath path_;
  std::size_t size_ = 0;
  int depth_ = 0;
  int rebuild_depth_ = 0;  ///< the depth the last rebuild left
  std::vector<Node> nodes_;
  std::vector<double> boxes_;  ///< per node: its lower corner, then its upper corner
  std::vector<Bucket> buckets_;
  std::vector<Where> where_;  ///< per index
};

}  // namespace dss
