// The collision model a checker works on: a robot (links with convex elements), a planning
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
//  - obstacle pruning: every moving link stays inside a reach ball about the origin of the
//    first group joint above it (motion_bounds.h); obstacles whose box no such ball reaches
//    (plus the pruning margin) are dropped.
// The stages that the sweep (sweep.h) runs before the narrow phase each live in their own
// file: bounding spheres and local boxes (element_bounds.h), the clearance grid
// (clearance_grid.h), the sphere-box filter (sphere_box_filter.h), oriented boxes (obb.h),
// inner balls and boxes (inner_shapes.h), self-pair tables (self_pair_table.h), pose links
// (pose_links.h) and pair blocks (pair_blocks.h).
//
// Every bound assumes the state's joints within their limits (a prismatic joint's travel,
// motion_bounds.h) or, for joints outside the group, at their held values.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "dss/checker/base_scene_table.h"
#include "dss/checker/clearance_grid.h"
#include "dss/checker/element_shapes_cache.h"
#include "dss/checker/obb.h"
#include "dss/checker/pair_blocks.h"
#include "dss/checker/self_pair_table.h"
#include "dss/checker/slot_spheres.h"
#include "dss/checker/sphere_box_filter.h"
#include "dss/core/simd_path.h"
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
  /// Self-pair tables (self_pair_table.h): cells per joint for pairs moved by two joints (0:
  /// no tables), and for pairs moved by one joint. A 256 x 256 table takes 64 KB.
  int self_table_cells_2d = 256;
  int self_table_cells_1d = 1024;
  /// The self padding the tables certify: a checker uses them when its own self padding is
  /// at most this.
  double self_table_padding = 0.0;
  /// Pair blocks (pair_blocks.h): a block keeps its ball when, on 256 random states of the
  /// group, the ball rules it out often enough to save at least this many per-pair sphere
  /// tests per state (the ball test itself costs about one). 0 keeps every ball.
  double pair_block_min_saving = 1.5;
  /// Sphere chains (sphere_chain.h): a link keeps its chain when, on 256 random states of
  /// the group where the clearance grid does not clear its sphere, the chain settles the link
  /// (clear, or a collision) on at least this fraction of them, times 1 + points / 8 (its
  /// lookups must save more than they cost). 0 keeps every chain.
  double chain_min_settled = 0.25;
  /// The base-scene table (base_scene_table.h) of a planar base: at most about this many
  /// cells (0: no table; one byte each), certified at this scene padding (a checker uses its
  /// colliding cells at a scene padding of at least this, its free ones at most this).
  std::size_t base_table_cells = std::size_t(1) << 16;
  double base_table_padding = 0.0;
};

