// Forward kinematics with fixed transforms folded in advance (see dss/robot/kinematics.h).
#include "dss/robot/kinematics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace dss {
namespace {

// sin and cos together, within about 2 ulp of libm for |x| < 1e5 (joint angles): Cody-Waite
// reduction by pi/2 with a 33-bit leading part (k * kPio2Hi is exact for |k| < 2^20), then
// Taylor polynomials on [-pi/4, pi/4] (truncation below 5e-17); the quadrant k mod 4 picks and
// negates them. Written without branches over arrays, so that the joints of a state are
// evaluated together: one joint's two polynomial chains are long and serial, and evaluated
// inside the kinematics loop they took about half of its time. Calling libm's sincos costs
// about as much as the rest of a kinematics step.
inline void fastSinCosArray(const double* x, double* s_out, double* c_out, int n) {
  constexpr double kPio2Hi = 0x1.921fb544p+0;  // M_PI_2 truncated to 33 significant bits
  constexpr double kPio2Mid = 0x1.0b46p-34;     // M_PI_2 - kPio2Hi, exact
  constexpr double kPio2Lo = 6.123233995736766e-17;  // pi/2 - M_PI_2
  static_assert(kPio2Hi + kPio2Mid == M_PI_2, "split of pi/2");
  // Round to nearest by the 1.5 * 2^52 trick (exact for |t| < 2^51, default rounding mode):
  // std::nearbyint is an out-of-line call without SSE4.1. The low bits of kRound + t are
  // those of the integer t (two's complement), so they give the quadrant too.
  constexpr double kRound = 0x1.8p52;
  constexpr std::uint64_t kSign = std::uint64_t(1) << 63;
  for (int i = 0; i < n; ++i) {
    const double shifted = x[i] * (2.0 / M_PI) + kRound;
    const double k = shifted - kRound;
    std::uint64_t bits;
    std::memcpy(&bits, &shifted, sizeof bits);
    const double r = ((x[i] - k * kPio2Hi) - k * kPio2Mid) - k * kPio2Lo;
    const double r2 = r * r;
    // 1/n! for the Taylor series
    const double s = r + r * r2 * (-1.0 / 6 + r2 * (1.0 / 120 + r2 * (-1.0 / 5040 + r2 * (1.0 / 362880 +
                     r2 * (-1.0 / 39916800 + r2 * (1.0 / 6227020800.0 + r2 * (-1.0 / 1307674368000.0)))))));
    const double c = 1.0 + r2 * (-0.5 + r2 * (1.0 / 24 + r2 * (-1.0 / 720 + r2 * (1.0 / 40320 + r2 * (-1.0 / 3628800 +
                     r2 * (1.0 / 479001600.0 + r2 * (-1.0 / 87178291200.0 + r2 * (1.0 / 20922789888000.0))))))));
    // Quadrant q = k mod 4: sin = (s, c, -s, -c)[q], cos = (c, -s, -c, s)[q].
    const std::uint64_t odd = bits & 1, half = (bits >> 1) & 1;
    const std::uint64_t swap = std::uint64_t(0) - odd;  // all ones for odd q
    std::uint64_t sb, cb;
    std::memcpy(&sb, &s, sizeof sb);
    std::memcpy(&cb, &c, sizeof cb);
    const std::uint64_t so = ((cb & swap) | (sb & ~swap)) ^ (kSign & (std::uint64_t(0) - half));
    const std::uint64_t co = ((sb & swap) | (cb & ~swap)) ^ (kSign & (std::uint64_t(0) - (half ^ odd)));
    std::memcpy(&s_out[i], &so, sizeof so);
    std::memcpy(&c_out[i], &co, sizeof co);
  }
}

}  // namespace

