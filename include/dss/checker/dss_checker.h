// The DSS state checker: the model's sweep with the exact DSS decision as its narrow phase.
//
// check(q): bounds first (non-finite or out-of-bounds values are invalid), then a planar
// base's table against the scene (base_scene_table.h) and the self-pair tables (a cell
// certified colliding needs no pose), then forward kinematics -- of the pose
// links alone when the held joints are at their held values -- into per-thread scratch, then
// the sweep, stopping at the first collision. DSS answers at the iteration cap count as
// collisions (and are counted).
//
// clearance(q): a guaranteed lower bound on the distance from the robot to the scene and
// between checked self pairs (beyond the paddings), within a tolerance: the largest extra
// padding r, found by doubling then bisection, for which exact DSS proves every pair farther
// apart than its padding + r.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "dss/checker/state_batch.h"
#include "dss/checker/state_checker.h"
#include "dss/core/result.h"

namespace dss {

struct DssCheckerSettings {
  Options options;             ///< mode (exact by default) and iteration cap
  double scene_padding = 0.0;  ///< "free" means distance > padding to every obstacle
  double self_padding = 0.0;
  bool obb_stage = true;  ///< the sweep's oriented-box stage (and inner balls)
  /// clearance(): the returned lower bound is within this of the true clearance (metres), up
  /// to clearance_max (returned when every pair is at least that far apart).
  double clearance_tolerance = 1e-3;
  double clearance_max = 10.0;
};

class DssChecker : public StateChecker {
 public:
  using Settings = DssCheckerSettings;
  explicit DssChecker(std::shared_ptr<const CollisionModel> model, const Settings& settings = {});

  std::string name() const override { return "dss"; }
  const Settings& settings() const { return settings_; }

  /// 0 for a colliding or invalid state, else a lower bound on the clearance within
  /// settings().clearance_tolerance (capped at settings().clearance_max and at what the
  /// model's obstacle pruning guarantees).
  double clearance(const double* q) const;

  /// The check of state q (counted as check() counts) with its link poses already computed by
  /// model().kinematics() into X_WL: the continuous motion check reuses the poses of its
  /// sub-motions' ends. True for a colliding or invalid state.
  bool collidesWithPoses(const double* q, const Eigen::Isometry3d* X_WL) const;

  /// The instruction set of freeStates' batched pass (activeSimdPath() by default; kScalar:
  /// no batched pass, every state to check()). Set before the checker is shared.
  void setBatchPath(SimdPath path) { batch_path_ = path; }
  SimdPath batchPath() const { return batch_path_; }
  const StateBatch& batch() const { return batch_; }
  /// An enabled batch on the AVX2 path (where the CPU has it).
  bool batchesPay() const override {
    return batch_.enabled() && batch_path_ == SimdPath::kAvx2 && simdPathAvailable(SimdPath::kAvx2);
  }

 private:
  bool collidesWithinBounds(const double* q, CounterSlots::Slot& counters) const override;
  /// The batch's lanes proven free (state_batch.h).
  unsigned provenFree(const double* lanes, int n) const override;
  /// The sweep at these paddings for a state whose poses are in X_WL (the pose links with
  /// `pose_links`, else every slot's own link); `skip`: the tables' flags for the state.
  /// `base_free`: the base-scene table's bits for the state (none by default).
  bool collidesAt(const Eigen::Isometry3d* X_WL, bool pose_links, const unsigned char* skip,
                  double scene_padding, double self_padding, std::uint8_t base_free = 0) const;

  Settings settings_;
  StateBatch batch_;
  SimdPath batch_path_ = activeSimdPath();
};

}  // namespace dss
