// The collision model a planner checks: a robot (links with convex elements), a planning
// group (the joints that move), the held values of every other joint, a scene of convex
// obstacles, and the pairs that are worth checking.
//
// Built once per (robot, scene, group):
//  - links are "moving" when some group joint (or a mimic of one) lies between them and the
//    root; the others never move relative to the world, so they are never checked against the
//    scene, and a self pair of two non-moving links is dropped;
//  - self pairs come from selfCollisionPairs() (adjacent, rigidly attached, SRDF-disabled and
//    scene-ACM-allowed pairs removed);
//  - robot-scene pairs are (moving link, obstacle) pairs the scene's ACM does not allow;
//  - obstacle pruning: every moving link stays inside a ball about the origin of the first
//    group joint above it (radius: the joint offsets down the chain, prismatic travel and the
//    link's geometry); obstacles whose box no such ball reaches (plus the scene padding) are
//    dropped.
// Each link and each element carries a bounding sphere in its link frame; with the link poses
// of a state they give a cheap world-space prefilter before the exact narrow phase (a link
// sphere is first looked up in a clearance grid, see clearance_grid.h, then tested against
// the obstacle boxes one by one). The
// narrow phase itself is a callback (DSS, FCL), so that every checker sees the same pairs.
//
// Pose links: a slot's link is rigid to the nearest link above it whose parent joint moves
// with the group (or to the root) as long as the joints in between -- fixed, or held outside
// the group -- keep their held values; the slot's sphere and its elements' shape poses are
// also stored in that pose link's frame (Slot::pose_link, center_P, Element::X_PS). With the
// held joints at their values (heldMatch) the sweep places every slot from its pose link, so
// that sweepKinematics() computes fewer poses (the Panda arm group: link1..link7, its hand
// and fingers riding on link7); otherwise it uses each slot's own link.
//
// Self-pair tables: when the relative pose of two links depends on one or two group joint
// values only (e.g. the Panda's link5 and link7: joints 6 and 7; link5 and a finger: joints 6
// and 7 with the finger joint held outside the group -- the table then answers only for the
// held value it was built with), the joint range is cut into cells
// and each cell is decided once, at build time, for every value inside it. Within a cell no
// point of one link moves more than L relative to the other (the joint's half-width times
// the distance of the geometry from the joint; a prismatic joint moves by its half-width).
// "Free": exact DSS proves the links at the cell centre farther apart than padding + L.
// "Colliding": the links at the centre still intersect when one is translated to each of the
// six points at distance sqrt(3) L along the axes, so their Minkowski difference holds the
// octahedron of those points and with it the ball of radius L: every pose in the cell
// intersects (h_{A-B(q)}(d) >= h_{A-B(c)}(d) - L >= 0 for every unit d). Cells are decided
// coarse to fine (a decided block decides all its cells). At query time a decided cell
// answers the pair without a narrow phase (colliding cells are looked up before anything
// else, so such a state is rejected at once); any other cell, or a value outside the range,
// takes the normal path. The tables never change an answer, only its cost.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "dss/planning/clearance_grid.h"
#include "dss/robot/collision_pairs.h"
#include "dss/robot/kinematics.h"
#include "dss/robot/robot_model.h"
#include "dss/robot/srdf.h"
#include "dss/scene/scene.h"

