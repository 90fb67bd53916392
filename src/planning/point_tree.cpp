// PointTree: the buckets, their splits and the search (see dss/planning/point_tree.h).
#include "dss/planning/point_tree.h"

#include <algorithm>
#include <cmath>

// (Every function here that passes a 32-byte vector is inlined: see block_distances.h.)
#pragma GCC diagnostic ignored "-Wpsabi"
#include "block_distances.h"

namespace dss {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The depth from which a tree of n points is built again: twice a balanced tree's, and some.
int depthLimit(std::size_t n) {
  const double leaves = double(n) / double(PointTree::kBucket) + 1.0;
  return 2 * static_cast<int>(std::ceil(std::log2(leaves))) + 8;
}
}  // namespace

PointTree::PointTree(unsigned dimension, SimdPath path)
    : dim_(dimension), path_(simdPathAvailable(path) ? path : bestSimdPath()) {}

void PointTree::clear() {
  size_ = 0;
  depth_ = 0;
  rebuild_depth_ = 0;
  nodes_.clear();
  boxes_.clear();
  buckets_.clear();
  where_.clear();
}

int PointTree::newNode() {
  nodes_.emplace_back();
  boxes_.resize(boxes_.size() + dim_, kInf);
  boxes_.resize(boxes_.size() + dim_, -kInf);
  return static_cast<int>(nodes_.size() - 1);
}

int PointTree::newBucket() {
  buckets_.emplace_back();
  return static_cast<int>(buckets_.size() - 1);
}

void PointTree::grow(int node, const double* v) {
  double* lo = lower(node);
  double* hi = upper(node);
  for (unsigned d = 0; d < dim_; ++d) {  // a NaN orders with nothing and changes neither
    if (v[d] < lo[d]) lo[d] = v[d];
    if (v[d] > hi[d]) hi[d] = v[d];
  }
}

void PointTree::append(int bucket, std::size_t index, const double* v) {
  Bucket& b = buckets_[std::size_t(bucket)];
  const std::size_t p = b.count;
  if (p % 4 == 0) {
    b.data.resize(b.data.size() + std::size_t(dim_) * 4, kNaN);
    b.index.resize(b.index.size() + 4, kNone);
  }
  double* at = placeIn(b, p);
  for (unsigned d = 0; d < dim_; ++d) at[4 * d] = v[d];
  b.index[p] = index;
  ++b.count;
  where_[index] = {bucket, p};
}

void PointTree::values(const Bucket& b, std::size_t place, double* v) const {
  const double* at = placeIn(b, place);
  for (unsigned d = 0; d < dim_; ++d) v[d] = at[4 * d];
}

void PointTree::insert(std::size_t index, const double* v) {
  if (nodes_.empty()) {
    newNode();
    nodes_[0].bucket = newBucket();
  }
  if (where_.size() <= index) where_.resize(index + 1);
  int n = 0, depth = 0;
  for (;;) {
    grow(n, v);
    const Node& node = nodes_[std::size_t(n)];
    if (node.dim < 0) break;
    n = node.child[v[node.dim] < node.split ? 0 : 1];
    ++depth;
  }
  append(nodes_[std::size_t(n)].bucket, index, v);
  ++size_;
  depth_ = std::max(depth_, depth);
  const Bucket& b = buckets_[std::size_t(nodes_[std::size_t(n)].bucket)];
  if (b.count > b.split_past) split(n, depth);
  if (depth_ > std::max(depthLimit(size_), 2 * rebuild_depth_)) rebuild();
}

void PointTree::swapRemove(std::size_t index, std::size_t moved) {
  const Where w = where_[index];
  Bucket& b = buckets_[std::size_t(w.bucket)];
  const std::size_t last = b.count - 1;
  if (w.place != last) {
    double* to = placeIn(b, w.place);
    const double* from = placeIn(b, last);
    for (unsigned d = 0; d < dim_; ++d) to[4 * d] = from[4 * d];
    b.index[w.place] = b.index[last];
    where_[b.index[w.place]].place = w.place;
  }
  double* at = placeIn(b, last);
  for (unsigned d = 0; d < dim_; ++d) at[4 * d] = kNaN;
  b.index[last] = kNone;
  --b.count;
  if (b.count % 4 == 0) {
    b.data.resize(b.data.size() - std::size_t(dim_) * 4);
    b.index.resize(b.index.size() - 4);
  }
  --size_;
  where_[index] = Where{};
  // The boxes stay as they are: a box that holds more than its points still bounds them.
  if (moved != kNone && moved != index) {
    const Where m = where_[moved];
    buckets_[std::size_t(m.bucket)].index[m.place] = index;
    where_[index] = m;
    where_[moved] = Where{};
  }
}

