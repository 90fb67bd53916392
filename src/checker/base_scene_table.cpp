// BaseSceneTable: the cells of a planar base decided against the scene (see
// dss/checker/base_scene_table.h).
#include "dss/checker/base_scene_table.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "dss/checker/collision_model.h"
#include "dss/checker/inner_shapes.h"
#include "dss/checker/motion_bounds.h"
#include "dss/checker/obb.h"
#include "dss/robot/kinematics.h"

namespace dss {

namespace {

// Relative and absolute rounding margins on the move bound V.
constexpr double kRelMargin = 1e-9;
constexpr double kAbsMargin = 1e-9;

struct Tabled {
  int slot = -1;
  int link = -1;
  double reach = 0.0;  // from the theta axis
  double move = 0.0;   // V
};

}  // namespace

BaseSceneTable::BaseSceneTable(const CollisionModel& model, std::size_t max_cells, double padding)
    : padding_(padding) {
  if (max_cells == 0 || !(padding >= 0.0)) return;
  const RobotModel& robot = model.robot();
  std::vector<char> in_group(robot.numActiveJoints(), 0);
  for (int a : model.groupActive()) in_group[std::size_t(a)] = 1;
  // The first planar joint whose three values the group moves, each bounded (theta turns
  // freely: a planar joint's theta is continuous).
  int joints[3] = {-1, -1, -1};
  for (const MultiDofJoint& md : robot.multi_dof_joints) {
    if (md.type != MultiDofType::kPlanar || md.joints.size() != 3) continue;
    bool ok = true;
    for (int k = 0; k < 3; ++k) {
      const RobotJoint& j = robot.joints[std::size_t(md.joints[std::size_t(k)])];
      const bool slides = j.type == JointType::kPrismatic;
      ok = ok && j.active_index >= 0 && in_group[std::size_t(j.active_index)] &&
           (k < 2 ? slides && j.limits.has_position_limits && std::isfinite(j.limits.lower) &&
                        std::isfinite(j.limits.upper) && j.limits.lower <= j.limits.upper
                  : j.type == JointType::kContinuous);
    }
    if (!ok) continue;
    for (int k = 0; k < 3; ++k) joints[k] = md.joints[std::size_t(k)];
    break;
  }
  if (joints[0] < 0) return;
  for (int k = 0; k < 3; ++k) var_[k] = robot.joints[std::size_t(joints[k])].active_index;

  // The links moved by these three joints alone (with fixed joints in between) and checked
  // against the scene.
  std::vector<Tabled> tabled;
  const auto& slots = model.slots();
  for (std::size_t s = 0; s < slots.size() && int(tabled.size()) < kMaxLinks; ++s) {
    const CollisionModel::Slot& slot = slots[s];
    if (!slot.moves || slot.obstacles.empty() || slot.num_elements == 0) continue;
    const std::vector<ChainTerm> chain =
        chainAbove(robot, slot.link, -1, slot.center_L.norm() + slot.radius, model.held());
    if (chain.size() != 3) continue;
    bool only = true;
    double reach = 0.0;
    for (const ChainTerm& t : chain) {
      only = only && (t.joint == joints[0] || t.joint == joints[1] || t.joint == joints[2]) &&
             t.multiplier == 1.0 && !t.ball;
      if (t.joint == joints[2]) reach = t.reach;
    }
    if (!only || !std::isfinite(reach)) continue;
    tabled.push_back({int(s), slot.link, reach, 0.0});
  }
  if (tabled.empty()) return;

  // The plane: theta's axis n in the world, and the world moves of unit x and y (at theta 0).
  const Kinematics kin(robot, /*all_links=*/true);
  std::vector<double> q = model.held();
  for (int k = 0; k < 3; ++k) q[std::size_t(var_[k])] = 0.0;
  const int theta_link = robot.joints[std::size_t(joints[2])].child_link;
  std::vector<Eigen::Isometry3d> X = kin.linkPoses(q);
  const Eigen::Vector3d origin = X[std::size_t(theta_link)].translation();
  const Eigen::Vector3d n =
      X[std::size_t(theta_link)].linear() * robot.joints[std::size_t(joints[2])].axis;
  q[std::size_t(var_[0])] = 1.0;
  const Eigen::Vector3d ex = kin.linkPoses(q)[std::size_t(theta_link)].translation() - origin;
  q[std::size_t(var_[0])] = 0.0;
  q[std::size_t(var_[1])] = 1.0;
  const Eigen::Vector3d ey = kin.linkPoses(q)[std::size_t(theta_link)].translation() - origin;
  q[std::size_t(var_[1])] = 0.0;
  // A planar joint slides in its plane: refuse anything else (the moves must be parallel to it).
  if (!(std::abs(n.norm() - 1.0) < 1e-9 && std::abs(ex.norm() - 1.0) < 1e-9 &&
        std::abs(ey.norm() - 1.0) < 1e-9 && std::abs(ex.dot(n)) < 1e-9 &&
        std::abs(ey.dot(n)) < 1e-9))
    return;

  // Cells: the x-y cell's half-diagonal and the theta cell's turn at the largest reach move
  // the links by about the same amount; at most about max_cells of them.
  double lo[2], hi[2];
  for (int k = 0; k < 2; ++k) {
    const JointLimits& l = robot.joints[std::size_t(joints[k])].limits;
    lo[k] = l.lower, hi[k] = l.upper;
  }
  double reach = 0.0;
  for (const Tabled& t : tabled) reach = std::max(reach, t.reach);
  const double lx = std::max(hi[0] - lo[0], 1e-6), ly = std::max(hi[1] - lo[1], 1e-6);
  const double ct = kPi * std::sqrt(2.0) * std::max(reach, 1e-3);  // n_theta = ct / c
  const double c = std::cbrt(lx * ly * ct / double(max_cells));
  auto count = [](double v) { return int(std::min(std::max(std::ceil(v), 1.0), 65535.0)); };
  n_[0] = count(lx / c), n_[1] = count(ly / c), n_[2] = std::max(8, count(ct / c));
  if (double(n_[0]) * double(n_[1]) * double(n_[2]) > 4.0 * double(max_cells)) {
    n_[0] = n_[1] = n_[2] = 0;
    return;
  }
  lo_[0] = lo[0], lo_[1] = lo[1], lo_[2] = -kPi;
  const double width[3] = {(hi[0] - lo[0]) / n_[0], (hi[1] - lo[1]) / n_[1], 2.0 * kPi / n_[2]};
  for (int k = 0; k < 3; ++k) inv_width_[k] = width[k] > 0.0 ? 1.0 / width[k] : 0.0;
  // Half-widths with a margin for the rounding of the cell index.
  double h[3];
  for (int k = 0; k < 3; ++k)
    h[k] = 0.5 * width[k] * (1.0 + 1e-6) + 1e-12 * (1.0 + std::abs(lo_[k]) + width[k] * n_[k]);
  for (Tabled& t : tabled) {
    t.move =
        (std::sqrt(h[0] * h[0] + h[1] * h[1]) + h[2] * t.reach) * (1.0 + kRelMargin) + kAbsMargin;
    max_move_ = std::max(max_move_, t.move);
  }

  const auto& elements = model.elements();
  const auto& boxes = model.obstacleBoxes();
  const auto& obbs = model.obstacleObbs();
  const ClearanceGrid& grid = model.clearanceGrid();
  // Link k at pose XL apart from every obstacle beyond the padding at every pose of the cell.
  auto free = [&](const Tabled& t, const Eigen::Isometry3d& XL, const std::vector<int>& near) {
    const double move = t.move;
    const CollisionModel::Slot& slot = slots[std::size_t(t.slot)];
    // The link's sphere first: one lookup for all its elements.
    if (grid.clear(XL * slot.center_L, slot.radius + move + padding)) return true;
    for (int e = slot.first_element; e < slot.first_element + slot.num_elements; ++e) {
      const CollisionModel::Element& el = elements[std::size_t(e)];
      const Eigen::Vector3d ce = XL * el.center_L;
      const double r = el.radius + move + padding;
      if (grid.clear(ce, r)) continue;
      Eigen::Isometry3d XS = Eigen::Isometry3d::Identity();
      bool posed = false;
      for (int o : near) {
        if (detail::sqDistPointAabb(ce, boxes[std::size_t(o)]) > r * r) continue;
        const Obb& ob = obbs[std::size_t(o)];
        if (!ob.axis_aligned && ballApartObb(ce, r, ob)) continue;
        if (!posed) XS = XL * el.source->X_LS, posed = true;
        if (obbApart(XS.linear(), XS * el.box_center_S, el.box_half, ob.R, ob.c, ob.h,
                     padding + move))
          continue;
        return false;
      }
    }
    return true;
  };
  // The inner boxes shrunk by V along the plane's directions: by V sqrt(1 - (a.n)^2) along a
  // box axis a, the same at every theta (the turn is about n). An element is useful for the
  // colliding test when its shrunk box or one of its shrunk balls is left.
  std::vector<Eigen::Vector3d> inner_half(elements.size(), Eigen::Vector3d::Constant(-1.0));
  std::vector<char> useful(elements.size(), 0);
  for (const Tabled& t : tabled) {
    const CollisionModel::Slot& slot = slots[std::size_t(t.slot)];
    for (int e = slot.first_element; e < slot.first_element + slot.num_elements; ++e) {
      const CollisionModel::Element& el = elements[std::size_t(e)];
      const Eigen::Matrix3d R = (X[std::size_t(t.link)] * el.source->X_LS).linear();
      if (el.has_inner_box)
        for (int i = 0; i < 3; ++i) {
          const double an = R.col(i).dot(n);
          inner_half[std::size_t(e)][i] =
              el.inner_box_h[i] - t.move * std::sqrt(std::max(0.0, 1.0 - an * an + 1e-12));
        }
      bool balls = false;
      for (int b = 0; b < el.num_inner; ++b) balls = balls || el.inner_S[b].w() > t.move;
      useful[std::size_t(e)] = inner_half[std::size_t(e)].minCoeff() > 0.0 || balls;
    }
  }
  // Some element of link k within the padding of an obstacle at every pose of the cell.
  auto colliding = [&](const Tabled& t, const Eigen::Isometry3d& XL, const std::vector<int>& near) {
    const double move = t.move;
    const CollisionModel::Slot& slot = slots[std::size_t(t.slot)];
    for (int e = slot.first_element; e < slot.first_element + slot.num_elements; ++e) {
      const CollisionModel::Element& el = elements[std::size_t(e)];
      if (!useful[std::size_t(e)]) continue;
      const Eigen::Vector3d ce = XL * el.center_L;
      const double r = el.radius + padding;
      const Eigen::Isometry3d XS = XL * el.source->X_LS;
      const Eigen::Vector3d& hb = inner_half[std::size_t(e)];
      const bool box_ok = hb.minCoeff() > 0.0;
      for (int o : near) {
        const Eigen::Vector3d& half = model.obstacleBoxHalf(o);
        if (half.x() < 0.0 || detail::sqDistPointAabb(ce, boxes[std::size_t(o)]) > r * r) continue;
        const Obb& ob = obbs[std::size_t(o)];
        if (box_ok && boxesTouch(XS.linear(), XS * el.inner_box_c, hb, ob.R, ob.c, half, padding))
          return true;
        for (int b = 0; b < el.num_inner; ++b) {
          const double rb = el.inner_S[b].w() - move;
          if (rb > 0.0 && ballTouchesBox(XS * Eigen::Vector3d(el.inner_S[b].head<3>()), rb, ob.R,
                                         ob.c, half, padding))
            return true;
        }
      }
    }
    return false;
  };

  cells_.assign(std::size_t(n_[0]) * std::size_t(n_[1]) * std::size_t(n_[2]), 0);
  num_free_.assign(tabled.size(), 0);
  // The tabled links' poses at x = y = 0 for every theta cell's centre; a cell's poses are
  // those moved by x ex + y ey.
  std::vector<Eigen::Isometry3d> X0(std::size_t(n_[2]) * tabled.size());
  for (int it = 0; it < n_[2]; ++it) {
    q[std::size_t(var_[2])] = lo_[2] + (it + 0.5) * width[2];
    X = kin.linkPoses(q);
    for (std::size_t k = 0; k < tabled.size(); ++k)
      X0[std::size_t(it) * tabled.size() + k] = X[std::size_t(tabled[k].link)];
  }
  // Column by column (x, y), with the obstacles each link can reach from the column at any
  // theta: the link stays within its reach of the theta axis, and within V of the column's
  // centre.
  std::vector<std::vector<int>> near(tabled.size());
  for (int iy = 0; iy < n_[1]; ++iy) {
    const double y = lo_[1] + (iy + 0.5) * width[1];
    for (int ix = 0; ix < n_[0]; ++ix) {
      const double x = lo_[0] + (ix + 0.5) * width[0];
      const Eigen::Vector3d shift = x * ex + y * ey;
      for (std::size_t k = 0; k < tabled.size(); ++k) {
        near[k].clear();
        const double r = tabled[k].reach + tabled[k].move + padding;
        for (int o : slots[std::size_t(tabled[k].slot)].obstacles)
          if (detail::sqDistPointAabb(origin + shift, boxes[std::size_t(o)]) <= r * r)
            near[k].push_back(o);
      }
      for (int it = 0; it < n_[2]; ++it) {
        std::uint8_t cell = 0;
        for (std::size_t k = 0; k < tabled.size(); ++k) {
          Eigen::Isometry3d XL = X0[std::size_t(it) * tabled.size() + k];
          XL.translation() += shift;
          if (free(tabled[k], XL, near[k])) {
            cell |= std::uint8_t(1u << k);
          } else if (colliding(tabled[k], XL, near[k])) {
            cell = kColliding;
            break;
          }
        }
        cells_[(std::size_t(it) * std::size_t(n_[1]) + std::size_t(iy)) * std::size_t(n_[0]) +
               std::size_t(ix)] = cell;
        if (cell == kColliding) {
          ++num_colliding_;
        } else {
          for (std::size_t k = 0; k < tabled.size(); ++k) num_free_[k] += (cell >> k) & 1u;
        }
      }
    }
  }
  for (const Tabled& t : tabled) slots_.push_back(t.slot);
}

std::uint8_t BaseSceneTable::freeAlong(const double* qa, const double* qb, double scene_padding,
                                       int max_cells) const {
  if (cells_.empty() || !(scene_padding <= padding_)) return 0;
  // x and y: the cells between the ends' cells (the index is monotone in the value).
  int lo[3], hi[3];
  for (int k = 0; k < 2; ++k) {
    const int a = index(qa[var_[k]], k), b = index(qb[var_[k]], k);
    lo[k] = std::min(a, b), hi[k] = std::max(a, b);
  }
  // theta: the cells of [min, max] unwrapped (floor of the same monotone map), taken modulo
  // the turn; all of them when it spans a whole turn.
  const double ta = qa[var_[2]], tb = qb[var_[2]];
  const double t0 = std::min(ta, tb), t1 = std::max(ta, tb);
  if (!(t0 >= -1e5 && t1 <= 1e5)) return 0;  // (the kinematics' trig is exact within 1e5)
  const double f0 = std::floor((t0 - lo_[2]) * inv_width_[2]);
  const double f1 = std::floor((t1 - lo_[2]) * inv_width_[2]);
  const bool whole = f1 - f0 + 1.0 >= double(n_[2]);
  lo[2] = whole ? 0 : int(f0), hi[2] = whole ? n_[2] - 1 : int(f1);
  const double count =
      double(hi[0] - lo[0] + 1) * double(hi[1] - lo[1] + 1) * double(hi[2] - lo[2] + 1);
  if (count > double(max_cells)) return 0;
  std::uint8_t bits = 0x7f;
  for (int it = lo[2]; it <= hi[2]; ++it) {
    const int t = ((it % n_[2]) + n_[2]) % n_[2];
    for (int iy = lo[1]; iy <= hi[1]; ++iy)
      for (int ix = lo[0]; ix <= hi[0]; ++ix) {
        const std::uint8_t cell =
            cells_[(std::size_t(t) * std::size_t(n_[1]) + std::size_t(iy)) * std::size_t(n_[0]) +
                   std::size_t(ix)];
        if (cell == kColliding) return 0;
        bits &= cell;
      }
  }
  return bits;
}

}  // namespace dss