namespace dss {

struct CollisionModelOptions {
  /// Drop obstacles that no moving link can reach.
  bool prune_obstacles = true;
  /// Margin added to the reach test (use the scene padding of the checkers).
  double prune_margin = 0.0;
  /// Drop self pairs of links rigidly attached to each other.
  bool exclude_rigid = true;
  /// Self-pair tables (see above): cells per joint for pairs moved by two joints (0: no
  /// tables), and for pairs moved by one joint. (Panda, MotionBenchMaker table_pick, uniform
  /// random states: 128 x 128 leaves 7.4 % of the link5-link7 cells undecided and costs 0.063
  /// narrow-phase tests per state on that pair; 256 x 256 halves the undecided cells, takes
  /// 0.04 s to build instead of 0.02 s and 64 KB per table; 512 x 512 (2 % undecided, 256 KB
  /// per table) measured slower than 256 x 256 on this machine.)
  int self_table_cells_2d = 256;
  int self_table_cells_1d = 1024;
  /// The self padding the tables certify: a checker uses them when its own self padding is
  /// at most this.
  double self_table_padding = 0.0;
  /// Pair blocks (see CollisionModel::PairBlock): a block keeps its ball when, on 256 random
  /// states of the group, the ball rules it out often enough to save at least this many
  /// per-pair sphere tests per state (the ball test itself costs about one). 0 keeps every
  /// ball. (Panda: its three balls save 9 to 12; the UR5 with its gripper: none pays.)
  double pair_block_min_saving = 1.5;
};

/// Decided cells of a self pair over the one or two group joint values it depends on.
struct SelfPairTable {
  enum Cell : unsigned char { kUnknown = 0, kFree = 1, kColliding = 2 };
  int num_vars = 0;
  int var[2] = {-1, -1};        ///< active joint indices
  double lo[2] = {0, 0}, hi[2] = {0, 0}, inv_width[2] = {0, 0};
  bool wrap[2] = {false, false};  ///< continuous joint: the value is taken modulo 2 pi
  int cells[2] = {1, 1};
  /// Joints outside the group that the pair's relative pose depends on, at the held value the
  /// table was built with: any other value gets kUnknown.
  static constexpr int kMaxFixed = 4;
  int num_fixed = 0;
  int fixed_var[kMaxFixed] = {-1, -1, -1, -1};
  double fixed_value[kMaxFixed] = {0, 0, 0, 0};
  double padding = 0.0;
  std::vector<unsigned char> free;  ///< Cell per cell, cells[0] x cells[1], row-major
  std::size_t num_free = 0;
  std::size_t num_colliding = 0;

  /// True when the cell of q is certified free (false outside the range, or for NaN).
  bool certifiedFree(const double* q) const { return cell(q) == kFree; }
  /// True when the cell of q is certified colliding (at zero padding, so at any padding).
  bool certifiedColliding(const double* q) const { return cell(q) == kColliding; }
  /// The decided state of the cell of q (kUnknown outside the range, or for NaN).
  Cell cell(const double* q) const {
    if (!heldMatch(q)) return kUnknown;
    const int idx = index(q);
    return idx < 0 ? kUnknown : static_cast<Cell>(free[idx]);
  }
  /// The joints held outside the group are at the values the table was built with.
  bool heldMatch(const double* q) const {
    for (int k = 0; k < num_fixed; ++k)
      if (!(q[fixed_var[k]] == fixed_value[k])) return false;
    return true;
  }
  /// The cell index of q (row-major), or -1 outside the range or for NaN.
  int index(const double* q) const {
    int idx = 0;
    for (int k = 0; k < num_vars; ++k) {
      double v = q[var[k]];
      if (wrap[k]) v -= 6.283185307179586 * std::floor((v + 3.141592653589793) / 6.283185307179586);
      if (!(v >= lo[k] && v <= hi[k])) return -1;
      int i = static_cast<int>((v - lo[k]) * inv_width[k]);
      if (i >= cells[k]) i = cells[k] - 1;
      idx = idx * cells[k] + i;
    }
    return idx;
  }
  /// Same variables, ranges and cells: the same index for every q.
  bool sameGrid(const SelfPairTable& o) const {
    if (num_vars != o.num_vars) return false;
    for (int k = 0; k < num_vars; ++k)
      if (var[k] != o.var[k] || lo[k] != o.lo[k] || hi[k] != o.hi[k] || wrap[k] != o.wrap[k] || cells[k] != o.cells[k])
        return false;
    return true;
  }
};

class CollisionModel {
 public:
  /// One convex collision element of a link with geometry.
  struct Element {
    int link = -1;                ///< model link index
    int slot = -1;                ///< index into slots()
    const CollisionElement* source = nullptr;  ///< in robot()
    Eigen::Vector3d center_L = Eigen::Vector3d::Zero();  ///< bounding sphere in the link frame
    double radius = 0.0;
    /// A box holding the element, axis-aligned in the shape frame, centred at box_center_S
    /// (half extents box_half): the oriented-box stage of the sweep.
    Eigen::Vector3d box_center_S = Eigen::Vector3d::Zero();
    Eigen::Vector3d box_half = Eigen::Vector3d::Zero();
    bool identity_LS = false;     ///< source->X_LS is exactly the identity (X_WS = X_WL)
    /// The same shape pose and sphere centre in the frame of the slot's pose link (see Slot):
    /// what the sweep uses when the held joints are at held().
    Eigen::Isometry3d X_PS = Eigen::Isometry3d::Identity();
    bool identity_PS = false;
    Eigen::Vector3d center_P = Eigen::Vector3d::Zero();
    /// Balls inside the element's shape (centre in the shape frame, radius; the radius already
    /// reduced by a margin far above rounding): one of them touching an obstacle's box proves
    /// the pair colliding without a narrow phase.
    static constexpr int kMaxInner = 4;
    int num_inner = 0;
    Eigen::Vector4d inner_S[kMaxInner];
  };
  /// A link with geometry.
  struct Slot {
    int link = -1;
    /// The nearest link at or above `link` whose parent joint moves with the group (or the
    /// root): joints between them are fixed or held, so `link` is rigid to it as long as the
    /// held joints keep their held() values. The sweep then needs only the poses of pose links
    /// (sweepKinematics()): a gripper's hand and fingers ride on the last arm link.
    int pose_link = -1;
    Eigen::Vector3d center_P = Eigen::Vector3d::Zero();  ///< center_L in the pose link's frame
    bool moves = false;           ///< moves with the group
    int first_element = 0;        ///< elements [first_element, first_element + num_elements)
    int num_elements = 0;
    Eigen::Vector3d center_L = Eigen::Vector3d::Zero();  ///< bounding sphere of all elements
    double radius = 0.0;
    std::vector<int> obstacles;   ///< kept obstacles this slot is checked against
    /// Their world boxes in the same order, as six arrays (lower x, y, z, upper x, y, z) of
    /// box_stride values each, padded with empty boxes: the sweep tests two at a time.
    std::vector<double> box_soa;
    std::size_t box_stride = 0;
    /// Reach ball in the world (moving slots): every pose of the link stays inside.
    Eigen::Vector3d reach_center_W = Eigen::Vector3d::Zero();
    double reach_radius = 0.0;
  };
  struct SelfPair {
    int a = -1, b = -1;  ///< slots
    int table = -1;      ///< index into selfTables(), or -1
    double radius_sum = 0.0;  ///< of the two slot spheres
  };

