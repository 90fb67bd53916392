// Forward kinematics with fixed transforms folded in advance (see dss/robot/kinematics.h).
#include "dss/robot/kinematics.h"

#include <cmath>

namespace dss {
namespace {

// sin and cos together, inlined, within about 2 ulp of libm for |x| < 1e5 (joint angles):
// Cody-Waite reduction by pi/2 with a 33-bit leading part (k * kPio2Hi is exact for |k| <
// 2^20), then Taylor polynomials on [-pi/4, pi/4] (truncation below 5e-17). Calling libm's
// sincos costs about as much as the rest of a kinematics step.
inline void fastSinCos(double x, double* s_out, double* c_out) {
  constexpr double kPio2Hi = 0x1.921fb544p+0;  // M_PI_2 truncated to 33 significant bits
  constexpr double kPio2Mid = 0x1.0b46p-34;     // M_PI_2 - kPio2Hi, exact
  constexpr double kPio2Lo = 6.123233995736766e-17;  // pi/2 - M_PI_2
  static_assert(kPio2Hi + kPio2Mid == M_PI_2, "split of pi/2");
  // Round to nearest by the 1.5 * 2^52 trick (exact for |t| < 2^51, default rounding mode):
  // std::nearbyint is an out-of-line call without SSE4.1.
  constexpr double kRound = 0x1.8p52;
  const double k = (x * (2.0 / M_PI) + kRound) - kRound;
  const double r = ((x - k * kPio2Hi) - k * kPio2Mid) - k * kPio2Lo;
  const double r2 = r * r;
  // 1/n! for the Taylor series
  const double s = r + r * r2 * (-1.0 / 6 + r2 * (1.0 / 120 + r2 * (-1.0 / 5040 + r2 * (1.0 / 362880 +
                   r2 * (-1.0 / 39916800 + r2 * (1.0 / 6227020800.0 + r2 * (-1.0 / 1307674368000.0)))))));
  const double c = 1.0 + r2 * (-0.5 + r2 * (1.0 / 24 + r2 * (-1.0 / 720 + r2 * (1.0 / 40320 + r2 * (-1.0 / 3628800 +
                   r2 * (1.0 / 479001600.0 + r2 * (-1.0 / 87178291200.0 + r2 * (1.0 / 20922789888000.0))))))));
  switch (static_cast<long long>(k) & 3) {
    case 0: *s_out = s; *c_out = c; break;
    case 1: *s_out = c; *c_out = -s; break;
    case 2: *s_out = -s; *c_out = -c; break;
    default: *s_out = -c; *c_out = s; break;
  }
}

}  // namespace

void sinCosForKinematics(double x, double* s, double* c) { fastSinCos(x, s, c); }

Kinematics::Kinematics(const RobotModel& model, bool all_links)
    : root_(model.root_link), num_links_(model.links.size()), num_active_(model.active_joints.size()) {
  const std::size_t n = model.links.size();
  for (const auto& j : model.joints)
    joints_.push_back({j.active_index, j.mimic_active, j.mimic_multiplier, j.mimic_offset});
  // needed[l]: l carries geometry or leads to a link that does.
  std::vector<char> needed(n, all_links ? 1 : 0);
  for (std::size_t l = 0; l < n; ++l)
    if (model.links[l].hasGeometry())
      for (int k = static_cast<int>(l); k >= 0 && !needed[k]; k = model.links[k].parent_link) needed[k] = 1;
  // computed[l]: the pose is written. A needed link is computed when it has geometry, is the
  // root, or its parent joint moves (fixed links without geometry are folded away).
  std::vector<char> computed(n, 0);
  for (std::size_t l = 0; l < n; ++l) {
    const RobotLink& link = model.links[l];
    computed[l] = needed[l] && (all_links || link.hasGeometry() || link.parent_joint < 0 ||
                                model.joints[link.parent_joint].isMoving());
  }
  computed[root_] = 1;
  updated_.push_back(root_);
  for (std::size_t l = 0; l < n; ++l) {  // depth-first order: parents first
    if (!computed[l] || static_cast<int>(l) == root_) continue;
    const RobotLink& link = model.links[l];
    const RobotJoint& joint = model.joints[link.parent_joint];
    // Constant part: from the nearest computed ancestor through fixed joints to the joint frame.
    Eigen::Isometry3d X = joint.X_PJ;
    int ref = link.parent_link;
    while (!computed[ref]) {
      const RobotJoint& pj = model.joints[model.links[ref].parent_joint];  // fixed, by construction
      X = pj.X_PJ * X;
      ref = model.links[ref].parent_link;
    }
    Step s;
    s.link = static_cast<int>(l);
    s.ref = ref == root_ ? -1 : ref;
    s.R_c = X.linear();
    s.rotates = !s.R_c.isIdentity(0.0);  // exact identity only: skipping must not change results
    s.p_c = X.translation();
    s.axis = joint.axis;
    s.multiplier = 1.0;
    s.offset = 0.0;
    s.q_index = joint.active_index;
    if (joint.mimic_active >= 0) {
      s.q_index = joint.mimic_active;
      s.multiplier = joint.mimic_multiplier;
      s.offset = joint.mimic_offset;
    }
    s.motion = Motion::kNone;
    if (joint.isMoving()) {
      const bool rot = joint.type != JointType::kPrismatic;
      s.motion = rot ? Motion::kRotAxis : Motion::kTransAxis;
      for (int k = 0; k < 3; ++k) {
        const double a = joint.axis[k];
        if (std::abs(a) == 1.0) {
          s.motion = static_cast<Motion>(static_cast<int>(rot ? Motion::kRotX : Motion::kTransX) + k);
          s.multiplier *= a;
          s.offset *= a;
        }
      }
    }
    steps_.push_back(s);
    updated_.push_back(s.link);
  }
}

double Kinematics::jointValue(const double* q, int joint) const {
  const JointRef& j = joints_[joint];
  if (j.active_index >= 0) return q[j.active_index];
  if (j.mimic_active >= 0) return j.mimic_multiplier * q[j.mimic_active] + j.mimic_offset;
  return 0.0;
}

void Kinematics::computeLinkPoses(const double* q, Eigen::Isometry3d* X_WL) const {
  X_WL[root_] = X_WR_;
  for (const Step& s : steps_) {
    const Eigen::Isometry3d& X_ref = s.ref < 0 ? X_WR_ : X_WL[s.ref];
    Eigen::Isometry3d& X = X_WL[s.link];
    Eigen::Matrix3d R = s.rotates ? Eigen::Matrix3d(X_ref.linear() * s.R_c) : Eigen::Matrix3d(X_ref.linear());
    Eigen::Vector3d p = X_ref.linear() * s.p_c + X_ref.translation();
    if (s.motion != Motion::kNone) {
      const double v = s.multiplier * q[s.q_index] + s.offset;
      switch (s.motion) {
        case Motion::kRotX:
        case Motion::kRotY:
        case Motion::kRotZ: {
          // Rotation about local axis k mixes the two other columns.
          const int k = static_cast<int>(s.motion) - static_cast<int>(Motion::kRotX);
          const int a = (k + 1) % 3, b = (k + 2) % 3;
          double sn, c;
          fastSinCos(v, &sn, &c);
          const Eigen::Vector3d ca = R.col(a), cb = R.col(b);
          R.col(a) = c * ca + sn * cb;
          R.col(b) = c * cb - sn * ca;
          break;
        }
        case Motion::kRotAxis: R = R * Eigen::AngleAxisd(v, s.axis).toRotationMatrix(); break;
        case Motion::kTransX:
        case Motion::kTransY:
        case Motion::kTransZ:
          p += v * R.col(static_cast<int>(s.motion) - static_cast<int>(Motion::kTransX));
          break;
        case Motion::kTransAxis: p += v * (R * s.axis); break;
        default: break;
      }
    }
    X.linear() = R;
    X.translation() = p;
    X.makeAffine();
  }
}

std::vector<Eigen::Isometry3d> Kinematics::linkPoses(const std::vector<double>& q) const {
  std::vector<Eigen::Isometry3d> X(num_links_, Eigen::Isometry3d::Identity());
  computeLinkPoses(q.data(), X.data());
  return X;
}

}  // namespace dss