// URDF origins rotate by multiples of pi/2 more often than not, written as
// rpy="-1.5707963267948966 0 0" or, as in the Panda's URDF, "1.57079632679" (cos = 4.9e-12),
// and then R_c holds tiny entries where the file means 0. Entries within 1e-11 of 0 or +-1
// that form a signed permutation are taken as exactly that permutation: R * R_c is then a
// selection of columns. A frame moves by at most 1e-11 times its distance from the joint (10
// pm per metre), a thousand times below the float32 precision of STL mesh vertices (1e-7
// relative). Anything else stays general. (On the Panda this makes 6 of its 10 constant
// frames permutations instead of none.)
void Kinematics::classifyConstantFrame(Step* s) {
  s->frame = Step::Frame::kGeneral;
  s->p_nonzero = 0;
  for (int k = 0; k < 3; ++k)
    if (s->p_c[k] != 0.0) s->p_nonzero |= static_cast<unsigned char>(1u << k);
  constexpr double kTol = 1e-11;
  bool used[3] = {false, false, false};
  for (int j = 0; j < 3; ++j) {
    int one = -1;
    for (int i = 0; i < 3; ++i) {
      const double a = s->R_c(i, j);
      if (std::abs(a) <= kTol) continue;
      if (std::abs(std::abs(a) - 1.0) > kTol || one >= 0) return;
      one = i;
    }
    if (one < 0 || used[one]) return;
    used[one] = true;
    s->perm[j] = one;
    s->sign[j] = s->R_c(one, j) > 0 ? 1.0 : -1.0;
  }
  bool identity = true;
  for (int j = 0; j < 3; ++j) {
    identity = identity && s->perm[j] == j && s->sign[j] == 1.0;
    for (int i = 0; i < 3; ++i) s->R_c(i, j) = i == s->perm[j] ? s->sign[j] : 0.0;
  }
  s->frame = identity ? Step::Frame::kIdentity : Step::Frame::kSignedPermutation;
}