  /// `group_active`: active joint indices of the group (empty: every active joint).
  /// `held`: one value per active joint of the model, used for joints outside the group (and
  /// to place fixed frames for resolveFrames()). `scene` is taken by value: its frames are
  /// resolved with the robot's non-moving links and its obstacles pruned. Throws on an
  /// inconsistent input (names the scene, the object or the link).
  CollisionModel(std::shared_ptr<const RobotModel> robot, const Srdf* srdf, Scene scene,
                 std::vector<int> group_active, std::vector<double> held,
                 const CollisionModelOptions& options = {});

  const RobotModel& robot() const { return *robot_; }
  /// Computes the poses of the links with geometry (others are left untouched).
  const Kinematics& kinematics() const { return kin_; }
  /// Computes only the slots' pose links (Slot::pose_link): enough for anyCollision when the
  /// state's held joints are at held() (heldMatch()).
  const Kinematics& sweepKinematics() const { return sweep_kin_; }
  /// Every active joint outside the group is at its held() value (exactly; NaN never is).
  bool heldMatch(const double* q) const {
    for (int a : held_active_)
      if (!(q[a] == held_[a])) return false;
    return true;
  }
  /// Some self pair is certified colliding by its table (needs no link pose), so that
  /// anyCollision(q, ...) returns true at this self padding. (Answers only when heldMatch(q).)
  bool tablesCollide(const double* q, double self_padding) const {
    if (!(self_padding >= table_padding_) || !heldMatch(q)) return false;
    for (const TableGroup& g : table_groups_) {
      const int idx = self_tables_[g.first].index(q);
      if (idx < 0) continue;
      const unsigned byte = g.packed[idx];
      if (TableGroup::colliding(byte)) return true;
    }
    return false;
  }
  /// Reads every self-pair table once for a state with heldMatch(q): true when one certifies
  /// a collision at this self padding (as tablesCollide); otherwise skip[t] (one flag per
  /// table, selfTables().size()) is set when table t certifies its pair free at this padding,
  /// and anyCollision can take the flags instead of reading the tables again.
  bool readTables(const double* q, double self_padding, unsigned char* skip) const {
    const bool use_colliding = self_padding >= table_padding_, use_free = self_padding <= table_padding_;
    for (const TableGroup& g : table_groups_) {
      const int idx = self_tables_[g.first].index(q);
      const unsigned byte = idx < 0 ? 0u : g.packed[idx];
      if (use_colliding && TableGroup::colliding(byte)) return true;
      const unsigned free = use_free ? TableGroup::free(byte) : 0u;
      for (int m = 0; m < g.count; ++m) skip[g.first + m] = (free >> (2 * m)) & 1u;
    }
    return false;
  }
  const Scene& scene() const { return scene_; }  ///< kept obstacles only
  const std::vector<int>& groupActive() const { return group_active_; }
  const std::vector<double>& held() const { return held_; }
  const std::vector<Element>& elements() const { return elements_; }
  const std::vector<Slot>& slots() const { return slots_; }
  const std::vector<SelfPair>& selfPairs() const { return self_pairs_; }
  const std::vector<SelfPairTable>& selfTables() const { return self_tables_; }
  /// Self pairs tested behind a block sphere first (see PairBlock).
  std::size_t pairsBehindBlockSpheres() const {
    std::size_t n = 0;
    for (const PairBlock& b : pair_blocks_) n += b.anchor >= 0 ? static_cast<std::size_t>(b.end - b.begin) : 0;
    return n;
  }
  const std::vector<Aabb>& obstacleBoxes() const { return boxes_; }
  /// Oriented box of obstacle o in the world: rotation, centre, half extents.
  struct Obb {
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    Eigen::Vector3d h = Eigen::Vector3d::Zero();
  };
  const std::vector<Obb>& obstacleObbs() const { return obbs_; }
  /// Lower bounds on the distance to the obstacle boxes over the region the moving links
  /// reach: the first test of the sweep for each link sphere.
  const ClearanceGrid& clearanceGrid() const { return grid_; }
  const SelfCollisionPairs& selfPairReport() const { return self_report_; }
  bool linkMovesWithGroup(int link) const { return moves_[link]; }

