// OMPL state validity checkers on a CollisionModel: DSS (the product) and FCL (the reference
// that MoveIt users know), with the same model, pruning, pairs and state mapping.
//
// isValid(state): bounds first (NaN/Inf or out-of-bounds values are invalid, never a crash),
// then forward kinematics into per-thread scratch (no allocation per call once a thread has
// warmed up; the only shared mutable state is a set of atomic counters), then robot vs scene
// and self pairs, stopping at the first collision. Both checkers are const and thread-safe.
//
// clearance() (DSS checker): a guaranteed lower bound on the distance from the robot to the
// scene and between checked self pairs (beyond the paddings), within a tolerance: the largest
// extra padding r, found by doubling then bisection, for which exact DSS proves every pair
// farther apart than its padding + r. specs_.clearanceComputationType is BOUNDED_APPROXIMATE
// (OMPL: "a lower bound on clearance is computed"). The FCL checker computes none (NONE).
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include <ompl/base/StateValidityChecker.h>

#include "dss/core/any_shape_query.h"
#include "dss/planning/collision_model.h"
#include "dss/planning/group_state_space.h"

namespace dss {

struct CheckerCounters {
  std::uint64_t checks = 0;      ///< isValid calls
  std::uint64_t invalid_input = 0;  ///< out of bounds or non-finite
  std::uint64_t collisions = 0;  ///< states found in collision
  std::uint64_t pair_tests = 0;  ///< narrow-phase calls
  std::uint64_t cap_hits = 0;    ///< DSS answers at the iteration cap (counted as collisions)
};

/// Common part: mapping, scratch, counters. Subclasses supply the narrow phase.
class ModelValidityChecker : public ompl::base::StateValidityChecker {
 public:
  ModelValidityChecker(const ompl::base::SpaceInformationPtr& si,
                       std::shared_ptr<const CollisionModel> model,
                       std::shared_ptr<const GroupStateMap> map, double scene_padding,
                       double self_padding);

  bool isValid(const ompl::base::State* state) const override;
  /// Validity of a full active-joint vector (no bounds check).
  bool isValidJoints(const double* q) const;

  virtual std::string name() const = 0;
  CheckerCounters counters() const;
  void resetCounters();
  const CollisionModel& model() const { return *model_; }
  const GroupStateMap& stateMap() const { return *map_; }
  void setObbStage(bool on) { obb_stage_ = on; }

 protected:
  /// `table_skip`: see CollisionModel::anyCollision (null: the sweep reads the tables itself).
  virtual bool collides(const double* q, const Eigen::Isometry3d* X_WL, const unsigned char* table_skip) const = 0;
  /// Poses (into X_WL) and collides() for one full active-joint vector, counted.
  bool checkJoints(const double* q, Eigen::Isometry3d* X_WL) const;

  std::shared_ptr<const CollisionModel> model_;
  std::shared_ptr<const GroupStateMap> map_;
  double scene_padding_ = 0.0;
  double self_padding_ = 0.0;
  bool obb_stage_ = true;
  /// collides() goes through CollisionModel::anyCollision with q: the self-pair tables may
  /// answer before any pose is computed, and when the held joints are at their held values
  /// the pose links (CollisionModel::sweepKinematics) are all it reads.
  bool sweep_poses_ = false;
  // Counters live in per-thread slots (one cache line each, a thread's slot chosen once), so
  // that threads checking in parallel never write to the same line; counters() sums them.
  struct alignas(64) CounterSlot {
    std::atomic<std::uint64_t> checks{0}, invalid_input{0}, collisions{0}, pair_tests{0}, cap_hits{0};
  };
  static constexpr int kCounterSlots = 16;
  mutable CounterSlot slots_[kCounterSlots];
  CounterSlot& slot() const;
};

struct DssCheckerSettings {
  Options options;  ///< mode (exact by default) and iteration cap
  Algorithm algorithm = Algorithm::kDss;
  double scene_padding = 0.0;  ///< "valid" means distance > padding to every obstacle
  double self_padding = 0.0;
  /// Oriented-box separating-axis stage of the shared sweep (CollisionModel::anyCollision).
  bool obb_stage = true;
  /// clearance(): the returned lower bound is within this of the true clearance (metres),
  /// up to clearance_max (returned when every pair is at least that far apart).
  double clearance_tolerance = 1e-3;
  double clearance_max = 10.0;
};

class DssValidityChecker : public ModelValidityChecker {
 public:
  using Settings = DssCheckerSettings;
  DssValidityChecker(const ompl::base::SpaceInformationPtr& si,
                     std::shared_ptr<const CollisionModel> model,
                     std::shared_ptr<const GroupStateMap> map, const Settings& settings = {});
  std::string name() const override { return "dss"; }
  const Settings& settings() const { return settings_; }
  /// 0 for an invalid state (or NaN/Inf/out of bounds), else a lower bound on the clearance
  /// within settings().clearance_tolerance.
  double clearance(const ompl::base::State* state) const override;

 protected:
  bool collides(const double* q, const Eigen::Isometry3d* X_WL, const unsigned char* table_skip) const override;

 private:
  bool collidesPadded(const double* q, const Eigen::Isometry3d* X_WL, double scene_padding,
                      double self_padding, const unsigned char* table_skip = nullptr) const;
  Settings settings_;
};

}  // namespace dss
