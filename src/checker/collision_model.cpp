// CollisionModel: slots and elements, pose links, reach balls and pruning, self pairs and
// their tables and blocks (see the header).
#include "dss/checker/collision_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>

#if defined(__SSE2__)
#include <emmintrin.h>
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif
#endif

#include "dss/checker/element_bounds.h"
#include "dss/checker/element_shapes_cache.h"
#include "dss/checker/inner_shapes.h"
#include "dss/checker/motion_bounds.h"
#include "dss/checker/pose_links.h"
#include "dss/checker/self_pair_table_cache.h"
#include "dss/robot/multi_dof.h"
#include "group_sample.h"

namespace dss {

CollisionModel::CollisionModel(std::shared_ptr<const RobotModel> robot, const Srdf* srdf,
                               Scene scene, std::vector<int> group_active, std::vector<double> held,
                               const CollisionModelOptions& options)
    : robot_(std::move(robot)),
      kin_(*robot_, /*all_links=*/false),
      sweep_kin_(*robot_, /*all_links=*/false),
      scene_(std::move(scene)),
      group_active_(std::move(group_active)),
      held_(std::move(held)) {
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
  frozen_.assign(m.numActiveJoints(), 0);
  for (const MultiDofJoint& md : m.multi_dof_joints) {
    bool moved = false;
    for (int j : md.joints)
      for (int k = 0; k < m.joints[j].numVariables(); ++k)
        moved = moved || in_group_[m.joints[j].active_index + k];
    if (moved) continue;
    for (int j : md.joints)
      for (int k = 0; k < m.joints[j].numVariables(); ++k)
        frozen_[m.joints[j].active_index + k] = 1;
  }
  if (std::find(frozen_.begin(), frozen_.end(), 1) != frozen_.end()) {
    const RobotModel folded = foldedRobot();
    kin_ = Kinematics(folded, /*all_links=*/false);
    sweep_kin_ = kin_;
  }

  // Which links move with the group (parents come before children in model order).
  moves_.assign(m.links.size(), 0);
  for (std::size_t l = 0; l < m.links.size(); ++l) {
    const RobotLink& link = m.links[l];
    if (link.parent_joint < 0) continue;
    const RobotJoint& j = m.joints[link.parent_joint];
    const int lead = j.active_index >= 0 ? j.active_index : j.mimic_active;
    moves_[l] = moves_[link.parent_link] || (lead >= 0 && in_group_[lead]);
  }

  // Link poses at the held state: frames for the scene, pivots for the reach balls.
  const std::vector<Eigen::Isometry3d> X_WL = Kinematics(m, /*all_links=*/true).linkPoses(held_);
  FrameMap frames;
  for (std::size_t l = 0; l < m.links.size(); ++l)
    if (!moves_[l]) frames[m.links[l].name] = X_WL[l];
  resolveFrames(scene_, frames, /*require_all=*/true);

  buildBounds();
  buildSlots();
  computeReach(X_WL);
  placeOnPoseLinks();
  buildSelfPairs(srdf, options);
  const std::vector<Obb> untouchable = pruneObstacles(options);
  keepPayingChains(options.chain_min_settled, untouchable);
  buildSelfTables(options);
  pair_blocks_ = buildPairBlocks(*this, options.pair_block_min_saving);
  base_table_ = BaseSceneTable(*this, options.base_table_cells, options.base_table_padding);
  for (std::size_t i = 0; i < base_table_.slots().size(); ++i)
    slots_[std::size_t(base_table_.slots()[i])].base_bit = std::uint8_t(1u << i);
  std::vector<SlotSpheres::Sphere> own, folded;
  for (const Slot& s : slots_) {
    own.push_back({s.link, s.center_L, s.radius, !s.obstacles.empty()});
    folded.push_back({s.pose_link, s.center_P, s.radius, !s.obstacles.empty()});
  }
  slot_spheres_ = SlotSpheres(own, folded);
}

RobotModel CollisionModel::foldedRobot() const {
  RobotModel folded = *robot_;
  for (RobotJoint& j : folded.joints) {
    if (j.active_index < 0 || !frozen_[j.active_index]) continue;
    const Eigen::Isometry3d motion = jointMotion(j, held_.data() + j.active_index);
    // The identity stays exactly the identity (no rounding from the products).
    if (!motion.matrix().isIdentity(0.0)) j.X_PJ = j.X_PJ * motion;
    j.type = JointType::kFixed;
  }
  return folded;
}

bool CollisionModel::withinBounds(const double* q) const {
  // One pass without branches over the ranges (a frozen value's range is its held value
  // alone; a held value outside its joint's limits is accepted as itself), then the
  // quaternions.
  const double* const lo = range_lower_.data();
  const double* const hi = range_upper_.data();
  const double* const held = range_held_.data();
  const std::size_t n = range_lower_.size();
  std::size_t a = 0;
  bool in_range = true;
#if defined(__SSE2__)
  // Two values at a time (the comparisons are false for NaN, as the scalar ones).
  __m128d ok = _mm_castsi128_pd(_mm_set1_epi32(-1));
  for (; a + 2 <= n; a += 2) {
    const __m128d v = _mm_loadu_pd(q + a);
    const __m128d range =
        _mm_and_pd(_mm_cmpge_pd(v, _mm_loadu_pd(lo + a)), _mm_cmple_pd(v, _mm_loadu_pd(hi + a)));
    ok = _mm_and_pd(ok, _mm_or_pd(range, _mm_cmpeq_pd(v, _mm_loadu_pd(held + a))));
  }
  in_range = _mm_movemask_pd(ok) == 3;
#endif
  for (; a < n; ++a) in_range &= ((q[a] >= lo[a]) & (q[a] <= hi[a])) | (q[a] == held[a]);
  if (!in_range) return false;
  for (const int a : quaternions_)
    if (!quaternionNormValid(q[a], q[a + 1], q[a + 2], q[a + 3])) return false;
  return true;
}

#if defined(__x86_64__) || defined(__i386__)
namespace {
// boundedHeldLanes' ranges and held values in four-lane AVX2 vectors: the same comparisons
// (ordered, false for NaN); a joint outside the group (in_group[a] zero) also equal to held[a].
DSS_TARGET_AVX2 unsigned rangeLanesAvx2(const double* qs, const double* lower, const double* upper,
                                        const double* range_held, const double* held,
                                        const char* in_group, std::size_t n) {
  __m256d ok[2];
  ok[0] = ok[1] = _mm256_castsi256_pd(_mm256_set1_epi32(-1));
  for (std::size_t a = 0; a < n; ++a) {
    const __m256d lo = _mm256_set1_pd(lower[a]), hi = _mm256_set1_pd(upper[a]),
                  h = _mm256_set1_pd(range_held[a]);
    const bool match = !in_group[a];
    const __m256d hv = _mm256_set1_pd(held[a]);
    for (int p = 0; p < 2; ++p) {
      const __m256d v = _mm256_loadu_pd(qs + a * 8 + 4 * p);
      __m256d in = _mm256_or_pd(
          _mm256_and_pd(_mm256_cmp_pd(v, lo, _CMP_GE_OQ), _mm256_cmp_pd(v, hi, _CMP_LE_OQ)),
          _mm256_cmp_pd(v, h, _CMP_EQ_OQ));
      if (match) in = _mm256_and_pd(in, _mm256_cmp_pd(v, hv, _CMP_EQ_OQ));
      ok[p] = _mm256_and_pd(ok[p], in);
    }
  }
  return unsigned(_mm256_movemask_pd(ok[0])) | (unsigned(_mm256_movemask_pd(ok[1])) << 4);
}
}  // namespace
#endif

unsigned CollisionModel::boundedHeldLanes(const double* qs, SimdPath path) const {
  constexpr int kLanes = 8;
  const std::size_t n = range_lower_.size();
  unsigned bits = 0;
#if defined(__x86_64__) || defined(__i386__)
  if (path == SimdPath::kAvx2 && simdPathAvailable(SimdPath::kAvx2)) {
    bits = rangeLanesAvx2(qs, range_lower_.data(), range_upper_.data(), range_held_.data(),
                          held_.data(), in_group_.data(), n);
  } else
#endif
  {
    // Lanes by pairs, the same comparisons as withinBounds (false for NaN); a joint outside
    // the group also equal to its held value.
    __m128d ok[kLanes / 2];
    for (__m128d& o : ok) o = _mm_castsi128_pd(_mm_set1_epi32(-1));
    for (std::size_t a = 0; a < n; ++a) {
      const __m128d lo = _mm_set1_pd(range_lower_[a]), hi = _mm_set1_pd(range_upper_[a]),
                    h = _mm_set1_pd(range_held_[a]);
      const bool match = !in_group_[a];
      const __m128d held_value = _mm_set1_pd(held_[a]);
      for (int p = 0; p < kLanes / 2; ++p) {
        const __m128d v = _mm_loadu_pd(qs + a * kLanes + 2 * p);
        __m128d in =
            _mm_or_pd(_mm_and_pd(_mm_cmpge_pd(v, lo), _mm_cmple_pd(v, hi)), _mm_cmpeq_pd(v, h));
        if (match) in = _mm_and_pd(in, _mm_cmpeq_pd(v, held_value));
        ok[p] = _mm_and_pd(ok[p], in);
      }
    }
    for (int p = 0; p < kLanes / 2; ++p) bits |= unsigned(_mm_movemask_pd(ok[p])) << (2 * p);
  }
  if (quaternions_.empty()) return bits;
  // Quaternion norms per lane.
  double q[kLanes][4];
  for (int l = 0; l < kLanes; ++l) {
    if (!((bits >> l) & 1u)) continue;
    for (const int a : quaternions_) {
      for (int k = 0; k < 4; ++k) q[l][k] = qs[(std::size_t(a) + std::size_t(k)) * kLanes + l];
      if (!quaternionNormValid(q[l][0], q[l][1], q[l][2], q[l][3])) bits &= ~(1u << l);
    }
  }
  return bits;
}

void CollisionModel::buildBounds() {
  const RobotModel& m = *robot_;
  constexpr double kMax = std::numeric_limits<double>::max();
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  range_lower_.clear();
  range_upper_.clear();
  range_held_.clear();
  quaternions_.clear();
  for (std::size_t a = 0; a < m.numActiveJoints(); ++a) {
    const RobotJoint& j = m.joints[m.active_joints[a]];
    const bool limited = j.type != JointType::kContinuous && j.limits.has_position_limits;
    // Limits are finite when read from a file; an infinite one stays a test for finiteness.
    double lo = limited ? std::max(j.limits.lower, -kMax) : -kMax;
    double hi = limited ? std::min(j.limits.upper, kMax) : kMax;
    double held = kNone;
    if (frozen_[a]) {
      // The held value exactly, and finite (a non-finite one admits nothing).
      const bool finite = std::abs(held_[a]) <= kMax;
      lo = finite ? held_[a] : kMax;
      hi = finite ? held_[a] : -kMax;
    } else if (j.type == JointType::kBall && int(a) == j.active_index) {
      lo = -kMax;  // finite here; the norm is tested apart
      hi = kMax;
      quaternions_.push_back(int(a));
    } else if (limited && !in_group_[a] && std::isfinite(held_[a])) {
      held = held_[a];  // a joint outside the group may stay at its held value
    }
    range_lower_.push_back(lo);
    range_upper_.push_back(hi);
    range_held_.push_back(held);
  }
}

void CollisionModel::buildSlots() {
  const RobotModel& m = *robot_;
  // The elements' own bounds, computed once per robot (element_shapes_cache.h).
  shapes_ = cachedElementShapes(robot_);
  const std::shared_ptr<const std::vector<CachedElementShapes>>& shapes = shapes_;
  std::size_t next_shape = 0;
  for (std::size_t l = 0; l < m.links.size(); ++l) {
    const RobotLink& link = m.links[l];
    if (!link.hasGeometry()) {
      next_shape += link.collisions.size();
      continue;
    }
    Slot s;
    s.link = int(l);
    s.moves = moves_[l];
    s.first_element = int(elements_.size());
    s.num_elements = int(link.collisions.size());
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (const auto& ce : link.collisions) {
      element_shape_.push_back(int(next_shape));
      const ElementShapes& es = shapes->at(next_shape++);
      Element e;
      static_cast<ElementShapes&>(e) = es;
      e.link = int(l);
      e.slot = int(slots_.size());
      e.source = &ce;
      e.identity_LS = ce.X_LS.matrix() == Eigen::Matrix4d::Identity();
      if (const auto* ball = std::get_if<Sphere>(&ce.shape)) e.ball_radius = ball->radius;
      if (e.has_inner_box && e.inner_box_c != e.box_center_S)
        throw std::logic_error("CollisionModel: the inner box of link " + link.name +
                               " is not centred on its local box");
      lo = lo.cwiseMin(e.center_L - Eigen::Vector3d::Constant(e.radius));
      hi = hi.cwiseMax(e.center_L + Eigen::Vector3d::Constant(e.radius));
      elements_.push_back(e);
    }
    s.center_L = 0.5 * (lo + hi);
    for (int e = s.first_element; e < s.first_element + s.num_elements; ++e)
      s.radius =
          std::max(s.radius, (elements_[e].center_L - s.center_L).norm() + elements_[e].radius);
    addChain(s, &shapes->at(next_shape - link.collisions.size()));
    slots_.push_back(s);
  }
}

void CollisionModel::addChain(Slot& s, const CachedElementShapes* cached) {
  constexpr int kMaxChainElements = 64;  // one bit each in the sweep
  if (s.num_elements > kMaxChainElements) return;
  std::vector<ChainPoint> points;
  bool adds = false;  // a ball smaller than the slot's sphere, or an inner ball
  for (int e = s.first_element; e < s.first_element + s.num_elements; ++e) {
    const SphereChain& chain = cached[e - s.first_element].chain;
    for (int k = 0; k < chain.num_points; ++k) {
      ChainPoint p;
      p.c_L = elements_[e].source->X_LS * chain.center_S[k];
      p.outer = chain.outer[k];
      p.inner = chain.inner[k] > 0.0 ? chain.inner[k] : -std::numeric_limits<double>::infinity();
      p.element = e - s.first_element;
      adds = adds || p.inner > 0.0 || p.outer < s.radius * (1.0 - 1e-6);
      points.push_back(p);
    }
  }
  if (!adds) return;
  std::stable_sort(points.begin(), points.end(), [&](const ChainPoint& a, const ChainPoint& b) {
    return (a.c_L - s.center_L).squaredNorm() > (b.c_L - s.center_L).squaredNorm();
  });
  s.first_chain = int(chain_.size());
  s.num_chain = int(points.size());
  chain_.insert(chain_.end(), points.begin(), points.end());
}

void CollisionModel::keepPayingChains(double min_settled, const std::vector<Obb>& untouchable) {
  if (chain_.empty()) return;
  // The grid's upper bounds serve the inner balls: up to the largest one's radius plus room
  // for a small scene padding (a larger one only proves fewer collisions this way).
  auto cap = [&] {
    double inner = 0.0;
    for (const ChainPoint& p : chain_) inner = std::max(inner, p.inner);
    return inner > 0.0 ? inner + 0.05 : 0.0;
  };
  // On random states of the group (a fixed seed, the held joints at their values), a slot's
  // chain runs where the grid does not clear its sphere; it is kept where it settles the slot
  // often enough (CollisionModelOptions::chain_min_settled) for its lookups to cost less than
  // the stages it saves. Measured: the free flyer's beam and our mobile base's mast and arm
  // settle half or more and keep theirs; the Panda's links, whose stages are few and cheap,
  // settle 10-30 % and would only be slowed down. The upper bounds are computed for the points
  // alone: a scene where no chain pays builds none.
  if (min_settled > 0.0) {
    const RobotModel& m = *robot_;
    constexpr int kSamples = 256;
    const double upper_cap = cap();
    std::mt19937_64 rng(1);
    std::vector<double> q = held_;
    std::vector<Eigen::Isometry3d> X(m.links.size(), Eigen::Isometry3d::Identity());
    std::vector<int> reached(slots_.size(), 0), settled(slots_.size(), 0);
    for (int k = 0; k < kSamples; ++k) {
      detail::drawGroupState(*this, rng, q);
      kin_.computeLinkPoses(q.data(), X.data());
      for (std::size_t i = 0; i < slots_.size(); ++i) {
        const Slot& s = slots_[i];
        if (s.num_chain == 0 || s.obstacles.empty()) continue;
        const Eigen::Isometry3d& XL = X[s.link];
        if (grid_.clear(XL * s.center_L, s.radius)) continue;
        ++reached[i];
        bool clear = true, deep = false;
        for (int c = s.first_chain; c < s.first_chain + s.num_chain && !deep; ++c) {
          const ChainPoint& p = chain_[std::size_t(c)];
          const Eigen::Vector3d w = XL * p.c_L;
          clear = clear && grid_.clear(w, p.outer);
          if (p.inner > 0.0) {
            const std::uint8_t u = grid_.upperAt(w, untouchable, upper_cap);
            deep = u != ClearanceGrid::kUnknown && u * ClearanceGrid::kQuantum <= p.inner;
          }
        }
        settled[i] += deep || clear;
      }
    }
    std::vector<ChainPoint> kept;
    for (std::size_t i = 0; i < slots_.size(); ++i) {
      Slot& s = slots_[i];
      const bool pays =
          reached[i] > 0 && settled[i] >= min_settled * (1.0 + s.num_chain / 8.0) * reached[i];
      const int first = s.first_chain;
      s.first_chain = int(kept.size());
      if (!pays) {
        s.num_chain = 0;
        continue;
      }
      kept.insert(kept.end(), chain_.begin() + first, chain_.begin() + first + s.num_chain);
    }
    chain_ = std::move(kept);
  }
  if (!chain_.empty()) grid_.buildUpper(untouchable, cap());
}

void CollisionModel::placeOnPoseLinks() {
  const RobotModel& m = *robot_;
  const PoseLinks p = poseLinks(m, kin_, held_, in_group_);
  std::vector<char> wanted(m.links.size(), 0);
  wanted[m.root_link] = 1;
  for (Slot& s : slots_) {
    s.pose_link = p.pose_of[s.link];
    wanted[s.pose_link] = 1;
    const Eigen::Isometry3d& X = p.X_PL[s.link];
    s.center_P = X * s.center_L;
    for (int k = s.first_chain; k < s.first_chain + s.num_chain; ++k)
      chain_[std::size_t(k)].c_P = X * chain_[std::size_t(k)].c_L;
    for (int e = s.first_element; e < s.first_element + s.num_elements; ++e) {
      Element& el = elements_[e];
      el.X_PS = X * el.source->X_LS;
      el.identity_PS = el.X_PS.matrix() == Eigen::Matrix4d::Identity();
      el.center_P = X * el.center_L;
    }
  }
  sweep_kin_ = std::find(frozen_.begin(), frozen_.end(), 1) != frozen_.end()
                   ? Kinematics(foldedRobot(), wanted)
                   : Kinematics(m, wanted);
}

void CollisionModel::computeReach(const std::vector<Eigen::Isometry3d>& X_WL) {
  const RobotModel& m = *robot_;
  // The motion of a joint at the held state (mimic joints through their leader).
  auto heldMotion = [&](int ji) {
    const RobotJoint& j = m.joints[ji];
    const double v = kin_.jointValue(held_.data(), ji);
    return jointMotion(j, j.type == JointType::kBall ? held_.data() + j.active_index : &v);
  };
  for (Slot& s : slots_) {
    if (!s.moves) continue;
    std::vector<int> path;  // the joints from the root down to the link
    for (int l = s.link; m.links[l].parent_joint >= 0; l = m.links[l].parent_link)
      path.push_back(m.links[l].parent_joint);
    std::reverse(path.begin(), path.end());
    // Joints that the group does not move stay at their held values. Prismatic group joints at
    // the top of the path (a mobile base's x and y, a gantry) slide the rest of the chain
    // without turning it: the origin below them ranges over a box (taken at the middle of each
    // joint's range, its held value included). The first other group joint turns what is below
    // it about its origin (or slides it by its travel), within the chain reach of that joint.
    Eigen::Isometry3d X = X_WL[m.root_link];
    Eigen::Vector3d half = Eigen::Vector3d::Zero();
    std::size_t k = 0;
    for (; k < path.size(); ++k) {
      const RobotJoint& j = m.joints[path[k]];
      const int lead = j.active_index >= 0 ? j.active_index : j.mimic_active;
      if (lead < 0 || !in_group_[lead]) {
        X = X * j.X_PJ * heldMotion(path[k]);
        continue;
      }
      if (j.type != JointType::kPrismatic || j.active_index < 0 || !j.limits.has_position_limits)
        break;
      const double h = held_[j.active_index];
      const double lo = std::min(j.limits.lower, h), hi = std::max(j.limits.upper, h);
      if (!std::isfinite(lo) || !std::isfinite(hi)) break;
      X = X * j.X_PJ;
      half += (X.linear() * j.axis).cwiseAbs() * (0.5 * (hi - lo));
      X = X * Eigen::Translation3d(j.axis * (0.5 * (lo + hi)));
    }
    double r;
    if (k == path.size()) {  // only sliding joints above the link
      s.reach_center_W = X * s.center_L;
      r = s.radius;
    } else {
      const RobotJoint& j0 = m.joints[path[k]];
      s.reach_center_W = X * j0.X_PJ.translation();
      const std::vector<ChainTerm> chain =
          chainAbove(m, s.link, -1, s.center_L.norm() + s.radius, held_);
      r = std::numeric_limits<double>::infinity();
      for (const ChainTerm& t : chain)
        if (t.joint == path[k]) r = t.reach + prismaticTravel(m, j0, held_);
    }
    // Rounding: a relative and an absolute margin on both parts.
    s.reach_half_W = half * (1.0 + 1e-9) + Eigen::Vector3d::Constant(half.any() ? 1e-9 : 0.0);
    s.reach_radius = r * (1.0 + 1e-9) + 1e-9 + 1e-9 * s.reach_center_W.norm();
  }
}

void CollisionModel::buildSelfPairs(const Srdf* srdf, const CollisionModelOptions& options) {
  const RobotModel& m = *robot_;
  // The robot library's selection plus the scene's allowed link pairs.
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
    self_pairs_.push_back(
        {slot_of[a], slot_of[b], -1, slots_[slot_of[a]].radius + slots_[slot_of[b]].radius});
  }
}

