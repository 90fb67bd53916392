// CollisionModel: moving links, pairs, reach balls and obstacle pruning (see the header).
#include "dss/planning/collision_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>

#include "dss/core/any_shape_query.h"
#include "dss/mesh/mesh.h"

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

// Up to Element::kMaxInner balls inside the shape (centre in the shape frame, radius), placed
// along the longest axis of its box (box_c, box_h). The radius of a ball at c is the distance
// from c to the shape's boundary: for a hull the smallest distance to its facet planes (qhull
// triangles, oriented outwards). It is then reduced by a relative 1e-7 of the shape's size,
// far above the rounding of the planes, and every kept ball is checked against the support
// function in the facet normals and 26 fixed directions.
int innerBalls(const AnyShape& shape, const Eigen::Vector3d& box_c, const Eigen::Vector3d& box_h,
               Eigen::Vector4d* out, int max_out) {
  std::vector<Eigen::Vector4d> planes;  // n, d with n.x <= d inside
  if (const auto* hull = std::get_if<ConvexHull>(&shape)) {
    const mesh::TriangleMesh m = mesh::tessellate(shape);
    if (m.triangles.empty()) return 0;  // flat or degenerate: no interior
    const Eigen::Vector3d centroid = hull->center();
    for (const auto& t : m.triangles) {
      const Eigen::Vector3d& a = m.vertices[t[0]];
      Eigen::Vector3d n = (m.vertices[t[1]] - a).cross(m.vertices[t[2]] - a);
      const double len = n.norm();
      if (!(len > 0.0)) continue;
      n /= len;
      if (n.dot(centroid - a) > 0.0) n = -n;
      planes.emplace_back(n.x(), n.y(), n.z(), n.dot(a));
    }
  }
  auto radius = [&](const Eigen::Vector3d& c) -> double {
    if (const auto* s = std::get_if<Sphere>(&shape)) return s->radius - c.norm();
    if (const auto* b = std::get_if<Box>(&shape)) return (b->half - c.cwiseAbs()).minCoeff();
    if (const auto* y = std::get_if<Cylinder>(&shape))
      return std::min(y->radius - c.head<2>().norm(), y->half_length - std::abs(c.z()));
    if (const auto* k = std::get_if<Capsule>(&shape))
      return k->radius - Eigen::Vector3d(c.x(), c.y(), std::max(0.0, std::abs(c.z()) - k->half_length)).norm();
    if (const auto* e = std::get_if<Ellipsoid>(&shape)) return e->radii.minCoeff() - c.norm();
    if (std::holds_alternative<ConvexHull>(shape)) {
      double r = std::numeric_limits<double>::infinity();
      for (const auto& p : planes) r = std::min(r, p.w() - p.head<3>().dot(c));
      return r;
    }
    return -1.0;  // cone: no inner balls
  };
  const double size = shapeMagnitude(shape) + box_c.norm();
  const double shrink = 1e-7 * size + 1e-12;
  int axis = 0;
  box_h.maxCoeff(&axis);
  std::vector<Eigen::Vector4d> cand;
  for (int i = -8; i <= 8; ++i) {
    Eigen::Vector3d c = box_c;
    c[axis] += 0.1 * i * box_h[axis];
    const double r = radius(c) - shrink;
    if (r > 0.05 * box_h.maxCoeff()) cand.emplace_back(c.x(), c.y(), c.z(), r);
  }
  std::sort(cand.begin(), cand.end(), [](const Eigen::Vector4d& a, const Eigen::Vector4d& b) { return a.w() > b.w(); });
  // Directions to check each ball against the support function: a ball inside the shape has
  // h(u) >= u.c + r for every unit u.
  std::vector<Eigen::Vector3d> dirs;
  for (const auto& p : planes) dirs.push_back(p.head<3>());
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) dirs.push_back(Eigen::Vector3d(x, y, z).normalized());
  int n = 0;
  for (const auto& b : cand) {
    if (n == max_out) break;
    bool spread = true;
    for (int k = 0; k < n; ++k)
      if ((out[k].head<3>() - b.head<3>()).norm() < 0.5 * std::max(out[k].w(), b.w())) spread = false;
    if (!spread) continue;
    bool inside = true;
    for (const auto& u : dirs) {
      const double h = std::visit([&](const auto& s) { return s.support(u, Eigen::Vector3d::Zero()).dot(u); }, shape);
      if (!(h >= u.dot(b.head<3>()) + b.w())) inside = false;
    }
    if (inside) out[n++] = b;
  }
  return n;
}

}  // namespace

