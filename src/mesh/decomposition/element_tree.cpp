// The element tree (see element_tree.h).
#include "element_tree.h"

#include <numeric>

namespace dss::mesh::decomposition {

ElementTree::ElementTree(const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& t) {
  const int n = static_cast<int>(t.size());
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0);
  corners_.resize(n);
  boxes_.resize(n);
  centres_.resize(n);
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      corners_[i][k] = v[t[i][k]];
      boxes_[i].add(corners_[i][k]);
    }
    centres_[i] = 0.5 * (boxes_[i].lo + boxes_[i].hi);
  }
  if (n > 0) build(0, n);
}

double ElementTree::nearest(const Vec3& p, Vec3* point) const {
  double best = kInf;
  Vec3 best_point = p;
  if (nodes_.empty()) return best;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (node.box.distanceSq(p) >= best) continue;
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        if (boxes_[order_[i]].distanceSq(p) >= best) continue;
        const auto& t = corners_[order_[i]];
        const Vec3 q = closestOnTriangle(p, t[0], t[1], t[2]);
        const double d = (q - p).squaredNorm();
        if (d < best) {
          best = d;
          best_point = q;
        }
      }
      continue;
    }
    // The nearer child is searched first (pushed last).
    const double dl = nodes_[node.left].box.distanceSq(p);
    const double dr = nodes_[node.right].box.distanceSq(p);
    if (dl < dr) {
      stack[top++] = node.right;
      stack[top++] = node.left;
    } else {
      stack[top++] = node.left;
      stack[top++] = node.right;
    }
  }
  if (point) *point = best_point;
  return std::sqrt(best);
}

int ElementTree::build(int first, int last) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Box box, centres;
  for (int i = first; i < last; ++i) {
    box.add(boxes_[order_[i]]);
    centres.add(centres_[order_[i]]);
  }
  nodes_[id].box = box;
  if (last - first <= 4) {
    nodes_[id].first = first;
    nodes_[id].count = last - first;
    return id;
  }
  int axis = 0;
  (centres.hi - centres.lo).maxCoeff(&axis);
  const int mid = (first + last) / 2;
  std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + last,
                   [&](int a, int b) {
                     const double ca = centres_[a][axis], cb = centres_[b][axis];
                     return ca < cb || (ca == cb && a < b);
                   });
  const int left = build(first, mid);
  const int right = build(mid, last);
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

}  // namespace dss::mesh::decomposition