void PointTree::split(int node, int depth) {
  const int bi = nodes_[std::size_t(node)].bucket;
  // The bucket's points, taken out of it.
  const Bucket& b = buckets_[std::size_t(bi)];
  const std::size_t count = b.count;
  std::vector<double> vals(count * dim_);
  std::vector<std::size_t> index(count);
  for (std::size_t p = 0; p < count; ++p) {
    values(b, p, vals.data() + p * dim_);
    index[p] = b.index[p];
  }
  // The widest value among them (the node's box may be wider than its points after removals).
  int best = -1;
  double widest = 0.0;
  for (unsigned d = 0; d < dim_; ++d) {
    double lo = kInf, hi = -kInf;
    for (std::size_t p = 0; p < count; ++p) {
      const double x = vals[p * dim_ + d];
      if (x < lo) lo = x;
      if (x > hi) hi = x;
    }
    if (hi - lo > widest) widest = hi - lo, best = static_cast<int>(d);
  }
  if (best < 0) {  // the points cannot be told apart: the bucket stays as it is
    buckets_[std::size_t(bi)].split_past = 2 * count;
    return;
  }
  // The median of that value; below it to child 0, the rest (NaN too) to child 1, neither empty.
  std::vector<double> xs;
  xs.reserve(count);
  for (std::size_t p = 0; p < count; ++p)
    if (!std::isnan(vals[p * dim_ + std::size_t(best)]))
      xs.push_back(vals[p * dim_ + std::size_t(best)]);
  std::sort(xs.begin(), xs.end());
  double split = xs[xs.size() / 2];
  if (!(xs.front() < split)) split = *std::upper_bound(xs.begin(), xs.end(), xs.front());
  Bucket& emptied = buckets_[std::size_t(bi)];
  emptied.data.clear();
  emptied.index.clear();
  emptied.count = 0;
  emptied.split_past = kBucket;
  const int c0 = newNode();
  const int c1 = newNode();
  Node& n = nodes_[std::size_t(node)];
  n.dim = best;
  n.split = split;
  n.child[0] = c0;
  n.child[1] = c1;
  n.bucket = -1;
  nodes_[std::size_t(c0)].bucket = bi;
  nodes_[std::size_t(c1)].bucket = newBucket();
  for (std::size_t p = 0; p < count; ++p) {
    const double* v = vals.data() + p * dim_;
    const int c = v[best] < split ? c0 : c1;
    grow(c, v);
    append(nodes_[std::size_t(c)].bucket, index[p], v);
  }
  depth_ = std::max(depth_, depth + 1);
}

