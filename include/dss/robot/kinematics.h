// Forward kinematics of a RobotModel, allocation-free per query.
//
// Compiled once from the model: links are visited in the model's depth-first order (parents
// first); each computed link pose is its reference pose (the nearest computed ancestor whose
// parent joint moves, or the base) times one constant transform (fixed joints folded in
// advance) times the joint motion. By default only the links that carry geometry and the
// moving links that lead to them are computed; links outside that set are left untouched in
// the output array (pass all_links = true to compute every link). Joint axes along +-x, +-y,
// +-z (nearly all real robots) take a short path with one sin/cos pair (computed two joints at
// a time) and 12 products; constant frames turned by multiples of pi/2 (most URDF origins)
// select and negate columns instead of multiplying by a rotation; poses are computed a column
// (four doubles) at a time, with AVX2 where the CPU has it (dss/core/simd_path.h: every path
// gives the same poses, bit for bit). A moving link without geometry that only leads to the next
// computed link (the x and y links of a planar joint, the position links of a floating one)
// is not written: its translation is applied in that next step (updatedLinks() leaves it out).
// Mimic joints read their leader's value: q = multiplier * q_leader + offset.
// Thread safety: const queries on one Kinematics may run concurrently. A Kinematics keeps
// no reference to its RobotModel.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "dss/core/simd_path.h"
#include "dss/robot/robot_model.h"

namespace dss {

class Kinematics {
 public:
  explicit Kinematics(const RobotModel& model, bool all_links = false);
  /// Computes the poses of the links flagged in `wanted` (one flag per model link) and of the
  /// moving links that lead to them; every other link is left untouched. Throws
  /// std::invalid_argument when the flags do not match the model.
  Kinematics(const RobotModel& model, const std::vector<char>& wanted);

  /// The pose of the root link in the world (identity by default).
  void setBasePose(const Eigen::Isometry3d& X_WR) { X_WR_ = X_WR; }

  /// joint_values: one value per active joint (RobotModel::active_joints order).
  /// X_WL: one pose per link (RobotModel::links order); only updatedLinks() are written.
  void computeLinkPoses(const double* joint_values, Eigen::Isometry3d* X_WL) const;
  /// The same on a given instruction-set path (tests compare them); an unavailable path
  /// (simdPathAvailable) takes the best available one.
  void computeLinkPoses(const double* joint_values, Eigen::Isometry3d* X_WL, SimdPath path) const;
  /// The path computeLinkPoses takes (activeSimdPath() when constructed).
  SimdPath simdPath() const { return path_; }

  /// Convenience (allocates): all links' poses, untouched entries identity.
  std::vector<Eigen::Isometry3d> linkPoses(const std::vector<double>& joint_values) const;

  /// The value of any joint (active, mimic or fixed = 0) for a state.
  double jointValue(const double* joint_values, int joint) const;

  /// Links written by computeLinkPoses, in the order they are computed.
  const std::vector<int>& updatedLinks() const { return updated_; }
  std::size_t numActiveJoints() const { return num_active_; }

 private:
  friend class KinematicsBatch;  // the same steps in float lanes (kinematics_batch.h)
  enum class Motion : unsigned char {
    kNone,
    kRotX,
    kRotY,
    kRotZ,
    kRotAxis,
    kTransX,
    kTransY,
    kTransZ,
    kTransAxis,
    kBall  // four values from q_index: a quaternion (x, y, z, w), normalised
  };
  struct Step {
    /// The constant transform from ref to the joint frame, as the 4x4 product needs it: m[j][i]
    /// holds entry (i, j) of [R_c | p_c] (column j = 3 is the translation).
    double m[4][3];
    Eigen::Vector3d axis;  // for kRotAxis / kTransAxis
    int link;
    int ref;            // computed link whose pose this one starts from; -1: the base pose
    int q_index;        // active joint index read
    int trig;           // kRotX/Y/Z: index into trig_args_; else -1
    double multiplier;  // sign of an axis-aligned axis, times the mimic multiplier
    double offset;      // mimic offset times the same sign
    bool identity_R;    // R_c is exactly the identity: only the translation applies
    /// R_c is a signed permutation (joint origins turned by multiples of pi/2): column j of
    /// the product is sign[j] times column col[j] of the reference pose, with no sum.
    bool perm;
    int col[3];
    int perm_code;  // col as a number, 2 * col[0] + (col[1] < col[2] ? 0 : 1)
    double sign[3];
    Motion motion;
    /// Translations along the columns of the pose (after the constant frame, before the
    /// motion): the steps of links that nothing else needs, folded into this one (the x and y of
    /// a planar joint, the position of a floating one). Translations commute, and the folded
    /// steps' own frames are the identity, so the pose is the same.
    struct Shift {
      int q_index;
      int col;
      double multiplier, offset;
    };
    int num_shifts = 0;
    Shift shifts[3];
    /// A signed permutation (or the identity) then a rotation about axis x, y or z, and nothing
    /// else: 3 * perm_code + axis, the case of run()'s combined switch; -1 otherwise.
    int perm_rotation = -1;
  };

  static void setConstantFrame(Step* s, const Eigen::Isometry3d& X);
  /// computeLinkPoses with a column type: four doubles as a vector (SSE2 or AVX2, by the
  /// function it is inlined in) or as a plain struct (the scalar path).
  template <class Column>
  void run(const double* q, Eigen::Isometry3d* X_WL) const;
  /// The path's function (an available path).
  void computeOn(SimdPath path, const double* q, Eigen::Isometry3d* X_WL) const;
  void computeScalar(const double* q, Eigen::Isometry3d* X_WL) const;
  void computeSse2(const double* q, Eigen::Isometry3d* X_WL) const;
  void computeAvx2(const double* q, Eigen::Isometry3d* X_WL) const;
  /// Folds axis-aligned translation steps of links that are not wanted into the step that
  /// follows them (Step::shifts), where that step starts from their pose with an identity frame.
  void foldTranslations(const std::vector<char>& wanted);

  std::vector<Step> steps_;
  /// The angle of each step with an axis-aligned rotation, in order: multiplier * q[q_index] +
  /// offset, read together before the steps (contiguous, not through the steps).
  static constexpr int kTrigBlock = 32;  ///< angles evaluated together (see run)
  struct TrigArg {
    int q_index;
    double multiplier, offset;
  };
  std::vector<TrigArg> trig_args_;
  /// Every angle is q[trig_first_ + t] itself (multiplier 1, offset 0), at most kTrigBlock of
  /// them: the angles are read as one run of q.
  bool trig_run_ = false;
  int trig_first_ = 0;
  std::vector<int> updated_;
  struct JointRef {  // copied, so that a Kinematics does not point into its model
    int active_index;
    int mimic_active;
    double mimic_multiplier;
    double mimic_offset;
  };
  std::vector<JointRef> joints_;
  int root_ = 0;
  std::size_t num_links_ = 0;
  std::size_t num_active_ = 0;
  Eigen::Isometry3d X_WR_ = Eigen::Isometry3d::Identity();
  SimdPath path_ = activeSimdPath();
};

/// The sine and cosine that Kinematics uses (inlined there; exposed for tests): within a
/// few ulp of std::sin / std::cos for |x| < 1e5.
void sinCosForKinematics(double x, double* s, double* c);

}  // namespace dss