CollisionModel::CollisionModel(std::shared_ptr<const RobotModel> robot, const Srdf* srdf, Scene scene,
                               std::vector<int> group_active, std::vector<double> held,
                               const CollisionModelOptions& options)
    : robot_(std::move(robot)), kin_(*robot_, /*all_links=*/false), sweep_kin_(*robot_, /*all_links=*/false),
      scene_(std::move(scene)),
      group_active_(std::move(group_active)), held_(std::move(held)) {
  const RobotModel& m = *robot_;
  if (held_.size() != m.numActiveJoints())
    throw std::invalid_argument("CollisionModel: held state has " + std::to_string(held_.size()) +
                                " values, robot " + m.name + " has " +
                                std::to_string(m.numActiveJoints()) + " active joints");
  if (group_active_.empty())
    for (std::size_t i = 0; i < m.numActiveJoints(); ++i) group_active_.push_back(int(i));
  in_group_.assign(m.numActiveJoints(), 0);
  for (int a : group_active_) in_group_.at(a) = 1;
  for (std::size_t a = 0; a < m.numActiveJoints(); ++a)
    if (!in_group_[a]) held_active_.push_back(int(a));

  // Which links move with the group (parents come before children in model order).
  moves_.assign(m.links.size(), 0);
  for (std::size_t l = 0; l < m.links.size(); ++l) {
    const RobotLink& link = m.links[l];
    if (link.parent_joint < 0) continue;
    const RobotJoint& j = m.joints[link.parent_joint];
    bool own = false;
    if (j.active_index >= 0) own = in_group_[j.active_index];
    else if (j.mimic_active >= 0) own = in_group_[j.mimic_active];
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
      e.identity_LS = ce.X_LS.matrix() == Eigen::Matrix4d::Identity();
      e.num_inner = innerBalls(ce.shape, e.box_center_S, e.box_half, e.inner_S, Element::kMaxInner);
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
  placeOnPoseLinks();

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
    self_pairs_.push_back({slot_of[a], slot_of[b], -1, slots_[slot_of[a]].radius + slots_[slot_of[b]].radius});
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
        const double d2 = detail::sqDistPointAabb(slots_[s].reach_center_W, boxes[o]);
        if (std::isfinite(r) && d2 > r * r) {
          // Pruned: the link never comes closer than this to the obstacle.
          pruned_gap_ = std::min(pruned_gap_, (std::sqrt(d2) - slots_[s].reach_radius) * (1.0 - 1e-9));
          continue;
        }
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
      obbs_.push_back(b);  // a box's: centre X_WO's translation, half extents grown by 1e-9
      const auto* box = std::get_if<Box>(&ob.shape);
      inner_half_.push_back(box ? box->half : Eigen::Vector3d::Constant(-1.0));
    }
  scene_.obstacles = std::move(kept);
  for (std::size_t s = 0; s < slots_.size(); ++s) {
    Slot& slot = slots_[s];
    for (int o : slot_obstacles[s]) slot.obstacles.push_back(new_index[o]);
    const std::size_t n = slot.obstacles.size();
    slot.box_stride = n + (n & 1);  // the sweep reads pairs
    const double inf = std::numeric_limits<double>::infinity();
    slot.box_soa.assign(6 * slot.box_stride, 0.0);
    for (std::size_t i = 0; i < slot.box_stride; ++i)
      for (int a = 0; a < 3; ++a) {
        // padding: an empty box (lower +inf, upper -inf) is infinitely far from every point
        slot.box_soa[a * slot.box_stride + i] = i < n ? boxes_[slot.obstacles[i]].lower[a] : inf;
        slot.box_soa[(3 + a) * slot.box_stride + i] = i < n ? boxes_[slot.obstacles[i]].upper[a] : -inf;
      }
    scene_pairs_ += n;
  }
  // The clearance grid covers the reach balls of the links checked against the scene.
  Aabb region;
  region.lower = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  region.upper = -region.lower;
  for (const Slot& slot : slots_)
    if (!slot.obstacles.empty() && std::isfinite(slot.reach_radius) && slot.reach_center_W.allFinite()) {
      const Eigen::Vector3d r = Eigen::Vector3d::Constant(slot.reach_radius);
      region.lower = region.lower.cwiseMin(slot.reach_center_W - r);
      region.upper = region.upper.cwiseMax(slot.reach_center_W + r);
    }
  grid_ = ClearanceGrid(region, boxes_);
  buildSelfTables(options);
  buildPairBlocks(options.pair_block_min_saving);
}