void PointTree::rebuild() {
  std::vector<std::size_t> index;
  std::vector<double> vals;
  index.reserve(size_);
  vals.reserve(size_ * dim_);
  std::vector<double> v(dim_);
  for (const Bucket& b : buckets_)
    for (std::size_t p = 0; p < b.count; ++p) {
      values(b, p, v.data());
      vals.insert(vals.end(), v.begin(), v.end());
      index.push_back(b.index[p]);
    }
  const std::size_t n = index.size();
  nodes_.clear();
  boxes_.clear();
  buckets_.clear();
  depth_ = 0;
  // The subtrees to build, without recursion: (node, first, end, depth) over the permutation.
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  struct Job {
    int node;
    std::size_t begin, end;
    int depth;
  };
  std::vector<Job> jobs;
  jobs.push_back({newNode(), 0, n, 0});
  auto value = [&](std::size_t r, int d) { return vals[r * dim_ + std::size_t(d)]; };
  while (!jobs.empty()) {
    const Job job = jobs.back();
    jobs.pop_back();
    for (std::size_t i = job.begin; i < job.end; ++i) grow(job.node, vals.data() + order[i] * dim_);
    int best = -1;
    if (job.end - job.begin > kBucket) {
      double widest = 0.0;
      const double* lo = lower(job.node);
      const double* hi = upper(job.node);
      for (unsigned d = 0; d < dim_; ++d)
        if (hi[d] - lo[d] > widest) widest = hi[d] - lo[d], best = static_cast<int>(d);
    }
    if (best < 0) {  // a bucket
      const int b = newBucket();
      nodes_[std::size_t(job.node)].bucket = b;
      for (std::size_t i = job.begin; i < job.end; ++i)
        append(b, index[order[i]], vals.data() + order[i] * dim_);
      buckets_[std::size_t(b)].split_past = std::max(kBucket, 2 * (job.end - job.begin));
      depth_ = std::max(depth_, job.depth);
      continue;
    }
    // The median of the widest value among those that order (NaN last, to child 1).
    auto* first = order.data() + job.begin;
    auto* last = order.data() + job.end;
    auto* ordered_end =
        std::partition(first, last, [&](std::size_t r) { return !std::isnan(value(r, best)); });
    auto* mid = first + (ordered_end - first) / 2;
    std::nth_element(first, mid, ordered_end,
                     [&](std::size_t a, std::size_t b) { return value(a, best) < value(b, best); });
    double split = value(*mid, best);
    const double least = lower(job.node)[best];
    if (!(least < split)) {  // as many values as the lower half equal the least: the next value
      split = kInf;
      for (auto* p = first; p != ordered_end; ++p)
        if (value(*p, best) > least && value(*p, best) < split) split = value(*p, best);
    }
    auto* cut = std::partition(first, last, [&](std::size_t r) { return value(r, best) < split; });
    const std::size_t c = job.begin + std::size_t(cut - first);
    const int c0 = newNode();
    const int c1 = newNode();
    Node& node = nodes_[std::size_t(job.node)];
    node.dim = best;
    node.split = split;
    node.child[0] = c0;
    node.child[1] = c1;
    jobs.push_back({c0, job.begin, c, job.depth + 1});
    jobs.push_back({c1, c, job.end, job.depth + 1});
  }
  rebuild_depth_ = depth_;
}

// What a search collects. prune(bound): no point at that squared distance or farther can be
// collected; point(d, i): point i at squared distance d (NaN possible); kFilter: blocks whose
// four distances all exceed best() hold nothing to collect (a NaN exceeds nothing and is
// passed over).
struct PointTree::Nearest {
  static constexpr bool kFilter = true;
  double best = kInf;
  std::size_t best_i = PointTree::kNone;
  double filter() const { return best; }
  bool prune(double bound) const { return bound > best; }
  // Nearer, or as near with a lower index (nothing found yet: best infinite, and an infinite
  // distance is never taken).
  void point(double d, std::size_t i) {
    if (d < best || (d == best && best_i != PointTree::kNone && i < best_i)) best = d, best_i = i;
  }
};

// The k least (distance, index) pairs, a NaN distance as infinite: a max-heap in `out`.
struct PointTree::NearestK {
  static constexpr bool kFilter = false;
  std::size_t k;
  std::vector<Found>& out;
  double filter() const { return kInf; }
  bool prune(double bound) const { return out.size() == k && bound > out.front().first; }
  void point(double d, std::size_t i) { detail::offerNearestK(out, k, d, i); }
};

// The points whose distance (the square root, as OMPL compares it) is at most the radius. The
// square root is monotone and correctly rounded, so a box beyond the radius holds none.
struct PointTree::WithinRadius {
  static constexpr bool kFilter = false;
  double radius;
  std::vector<Found>& out;
  double filter() const { return kInf; }
  bool prune(double bound) const { return std::sqrt(bound) > radius; }
  void point(double d, std::size_t i) {
    if (std::sqrt(d) <= radius) out.emplace_back(d, i);
  }
};

// The squared distance from q to a node's box, summed value by value from the first as a
// point's distance is: for a point in the box each term is at most the point's own (the
// difference to the nearer face is at most the difference to the point, and rounding keeps that
// order), and so is each partial sum. Never NaN: a NaN in q orders with nothing and adds 0.
__attribute__((always_inline)) inline double PointTree::boxBound(int node, const double* q) const {
  const double* lo = lower(node);
  const double* hi = upper(node);
  double s = 0.0;
  for (unsigned d = 0; d < dim_; ++d) {
    double t = 0.0;
    if (q[d] < lo[d])
      t = lo[d] - q[d];
    else if (q[d] > hi[d])
      t = q[d] - hi[d];
    s += t * t;
  }
  return s;
}