std::vector<Obb> CollisionModel::pruneObstacles(const CollisionModelOptions& options) {
  const RobotModel& m = *robot_;
  obstacles_before_ = scene_.obstacles.size();
  std::vector<Aabb> boxes;
  for (const auto& o : scene_.obstacles) boxes.push_back(worldAabb(o));
  std::vector<char> keep(scene_.obstacles.size(), 0);
  std::vector<char> allowed_somewhere(scene_.obstacles.size(), 0);
  std::vector<std::vector<int>> slot_obstacles(slots_.size());
  for (std::size_t s = 0; s < slots_.size(); ++s) {
    if (!slots_[s].moves) continue;
    const std::string& lname = m.links[slots_[s].link].name;
    for (std::size_t o = 0; o < scene_.obstacles.size(); ++o) {
      if (scene_.allowed_collisions.allowed(lname, scene_.obstacles[o].object_id)) {
        allowed_somewhere[o] = 1;
        continue;
      }
      ++scene_pairs_before_;
      if (options.prune_obstacles) {
        const double r = slots_[s].reach_radius + options.prune_margin;
        // The distance from the box of centres to the obstacle's box.
        Aabb grown = boxes[o];
        grown.lower -= slots_[s].reach_half_W;
        grown.upper += slots_[s].reach_half_W;
        const double d2 = detail::sqDistPointAabb(slots_[s].reach_center_W, grown);
        if (std::isfinite(r) && d2 > r * r) {
          // Pruned: the link never comes closer than this to the obstacle.
          pruned_gap_ =
              std::min(pruned_gap_, (std::sqrt(d2) - slots_[s].reach_radius) * (1.0 - 1e-9));
          continue;
        }
      }
      keep[o] = 1;
      slot_obstacles[s].push_back(int(o));
    }
    // Nearest obstacles first (from the joint the link turns about): a colliding state is most
    // often caught by them, so the sweep stops early.
    const Eigen::Vector3d c = slots_[s].reach_center_W;
    if (c.allFinite()) {
      std::stable_sort(slot_obstacles[s].begin(), slot_obstacles[s].end(), [&](int a, int b) {
        return detail::sqDistPointAabb(c, boxes[a]) < detail::sqDistPointAabb(c, boxes[b]);
      });
    }
  }
  std::vector<int> new_index(scene_.obstacles.size(), -1);
  std::vector<Obstacle> kept;
  std::vector<Obb> untouchable;  // box obstacles no moving link may touch
  for (std::size_t o = 0; o < scene_.obstacles.size(); ++o) {
    if (!keep[o]) continue;
    new_index[o] = int(kept.size());
    kept.push_back(std::move(scene_.obstacles[o]));
    boxes_.push_back(boxes[o]);
    Obb b;
    const Obstacle& ob = kept.back();
    Eigen::Vector3d c_S;
    localBox(ob.shape, &c_S, &b.h);
    b.R = ob.X_WO.linear();
    b.axis_aligned = b.R == Eigen::Matrix3d::Identity();
    b.ball = std::holds_alternative<Sphere>(ob.shape);  // c_S = 0, h = (r, r, r)
    b.c = ob.X_WO * c_S;
    obbs_.push_back(b);
    const auto* box = std::get_if<Box>(&ob.shape);
    // The inner stage's box: a box obstacle itself, else the box inside a cylinder, capsule or
    // ellipsoid (inner_shapes.h; about the centre of its local box), else none (spheres have
    // the ball stage; hulls, which may come by the thousand from scene meshes, are left out).
    Eigen::Vector3d inner_c, inner_h = Eigen::Vector3d::Constant(-1.0);
    const bool round = std::holds_alternative<Cylinder>(ob.shape) ||
                       std::holds_alternative<Capsule>(ob.shape) ||
                       std::holds_alternative<Ellipsoid>(ob.shape);
    if (box)
      inner_h = box->half;
    else if (!round || !innerBox(ob.shape, c_S, b.h, &inner_c, &inner_h) || inner_c != c_S)
      inner_h = Eigen::Vector3d::Constant(-1.0);
    inner_half_.push_back(inner_h);
    if (box && !allowed_somewhere[o]) {
      Obb exact = b;
      exact.c = ob.X_WO.translation();
      exact.h = box->half;
      untouchable.push_back(exact);
    }
  }
  scene_.obstacles = std::move(kept);
  for (std::size_t s = 0; s < slots_.size(); ++s) {
    Slot& slot = slots_[s];
    std::vector<Aabb> slot_boxes;
    for (int o : slot_obstacles[s]) {
      slot.obstacles.push_back(new_index[o]);
      slot_boxes.push_back(boxes_[new_index[o]]);
    }
    slot.boxes = BoxSoa(slot_boxes);
    scene_pairs_ += slot.obstacles.size();
  }
  // The clearance grid covers the reach of the links checked against the scene.
  Aabb region;
  region.lower = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  region.upper = -region.lower;
  for (const Slot& slot : slots_)
    if (!slot.obstacles.empty() && std::isfinite(slot.reach_radius) &&
        slot.reach_center_W.allFinite()) {
      const Eigen::Vector3d r = Eigen::Vector3d::Constant(slot.reach_radius) + slot.reach_half_W;
      region.lower = region.lower.cwiseMin(slot.reach_center_W - r);
      region.upper = region.upper.cwiseMax(slot.reach_center_W + r);
    }
  grid_ = ClearanceGrid(region, boxes_, obbs_);
  // Candidate lists pay where many obstacles are kept (a mobile base among shelves): a link
  // sphere the grid cannot clear is then tested against the few obstacles near it only.
  constexpr std::size_t kMinCandidateObstacles = 16;
  constexpr std::size_t kMaxCandidateBytes = std::size_t(16) << 20;
  if (boxes_.size() >= kMinCandidateObstacles) {
    double radius = 0.0;
    for (const Slot& slot : slots_)
      if (!slot.obstacles.empty()) radius = std::max(radius, slot.radius);
    // Room for a small scene padding on top of the largest link sphere.
    grid_.buildCandidates(boxes_, radius + 0.01, kMaxCandidateBytes, obbs_);
  }
  if (const std::size_t words = grid_.candidateWords())
    for (Slot& slot : slots_) {
      if (slot.obstacles.empty()) continue;
      slot.obstacle_bits.assign(words, 0);
      for (int o : slot.obstacles) slot.obstacle_bits[o / 64] |= std::uint64_t(1) << (o % 64);
    }
  return untouchable;
}