void CollisionModel::buildPairBlocks(double min_saving) {
  // Runs of consecutive pairs with the same slot a; a run with at least kMinBlock pairs outside
  // the tables (the tables skip most of theirs already) gets an anchor when one exists.
  constexpr int kMinBlock = 3;
  const RobotModel& m = *robot_;
  auto isAncestorOrSelf = [&](int anc, int link) {
    for (int l = link; l >= 0; l = m.links[l].parent_link)
      if (l == anc) return true;
    return false;
  };
  // A bound on the distance from the anchor's origin to any point of slot s's sphere with the
  // held joints at held() (the folded sweep, the only one that tests blocks), or a negative
  // value when a prismatic joint of the group lies between them.
  auto reach = [&](int anchor, int s) {
    double bound = slots_[s].center_L.norm() + slots_[s].radius;
    for (int l = slots_[s].link; l != anchor; l = m.links[l].parent_link) {
      const RobotJoint& j = m.joints[m.links[l].parent_joint];
      bound += j.X_PJ.translation().norm();
      if (j.type != JointType::kPrismatic) continue;
      const int lead = j.active_index >= 0 ? j.active_index : j.mimic_active;
      if (lead < 0 || in_group_[lead]) return -1.0;
      const double d = j.active_index >= 0 ? held_[lead] : j.mimic_multiplier * held_[lead] + j.mimic_offset;
      bound += std::abs(d) * j.axis.norm();
    }
    return bound;
  };
  pair_blocks_.clear();
  for (std::size_t i = 0; i < self_pairs_.size();) {
    std::size_t j = i;
    int untabled = 0;
    while (j < self_pairs_.size() && self_pairs_[j].a == self_pairs_[i].a) untabled += self_pairs_[j++].table < 0;
    PairBlock blk;
    blk.a = self_pairs_[i].a;
    blk.begin = static_cast<int>(i);
    blk.end = static_cast<int>(j);
    if (untabled >= kMinBlock) {
      // Of the pose links that are ancestors of every b slot, the one with the smallest ball.
      double best = std::numeric_limits<double>::infinity();
      for (const Slot& cand : slots_) {
        const int anchor = cand.pose_link;
        double radius = 0.0;
        for (std::size_t k = i; k < j && radius >= 0.0; ++k) {
          const int b = self_pairs_[k].b;
          const double r = isAncestorOrSelf(anchor, slots_[b].link) ? reach(anchor, b) : -1.0;
          radius = r < 0.0 ? -1.0 : std::max(radius, r);
        }
        if (radius >= 0.0 && radius < best) best = radius, blk.anchor = anchor;
      }
      if (blk.anchor >= 0) blk.radius = best + 1e-9 * (1.0 + best);
    }
    pair_blocks_.push_back(blk);
    i = j;
  }
  // A ball is kept only where it pays: on random states of the group (a fixed seed, the held
  // joints at held()) it must rule its block out often enough to save more per-pair sphere
  // tests than the one test it costs (a ball about a gripper whose links always overlap the
  // shared link's sphere would only add work).
  constexpr int kSamples = 256;
  std::mt19937_64 rng(1);
  std::vector<double> q = held_;
  std::vector<Eigen::Isometry3d> X(m.links.size(), Eigen::Isometry3d::Identity());
  std::vector<int> ruled_out(pair_blocks_.size(), 0);
  for (int k = 0; k < kSamples; ++k) {
    for (std::size_t a = 0; a < q.size(); ++a) {
      if (!in_group_[a]) continue;
      const RobotJoint& jt = m.joints[m.active_joints[a]];
      const bool bounded = jt.type != JointType::kContinuous && jt.limits.has_position_limits;
      const double lo = bounded ? jt.limits.lower : -3.141592653589793;
      const double hi = bounded ? jt.limits.upper : 3.141592653589793;
      q[a] = std::uniform_real_distribution<double>(lo, hi)(rng);
    }
    sweep_kin_.computeLinkPoses(q.data(), X.data());
    for (std::size_t b = 0; b < pair_blocks_.size(); ++b) {
      const PairBlock& blk = pair_blocks_[b];
      if (blk.anchor < 0) continue;
      const Slot& sa = slots_[blk.a];
      const double r = blk.radius + sa.radius;
      ruled_out[b] += (X[sa.pose_link] * sa.center_P - X[blk.anchor].translation()).squaredNorm() > r * r;
    }
  }
  std::vector<PairBlock> kept;
  for (std::size_t b = 0; b < pair_blocks_.size(); ++b) {
    PairBlock blk = pair_blocks_[b];
    const double saved = static_cast<double>(ruled_out[b]) / kSamples * (blk.end - blk.begin);
    if (blk.anchor >= 0 && saved < min_saving) blk.anchor = -1;
    if (blk.anchor < 0 && !kept.empty() && kept.back().anchor < 0 && kept.back().end == blk.begin)
      kept.back().end = blk.end;  // one run of pairs without a ball
    else
      kept.push_back(blk);
  }
  pair_blocks_ = std::move(kept);
}

