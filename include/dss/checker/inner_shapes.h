// Inner balls and inner boxes: up to four balls and one box inside an element's shape. One
// that comes within the padding of an obstacle box proves the pair colliding without a narrow
// phase (the sweep's inner stage, for narrow phases that see the elements' own shapes). The box
// matters for flat and wide elements (a mobile base's bumper, a deck), whose balls are small.
#pragma once

#include <Eigen/Geometry>
#include <cmath>

#include "dss/checker/obb.h"
#include "dss/core/any_shape.h"

namespace dss {

namespace mesh {
struct TriangleMesh;
}

/// Up to `max_out` balls inside `shape` (centre in the shape frame, radius), along the longest
/// axis of its local box (box_c, box_h; element_bounds.h). The radius of a ball at c is the
/// distance from c to the shape's boundary (for a hull: to its facet planes), reduced by a
/// relative 1e-7 of the shape's size, far above the rounding of the planes; every ball kept is
/// checked against the support function in the facet normals and 26 fixed directions. Cones
/// and flat hulls get none. Returns the number written.
int innerBalls(const AnyShape& shape, const Eigen::Vector3d& box_c, const Eigen::Vector3d& box_h,
               Eigen::Vector4d* out, int max_out);

/// For each of the n points c[k] (shape frame), the radius of a ball about it inside `shape`:
/// the distance to the boundary (for a hull: to its facet planes) reduced by a relative 1e-7 of
/// the shape's size, each ball checked as innerBalls checks its own; 0 for a point outside or
/// on the boundary, and for cones and flat hulls. `tessellated`: a hull's tessellation
/// (mesh::tessellate) when the caller has it.
void innerRadii(const AnyShape& shape, const Eigen::Vector3d* c, int n, double* r,
                const mesh::TriangleMesh* tessellated = nullptr);

/// True when the ball (c, r) comes within `pad` of the box (rotation, centre, half extents),
/// with a relative margin against rounding: a safe "colliding". NaN anywhere gives false.
inline bool ballTouchesBox(const Eigen::Vector3d& c, double r, const Eigen::Matrix3d& R,
                           const Eigen::Vector3d& bc, const Eigen::Vector3d& h, double pad) {
  const Eigen::Vector3d t = c - bc;
  const Eigen::Vector3d p(R.col(0).dot(t), R.col(1).dot(t), R.col(2).dot(t));
  const double reach = r + pad - 1e-9 * (1.0 + t.cwiseAbs().sum() + h.sum() + r);
  if (!(reach > 0.0) || !(h.x() >= 0.0)) return false;
  const Eigen::Vector3d d = (p.cwiseAbs() - h).cwiseMax(0.0);
  return d.squaredNorm() < reach * reach;
}

/// A box inside `shape`, axis-aligned in the shape frame (centre, half extents): boxes are
/// themselves, cylinders and capsules get a square section, ellipsoids radii/sqrt(3), hulls the
/// local box (box_c, box_h) shrunk about its centre, axis by axis, until its corners lie
/// inside every facet plane. Shrunk by a relative 1e-7 of the shape's size; every corner is
/// checked against the support function as the balls are. False (no box) for spheres (their
/// ball is better), cones, flat hulls, and hulls whose box is thinner than 5 % of the local box.
bool innerBox(const AnyShape& shape, const Eigen::Vector3d& box_c, const Eigen::Vector3d& box_h,
              Eigen::Vector3d* c, Eigen::Vector3d* h);

/// True when the oriented boxes A (rotation, centre, half extents) and B come within `pad` of
/// each other: a safe "colliding". A grown by pad/sqrt(3) per axis stays within pad of A, and
/// two boxes that overlap on all 15 separating axes intersect; every axis must show an overlap
/// larger than a relative margin that covers rounding, and a cross axis of nearly parallel
/// edges (sine below 1e-12), which rounding cannot decide, is left out: for such edges the
/// face axes' margin covers it. NaN anywhere gives false.
inline bool boxesTouch(const Eigen::Matrix3d& Ra, const Eigen::Vector3d& ca,
                       const Eigen::Vector3d& ha_in, const Eigen::Matrix3d& Rb,
                       const Eigen::Vector3d& cb, const Eigen::Vector3d& hb, double pad) {
  const Eigen::Vector3d ha = ha_in.array() + pad * 0.57735026918962573;  // 1/sqrt(3), rounded down
  const Eigen::Vector3d t = Ra.transpose() * (cb - ca);
  const double margin = 1e-9 * (ha.sum() + hb.sum() + t.cwiseAbs().sum()) + 1e-300;
  Eigen::Matrix3d R, A;
  for (int j = 0; j < 3; ++j) {
    R.col(j) = Ra.transpose() * Rb.col(j);
    A.col(j) = R.col(j).cwiseAbs();
    if (!(std::abs(t.dot(R.col(j))) < ha.dot(A.col(j)) + hb[j] - margin)) return false;
  }
  for (int i = 0; i < 3; ++i)
    if (!(std::abs(t[i]) < ha[i] + hb.dot(A.row(i)) - margin)) return false;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      // The axis a_i x b_j has length sqrt(R(i1,j)^2 + R(i2,j)^2) (the sine of their angle).
      if (R(i1, j) * R(i1, j) + R(i2, j) * R(i2, j) < 1e-24) continue;
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double ra = ha[i1] * A(i2, j) + ha[i2] * A(i1, j);
      const double rb = hb[j1] * A(i, j2) + hb[j2] * A(i, j1);
      if (!(std::abs(t[i2] * R(i1, j) - t[i1] * R(i2, j)) < ra + rb - margin)) return false;
    }
  }
  return true;
}