  std::size_t obstaclesBefore() const { return obstacles_before_; }
  /// A lower bound on the distance of any moving link to any obstacle pruned for it
  /// (infinity when none was pruned): clearance never exceeds what the pruning guarantees.
  double prunedClearance() const { return pruned_gap_; }
  std::size_t scenePairs() const { return scene_pairs_; }
  std::size_t scenePairsBefore() const { return scene_pairs_before_; }
  /// e.g. "kept 12 of 40 obstacles, 60 of 400 robot-scene link pairs, 21 of 55 self link pairs"
  std::string summary() const;
  std::vector<std::string> warnings;

  /// Sweeps the pairs in order (robot vs scene, then self) with sphere prefilters and calls the
  /// narrow phase for the element pairs that survive; returns true at the first collision.
  ///   scene(element, X_WS, obstacle) -> bool collides
  ///   self(element_a, X_WA, element_b, X_WB) -> bool collides
  /// X_WL: link poses from kinematics().computeLinkPoses for the state; when q is given and
  /// heldMatch(q), from sweepKinematics() is enough (the sweep then places each slot from its
  /// pose link; otherwise from its own link).
  /// With `obb_stage`, element pairs whose oriented boxes a separating-axis test (with a
  /// relative safety margin against rounding) proves apart are skipped too.
  /// With `q` (the active joint values of the state, may be null) self pairs in a certified
  /// cell of their table are skipped.
  /// With `inner_stage` (only for a narrow phase that sees the elements' own shapes -- hulls,
  /// not the meshes inside them), a robot-scene pair that survives the filters is first tested
  /// with the element's inner balls (Element::inner_S): a ball within the padding of an
  /// obstacle box proves a collision, and the narrow phase is skipped. (Self pairs do not use
  /// them: their collisions are mostly decided by the tables, and 16 ball pairs per element
  /// pair cost about what they saved.)
  /// `table_skip`: for a state with heldMatch(q) whose tables readTables() has already read
  /// (and found no certified collision), its flags, so that the tables are not read twice.
  template <class SceneNarrow, class SelfNarrow>
  bool anyCollision(const double* q, const Eigen::Isometry3d* X_WL, double scene_padding,
                    double self_padding, SceneNarrow&& scene, SelfNarrow&& self,
                    bool obb_stage = true, bool inner_stage = false,
                    const unsigned char* table_skip = nullptr) const;
  template <class SceneNarrow, class SelfNarrow>
  bool anyCollision(const Eigen::Isometry3d* X_WL, double scene_padding, double self_padding,
                    SceneNarrow&& scene, SelfNarrow&& self, bool obb_stage = true) const {
    return anyCollision(nullptr, X_WL, scene_padding, self_padding, std::forward<SceneNarrow>(scene),
                        std::forward<SelfNarrow>(self), obb_stage);
  }

