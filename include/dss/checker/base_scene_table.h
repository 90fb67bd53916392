// The base-scene table: decided cells of a planar base against the scene.
//
// The links that a planar joint carries with nothing else moving them (a mobile base's body,
// a mast fixed to it) have world poses that depend on the joint's x, y and theta alone. Their
// range (x and y within their bounds, theta over the whole turn) is cut into cells, and each
// cell is decided once, when the model is built, for every pose inside it. Within a cell no
// point of such a link moves more than V from its place at the cell's centre:
//   V = sqrt(hx^2 + hy^2) + h_theta R
// (hx, hy, h_theta: the cell's half-widths; R: the link's reach from the theta axis,
// motion_bounds.h), and every move is parallel to the joint's plane. The same bound holds for
// the inverse move (a point fixed in space seen from the link).
//  - Free (per link): every element's sphere, grown by V, is cleared by the clearance grid or
//    is apart from the obstacle's boxes, or the element's local box is apart from the
//    obstacle's oriented box by more than the padding + V (oriented-box test, obb.h).
//  - Colliding (the cell): an element's inner box (inner_shapes.h), shrunk by V along the
//    directions of the plane, comes within the padding of a box obstacle; every pose in the
//    cell holds that shrunk box inside the element's inner box, so the element touches the
//    obstacle. Inner balls likewise, shrunk by V.
// At query time a colliding cell answers the state before any kinematics, and a link certified
// free skips its robot-scene stages. The table never changes a state's answer, only its cost
// (a pair that would reach the iteration cap is the one exception: the table answers it
// correctly). In the continuous check it clears a link over a sub-motion whose cells are all
// free for it (freeAlong), which can only remove false alarms, never miss a collision.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dss {

class CollisionModel;

class BaseSceneTable {
 public:
  /// The cell's flag: every pose in it collides.
  static constexpr std::uint8_t kColliding = 0x80;
  /// At most this many links are tabled (bits 0..6 of a cell: tabled link i certified free).
  static constexpr int kMaxLinks = 7;

  BaseSceneTable() = default;
  /// Builds the table of `model` (its slots, obstacles, boxes and clearance grid must be
  /// built) with at most about `max_cells` cells, certified at scene padding `padding`. Empty
  /// when the model has no planar joint whose three values are all in the group and bounded,
  /// no link moved by that joint alone and checked against the scene, or max_cells == 0.
  BaseSceneTable(const CollisionModel& model, std::size_t max_cells, double padding);

  bool empty() const { return cells_.empty(); }
  /// The model slots tabled, in bit order.
  const std::vector<int>& slots() const { return slots_; }
  double padding() const { return padding_; }
  /// Cells along x, y and theta, and the largest move V of a tabled link within a cell.
  int cells(int axis) const { return n_[axis]; }
  double maxMove() const { return max_move_; }
  std::size_t numColliding() const { return num_colliding_; }
  std::size_t numCells() const { return cells_.size(); }
  /// Cells where tabled link i is certified free (not counting colliding cells).
  std::size_t numFree(int i) const { return num_free_[std::size_t(i)]; }

  /// The cell of state q (finite values, x and y within their bounds: a state within the
  /// model's bounds): kColliding, or the bits of the tabled links certified free there.
  std::uint8_t read(const double* q) const {
    const double x = q[var_[0]], y = q[var_[1]];
    double t = q[var_[2]];
    if (!(t >= -kPi && t < kPi)) t = std::remainder(t, 2.0 * kPi);
    const int ix = index(x, 0), iy = index(y, 1), it = index(t, 2);
    return cells_[(std::size_t(it) * std::size_t(n_[1]) + std::size_t(iy)) * std::size_t(n_[0]) +
                  std::size_t(ix)];
  }

  /// read(q) as a check at scene padding `scene_padding` may use it: kColliding when that
  /// padding is at least padding(), the free bits when it is at most padding(), else 0.
  std::uint8_t read(const double* q, double scene_padding) const {
    if (cells_.empty()) return 0;
    const std::uint8_t cell = read(q);
    if (cell == kColliding) return scene_padding >= padding_ ? cell : std::uint8_t(0);
    return scene_padding <= padding_ ? cell : std::uint8_t(0);
  }

  /// The bits of the tabled links certified free, at scene padding `scene_padding` (0 when it
  /// exceeds padding()), in every cell that the straight motion qa -> qb (states within the
  /// model's bounds; x, y and theta each moving linearly) can cross: those of the box of
  /// cells between its ends, when it has at most `max_cells` cells; 0 otherwise, or when a
  /// colliding cell is among them.
  std::uint8_t freeAlong(const double* qa, const double* qb, double scene_padding,
                         int max_cells = 64) const;

 private:
  static constexpr double kPi = 3.14159265358979323846;
  int index(double v, int axis) const {
    const double f = (v - lo_[axis]) * inv_width_[axis];
    // Values on the upper bound (and a hair outside it from rounding) go to the last cell.
    if (!(f >= 0.0)) return 0;
    const int i = f < double(n_[axis]) ? int(f) : n_[axis] - 1;
    return i;
  }

  int var_[3] = {0, 0, 0};  ///< active indices of x, y, theta
  double lo_[3] = {0, 0, 0}, inv_width_[3] = {1, 1, 1};
  int n_[3] = {0, 0, 0};
  std::vector<std::uint8_t> cells_;  ///< theta-major, then y, then x
  std::vector<int> slots_;
  std::vector<std::size_t> num_free_;
  std::size_t num_colliding_ = 0;
  double padding_ = 0.0;
  double max_move_ = 0.0;
};

}  // namespace dss