template <bool kQuad, class Visitor>
__attribute__((always_inline)) inline void PointTree::scanBucket(const Bucket& b, const double* q,
                                                                 Visitor& v) const {
  const std::size_t blocks = (b.count + 3) / 4;
  const double* data = b.data.data();
  for (std::size_t k = 0; k < blocks; ++k, data += std::size_t(dim_) * 4) {
    const std::size_t* index = b.index.data() + 4 * k;
    const int lanes = static_cast<int>(std::min<std::size_t>(4, b.count - 4 * k));
    if constexpr (kQuad) {
      const detail::Quad dist = detail::blockQuad(data, q, dim_);
      if constexpr (Visitor::kFilter) {
        const auto near = dist <= v.filter();  // false for NaN
        if (!(near[0] | near[1] | near[2] | near[3])) continue;
      }
      for (int l = 0; l < lanes; ++l) v.point(dist[l], index[l]);
    } else {
      double dist[4];
      detail::blockScalar(data, q, dim_, dist);
      for (int l = 0; l < lanes; ++l) v.point(dist[l], index[l]);
    }
  }
}

template <bool kQuad, class Visitor>
__attribute__((always_inline)) inline void PointTree::search(const double* q, Visitor& v) const {
  if (size_ == 0 || nodes_.empty()) return;
  struct Entry {
    int node;
    double bound;
  };
  thread_local std::vector<Entry> stack;
  stack.clear();
  stack.push_back({0, boxBound(0, q)});
  while (!stack.empty()) {
    const Entry e = stack.back();
    stack.pop_back();
    if (v.prune(e.bound)) continue;
    const Node& node = nodes_[std::size_t(e.node)];
    if (node.dim < 0) {
      scanBucket<kQuad>(buckets_[std::size_t(node.bucket)], q, v);
      continue;
    }
    const int c0 = node.child[0], c1 = node.child[1];
    const double b0 = boxBound(c0, q), b1 = boxBound(c1, q);
    // The nearer child on top, so that it is searched first.
    const bool first0 = b0 <= b1;
    const int near = first0 ? c0 : c1, far = first0 ? c1 : c0;
    const double bn = first0 ? b0 : b1, bf = first0 ? b1 : b0;
    if (!v.prune(bf)) stack.push_back({far, bf});
    if (!v.prune(bn)) stack.push_back({near, bn});
  }
}

// Each search on each instruction set (the AVX2 one compiled for it).
#define DSS_POINT_TREE_PATHS(Name, Visitor)                                                \
  DSS_TARGET_AVX2 void PointTree::Name##Avx2(const double* q, Visitor& v) const {          \
    search<true>(q, v);                                                                    \
  }                                                                                        \
  void PointTree::Name##Sse2(const double* q, Visitor& v) const { search<true>(q, v); }    \
  void PointTree::Name##Scalar(const double* q, Visitor& v) const { search<false>(q, v); } \
  void PointTree::Name##On(const double* q, Visitor& v) const {                            \
    switch (path_) {                                                                       \
      case SimdPath::kAvx2:                                                                \
        return Name##Avx2(q, v);                                                           \
      case SimdPath::kSse2:                                                                \
        return Name##Sse2(q, v);                                                           \
      case SimdPath::kScalar:                                                              \
        break;                                                                             \
    }                                                                                      \
    Name##Scalar(q, v);                                                                    \
  }
DSS_POINT_TREE_PATHS(nearest, Nearest)
DSS_POINT_TREE_PATHS(nearestK, NearestK)
DSS_POINT_TREE_PATHS(withinRadius, WithinRadius)
#undef DSS_POINT_TREE_PATHS

std::size_t PointTree::nearest(const double* q) const {
  Nearest v;
  nearestOn(q, v);
  return v.best_i;
}

void PointTree::nearestK(const double* q, std::size_t k, std::vector<Found>& out) const {
  out.clear();
  if (k == 0) return;
  NearestK v{k, out};
  nearestKOn(q, v);
  std::sort_heap(out.begin(), out.end());
}

void PointTree::withinRadius(const double* q, double radius, std::vector<Found>& out) const {
  out.clear();
  WithinRadius v{radius, out};
  withinRadiusOn(q, v);
  std::sort(out.begin(), out.end());
}

}  // namespace dss