void sinCosForKinematics(double x, double* s, double* c) { fastSinCosArray(&x, s, c, 1); }

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
    s.p_c = X.translation();
    classifyConstantFrame(&s);
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
    s.trig = -1;
    if (s.motion == Motion::kRotX || s.motion == Motion::kRotY || s.motion == Motion::kRotZ) {
      s.trig = static_cast<int>(trig_steps_.size());
      trig_steps_.push_back(static_cast<int>(steps_.size()));
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
  // The sines and cosines of the axis-aligned revolute joints first, all together (see
  // fastSinCosArray), in blocks of kTrigBlock.
  constexpr int kTrigBlock = 32;
  double v[kTrigBlock], sn[kTrigBlock], cs[kTrigBlock];
  const int num_trig = static_cast<int>(trig_steps_.size());
  X_WL[root_] = X_WR_;
  int block_begin = 0, block_end = 0;
  int prev_link = -2;  // the link of the previous step, whose pose is in c0, c1, c2, p
  Eigen::Vector3d c0, c1, c2, p;
  // The step array and its size are read once: the stores into X_WL below would otherwise make
  // the compiler reload them every step.
  const Step* const steps = steps_.data();
  const std::size_t num_steps = steps_.size();
  const int* const trig_steps = trig_steps_.data();
  for (std::size_t i = 0; i < num_steps; ++i) {
    const Step& s = steps[i];
    if (s.trig >= block_end) {
      block_begin = block_end;
      const int n = std::min(kTrigBlock, num_trig - block_begin);
      for (int t = 0; t < n; ++t) {
        const Step& st = steps[trig_steps[block_begin + t]];
        v[t] = st.multiplier * q[st.q_index] + st.offset;
      }
      fastSinCosArray(v, sn, cs, n);
      block_end = block_begin + n;
    }
    // The reference frame's columns: from the previous step when it is the reference (a
    // chain), so that they come from registers rather than from the stores just made.
    Eigen::Vector3d a0, a1, a2, at;
    if (s.ref == prev_link) {
      a0 = c0; a1 = c1; a2 = c2; at = p;
    } else {
      const Eigen::Matrix4d& A = (s.ref < 0 ? X_WR_ : X_WL[s.ref]).matrix();
      a0 = A.col(0).head<3>(); a1 = A.col(1).head<3>(); a2 = A.col(2).head<3>(); at = A.col(3).head<3>();
    }
    const Eigen::Vector3d* a[3] = {&a0, &a1, &a2};
    switch (s.frame) {
      case Step::Frame::kIdentity: c0 = a0; c1 = a1; c2 = a2; break;
      case Step::Frame::kSignedPermutation:
        c0 = s.sign[0] * *a[s.perm[0]];
        c1 = s.sign[1] * *a[s.perm[1]];
        c2 = s.sign[2] * *a[s.perm[2]];
        break;
      default:
        c0 = a0 * s.R_c(0, 0) + a1 * s.R_c(1, 0) + a2 * s.R_c(2, 0);
        c1 = a0 * s.R_c(0, 1) + a1 * s.R_c(1, 1) + a2 * s.R_c(2, 1);
        c2 = a0 * s.R_c(0, 2) + a1 * s.R_c(1, 2) + a2 * s.R_c(2, 2);
        break;
    }
    // p = A.linear() * p_c + A.translation(), skipping the zero terms of p_c
    p = at;
    if (s.p_nonzero & 1u) p += s.p_c[0] * a0;
    if (s.p_nonzero & 2u) p += s.p_c[1] * a1;
    if (s.p_nonzero & 4u) p += s.p_c[2] * a2;
    auto rotate = [](Eigen::Vector3d& ca, Eigen::Vector3d& cb, double sv, double c) {
      // rotation about the third axis mixes these two columns
      const Eigen::Vector3d x = ca, y = cb;
      ca = c * x + sv * y;
      cb = c * y - sv * x;
    };
    switch (s.motion) {
      case Motion::kNone: break;
      case Motion::kRotX: rotate(c1, c2, sn[s.trig - block_begin], cs[s.trig - block_begin]); break;
      case Motion::kRotY: rotate(c2, c0, sn[s.trig - block_begin], cs[s.trig - block_begin]); break;
      case Motion::kRotZ: rotate(c0, c1, sn[s.trig - block_begin], cs[s.trig - block_begin]); break;
      case Motion::kRotAxis: {
        const Eigen::Matrix3d M = Eigen::AngleAxisd(s.multiplier * q[s.q_index] + s.offset, s.axis).toRotationMatrix();
        const Eigen::Vector3d x = c0, y = c1, z = c2;
        c0 = x * M(0, 0) + y * M(1, 0) + z * M(2, 0);
        c1 = x * M(0, 1) + y * M(1, 1) + z * M(2, 1);
        c2 = x * M(0, 2) + y * M(1, 2) + z * M(2, 2);
        break;
      }
      case Motion::kTransX: p += (s.multiplier * q[s.q_index] + s.offset) * c0; break;
      case Motion::kTransY: p += (s.multiplier * q[s.q_index] + s.offset) * c1; break;
      case Motion::kTransZ: p += (s.multiplier * q[s.q_index] + s.offset) * c2; break;
      case Motion::kTransAxis:
        p += (s.multiplier * q[s.q_index] + s.offset) * (c0 * s.axis.x() + c1 * s.axis.y() + c2 * s.axis.z());
        break;
    }
    // Column-major 4x4, written entry by entry (the comma initializer tests alignment).
    double* X = X_WL[s.link].matrix().data();
    X[0] = c0.x(), X[1] = c0.y(), X[2] = c0.z(), X[3] = 0.0;
    X[4] = c1.x(), X[5] = c1.y(), X[6] = c1.z(), X[7] = 0.0;
    X[8] = c2.x(), X[9] = c2.y(), X[10] = c2.z(), X[11] = 0.0;
    X[12] = p.x(), X[13] = p.y(), X[14] = p.z(), X[15] = 1.0;
    prev_link = s.link;
  }
}

std::vector<Eigen::Isometry3d> Kinematics::linkPoses(const std::vector<double>& q) const {
  std::vector<Eigen::Isometry3d> X(num_links_, Eigen::Isometry3d::Identity());
  computeLinkPoses(q.data(), X.data());
  return X;
}

}  // namespace dss
