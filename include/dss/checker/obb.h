// The oriented-box stage of the sweep: a separating-axis test of two oriented boxes (each
// element's local box, each obstacle's) that proves a pair apart before the narrow phase.
#pragma once

#include <Eigen/Geometry>
#include <cmath>

namespace dss {

/// An oriented box in the world: rotation, centre, half extents.
struct Obb {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  Eigen::Vector3d h = Eigen::Vector3d::Zero();
  bool axis_aligned = false;  ///< R is exactly the identity (obbApartAxisAligned)
  /// The obstacle is the ball inscribed in this box (a sphere obstacle: centre c, radius
  /// h.x()); the sweep's ball stage (ball_stage.h) decides its pairs.
  bool ball = false;
};

namespace detail {
/// The 15-axis test of obbApart with B's axes in A's frame: column(j) gives column j of
/// R = Ra^T Rb, t is B's centre minus A's in A's frame.
template <class Column>
inline bool obbApartInA(const Eigen::Vector3d& t, const Eigen::Vector3d& ha,
                        const Eigen::Vector3d& hb, double pad, Column&& column) {
  const double margin = pad + 1e-9 * (ha.sum() + hb.sum() + t.cwiseAbs().sum()) + 1e-12;
  // B's axes first, each as soon as its column of R is known: in the sweep B is the obstacle
  // (walls, shelves, tables), whose face normals separate most pairs that get here.
  Eigen::Matrix3d R, A;
  for (int j = 0; j < 3; ++j) {
    R.col(j) = column(j);
    A.col(j) = R.col(j).cwiseAbs().array() + 1e-12;
    if (std::abs(t.dot(R.col(j))) > ha.dot(A.col(j)) + hb[j] + margin) return true;
  }
  for (int i = 0; i < 3; ++i)
    if (std::abs(t[i]) > ha[i] + hb.dot(A.row(i)) + margin) return true;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double ra = ha[i1] * A(i2, j) + ha[i2] * A(i1, j);
      const double rb = hb[j1] * A(i, j2) + hb[j2] * A(i, j1);
      if (std::abs(t[i2] * R(i1, j) - t[i1] * R(i2, j)) > ra + rb + margin) return true;
    }
  }
  return false;
}
}  // namespace detail

/// Separating-axis test of two oriented boxes: true when one of the 15 axes separates them by
/// more than `pad` plus a relative margin that covers the rounding of the test, so "true" is a
/// safe "disjoint (distance > pad)". NaN anywhere gives false.
inline bool obbApart(const Eigen::Matrix3d& Ra, const Eigen::Vector3d& ca,
                     const Eigen::Vector3d& ha, const Eigen::Matrix3d& Rb,
                     const Eigen::Vector3d& cb, const Eigen::Vector3d& hb, double pad) {
  return detail::obbApartInA(Ra.transpose() * (cb - ca), ha, hb, pad,
                             [&](int j) { return Eigen::Vector3d(Ra.transpose() * Rb.col(j)); });
}

/// The squared distance from p to the box b (0 inside), and in `error` a bound on its rounding
/// as a distance (a relative margin on the coordinates in b's frame).
inline double sqDistPointObb(const Eigen::Vector3d& p, const Obb& b, double* error) {
  const Eigen::Vector3d t = b.R.transpose() * (p - b.c);
  const Eigen::Vector3d at = t.cwiseAbs();
  *error = 1e-9 * (at.sum() + b.h.sum()) + 1e-12;
  return (at - b.h).cwiseMax(0.0).squaredNorm();
}

/// True when the ball (c, r) is proved farther than r from the box b, beyond the rounding of
/// the test; NaN anywhere gives false. Tighter than the ball against b's world AABB when b is
/// turned (a wall or a shelf at an angle).
inline bool ballApartObb(const Eigen::Vector3d& c, double r, const Obb& b) {
  double error;
  const double d2 = sqDistPointObb(c, b, &error);
  const double reach = r + error;
  return d2 > reach * reach;
}

/// obbApart for a box B whose rotation is exactly the identity (most obstacles: walls,
/// shelves, tables): R = Ra^T needs no product.
inline bool obbApartAxisAligned(const Eigen::Matrix3d& Ra, const Eigen::Vector3d& ca,
                                const Eigen::Vector3d& ha, const Eigen::Vector3d& cb,
                                const Eigen::Vector3d& hb, double pad) {
  return detail::obbApartInA(Ra.transpose() * (cb - ca), ha, hb, pad,
                             [&](int j) { return Eigen::Vector3d(Ra.row(j).transpose()); });
}

}  // namespace dss
