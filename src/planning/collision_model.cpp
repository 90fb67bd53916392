// CollisionModel: moving links, pairs, reach balls and obstacle pruning (see the header).
#include "dss/planning/collision_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

namespace dss {

namespace {

// Bounding sphere of one element in its link frame.
void elementSphere(const CollisionElement& ce, Eigen::Vector3d* c, double* r) {
  if (const auto* hull = std::get_if<ConvexHull>(&ce.shape)) {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (const auto& p : hull->points()) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const Eigen::Vector3d m = 0.5 * (lo + hi);
    double rr = 0.0;
    for (const auto& p : hull->points()) rr = std::max(rr, (p - m).norm());
    *c = ce.X_LS * m;
    *r = rr * (1.0 + 1e-12) + 1e-12;
    return;
  }
  // Primitives are centred at their origin (the cone's magnitude is also about the origin).
  *c = ce.X_LS.translation();
  *r = shapeMagnitude(ce.shape) * (1.0 + 1e-12) + 1e-12;
}

// A box holding the shape, axis-aligned in its own frame: centre and half extents, grown by a
// relative 1e-9 so that rounding of the centre never cuts a point off.
void localBox(const AnyShape& shape, Eigen::Vector3d* c, Eigen::Vector3d* h) {
  *c = Eigen::Vector3d::Zero();
  if (const auto* s = std::get_if<Sphere>(&shape)) *h = Eigen::Vector3d::Constant(s->radius);
  else if (const auto* b = std::get_if<Box>(&shape)) *h = b->half;
  else if (const auto* k = std::get_if<Capsule>(&shape)) *h = Eigen::Vector3d(k->radius, k->radius, k->half_length + k->radius);
  else if (const auto* y = std::get_if<Cylinder>(&shape)) *h = Eigen::Vector3d(y->radius, y->radius, y->half_length);
  else if (const auto* n = std::get_if<Cone>(&shape)) *h = Eigen::Vector3d(n->radius, n->radius, n->half_length);
  else if (const auto* e = std::get_if<Ellipsoid>(&shape)) *h = e->radii;
  else {
    const auto& hull = std::get<ConvexHull>(shape);
    Eigen::Vector3d lo = hull.points()[0], hi = lo;
    for (const auto& p : hull.points()) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    *c = 0.5 * (lo + hi);
    *h = 0.5 * (hi - lo);
  }
  *h += Eigen::Vector3d::Constant(1e-9 * (1.0 + h->maxCoeff() + c->cwiseAbs().maxCoeff()));
}

}  // namespace

CollisionModel::CollisionModel(std::shared_ptr<const RobotModel> robot, const Srdf* srdf, Scene scene,
                               std::vector<int> group_active, std::vector<double> held,
                               const CollisionModelOptions& options)
    : robot_(std::move(robot)), kin_(*robot_, /*all_links=*/false), scene_(std::move(scene)),
      group_active_(std::move(group_active)), held_(std::move(held)) {
  const RobotModel& m = *robot_;
  if (held_.size() != m.numActiveJoints())
    throw std::invalid_argument("CollisionModel: held state has " + std::to_string(held_.size()) +
                                " values, robot " + m.name + " has " +
                                std::to_string(m.numActiveJoints()) + " active joints");
  if (group_active_.empty())
    for (std::size_t i = 0; i < m.numActiveJoints(); ++i) group_active_.push_back(int(i));
  std::vector<char> in_group(m.numActiveJoints(), 0);
  for (int a : group_active_) in_group.at(a) = 1;

  // Which links move with the group (parents come before children in model order).
  moves_.assign(m.links.size(), 0);
  for (std::size_t l = 0; l < m.links.size(); ++l) {
    const RobotLink& link = m.links[l];
    if (link.parent_joint < 0) continue;
    const RobotJoint& j = m.joints[link.parent_joint];
    bool own = false;
    if (j.active_index >= 0) own = in_group[j.active_index];
    else if (j.mimic_active >= 0) own = in_group[j.mimic_active];
    moves_[l] = moves_[link.parent_link] || own;
  }

  // Link poses at the held state: frames for the scene, pivots for the reach balls.
  const std::vector<Eigen::Isometry3d> X_WL = Kinematics(m, /*all_links=*/true).linkPoses(held_);
  FrameMap frames;
  for (std::size_t l = 0; l < m.links.size(); ++l)
    if (!moves_[l]) frames[m.links[l].name] = X_WL[l];
  resolveFrames(scene_, frames, /*require_all=*/true);
  bakeHullsToWorld(scene_);

  // Slots and elements.
  for (std::size_t l = 0; l < m.links.size(); ++l) {
    const RobotLink& link = m.links[l];
    if (!link.hasGeometry()) continue;
    Slot s;
    s.link = int(l);
    s.moves = moves_[l];
    s.first_element = int(elements_.size());
    s.num_elements = int(link.collisions.size());
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (const auto& ce : link.collisions) {
      Element e;
      e.link = int(l);
      e.slot = int(slots_.size());
      e.source = &ce;
      elementSphere(ce, &e.center_L, &e.radius);
      localBox(ce.shape, &e.box_center_S, &e.box_half);
      lo = lo.cwiseMin(e.center_L - Eigen::Vector3d::Constant(e.radius));
      hi = hi.cwiseMax(e.center_L + Eigen::Vector3d::Constant(e.radius));
      elements_.push_back(e);
    }
    s.center_L = 0.5 * (lo + hi);
    for (int e = s.first_element; e < s.first_element + s.num_elements; ++e)
      s.radius = std::max(s.radius, (elements_[e].center_L - s.center_L).norm() + elements_[e].radius);
    slots_.push_back(s);
  }
  computeReach(X_WL);

  // Self pairs: the robot library's selection plus the scene's allowed link pairs.
  std::vector<std::pair<std::string, std::string>> allowed;
  for (const auto& p : scene_.allowed_collisions.pairs())
    if (m.linkIndex(p.first) >= 0 && m.linkIndex(p.second) >= 0) allowed.push_back(p);
  for (const auto& name : scene_.allowed_collisions.alwaysAllowed())
    if (m.linkIndex(name) >= 0)
      for (const auto& link : m.links)
        if (link.name != name && link.hasGeometry()) allowed.emplace_back(name, link.name);
  self_report_ = selfCollisionPairs(m, srdf, allowed, options.exclude_rigid);
  std::vector<int> slot_of(m.links.size(), -1);
  for (std::size_t s = 0; s < slots_.size(); ++s) slot_of[slots_[s].link] = int(s);
  for (const auto& [a, b] : self_report_.pairs) {
    if (!moves_[a] && !moves_[b]) continue;  // their relative pose never changes
    if (slot_of[a] < 0 || slot_of[b] < 0) continue;
    self_pairs_.push_back({slot_of[a], slot_of[b]});
  }

  // Robot-scene pairs and pruning.
  obstacles_before_ = scene_.obstacles.size();
  std::vector<Aabb> boxes;
  for (const auto& o : scene_.obstacles) boxes.push_back(worldAabb(o));
  std::vector<char> keep(scene_.obstacles.size(), 0);
  std::vector<std::vector<int>> slot_obstacles(slots_.size());
  for (std::size_t s = 0; s < slots_.size(); ++s) {
    if (!slots_[s].moves) continue;
    const std::string& lname = m.links[slots_[s].link].name;
    for (std::size_t o = 0; o < scene_.obstacles.size(); ++o) {
      if (scene_.allowed_collisions.allowed(lname, scene_.obstacles[o].object_id)) continue;
      ++scene_pairs_before_;
      if (options.prune_obstacles) {
        const double r = slots_[s].reach_radius + options.prune_margin;
        if (std::isfinite(r) && detail::sqDistPointAabb(slots_[s].reach_center_W, boxes[o]) > r * r) continue;
      }
      keep[o] = 1;
      slot_obstacles[s].push_back(int(o));
    }
    // Nearest obstacles first (from the joint the link turns about): a colliding state is
    // most often caught by them, so the sweep stops early (VAMP sorts by distance too).
    const Eigen::Vector3d c = slots_[s].reach_center_W;
    if (c.allFinite()) {
      std::stable_sort(slot_obstacles[s].begin(), slot_obstacles[s].end(), [&](int a, int b) {
        return detail::sqDistPointAabb(c, boxes[a]) < detail::sqDistPointAabb(c, boxes[b]);
      });
    }
  }
  std::vector<int> new_index(scene_.obstacles.size(), -1);
  std::vector<Obstacle> kept;
  for (std::size_t o = 0; o < scene_.obstacles.size(); ++o)
    if (keep[o]) {
      new_index[o] = int(kept.size());
      kept.push_back(std::move(scene_.obstacles[o]));
      boxes_.push_back(boxes[o]);
      Obb b;
      const Obstacle& ob = kept.back();
      Eigen::Vector3d c_S;
      localBox(ob.shape, &c_S, &b.h);
      b.R = ob.X_WO.linear();
      b.c = ob.X_WO * c_S;
      obbs_.push_back(b);
    }
  scene_.obstacles = std::move(kept);
  for (std::size_t s = 0; s < slots_.size(); ++s) {
    for (int o : slot_obstacles[s]) slots_[s].obstacles.push_back(new_index[o]);
    scene_pairs_ += slots_[s].obstacles.size();
  }
}

void CollisionModel::computeReach(const std::vector<Eigen::Isometry3d>& X_WL) {
  const RobotModel& m = *robot_;
  const double inf = std::numeric_limits<double>::infinity();
  for (Slot& s : slots_) {
    if (!s.moves) continue;
    // Joints from the root down to the link.
    std::vector<int> chain;
    for (int l = s.link; m.links[l].parent_joint >= 0; l = m.links[l].parent_link)
      chain.push_back(m.links[l].parent_joint);
    std::reverse(chain.begin(), chain.end());
    // The first joint that moves with the group: its frame origin is fixed in the world
    // (revolute) or slides along its axis (prismatic: travel added below).
    std::size_t k = 0;
    for (; k < chain.size(); ++k) {
      const RobotJoint& j = m.joints[chain[k]];
      if (moves_[j.child_link]) break;
    }
    const RobotJoint& j0 = m.joints[chain[k]];
    s.reach_center_W = X_WL[j0.parent_link] * j0.X_PJ.translation();
    double r = 0.0;
    for (std::size_t i = k; i < chain.size(); ++i) {
      const RobotJoint& j = m.joints[chain[i]];
      if (i > k) r += j.X_PJ.translation().norm();
      if (j.type == JointType::kPrismatic) {
        double travel = 0.0;
        if (j.active_index >= 0) travel = std::abs(held_[j.active_index]);
        if (j.limits.has_position_limits) travel = std::max({travel, std::abs(j.limits.lower), std::abs(j.limits.upper)});
        else if (moves_[j.child_link]) travel = inf;
        // Mimic prismatic joints: the leader's range and held value through the multiplier.
        if (j.mimic_active >= 0) {
          const RobotJoint& lead = m.joints[m.active_joints[j.mimic_active]];
          const double lr = lead.limits.has_position_limits
                                ? std::max(std::abs(lead.limits.lower), std::abs(lead.limits.upper))
                                : inf;
          travel = std::max({travel, std::abs(j.mimic_multiplier) * lr + std::abs(j.mimic_offset),
                             std::abs(j.mimic_multiplier * held_[j.mimic_active] + j.mimic_offset)});
        }
        r += travel;
      }
    }
    r += s.center_L.norm() + s.radius;
    s.reach_radius = r * (1.0 + 1e-9) + 1e-9;
  }
}

std::string CollisionModel::summary() const {
  std::ostringstream os;
  std::size_t moving = 0;
  for (const auto& s : slots_) moving += s.moves;
  os << "kept " << scene_.obstacles.size() << " of " << obstacles_before_ << " obstacles, "
     << scene_pairs_ << " of " << scene_pairs_before_ << " robot-scene link pairs, "
     << self_pairs_.size() << " of " << self_report_.all_pairs << " self link pairs ("
     << moving << " of " << slots_.size() << " links with geometry move)";
  return os.str();
}

}  // namespace dss