void CollisionModel::buildSelfTables(const CollisionModelOptions& options) {
  if (options.self_table_cells_2d <= 0 && options.self_table_cells_1d <= 0) return;
  auto side = [&](int s) {
    SelfPairSide side;
    side.link = slots_[s].link;
    for (int e = slots_[s].first_element; e < slots_[s].first_element + slots_[s].num_elements; ++e)
      side.elements.push_back(elements_[e].source);
    side.radius = slots_[s].center_L.norm() + slots_[s].radius;
    return side;
  };
  std::vector<SelfPairTable> tables;
  for (SelfPair& pair : self_pairs_) {
    std::optional<SelfPairTable> t = cachedSelfPairTable(
        robot_, kin_, held_, in_group_, side(pair.a), side(pair.b), options.self_table_cells_1d,
        options.self_table_cells_2d, options.self_table_padding);
    if (!t) continue;
    pair.table = int(tables.size());
    tables.push_back(std::move(*t));
  }
  std::vector<int> new_index;
  self_tables_ = SelfPairTables(std::move(tables), options.self_table_padding, &new_index);
  for (SelfPair& pair : self_pairs_)
    if (pair.table >= 0) pair.table = new_index[pair.table];
}

std::size_t CollisionModel::pairsBehindBlockBalls() const {
  std::size_t n = 0;
  for (const PairBlock& b : pair_blocks_)
    n += b.anchor >= 0 ? static_cast<std::size_t>(b.end - b.begin) : 0;
  return n;
}

