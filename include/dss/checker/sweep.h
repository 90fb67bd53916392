// The sweep: every pair of a state that the model keeps, through the cheap stages first, and
// the narrow phase (a callback: DSS, FCL) only for the element pairs that survive them. It
// stops at the first collision.
//
// Robot vs scene, per moving slot: the clearance grid (one lookup proves the slot's sphere
// clear of every obstacle; all slots in one pass, slot_spheres.h); the obstacles the sphere reaches
// (the grid's candidate lists, or the sphere-box filter, two obstacle boxes at a time); each
// element's sphere against the box (slots of several elements); the ball stage (a sphere obstacle
// or a sphere element against a primitive: ball_stage.h), the oriented-box stage, the inner stage
// (a box or a ball inside the element within the padding of a box inside the obstacle proves a
// collision), the narrow phase. Self pairs, block by block: a block's ball (pair_blocks.h), the
// pair's table flag (self_pair_table.h), the slots' spheres, the elements' spheres, the
// oriented-box stage, the narrow phase. Every stage is conservative: it skips a pair only when the
// pair is proved apart (beyond the padding) and reports a collision only when one is proved.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "dss/checker/ball_stage.h"
#include "dss/checker/collision_model.h"
#include "dss/checker/inner_shapes.h"
#include "dss/checker/obb.h"
#include "dss/checker/slot_spheres.h"