class CollisionModel {
 public:
  /// One convex collision element of a link with geometry.
  /// An element: its own bounds (ElementShapes: bounding sphere in the link frame, local box
  /// for the oriented-box stage, inner balls and box, all in the shape frame) and where it
  /// sits in the model.
  struct Element : ElementShapes {
    int link = -1;                             ///< model link index
    int slot = -1;                             ///< index into slots()
    const CollisionElement* source = nullptr;  ///< in robot()
    bool identity_LS = false;  ///< source->X_LS is exactly the identity (X_WS = X_WL)
    /// The same shape pose and sphere centre in the frame of the slot's pose link (see Slot):
    /// what the sweep uses when the held joints are at held().
    Eigen::Isometry3d X_PS = Eigen::Isometry3d::Identity();
    bool identity_PS = false;
    Eigen::Vector3d center_P = Eigen::Vector3d::Zero();
    /// The radius of the element when its shape is a sphere (centred at the shape frame's
    /// origin), else negative: the ball stage (ball_stage.h) decides its pairs.
    double ball_radius = -1.0;
  };
  /// A point of an element's chain of balls (sphere_chain.h), in the link frame and in the
  /// frame of the slot's pose link, with the radii of its outer ball and of its inner ball
  /// (-infinity: none); `element` counts from the slot's first element.
  struct ChainPoint {
    Eigen::Vector3d c_L = Eigen::Vector3d::Zero();
    Eigen::Vector3d c_P = Eigen::Vector3d::Zero();
    double outer = 0.0;
    double inner = 0.0;
    int element = 0;
  };
  /// A link with geometry.
  struct Slot {
    int link = -1;
    /// Its pose link (pose_links.h) and its sphere's centre in that link's frame.
    int pose_link = -1;
    Eigen::Vector3d center_P = Eigen::Vector3d::Zero();
    bool moves = false;     ///< moves with the group
    int first_element = 0;  ///< elements [first_element, first_element + num_elements)
    int num_elements = 0;
    Eigen::Vector3d center_L = Eigen::Vector3d::Zero();  ///< bounding sphere of all elements
    double radius = 0.0;
    /// Its elements' chain points, chainPoints()[first_chain, first_chain + num_chain), the
    /// farthest from the sphere's centre first; none when they add nothing to the sphere (or
    /// the slot has more than 64 elements).
    int first_chain = 0;
    int num_chain = 0;
    std::vector<int> obstacles;  ///< kept obstacles this slot is checked against
    BoxSoa boxes;                ///< their world boxes, in the same order
    /// The same obstacles as bits (kept obstacle indices), when the clearance grid has
    /// candidate lists (ClearanceGrid::candidates); empty otherwise.
    std::vector<std::uint64_t> obstacle_bits;
    /// Reach in the world (moving slots): every pose of the link stays within reach_radius of
    /// a point of the box reach_center_W +- reach_half_W. The box is flat (a ball) unless
    /// prismatic group joints slide the chain without turning it (a mobile base's x and y).
    Eigen::Vector3d reach_center_W = Eigen::Vector3d::Zero();
    Eigen::Vector3d reach_half_W = Eigen::Vector3d::Zero();
    double reach_radius = 0.0;
    /// Its bit in the base-scene table's cells (0: not tabled).
    std::uint8_t base_bit = 0;
  };
  struct SelfPair {
    int a = -1, b = -1;       ///< slots
    int table = -1;           ///< index into selfTables(), or -1
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
  /// Computes only the slots' pose links: enough for the sweep when the state's held joints
  /// are at held() (heldMatch()).
  const Kinematics& sweepKinematics() const { return sweep_kin_; }
  /// Every active joint outside the group is at its held() value (exactly; NaN never is).
  bool heldMatch(const double* q) const {
    for (int a : held_active_)
      if (!(q[a] == held_[a])) return false;
    return true;
  }
  /// Every value finite, every group joint within its limits (continuous joints: any value),
  /// every joint outside the group at its held value or within its limits: the states the
  /// model's bounds hold for; a ball joint's quaternion also needs a norm of at least
  /// kMinQuaternionNorm (multi_dof.h), and a multi-DOF joint that the group does not move
  /// (the Panda's floating virtual joint) must be at its held values.
  bool withinBounds(const double* q) const;
  /// withinBounds() and heldMatch() of eight states at once, value j of state l at qs[8 j + l]:
  /// bit l set when state l passes both. kAvx2 compares four lanes at a time where the CPU
  /// has it, any other path two; the comparisons, and so the answers, are the same.
  unsigned boundedHeldLanes(const double* qs, SimdPath path = SimdPath::kSse2) const;

  const Scene& scene() const { return scene_; }  ///< kept obstacles only
  const std::vector<int>& groupActive() const { return group_active_; }
  const std::vector<double>& held() const { return held_; }
  const std::vector<Element>& elements() const { return elements_; }
  const std::vector<Slot>& slots() const { return slots_; }
  const std::vector<ChainPoint>& chainPoints() const { return chain_; }
  /// Element e's chain of balls (sphere_chain.h, in its shape frame), whether or not its slot
  /// keeps it among the chainPoints(): the robot's element cache's (element_shapes_cache.h).
  const SphereChain& elementChain(int e) const {
    return (*shapes_)[std::size_t(element_shape_[std::size_t(e)])].chain;
  }
  const std::vector<SelfPair>& selfPairs() const { return self_pairs_; }
  const SelfPairTables& selfTables() const { return self_tables_; }
  const std::vector<PairBlock>& pairBlocks() const { return pair_blocks_; }
  /// The planar base's table against the scene (empty without one).
  const BaseSceneTable& baseTable() const { return base_table_; }
  /// World boxes and oriented boxes of the kept obstacles.
  const std::vector<Aabb>& obstacleBoxes() const { return boxes_; }
  const std::vector<Obb>& obstacleObbs() const { return obbs_; }
  /// Half extents of a box inside obstacle o, centred and turned as obstacleObbs()[o]: the
  /// obstacle itself when it is a box, else the inner box of a cylinder, capsule or ellipsoid
  /// (inner_shapes.h: a cylinder's square section), else negative. The inner stage tests balls and
  /// boxes against it.
  const Eigen::Vector3d& obstacleBoxHalf(int o) const { return inner_half_[o]; }
  /// Lower bounds on the distance to the obstacle boxes over the region the moving links
  /// reach: the first test of the sweep for each link sphere.
  const ClearanceGrid& clearanceGrid() const { return grid_; }
  /// The slots' spheres (slot k's is sphere k), for the sweep's first pass.
  const SlotSpheres& slotSpheres() const { return slot_spheres_; }