 private:
  void computeReach(const std::vector<Eigen::Isometry3d>& X_WL);
  /// Sets Slot::pose_link, Slot::center_P and the elements' X_PS / center_P, and
  /// sweepKinematics() to compute the pose links.
  void placeOnPoseLinks();
  void buildSelfTables(const CollisionModelOptions& options);
  template <bool kFolded, class SceneNarrow, class SelfNarrow>
  bool sweep(const Eigen::Isometry3d* X_WL, double scene_padding, double self_padding,
             const unsigned char* skip, SceneNarrow& scene, SelfNarrow& self, bool obb_stage,
             bool inner_stage) const;
  /// The pose of element e's shape given the pose X of its slot's pose link (kFolded) or of
  /// its own link: X itself when the shape frame is the identity there, else the product,
  /// written into `scratch`.
  template <bool kFolded>
  static const Eigen::Isometry3d& placedShape(const Eigen::Isometry3d& X, const Element& e,
                                              Eigen::Isometry3d& scratch) {
    if (kFolded ? e.identity_PS : e.identity_LS) return X;
    scratch = X * (kFolded ? e.X_PS : e.source->X_LS);
    return scratch;
  }
  double prismaticTravel(const RobotJoint& j) const;

  std::shared_ptr<const RobotModel> robot_;
  Kinematics kin_;
  Kinematics sweep_kin_;
  std::vector<int> held_active_;  ///< active joints outside the group
  Scene scene_;
  std::vector<int> group_active_;
  std::vector<double> held_;
  std::vector<char> moves_;
  std::vector<char> in_group_;  ///< per active joint: in the group
  std::vector<Element> elements_;
  std::vector<Slot> slots_;
  std::vector<SelfPair> self_pairs_;
  /// Self pairs [begin, end) share slot a (consecutive in self_pairs_). With anchor >= 0, the
  /// spheres of all their b slots lie, in every state with the held joints at held(), inside
  /// the ball of `radius` about the origin of link `anchor` (an ancestor of them all, and a
  /// pose link, so the folded sweep has its pose): when a's sphere misses that ball, no pair
  /// of the block can pass its own sphere test, and the folded sweep skips the block in one
  /// test. The radius adds, from each b slot up to the anchor, the lengths of the joint
  /// origins' offsets (revolute and continuous joints turn about their origins), the held
  /// travel of held prismatic joints (a prismatic joint of the group: no anchor), the sphere
  /// centre's distance from its link and the sphere radius. A ball is kept only where it pays
  /// on random states (CollisionModelOptions::pair_block_min_saving); consecutive blocks
  /// without a ball are merged. (The Panda: link0, link1 and link2 against link5 .. the
  /// fingers, 17 of its 21 self pairs, behind balls about link5.)
  struct PairBlock {
    int a = -1;
    int begin = 0, end = 0;
    int anchor = -1;
    double radius = 0.0;
  };
  std::vector<PairBlock> pair_blocks_;
  void buildPairBlocks(double min_saving);
  std::vector<SelfPairTable> self_tables_;
  /// Tables on the same grid (e.g. the Panda's link5 against link7, the hand and the two
  /// fingers: joints 6 and 7) packed together, two bits per table in one byte per cell, so
  /// that a state reads one byte for all of them.
  struct TableGroup {
    int first = 0;  ///< its tables: self_tables_[first, first + count), on the grid of the first
    int count = 0;  ///< at most 4
    std::vector<std::uint8_t> packed;
    /// Of a packed byte: bit 2m + 1 set when table m's cell is kColliding (2), bit 2m when it
    /// is kFree (1).
    static unsigned colliding(unsigned byte) { return byte & 0xAAu & ~(byte << 1); }
    static unsigned free(unsigned byte) { return byte & 0x55u & ~(byte >> 1); }
  };
  std::vector<TableGroup> table_groups_;
  double table_padding_ = 0.0;  ///< the padding every table certifies
  std::vector<Aabb> boxes_;
  std::vector<Obb> obbs_;
  ClearanceGrid grid_;
  /// Exact half extents of obstacle o when it is a box (centred and turned as obbs_[o]), else
  /// -1: the inner-ball stage tests balls against it.
  std::vector<Eigen::Vector3d> inner_half_;
  SelfCollisionPairs self_report_;
  std::size_t obstacles_before_ = 0;
  double pruned_gap_ = std::numeric_limits<double>::infinity();
  std::size_t scene_pairs_ = 0;
  std::size_t scene_pairs_before_ = 0;
};

namespace detail {
/// Separating-axis test of two oriented boxes (rotation, centre, half extents): true when one
/// of the 15 axes separates them by more than `pad` plus a relative margin that covers the
/// rounding of the test, so "true" is a safe "disjoint (distance > pad)".
inline bool obbApart(const Eigen::Matrix3d& Ra, const Eigen::Vector3d& ca, const Eigen::Vector3d& ha,
                     const Eigen::Matrix3d& Rb, const Eigen::Vector3d& cb, const Eigen::Vector3d& hb,
                     double pad) {
  const Eigen::Vector3d t = Ra.transpose() * (cb - ca);
  const double margin = pad + 1e-9 * (ha.sum() + hb.sum() + t.cwiseAbs().sum()) + 1e-12;
  // B's axes first, each as soon as its column of R = Ra^T Rb is known: in the sweep B is the
  // obstacle (walls, shelves, tables), whose face normals separate most pairs that get here.
  Eigen::Matrix3d R, A;
  for (int j = 0; j < 3; ++j) {
    R.col(j) = Ra.transpose() * Rb.col(j);
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

/// True when the ball (c, r) comes within `pad` of the box (rotation, centre, half extents),
/// with a relative margin against rounding: a safe "colliding". A box with h.x() < 0 never.
inline bool ballTouchesBox(const Eigen::Vector3d& c, double r, const Eigen::Matrix3d& R, const Eigen::Vector3d& bc,
                           const Eigen::Vector3d& h, double pad) {
  const Eigen::Vector3d t = c - bc;
  const Eigen::Vector3d p(R.col(0).dot(t), R.col(1).dot(t), R.col(2).dot(t));
  const double reach = r + pad - 1e-9 * (1.0 + t.cwiseAbs().sum() + h.sum() + r);
  if (!(reach > 0.0) || !(h.x() >= 0.0)) return false;
  const Eigen::Vector3d d = (p.cwiseAbs() - h).cwiseMax(0.0);
  return d.squaredNorm() < reach * reach;
}

/// Bit i (i < n <= 64) set when box begin + i of a Slot's box_soa (six arrays of `stride`
/// values, n rounded up to even within them) is not farther than sqrt(r2) from c, or when the
/// distance is NaN: a set bit means "test further", so NaN is never a skip.
inline std::uint64_t sphereBoxHits(const double* soa, std::size_t stride, std::size_t begin, std::size_t n,
                                   const Eigen::Vector3d& c, double r2) {
  std::uint64_t hits = 0;
  const double* lx = soa + begin;
  const double* ly = lx + stride;
  const double* lz = ly + stride;
  const double* ux = lz + stride;
  const double* uy = ux + stride;
  const double* uz = uy + stride;
#if defined(__SSE2__)
  const __m128d cx = _mm_set1_pd(c.x()), cy = _mm_set1_pd(c.y()), cz = _mm_set1_pd(c.z());
  const __m128d zero = _mm_setzero_pd(), rr = _mm_set1_pd(r2);
  // max(0, t) keeps a NaN t (maxpd returns its second operand when one is NaN).
  auto axis = [&](const double* lo, const double* up, std::size_t i, __m128d ci) {
    const __m128d d = _mm_max_pd(_mm_sub_pd(ci, _mm_loadu_pd(up + i)), _mm_max_pd(zero, _mm_sub_pd(_mm_loadu_pd(lo + i), ci)));
    return _mm_mul_pd(d, d);
  };
  for (std::size_t i = 0; i < n; i += 2) {
    const __m128d d2 = _mm_add_pd(_mm_add_pd(axis(lx, ux, i, cx), axis(ly, uy, i, cy)), axis(lz, uz, i, cz));
    hits |= static_cast<std::uint64_t>(_mm_movemask_pd(_mm_cmpngt_pd(d2, rr))) << i;
  }
  return hits & (n == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << n) - 1);
#else
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = std::max(0.0, std::max(lx[i] - c.x(), c.x() - ux[i]));
    const double dy = std::max(0.0, std::max(ly[i] - c.y(), c.y() - uy[i]));
    const double dz = std::max(0.0, std::max(lz[i] - c.z(), c.z() - uz[i]));
    if (!(dx * dx + dy * dy + dz * dz > r2)) hits |= std::uint64_t(1) << i;
  }
  return hits;
#endif
}
}  // namespace detail

template <class SceneNarrow, class SelfNarrow>
bool CollisionModel::anyCollision(const double* q, const Eigen::Isometry3d* X_WL, double scene_padding,
                                  double self_padding, SceneNarrow&& scene, SelfNarrow&& self,
                                  bool obb_stage, bool inner_stage, const unsigned char* table_skip) const {
  if (table_skip)  // read already (readTables), for a state with heldMatch(q)
    return sweep<true>(X_WL, scene_padding, self_padding, table_skip, scene, self, obb_stage, inner_stage);
  // Self pairs whose table says "colliding" for this state: rejected before anything else.
  // The cells that let a pair be skipped ("free" at this padding) are kept for the self-pair
  // sweep.
  thread_local std::vector<unsigned char> skip_store;
  if (skip_store.size() < self_tables_.size()) skip_store.resize(self_tables_.size());
  unsigned char* const skip = skip_store.data();
  const bool held = q && heldMatch(q);
  if (held) {
    // Every table was built at held() with the same padding: with the held joints there, a
    // table's cell applies as it is, and the two-bit cells of a group are read as masks.
    if (readTables(q, self_padding, skip)) return true;
  } else if (q) {
    for (const TableGroup& g : table_groups_) {
      const int idx = self_tables_[g.first].index(q);
      const unsigned byte = idx < 0 ? 0u : g.packed[idx];
      for (int m = 0; m < g.count; ++m) {
        const int ti = g.first + m;
        const SelfPairTable& t = self_tables_[ti];
        const unsigned c = (byte >> (2 * m)) & 3u;
        const bool held = c == SelfPairTable::kUnknown || t.heldMatch(q);
        if (c == SelfPairTable::kColliding && held && self_padding >= t.padding) return true;
        skip[ti] = c == SelfPairTable::kFree && held && self_padding <= t.padding;
      }
    }
  } else {
    std::fill(skip, skip + self_tables_.size(), 0);
  }
  if (held)
    return sweep<true>(X_WL, scene_padding, self_padding, skip, scene, self, obb_stage, inner_stage);
  return sweep<false>(X_WL, scene_padding, self_padding, skip, scene, self, obb_stage, inner_stage);
}

template <bool kFolded, class SceneNarrow, class SelfNarrow>
bool CollisionModel::sweep(const Eigen::Isometry3d* X_WL, double scene_padding, double self_padding,
                           const unsigned char* skip, SceneNarrow& scene, SelfNarrow& self, bool obb_stage,
                           bool inner_stage) const {
  // Where a slot and an element sit: from the slot's pose link (kFolded) or its own link.
  auto linkOf = [](const Slot& s) { return kFolded ? s.pose_link : s.link; };
  auto slotCenter = [](const Slot& s) -> const Eigen::Vector3d& { return kFolded ? s.center_P : s.center_L; };
  auto elementCenter = [](const Element& e) -> const Eigen::Vector3d& { return kFolded ? e.center_P : e.center_L; };
  // World centres of the slot spheres, once per state (per-thread scratch, no allocation
  // after the first call with a model this size). The thread-local vector and the slot count
  // are read once: inside the loops the compiler would reload both after every store.
  thread_local std::vector<Eigen::Vector3d> center_store;
  const std::size_t num_slots = slots_.size();
  if (center_store.size() < num_slots) center_store.resize(num_slots);
  Eigen::Vector3d* const centers = center_store.data();
  const Slot* const slots = slots_.data();
  for (std::size_t k = 0; k < num_slots; ++k) {
    const Eigen::Isometry3d& X = X_WL[linkOf(slots[k])];
    centers[k] = X.linear() * slotCenter(slots[k]) + X.translation();
  }
  // Robot vs scene.
  for (std::size_t k = 0; k < num_slots; ++k) {
    const Slot& s = slots_[k];
    const std::size_t nb = s.obstacles.size();
    if (nb == 0) continue;
    const Eigen::Isometry3d& X = X_WL[linkOf(s)];
    const Eigen::Vector3d& c = centers[k];
    const double r = s.radius + scene_padding;
    if (grid_.clear(c, r)) continue;
    for (std::size_t begin = 0; begin < nb; begin += 64) {
      const std::size_t n = std::min<std::size_t>(64, nb - begin);
      for (std::uint64_t hits = detail::sphereBoxHits(s.box_soa.data(), s.box_stride, begin, n, c, r * r); hits;
           hits &= hits - 1) {
        const std::size_t i = begin + static_cast<std::size_t>(__builtin_ctzll(hits));
        const int o = s.obstacles[i];
        for (int e = s.first_element; e < s.first_element + s.num_elements; ++e) {
          const Element& el = elements_[e];
          if (s.num_elements > 1) {
            const double re = el.radius + scene_padding;
            if (detail::sqDistPointAabb(X * elementCenter(el), boxes_[o]) > re * re) continue;
          }
          Eigen::Isometry3d X_prod;
          const Eigen::Isometry3d& X_WS = placedShape<kFolded>(X, el, X_prod);
          if (obb_stage) {
            const Obb& ob = obbs_[o];
            if (detail::obbApart(X_WS.linear(), X_WS * el.box_center_S, el.box_half, ob.R, ob.c, ob.h,
                                 scene_padding))
              continue;
          }
          if (inner_stage && el.num_inner > 0 && inner_half_[o].x() >= 0.0) {
            const Obb& ob = obbs_[o];
            for (int k = 0; k < el.num_inner; ++k)
              if (detail::ballTouchesBox(X_WS * el.inner_S[k].head<3>(), el.inner_S[k].w(), ob.R, ob.c,
                                         inner_half_[o], scene_padding))
                return true;
          }
          if (scene(e, X_WS, o)) return true;
        }
      }
    }
  }
  // Self pairs, block by block (see PairBlock).
  for (const PairBlock& blk : pair_blocks_) {
    if (kFolded && blk.anchor >= 0) {  // the held joints at held(): see PairBlock
      const double r = blk.radius + slots[blk.a].radius + self_padding;
      if ((centers[blk.a] - X_WL[blk.anchor].translation()).squaredNorm() > r * r) continue;
    }
    const SelfPair* const block_end = self_pairs_.data() + blk.end;
    for (const SelfPair* pair = self_pairs_.data() + blk.begin; pair != block_end; ++pair) {
      const SelfPair& p = *pair;
      if (p.table >= 0 && skip[p.table]) continue;
      const double r = p.radius_sum + self_padding;
      if ((centers[p.a] - centers[p.b]).squaredNorm() > r * r) continue;
      const Slot& sa = slots_[p.a];
      const Slot& sb = slots_[p.b];
      const Eigen::Isometry3d& XA = X_WL[linkOf(sa)];
      const Eigen::Isometry3d& XB = X_WL[linkOf(sb)];
      const bool single = sa.num_elements == 1 && sb.num_elements == 1;
      for (int ea = sa.first_element; ea < sa.first_element + sa.num_elements; ++ea) {
        const Element& a = elements_[ea];
        Eigen::Isometry3d X_prod_a;
        const Eigen::Isometry3d& X_WA = placedShape<kFolded>(XA, a, X_prod_a);
        for (int eb = sb.first_element; eb < sb.first_element + sb.num_elements; ++eb) {
          const Element& b = elements_[eb];
          if (!single) {
            const double rr = a.radius + b.radius + self_padding;
            if ((XA * elementCenter(a) - XB * elementCenter(b)).squaredNorm() > rr * rr) continue;
          }
          Eigen::Isometry3d X_prod_b;
          const Eigen::Isometry3d& X_WB = placedShape<kFolded>(XB, b, X_prod_b);
          if (obb_stage && detail::obbApart(X_WA.linear(), X_WA * a.box_center_S, a.box_half, X_WB.linear(),
                                            X_WB * b.box_center_S, b.box_half, self_padding))
            continue;
          if (self(ea, X_WA, eb, X_WB)) return true;
        }
      }
    }
  }
  return false;
}

}  // namespace dss