std::string CollisionModel::summary() const {
  std::ostringstream os;
  std::size_t moving = 0;
  for (const auto& s : slots_) moving += s.moves;
  os << "kept " << scene_.obstacles.size() << " of " << obstacles_before_ << " obstacles, "
     << scene_pairs_ << " of " << scene_pairs_before_ << " robot-scene link pairs, "
     << self_pairs_.size() << " of " << self_report_.all_pairs << " self link pairs (" << moving
     << " of " << slots_.size() << " links with geometry move)";
  // Decomposed meshes: their pieces are elements of their links.
  std::size_t pieces = 0, meshes = 0;
  for (const auto& e : elements_)
    if (e.source->piece >= 0) ++pieces, meshes += e.source->piece == 0;
  if (pieces > 0) os << ", " << meshes << " meshes as " << pieces << " convex pieces";
  std::size_t chained = 0;
  for (const auto& s : slots_) chained += s.num_chain > 0;
  if (chained > 0)
    os << ", sphere chains on " << chained << (chained == 1 ? " link (" : " links (")
       << chain_.size() << " points)";
  if (self_tables_.size() > 0) {
    std::size_t cells = 0, free = 0, colliding = 0;
    for (const auto& t : self_tables_.tables())
      cells += t.cell_state.size(), free += t.num_free, colliding += t.num_colliding;
    os << ", " << self_tables_.size() << " self-pair tables (of " << cells << " cells " << free
       << " certified free, " << colliding << " colliding)";
  }
  if (!base_table_.empty()) {
    os << ", base-scene table (" << base_table_.numCells() << " cells, "
       << base_table_.numColliding() << " colliding; free for";
    for (std::size_t i = 0; i < base_table_.slots().size(); ++i)
      os << (i ? ", " : " ")
         << robot_->links[std::size_t(slots_[std::size_t(base_table_.slots()[i])].link)].name
         << " in " << base_table_.numFree(int(i));
    os << ")";
  }
  return os.str();
}

}  // namespace dss