void CollisionModel::placeOnPoseLinks() {
  const RobotModel& m = *robot_;
  // X_PL[l]: link l in the frame of its pose link pose_of[l], the joints in between at their
  // held values (parents come before children in model order).
  std::vector<int> pose_of(m.links.size(), -1);
  std::vector<Eigen::Isometry3d> X_PL(m.links.size(), Eigen::Isometry3d::Identity());
  for (std::size_t l = 0; l < m.links.size(); ++l) {
    const RobotLink& link = m.links[l];
    pose_of[l] = int(l);
    if (link.parent_joint < 0) continue;
    const RobotJoint& j = m.joints[link.parent_joint];
    const int lead = j.active_index >= 0 ? j.active_index : j.mimic_active;
    if (lead >= 0 && in_group_[lead]) continue;  // moves with the group: a pose link itself
    const double v = kin_.jointValue(held_.data(), link.parent_joint);
    Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
    if (j.type == JointType::kRevolute || j.type == JointType::kContinuous)
      motion.linear() = Eigen::AngleAxisd(v, j.axis).toRotationMatrix();
    else if (j.type == JointType::kPrismatic)
      motion.translation() = v * j.axis;
    if (!motion.matrix().allFinite()) continue;  // a held value that places nothing: keep the link
    pose_of[l] = pose_of[link.parent_link];
    X_PL[l] = X_PL[link.parent_link] * j.X_PJ * motion;
  }
  std::vector<char> wanted(m.links.size(), 0);
  wanted[m.root_link] = 1;
  for (Slot& s : slots_) {
    s.pose_link = pose_of[s.link];
    wanted[s.pose_link] = 1;
    const Eigen::Isometry3d& X = X_PL[s.link];
    s.center_P = X * s.center_L;
    for (int e = s.first_element; e < s.first_element + s.num_elements; ++e) {
      Element& el = elements_[e];
      el.X_PS = X * el.source->X_LS;
      el.identity_PS = el.X_PS.matrix() == Eigen::Matrix4d::Identity();
      el.center_P = X * el.center_L;
    }
  }
  sweep_kin_ = Kinematics(m, wanted);
}