/// The oriented-box stage and the inner-box stage of one element against one box obstacle in a
/// single pass, for an element whose local box and inner box share their centre (every shape
/// but a cone: innerBox shrinks about the local box's centre). The same answers as
/// obbApart(Ra, ca, h_outer, Rb, cb, hb_outer, pad) followed by
/// boxesTouch(Ra, ca, h_inner, Rb, cb, hb_inner, pad), with the relative position and rotation
/// computed once for both.
enum class BoxStage { kApart, kTouch, kUnknown };

namespace detail {
/// `column(j)`: column j of R = Ra^T Rb; t = Ra^T (cb - ca). See boxStages. One pass over the
/// 15 axes: the outer test (early exit on a separating axis), and the inner one while every
/// axis so far shows the overlap it needs.
template <class Column>
__attribute__((always_inline)) inline BoxStage boxStagesInA(
    const Eigen::Vector3d& t_in, const Eigen::Vector3d& ho, const Eigen::Vector3d& hbo,
    const Eigen::Vector3d& hi_in, const Eigen::Vector3d& hbi, double pad, Column&& column) {
  // In scalars, each sum in the order obbApartInA and boxesTouch form it (their Eigen dot
  // products and sums add the first two terms, then the third): a vector load of values just
  // stored one by one would wait for both stores.
  const double t[3] = {t_in[0], t_in[1], t_in[2]};
  const double at[3] = {std::abs(t[0]), std::abs(t[1]), std::abs(t[2])};
  const double tsum = (at[0] + at[1]) + at[2];
  const double margin_o =
      pad + 1e-9 * ((((ho[0] + ho[1]) + ho[2]) + ((hbo[0] + hbo[1]) + hbo[2])) + tsum) + 1e-12;
  const double hi[3] = {hi_in[0] + pad * 0.57735026918962573, hi_in[1] + pad * 0.57735026918962573,
                        hi_in[2] + pad * 0.57735026918962573};
  const double margin_i =
      1e-9 * ((((hi[0] + hi[1]) + hi[2]) + ((hbi[0] + hbi[1]) + hbi[2])) + tsum) + 1e-300;
  double R[3][3], A[3][3], Ao[3][3];  // R(i, j) = R[i][j]; A = |R|; Ao = |R| + 1e-12
  bool touch = true;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d col = column(j);
    for (int i = 0; i < 3; ++i) {
      R[i][j] = col[i];
      A[i][j] = std::abs(col[i]);
      Ao[i][j] = A[i][j] + 1e-12;
    }
    const double d = std::abs((t[0] * R[0][j] + t[1] * R[1][j]) + t[2] * R[2][j]);
    if (d > (((ho[0] * Ao[0][j] + ho[1] * Ao[1][j]) + ho[2] * Ao[2][j]) + hbo[j]) + margin_o)
      return BoxStage::kApart;
    touch =
        touch && d < (((hi[0] * A[0][j] + hi[1] * A[1][j]) + hi[2] * A[2][j]) + hbi[j]) - margin_i;
  }
  for (int i = 0; i < 3; ++i) {
    if (at[i] > (ho[i] + ((hbo[0] * Ao[i][0] + hbo[1] * Ao[i][1]) + hbo[2] * Ao[i][2])) + margin_o)
      return BoxStage::kApart;
    touch = touch &&
            at[i] < (hi[i] + ((hbi[0] * A[i][0] + hbi[1] * A[i][1]) + hbi[2] * A[i][2])) - margin_i;
  }
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double d = std::abs(t[i2] * R[i1][j] - t[i1] * R[i2][j]);
      const double rao = ho[i1] * Ao[i2][j] + ho[i2] * Ao[i1][j];
      const double rbo = hbo[j1] * Ao[i][j2] + hbo[j2] * Ao[i][j1];
      if (d > rao + rbo + margin_o) return BoxStage::kApart;
      if (!touch || R[i1][j] * R[i1][j] + R[i2][j] * R[i2][j] < 1e-24) continue;
      const double rai = hi[i1] * A[i2][j] + hi[i2] * A[i1][j];
      const double rbi = hbi[j1] * A[i][j2] + hbi[j2] * A[i][j1];
      touch = d < rai + rbi - margin_i;
    }
  }
  return touch ? BoxStage::kTouch : BoxStage::kUnknown;
}
}  // namespace detail

inline BoxStage boxStages(const Eigen::Matrix3d& Ra, const Eigen::Vector3d& ca,
                          const Eigen::Vector3d& h_outer, const Eigen::Vector3d& h_inner,
                          const Eigen::Matrix3d& Rb, const Eigen::Vector3d& cb,
                          const Eigen::Vector3d& hb_outer, const Eigen::Vector3d& hb_inner,
                          double pad) {
  return detail::boxStagesInA(Ra.transpose() * (cb - ca), h_outer, hb_outer, h_inner, hb_inner, pad,
                              [&](int j) { return Eigen::Vector3d(Ra.transpose() * Rb.col(j)); });
}

/// boxStages for an obstacle box whose rotation is exactly the identity.
inline BoxStage boxStagesAxisAligned(const Eigen::Matrix3d& Ra, const Eigen::Vector3d& ca,
                                     const Eigen::Vector3d& h_outer, const Eigen::Vector3d& h_inner,
                                     const Eigen::Vector3d& cb, const Eigen::Vector3d& hb_outer,
                                     const Eigen::Vector3d& hb_inner, double pad) {
  return detail::boxStagesInA(Ra.transpose() * (cb - ca), h_outer, hb_outer, h_inner, hb_inner, pad,
                              [&](int j) { return Eigen::Vector3d(Ra.row(j).transpose()); });
}

}  // namespace dss