namespace dss {

struct SweepOptions {
  double scene_padding = 0.0;  ///< a robot-scene pair collides at distance <= this
  double self_padding = 0.0;   ///< a self pair collides at distance <= this
  bool obb_stage = true;       ///< the oriented-box stage
  /// The inner stage (inner boxes and balls): only for a narrow phase that sees the elements' own
  /// shapes (hulls, not the meshes inside them). Self pairs never use it (their collisions are
  /// mostly decided by the tables).
  bool inner_shapes = false;
  /// The base-scene table's bits for the state (base_scene_table.h): a slot whose
  /// Slot::base_bit is set here is certified free of the scene and skips its stages.
  std::uint8_t base_free = 0;
};

/// Where the sweep takes a slot's pose from.
enum class SweepPoses {
  kOwnLinks,  ///< X_WL holds every slot's own link (CollisionModel::kinematics())
  kPoseLinks  ///< X_WL holds the pose links only (sweepKinematics()): the state's held
              ///< joints must be at held() (heldMatch())
};

/// Sweeps the pairs of one state: true at the first collision.
///   scene(element, X_WS, obstacle) -> bool collides
///   self(element_a, X_WA, element_b, X_WB) -> bool collides
/// `table_skip`: one flag per self-pair table (SelfPairTables::read for the state): a flagged
/// table's pair is certified free and skipped.
template <SweepPoses kPoses, class SceneNarrow, class SelfNarrow>
bool sweep(const CollisionModel& model, const Eigen::Isometry3d* X_WL,
           const unsigned char* table_skip, const SweepOptions& opt, SceneNarrow&& scene,
           SelfNarrow&& self);

/// The whole check of one state q (active joint values) with the link poses of
/// model.kinematics() in X_WL: the tables first, then the sweep. (Checkers do the same with the
/// pose links alone when heldMatch(q).)
template <class SceneNarrow, class SelfNarrow>
bool anyCollision(const CollisionModel& model, const double* q, const Eigen::Isometry3d* X_WL,
                  const SweepOptions& opt, SceneNarrow&& scene, SelfNarrow&& self) {
  thread_local std::vector<unsigned char> skip;
  if (skip.size() < model.selfTables().size()) skip.resize(model.selfTables().size());
  if (model.selfTables().read(q, model.heldMatch(q), opt.self_padding, skip.data())) return true;
  return sweep<SweepPoses::kOwnLinks>(model, X_WL, skip.data(), opt, scene, self);
}

namespace detail {
/// The pose of element e's shape given the pose X of its slot's pose link (kPoseLinks) or of its
/// own link: X itself when the shape frame is the identity there, else the product, written
/// into `scratch`.
template <SweepPoses kPoses>
const Eigen::Isometry3d& placedShape(const Eigen::Isometry3d& X, const CollisionModel::Element& e,
                                     Eigen::Isometry3d& scratch) {
  constexpr bool kFolded = kPoses == SweepPoses::kPoseLinks;
  if (kFolded ? e.identity_PS : e.identity_LS) return X;
  // The product of the two rigid transforms written out (inlined; Eigen's goes through a call
  // and multiplies the bottom rows too).
  const Eigen::Isometry3d& Y = kFolded ? e.X_PS : e.source->X_LS;
  scratch.linear().noalias() = X.linear() * Y.linear();
  scratch.translation().noalias() = X.linear() * Y.translation();
  scratch.translation() += X.translation();
  scratch.makeAffine();
  return scratch;
}
}  // namespace detail

template <SweepPoses kPoses, class SceneNarrow, class SelfNarrow>
bool sweep(const CollisionModel& model, const Eigen::Isometry3d* X_WL, const unsigned char* skip,
           const SweepOptions& opt, SceneNarrow&& scene, SelfNarrow&& self) {
  using Slot = CollisionModel::Slot;
  using Element = CollisionModel::Element;
  constexpr bool kFolded = kPoses == SweepPoses::kPoseLinks;
  auto linkOf = [](const Slot& s) { return kFolded ? s.pose_link : s.link; };
  auto elementCenter = [](const Element& e) -> const Eigen::Vector3d& {
    return kFolded ? e.center_P : e.center_L;
  };
  const double scene_padding = opt.scene_padding, self_padding = opt.self_padding;
  const std::vector<Element>& elements = model.elements();
  const std::vector<Aabb>& boxes = model.obstacleBoxes();
  const std::vector<Obb>& obbs = model.obstacleObbs();
  const std::vector<Obstacle>& obstacles = model.scene().obstacles;
  const ClearanceGrid& grid = model.clearanceGrid();
  // World centres of the slot spheres and the grid's verdicts, all slots in one pass before
  // any stage (slot_spheres.h); the self pairs use the centres too (per-thread scratch, no
  // allocation after the first call with a model this size). The scratch vectors are read
  // once: inside the loops the compiler would reload them after every store.
  thread_local std::vector<Eigen::Vector3d> center_store, element_store;
  thread_local std::vector<std::uint64_t> clear_store;
  const SlotSpheres& spheres = model.slotSpheres();
  const std::size_t words = spheres.words();
  if (center_store.size() < spheres.centersWritten()) center_store.resize(spheres.centersWritten());
  if (clear_store.size() < words) clear_store.resize(words);
  Eigen::Vector3d* const centers = center_store.data();
  std::uint64_t* const clear = clear_store.data();
  spheres.place(kFolded, X_WL, grid, scene_padding, centers, clear);
  const std::uint64_t* const tested = spheres.scene();
  const Slot* const slots = model.slots().data();
  using ChainPoint = CollisionModel::ChainPoint;
  const ChainPoint* const chain = model.chainPoints().data();
  // Robot vs scene: the slots checked against the scene that the grid does not clear, from
  // the last to the first. Links are numbered depth first from the root, so in this order a
  // link comes before its ancestors: the links far along a chain, which sweep the most space,
  // meet the scene most often, and a colliding state ends sooner. The order changes no verdict.
  for (std::size_t w = words; w-- > 0;)
    for (std::uint64_t open_slots = tested[w] & ~clear[w]; open_slots;) {
      const int top = 63 - __builtin_clzll(open_slots);
      open_slots ^= std::uint64_t(1) << top;
      const std::size_t k = w * 64 + static_cast<std::size_t>(top);
      const Slot& s = slots[k];
      if (s.base_bit & opt.base_free) continue;
      const Eigen::Isometry3d& X = X_WL[linkOf(s)];
      const std::size_t nb = s.obstacles.size();
      const Eigen::Vector3d& c = centers[k];
      const double r = s.radius + scene_padding;
      // The chains of balls along the elements (sphere_chain.h): an element whose outer balls
      // the grid clears is clear; an inner ball within the padding of an obstacle (the grid's
      // upper bound, for narrow phases that see the elements' own shapes) is a collision.
      std::uint64_t open = ~std::uint64_t(0);  // the elements left to test, one bit each
      if (s.num_chain > 0) {
        open = 0;
        const double deep_padding =
            opt.inner_shapes ? scene_padding : -std::numeric_limits<double>::infinity();
        const ClearanceGrid::Frame frame = grid.frame(X);
        const ChainPoint* const first = chain + s.first_chain;
        for (const ChainPoint* p = first; p != first + s.num_chain; ++p) {
          const std::uint16_t v = grid.cell(frame, kFolded ? p->c_P : p->c_L);
          // The farthest points first: a collision found there ends the state.
          const double lower = (v & 0xff) * ClearanceGrid::kQuantum;
          const double upper = (v >> 8) * ClearanceGrid::kQuantum;
          if (((v >> 8) != ClearanceGrid::kUnknown) & (upper <= p->inner + deep_padding))
            return true;
          open |= std::uint64_t(!(lower > p->outer + scene_padding)) << p->element;
        }
        if (!open) continue;
      }
      // Element e against obstacle o, whose box the element's sphere reaches: the stages.
      auto pair = [&](int e, int o) {
        const Element& el = elements[e];
        Eigen::Isometry3d X_prod;
        const Eigen::Isometry3d& X_WS = detail::placedShape<kPoses>(X, el, X_prod);
        const Eigen::Vector3d& half = model.obstacleBoxHalf(o);  // x < 0: no box inside it
        const bool inner =
            opt.inner_shapes && (el.has_inner_box || el.num_inner > 0) && half.x() >= 0.0;
        if (opt.obb_stage) {
          // The ball stage: a sphere obstacle against the element, or a sphere element against
          // the obstacle, decided by a distance in closed form where the other is a primitive.
          BoxStage v = BoxStage::kUnknown;
          if (const Obb& ob = obbs[o]; ob.ball)
            v = ballStage(el.source->shape, X_WS, ob.c, ob.h.x(), scene_padding);
          else if (el.ball_radius >= 0.0)
            v = ballStage(obstacles[o].shape, obstacles[o].X_WO, X_WS.translation(), el.ball_radius,
                          scene_padding);
          if (v == BoxStage::kApart) return false;
          if (v == BoxStage::kTouch && opt.inner_shapes) return true;
        }
        bool box_tested = false;  // the inner box, with the oriented boxes (boxStages)
        if (opt.obb_stage) {
          const Obb& ob = obbs[o];
          const Eigen::Vector3d box_c = X_WS * el.box_center_S;
          if (inner && el.has_inner_box) {
            const BoxStage v =
                ob.axis_aligned
                    ? boxStagesAxisAligned(X_WS.linear(), box_c, el.box_half, el.inner_box_h, ob.c,
                                           ob.h, half, scene_padding)
                    : boxStages(X_WS.linear(), box_c, el.box_half, el.inner_box_h, ob.R, ob.c, ob.h,
                                half, scene_padding);
            if (v == BoxStage::kApart) return false;
            if (v == BoxStage::kTouch) return true;
            box_tested = true;
          } else if (ob.axis_aligned ? obbApartAxisAligned(X_WS.linear(), box_c, el.box_half, ob.c,
                                                           ob.h, scene_padding)
                                     : obbApart(X_WS.linear(), box_c, el.box_half, ob.R, ob.c, ob.h,
                                                scene_padding)) {
            return false;
          }
        }
        if (inner) {
          const Obb& ob = obbs[o];
          if (el.has_inner_box && !box_tested &&
              boxesTouch(X_WS.linear(), X_WS * el.inner_box_c, el.inner_box_h, ob.R, ob.c, half,
                         scene_padding))
            return true;
          for (int b = 0; b < el.num_inner; ++b)
            if (ballTouchesBox(X_WS * el.inner_S[b].head<3>(), el.inner_S[b].w(), ob.R, ob.c, half,
                               scene_padding))
              return true;
        }
        return scene(e, X_WS, o);
      };
      // Whether the sphere (cc, rr), which reaches obstacle o's world box, also reaches its
      // oriented box: a turned obstacle (a wall at an angle) fills little of its world box; a
      // sphere obstacle only its own ball (with a relative margin against rounding).
      auto reachesObb = [&](const Eigen::Vector3d& cc, double rr, int o) {
        const Obb& ob = obbs[o];
        if (ob.ball) {
          const double reach = (rr + ob.h.x()) * (1.0 + 1e-12) + 1e-300;
          return !((cc - ob.c).squaredNorm() > reach * reach);
        }
        return ob.axis_aligned || !ballApartObb(cc, rr, ob);
      };
      // The obstacles whose boxes the sphere (cc, rr) reaches, each through `visit` (true: a
      // collision): the grid's candidates for the sphere's voxel (obstacles it can reach from
      // there), else every obstacle of the slot, two boxes at a time.
      auto reached = [&](const Eigen::Vector3d& cc, double rr, auto&& visit) {
        if (const std::uint64_t* cand =
                s.obstacle_bits.empty() ? nullptr : grid.candidates(cc, rr)) {
          const std::size_t words = s.obstacle_bits.size();
          for (std::size_t w = 0; w < words; ++w)
            for (std::uint64_t bits = cand[w] & s.obstacle_bits[w]; bits; bits &= bits - 1) {
              const int o =
                  static_cast<int>(w * 64 + static_cast<std::size_t>(__builtin_ctzll(bits)));
              if (detail::sqDistPointAabb(cc, boxes[o]) > rr * rr || !reachesObb(cc, rr, o))
                continue;
              if (visit(o)) return true;
            }
          return false;
        }
        for (std::size_t begin = 0; begin < nb; begin += 64) {
          const std::size_t n = std::min<std::size_t>(64, nb - begin);
          for (std::uint64_t hits = s.boxes.hits(begin, n, cc, rr * rr); hits; hits &= hits - 1) {
            const int o = s.obstacles[begin + static_cast<std::size_t>(__builtin_ctzll(hits))];
            if (reachesObb(cc, rr, o) && visit(o)) return true;
          }
        }
        return false;
      };
      if (s.num_elements == 1) {
        const int e = s.first_element;
        if (reached(c, r, [&](int o) { return pair(e, o); })) return true;
        continue;
      }
      // Several elements (a base with its bumper, deck and wheels): the obstacles the slot's
      // sphere reaches, each against the elements whose own spheres reach its box.
      const auto element = [&](int o) {
        for (int e = s.first_element; e < s.first_element + s.num_elements; ++e) {
          if (!((open >> (e - s.first_element)) & 1)) continue;
          const double re = elements[e].radius + scene_padding;
          const Eigen::Vector3d ce = X * elementCenter(elements[e]);
          if (detail::sqDistPointAabb(ce, boxes[o]) > re * re || !reachesObb(ce, re, o)) continue;
          if (pair(e, o)) return true;
        }
        return false;
      };
      if (reached(c, r, element)) return true;
    }
  // Self pairs, block by block.
  const CollisionModel::SelfPair* const pairs = model.selfPairs().data();
  for (const PairBlock& blk : model.pairBlocks()) {
    if (kFolded && blk.anchor >= 0) {  // the held joints at held(): see pair_blocks.h
      const double r = blk.radius + slots[blk.a].radius + self_padding;
      if ((centers[blk.a] - X_WL[blk.anchor].translation()).squaredNorm() > r * r) continue;
    }
    for (const CollisionModel::SelfPair* pair = pairs + blk.begin; pair != pairs + blk.end;
         ++pair) {
      const CollisionModel::SelfPair& p = *pair;
      if (p.table >= 0 && skip[p.table]) continue;
      const double r = p.radius_sum + self_padding;
      if ((centers[p.a] - centers[p.b]).squaredNorm() > r * r) continue;
      const Slot& sa = slots[p.a];
      const Slot& sb = slots[p.b];
      const Eigen::Isometry3d& XA = X_WL[linkOf(sa)];
      const Eigen::Isometry3d& XB = X_WL[linkOf(sb)];
      if (sa.num_elements == 1 && sb.num_elements == 1) {
        const int ea = sa.first_element, eb = sb.first_element;
        Eigen::Isometry3d X_prod_a, X_prod_b;
        const Eigen::Isometry3d& X_WA = detail::placedShape<kPoses>(XA, elements[ea], X_prod_a);
        const Eigen::Isometry3d& X_WB = detail::placedShape<kPoses>(XB, elements[eb], X_prod_b);
        if (opt.obb_stage &&
            obbApart(X_WA.linear(), X_WA * elements[ea].box_center_S, elements[ea].box_half,
                     X_WB.linear(), X_WB * elements[eb].box_center_S, elements[eb].box_half,
                     self_padding))
          continue;
        if (self(ea, X_WA, eb, X_WB)) return true;
        continue;
      }
      // Several elements (the pieces of decomposed meshes): b's element centres once; each
      // element of a against b's sphere first, then against b's elements.
      if (element_store.size() < std::size_t(sb.num_elements))
        element_store.resize(std::size_t(sb.num_elements));
      Eigen::Vector3d* const cb = element_store.data();
      for (int k = 0; k < sb.num_elements; ++k)
        cb[k] = XB * elementCenter(elements[sb.first_element + k]);
      for (int ea = sa.first_element; ea < sa.first_element + sa.num_elements; ++ea) {
        const Element& a = elements[ea];
        const Eigen::Vector3d ca = XA * elementCenter(a);
        const double row = a.radius + sb.radius + self_padding;
        if ((ca - centers[p.b]).squaredNorm() > row * row) continue;
        Eigen::Isometry3d X_prod_a;
        const Eigen::Isometry3d* X_WA = nullptr;  // placed when a pair first needs it
        for (int k = 0; k < sb.num_elements; ++k) {
          const int eb = sb.first_element + k;
          const Element& b = elements[eb];
          const double rr = a.radius + b.radius + self_padding;
          if ((ca - cb[k]).squaredNorm() > rr * rr) continue;
          if (!X_WA) X_WA = &detail::placedShape<kPoses>(XA, a, X_prod_a);
          Eigen::Isometry3d X_prod_b;
          const Eigen::Isometry3d& X_WB = detail::placedShape<kPoses>(XB, b, X_prod_b);
          if (opt.obb_stage &&
              obbApart(X_WA->linear(), *X_WA * a.box_center_S, a.box_half, X_WB.linear(),
                       X_WB * b.box_center_S, b.box_half, self_padding))
            continue;
          if (self(ea, *X_WA, eb, X_WB)) return true;
        }
      }
    }
  }
  return false;
}

}  // namespace dss
