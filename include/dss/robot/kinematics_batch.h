// Forward kinematics of eight states at once, in float lanes: the steps of a Kinematics (its
// constant frames, joints and reference links), one state per lane, for passes that only need
// the poses to within a known error (state_batch.h certifies free states with them and leaves
// every other state to the exact checker).
//
// Arms only: revolute joints (about an axis of the joint frame, or any axis) and fixed frames.
// A Kinematics with a prismatic, planar or floating step gives an unsupported batch. The angles
// are reduced by pi/2 in double before they are rounded to float, so that continuous joints at
// any value within 1e5 rad keep their accuracy; beyond that, and for non-finite values, the
// lane's poses are NaN.
//
// Error: every pose entry is within positionError() (translations, metres) or rotationError()
// (rotation entries) of the double kinematics for states whose angles are within 1e5 rad: a
// bound from the float roundings of each step, with a wide factor of safety (tests check the
// observed error against it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "dss/core/simd_path.h"
#include "dss/robot/kinematics.h"

namespace dss {

class KinematicsBatch {
 public:
  static constexpr int kLanes = 8;
  /// A pose in lanes: v[3 * k + i][l] is entry (i, k) of lane l's [R | t] (k = 3: t).
  struct Pose {
    float v[12][kLanes];
  };

  KinematicsBatch() = default;
  /// The steps of `kin` (which must outlive nothing: they are copied).
  explicit KinematicsBatch(const Kinematics& kin);

  bool supported() const { return supported_; }
  double positionError() const { return position_error_; }
  double rotationError() const { return rotation_error_; }
  /// Links written by compute (the Kinematics' updatedLinks()).
  const std::vector<int>& updatedLinks() const { return updated_; }

  /// q[j * kLanes + l]: active joint j's value in lane l. Writes the pose of every link of
  /// updatedLinks() to X[link] (X holds one Pose per model link). `path`: kAvx2 runs the AVX2
  /// build where the CPU has it; any other path the generic vectors (SSE2 on x86-64).
  void compute(const double* q, Pose* X, SimdPath path) const;

 private:
  struct Step {
    float m[4][3];      ///< the constant frame, as Kinematics::Step::m
    bool perm = false;  ///< its rotation a signed permutation: column j is +-column col[j]
    int col[3] = {0, 1, 2};
    std::int32_t flip[3] = {0, 0, 0};  ///< the sign bit where column j is negated, else 0
    int link = -1;
    int ref = -1;  ///< -1: the base pose
    /// 0: fixed; 1, 2, 3: rotation about x, y, z; 4: about `axis`
    int motion = 0;
    int q_index = 0;
    double multiplier = 1.0, offset = 0.0;
    float axis[3] = {0, 0, 0};
  };
  /// `wide`: compiled for AVX2 (lanes.h).
  void run(const double* q, Pose* X, bool wide) const;
  void computeGeneric(const double* q, Pose* X) const;
  void computeAvx2(const double* q, Pose* X) const;

  std::vector<Step> steps_;
  std::vector<int> updated_;
  int root_ = 0;
  float base_[4][3] = {};
  bool supported_ = false;
  double position_error_ = 0.0, rotation_error_ = 0.0;
};

}  // namespace dss