  std::size_t obstaclesBefore() const { return obstacles_before_; }
  /// A lower bound on the distance of any moving link to any obstacle pruned for it
  /// (infinity when none was pruned): clearance never exceeds what the pruning guarantees.
  double prunedClearance() const { return pruned_gap_; }
  std::size_t scenePairs() const { return scene_pairs_; }
  std::size_t scenePairsBefore() const { return scene_pairs_before_; }
  /// Self pairs tested behind a block ball first (pair_blocks.h).
  std::size_t pairsBehindBlockBalls() const;
  /// e.g. "kept 12 of 40 obstacles, 60 of 400 robot-scene link pairs, 21 of 55 self link pairs"
  std::string summary() const;
  std::vector<std::string> warnings;

 private:
  RobotModel foldedRobot() const;
  void buildBounds();
  void buildSlots();
  /// The slot's chain points (sphere_chain.h), when they add to its sphere; `cached`: its
  /// elements' entries in the element cache.
  void addChain(Slot& s, const CachedElementShapes* cached);
  /// Drops the chains that do not pay on random states of the group (after the grid), then
  /// gives the grid its upper bounds from `untouchable` where chains remain.
  void keepPayingChains(double min_settled, const std::vector<Obb>& untouchable);
  void placeOnPoseLinks();
  void computeReach(const std::vector<Eigen::Isometry3d>& X_WL);
  void buildSelfPairs(const Srdf* srdf, const CollisionModelOptions& options);
  /// Returns the kept box obstacles that no moving link may touch (the grid's upper bounds).
  std::vector<Obb> pruneObstacles(const CollisionModelOptions& options);
  void buildSelfTables(const CollisionModelOptions& options);

  std::shared_ptr<const RobotModel> robot_;
  Kinematics kin_;
  Kinematics sweep_kin_;
  Scene scene_;
  std::vector<int> group_active_;
  std::vector<double> held_;
  std::vector<int> held_active_;  ///< active joints outside the group
  std::vector<char> in_group_;    ///< per active joint: in the group
  /// Per active joint: a value of a multi-DOF joint that the group does not move; the
  /// kinematics fold the joint at its held values (foldedRobot), so states must hold it there.
  std::vector<char> frozen_;
  std::vector<char> moves_;  ///< per link: moves with the group
  /// withinBounds() per active joint: the range a value must lie in (+-DBL_MAX without
  /// limits, so that the range test alone rejects NaN and infinities; a frozen value's range
  /// is its held value), and a held value accepted outside the range (a joint outside the
  /// group held outside its limits), else NaN, which no value equals.
  std::vector<double> range_lower_, range_upper_, range_held_;
  std::vector<int> quaternions_;  ///< the first value of each quaternion
  std::vector<Element> elements_;
  std::shared_ptr<const std::vector<CachedElementShapes>> shapes_;  ///< the robot's cache entry
  std::vector<int> element_shape_;  ///< per element: its index in *shapes_
  std::vector<Slot> slots_;
  std::vector<ChainPoint> chain_;
  std::vector<SelfPair> self_pairs_;
  std::vector<PairBlock> pair_blocks_;
  SelfPairTables self_tables_;
  BaseSceneTable base_table_;
  std::vector<Aabb> boxes_;
  std::vector<Obb> obbs_;
  std::vector<Eigen::Vector3d> inner_half_;
  ClearanceGrid grid_;
  SlotSpheres slot_spheres_;
  SelfCollisionPairs self_report_;
  std::size_t obstacles_before_ = 0;
  double pruned_gap_ = std::numeric_limits<double>::infinity();
  std::size_t scene_pairs_ = 0;
  std::size_t scene_pairs_before_ = 0;
};

}  // namespace dss