double CollisionModel::prismaticTravel(const RobotJoint& j) const {
  const RobotModel& m = *robot_;
  const double inf = std::numeric_limits<double>::infinity();
  if (j.type != JointType::kPrismatic) return 0.0;
  double travel = 0.0;
  if (j.active_index >= 0) {
    travel = std::abs(held_[j.active_index]);
    travel = j.limits.has_position_limits ? std::max({travel, std::abs(j.limits.lower), std::abs(j.limits.upper)})
                                          : inf;
  }
  if (j.mimic_active >= 0) {
    const RobotJoint& lead = m.joints[m.active_joints[j.mimic_active]];
    const double lr = lead.limits.has_position_limits
                          ? std::max(std::abs(lead.limits.lower), std::abs(lead.limits.upper))
                          : inf;
    travel = std::max({travel, std::abs(j.mimic_multiplier) * lr + std::abs(j.mimic_offset),
                       std::abs(j.mimic_multiplier * held_[j.mimic_active] + j.mimic_offset)});
  }
  return travel;
}

void CollisionModel::buildSelfTables(const CollisionModelOptions& options) {
  const RobotModel& m = *robot_;
  if (options.self_table_cells_2d <= 0 && options.self_table_cells_1d <= 0) return;
  const double pi = 3.141592653589793;
  std::vector<Eigen::Isometry3d> X(m.links.size(), Eigen::Isometry3d::Identity());
  std::vector<double> q = held_;
  // Joints from a link up to (not including) the link `stop`.
  auto chainUp = [&](int link, int stop) {
    std::vector<int> out;
    for (int l = link; l != stop && m.links[l].parent_joint >= 0; l = m.links[l].parent_link)
      out.push_back(m.links[l].parent_joint);
    return out;
  };
  auto ancestors = [&](int link) {
    std::vector<int> out;
    for (int l = link; l >= 0; l = m.links[l].parent_link) out.push_back(l);
    return out;
  };
  for (SelfPair& pair : self_pairs_) {
    const Slot& sa = slots_[pair.a];
    const Slot& sb = slots_[pair.b];
    const std::vector<int> up_a = ancestors(sa.link), up_b = ancestors(sb.link);
    int common = -1;
    for (int l : up_a)
      if (std::find(up_b.begin(), up_b.end(), l) != up_b.end()) {
        common = l;
        break;
      }
    if (common < 0) continue;
    const std::vector<int> path_a = chainUp(sa.link, common), path_b = chainUp(sb.link, common);
    // Bounds on how far a point of B moves (relative to A) per unit change of each joint on
    // the path: the joint origin's distance to B's geometry, through the common ancestor.
    const double radius_b = sb.center_L.norm() + sb.radius;
    struct Term {
      int joint;
      double per_unit;  // displacement bound per unit of the joint value
    };
    std::vector<Term> terms;
    double below = radius_b;  // bound on |p - origin of the current frame|, p in B
    bool ok = true;
    for (int j : path_b) {
      const RobotJoint& J = m.joints[j];
      if (J.isMoving()) terms.push_back({j, J.type == JointType::kPrismatic ? 1.0 : below});
      below += J.X_PJ.translation().norm() + prismaticTravel(J);
    }
    // A-side joints: |joint origin - ancestor origin| + below (B's bound from the ancestor).
    std::vector<double> up_len(path_a.size() + 1, 0.0);
    for (int i = int(path_a.size()) - 1; i >= 0; --i) {
      const RobotJoint& J = m.joints[path_a[i]];
      up_len[i] = up_len[i + 1] + J.X_PJ.translation().norm() + prismaticTravel(J);
    }
    for (std::size_t i = 0; i < path_a.size(); ++i) {
      const RobotJoint& J = m.joints[path_a[i]];
      if (!J.isMoving()) continue;
      terms.push_back({path_a[i], J.type == JointType::kPrismatic
                                      ? 1.0
                                      : J.X_PJ.translation().norm() + up_len[i + 1] + below});
    }
    // Variables: the group joints the path joints read (mimic joints through their leader).
    // Joints outside the group keep their held value: the table records it and answers only
    // for states that have it.
    SelfPairTable t;
    double per_var[2] = {0.0, 0.0};
    for (const Term& term : terms) {
      const RobotJoint& J = m.joints[term.joint];
      int v = J.active_index;
      double mult = 1.0;
      if (v < 0) {
        v = J.mimic_active;
        mult = J.mimic_multiplier;
      }
      if (v < 0 || !std::isfinite(term.per_unit)) {
        ok = false;
        break;
      }
      if (!in_group_[v]) {
        int f = 0;
        while (f < t.num_fixed && t.fixed_var[f] != v) ++f;
        if (f == t.num_fixed) {
          if (t.num_fixed == SelfPairTable::kMaxFixed) {
            ok = false;
            break;
          }
          t.fixed_var[t.num_fixed] = v;
          t.fixed_value[t.num_fixed++] = held_[v];
        }
        continue;
      }
      int k = 0;
      while (k < t.num_vars && t.var[k] != v) ++k;
      if (k == t.num_vars) {
        if (t.num_vars == 2) {
          ok = false;
          break;
        }
        t.var[t.num_vars++] = v;
      }
      per_var[k] += std::abs(mult) * term.per_unit;
    }
    if (!ok || t.num_vars == 0) continue;
    const int n = t.num_vars == 1 ? options.self_table_cells_1d : options.self_table_cells_2d;
    if (n <= 0) continue;
    for (int k = 0; k < t.num_vars; ++k) {
      const RobotJoint& L = m.joints[m.active_joints[t.var[k]]];
      if (L.type == JointType::kContinuous ||
          (L.type == JointType::kRevolute && !L.limits.has_position_limits)) {
        t.wrap[k] = true;
        t.lo[k] = -pi;
        t.hi[k] = pi;
      } else if (L.limits.has_position_limits && L.limits.lower < L.limits.upper) {
        t.lo[k] = L.limits.lower;
        t.hi[k] = L.limits.upper;
      } else {
        ok = false;
      }
      t.cells[k] = n;
      t.inv_width[k] = double(n) / (t.hi[k] - t.lo[k]);
    }
    if (!ok) continue;
    t.padding = options.self_table_padding;
    table_padding_ = t.padding;
    t.free.assign(std::size_t(t.cells[0]) * std::size_t(t.cells[1]), 0);
    Options exact;
    exact.mode = Mode::kExact;
    // Certify the block [i0, i1) x [j0, j1) of cells; split it until its cells are decided.
    const double width[2] = {(t.hi[0] - t.lo[0]) / t.cells[0],
                             t.num_vars > 1 ? (t.hi[1] - t.lo[1]) / t.cells[1] : 0.0};
    auto certify = [&](auto&& self, int i0, int i1, int j0, int j1) -> void {
      double moved = 0.0;
      const int lo_idx[2] = {i0, j0}, hi_idx[2] = {i1, j1};
      for (int k = 0; k < t.num_vars; ++k) {
        const double a = t.lo[k] + lo_idx[k] * width[k];
        const double b = hi_idx[k] == t.cells[k] ? t.hi[k] : t.lo[k] + hi_idx[k] * width[k];
        q[t.var[k]] = 0.5 * (a + b);
        // Half-width, grown so that a value whose cell index rounds into this block is covered.
        const double half = 0.5 * (b - a) * (1.0 + 1e-6) + 1e-12 * (1.0 + std::abs(b) + std::abs(a));
        moved += per_var[k] * half;
      }
      kin_.computeLinkPoses(q.data(), X.data());
      const double pad = t.padding + moved * (1.0 + 1e-9) + 1e-12;
      auto mark = [&](unsigned char value) {
        for (int i = i0; i < i1; ++i)
          for (int j = j0; j < j1; ++j) t.free[std::size_t(i) * t.cells[1] + j] = value;
      };
      // Free: every element pair farther apart than pad.
      bool free = true;
      for (int ea = sa.first_element; ea < sa.first_element + sa.num_elements && free; ++ea)
        for (int eb = sb.first_element; eb < sb.first_element + sb.num_elements && free; ++eb) {
          const CollisionElement& A = *elements_[ea].source;
          const CollisionElement& B = *elements_[eb].source;
          free = !intersect(A.shape, X[sa.link] * A.X_LS, B.shape, X[sb.link] * B.X_LS, exact, pad,
                            Algorithm::kDss).intersect;
        }
      if (free) return mark(SelfPairTable::kFree);
      // Colliding: some element pair intersects under the six translations by sqrt(3) L (and
      // a 1e-9 margin for the rounding of the poses) along the axes, hence under any motion
      // within the cell. (At a self padding above the table's, colliding stays colliding.)
      const double reach = std::sqrt(3.0) * (moved * (1.0 + 1e-9) + 1e-9);
      for (int ea = sa.first_element; ea < sa.first_element + sa.num_elements; ++ea)
        for (int eb = sb.first_element; eb < sb.first_element + sb.num_elements; ++eb) {
          const CollisionElement& A = *elements_[ea].source;
          const CollisionElement& B = *elements_[eb].source;
          const Eigen::Isometry3d XA = X[sa.link] * A.X_LS;
          bool all = true;
          for (int axis = 0; axis < 6 && all; ++axis) {
            Eigen::Isometry3d XB = X[sb.link] * B.X_LS;
            XB.translation()[axis / 2] += (axis % 2 ? -reach : reach);
            all = intersect(A.shape, XA, B.shape, XB, exact, 0.0, Algorithm::kDss).intersect;
          }
          if (all) return mark(SelfPairTable::kColliding);
        }
      if (i1 - i0 <= 1 && j1 - j0 <= 1) return;
      const int im = i1 - i0 > 1 ? (i0 + i1) / 2 : i1;
      const int jm = j1 - j0 > 1 ? (j0 + j1) / 2 : j1;
      self(self, i0, im, j0, jm);
      if (jm < j1) self(self, i0, im, jm, j1);
      if (im < i1) {
        self(self, im, i1, j0, jm);
        if (jm < j1) self(self, im, i1, jm, j1);
      }
    };
    certify(certify, 0, t.cells[0], 0, t.cells[1]);
    q = held_;
    for (unsigned char c : t.free) {
      t.num_free += c == SelfPairTable::kFree;
      t.num_colliding += c == SelfPairTable::kColliding;
    }
    if (t.num_free == 0 && t.num_colliding == 0) continue;
    pair.table = int(self_tables_.size());
    self_tables_.push_back(std::move(t));
  }
  // Tables on the same grid next to each other, at most four per group, packed.
  std::vector<SelfPairTable> ordered;
  std::vector<int> new_index(self_tables_.size(), -1);
  for (std::size_t i = 0; i < self_tables_.size(); ++i) {
    if (new_index[i] >= 0) continue;
    TableGroup g;
    g.first = int(ordered.size());
    for (std::size_t j = i; j < self_tables_.size() && g.count < 4; ++j) {
      if (new_index[j] >= 0 || (j != i && !self_tables_[j].sameGrid(ordered[g.first]))) continue;
      new_index[j] = int(ordered.size());
      ordered.push_back(std::move(self_tables_[j]));
      ++g.count;
    }
    g.packed.assign(ordered[g.first].free.size(), 0);
    for (int k = 0; k < g.count; ++k) {
      const std::vector<unsigned char>& cells = ordered[g.first + k].free;
      for (std::size_t c = 0; c < cells.size(); ++c) g.packed[c] |= static_cast<std::uint8_t>(cells[c] << (2 * k));
    }
    table_groups_.push_back(std::move(g));
  }
  self_tables_ = std::move(ordered);
  for (SelfPair& pair : self_pairs_)
    if (pair.table >= 0) pair.table = new_index[pair.table];
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
  if (!self_tables_.empty()) {
    std::size_t cells = 0, free = 0, colliding = 0;
    for (const auto& t : self_tables_) cells += t.free.size(), free += t.num_free, colliding += t.num_colliding;
    os << ", " << self_tables_.size() << " self-pair tables (of " << cells << " cells " << free
       << " certified free, " << colliding << " colliding)";
  }
  return os.str();
}

}  // namespace dss
