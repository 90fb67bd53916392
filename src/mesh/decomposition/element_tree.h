// An AABB tree over a mesh's elements (triangles, and lone vertices as repeated-index
// elements): the nearest point of the mesh, and the elements a box or a ray meets.
#pragma once

#include <array>
#include <utility>
#include <vector>

#include "geometry.h"

namespace dss::mesh::decomposition {

class ElementTree {
 public:
  ElementTree() = default;
  ElementTree(const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& t);

  /// Distance from p to the nearest element, and that element's nearest point.
  double nearest(const Vec3& p, Vec3* point = nullptr) const;

  /// Calls f(element) for every element whose bounding box, grown by `pad`, the ray p + t d
  /// (t >= 0) meets, until f returns false; returns false when stopped. The padding absorbs the
  /// rounding of the slab test, so no box the ray touches is skipped.
  template <class F>
  bool visitRay(const Vec3& p, const Vec3& d, double pad, F&& f) const {
    if (nodes_.empty()) return true;
    const Vec3 inv = d.cwiseInverse();
    auto meets = [&](const Box& b) {
      double t0 = 0.0, t1 = kInf;
      for (int k = 0; k < 3; ++k) {
        double a = (b.lo[k] - pad - p[k]) * inv[k], c = (b.hi[k] + pad - p[k]) * inv[k];
        if (a > c) std::swap(a, c);
        t0 = std::max(t0, a);
        t1 = std::min(t1, c);
      }
      return t0 <= t1;
    };
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (!meets(node.box)) continue;
      if (node.count > 0) {
        for (int i = node.first; i < node.first + node.count; ++i)
          if (meets(boxes_[order_[i]]) && !f(order_[i])) return false;
        continue;
      }
      stack[top++] = node.right;
      stack[top++] = node.left;
    }
    return true;
  }

  /// Calls f(element) for every element whose bounding box overlaps `box` until f returns
  /// false; returns false when stopped.
  template <class F>
  bool visit(const Box& box, F&& f) const {
    if (nodes_.empty()) return true;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (!node.box.overlaps(box)) continue;
      if (node.count > 0) {
        for (int i = node.first; i < node.first + node.count; ++i)
          if (boxes_[order_[i]].overlaps(box) && !f(order_[i])) return false;
        continue;
      }
      stack[top++] = node.right;
      stack[top++] = node.left;
    }
    return true;
  }

 private:
  struct Node {
    Box box;
    int first = 0, count = 0;  // a leaf when count > 0
    int left = -1, right = -1;
  };

  // Median split along the longest axis of the centres: depth stays near log2(n), far below
  // the query stack's 128 entries.
  int build(int first, int last);

  std::vector<std::array<Vec3, 3>> corners_;  // per element, in the mesh's order
  std::vector<int> order_;
  std::vector<Box> boxes_;
  std::vector<Vec3> centres_;
  std::vector<Node> nodes_;
};

}  // namespace dss::mesh::decomposition
