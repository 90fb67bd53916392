// Forward kinematics with fixed transforms folded in advance (see dss/robot/kinematics.h).
#include "dss/robot/kinematics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "dss/robot/multi_dof.h"

namespace dss {
namespace {

using Pair = double __attribute__((vector_size(16)));
using PairBits = std::int64_t __attribute__((vector_size(16)));

inline Pair loadPair(const double* p) {
  Pair v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void storePair(double* p, Pair v) { std::memcpy(p, &v, sizeof v); }

// sin and cos together, within about 2 ulp of libm for |x| < 1e5 (joint angles; libm beyond):
// Cody-Waite reduction by pi/2 with a 33-bit leading part (k * kPio2Hi is exact for |k| < 2^20),
// then Taylor polynomials on [-pi/4, pi/4] (truncation below 5e-17); the quadrant k mod 4 picks and
// negates them. Without branches, two joints per SIMD pair, so that the joints of a state are
// evaluated together: one joint's two polynomial chains are long and serial, and evaluated
// inside the kinematics loop they took about half of its time. Calling libm's sincos costs
// about as much as the rest of a kinematics step. Reads and writes n rounded up to a whole
// number of lanes (two; four in the AVX2 kinematics): every lane forms the same operations.
template <class V, class VBits>
__attribute__((always_inline)) inline void fastSinCosLanes(const double* x, double* s_out,
                                                           double* c_out, int n) {
  constexpr int kLanes = sizeof(V) / sizeof(double);
  constexpr double kPio2Hi = 0x1.921fb544p+0;        // M_PI_2 truncated to 33 significant bits
  constexpr double kPio2Mid = 0x1.0b46p-34;          // M_PI_2 - kPio2Hi, exact
  constexpr double kPio2Lo = 6.123233995736766e-17;  // pi/2 - M_PI_2
  static_assert(kPio2Hi + kPio2Mid == M_PI_2, "split of pi/2");
  // Round to nearest by the 1.5 * 2^52 trick (exact for |t| < 2^51, default rounding mode):
  // std::nearbyint is an out-of-line call without SSE4.1. The low bits of kRound + t are
  // those of the integer t (two's complement), so they give the quadrant too.
  constexpr double kRound = 0x1.8p52;
  const VBits kSign = (VBits{} + 1) << 63;
  for (int i = 0; i < n; i += kLanes) {
    V xi;
    std::memcpy(&xi, x + i, sizeof xi);
    const V shifted = xi * (2.0 / M_PI) + kRound;
    const V k = shifted - kRound;
    const VBits bits = (VBits)shifted;
    const V r = ((xi - k * kPio2Hi) - k * kPio2Mid) - k * kPio2Lo;
    const V r2 = r * r;
    // 1/n! for the Taylor series
    const V s =
        r + r * r2 *
                (-1.0 / 6 +
                 r2 * (1.0 / 120 +
                       r2 * (-1.0 / 5040 +
                             r2 * (1.0 / 362880 + r2 * (-1.0 / 39916800 +
                                                        r2 * (1.0 / 6227020800.0 +
                                                              r2 * (-1.0 / 1307674368000.0)))))));
    const V c =
        1.0 + r2 * (-0.5 + r2 * (1.0 / 24 +
                                 r2 * (-1.0 / 720 +
                                       r2 * (1.0 / 40320 +
                                             r2 * (-1.0 / 3628800 +
                                                   r2 * (1.0 / 479001600.0 +
                                                         r2 * (-1.0 / 87178291200.0 +
                                                               r2 * (1.0 / 20922789888000.0))))))));
    // Quadrant q = k mod 4: sin = (s, c, -s, -c)[q], cos = (c, -s, -c, s)[q].
    const VBits odd = bits & 1, half = (bits >> 1) & 1;
    const VBits swap = 0 - odd;  // all ones for odd q
    const VBits sb = (VBits)s, cb = (VBits)c;
    const VBits so = ((cb & swap) | (sb & ~swap)) ^ (kSign & (0 - half));
    const VBits co = ((sb & swap) | (cb & ~swap)) ^ (kSign & (0 - (half ^ odd)));
    std::memcpy(s_out + i, &so, sizeof so);
    std::memcpy(c_out + i, &co, sizeof co);
    // Beyond the reduction's range (joints without limits, or limits far beyond a turn) libm
    // takes over: a rare branch, and every finite angle stays right.
    // (One test for the lanes together: |x| >= 1e5 in any of them, a NaN in none.)
    const VBits big = (VBits)((V)((VBits)xi & ~kSign) >= 1e5);
    VBits any = big;
    for (int l = 1; l < kLanes; ++l) any[0] |= big[l];
    if (any[0])
      for (int k = i; k < i + kLanes; ++k)
        if (std::abs(x[k]) >= 1e5) s_out[k] = std::sin(x[k]), c_out[k] = std::cos(x[k]);
  }
}

inline void fastSinCosArray(const double* x, double* s_out, double* c_out, int n) {
  fastSinCosLanes<Pair, PairBits>(x, s_out, c_out, n);
}

}  // namespace

// URDF origins rotate by multiples of pi/2 more often than not, written as
// rpy="-1.5707963267948966 0 0" or, as in the Panda's URDF, "1.57079632679" (cos = 4.9e-12),
// and then R_c holds tiny entries where the file means 0. Entries within 1e-11 of 0 or +-1
// that form a signed permutation are taken as exactly that permutation, so that the product
// with R_c selects columns without rounding. A frame moves by at most 1e-11 times its
// distance from the joint (10 pm per metre), a thousand times below the float32 precision of
// STL mesh vertices (1e-7 relative). Anything else stays as it is.
void Kinematics::setConstantFrame(Step* s, const Eigen::Isometry3d& X) {
  Eigen::Matrix3d R_c = X.linear();
  const Eigen::Vector3d p_c = X.translation();
  constexpr double kTol = 1e-11;
  bool used[3] = {false, false, false};
  int perm[3];
  bool permutation = true;
  for (int j = 0; j < 3 && permutation; ++j) {
    perm[j] = -1;
    for (int i = 0; i < 3; ++i) {
      const double a = R_c(i, j);
      if (std::abs(a) <= kTol) continue;
      if (std::abs(std::abs(a) - 1.0) > kTol || perm[j] >= 0) permutation = false;
      perm[j] = i;
    }
    if (perm[j] < 0 || used[perm[j]]) permutation = false;
    if (permutation) used[perm[j]] = true;
  }
  if (permutation)
    for (int j = 0; j < 3; ++j) {
      const double sign = R_c(perm[j], j) > 0 ? 1.0 : -1.0;
      for (int i = 0; i < 3; ++i) R_c(i, j) = i == perm[j] ? sign : 0.0;
    }
  s->identity_R = R_c == Eigen::Matrix3d::Identity();
  s->perm = permutation;
  for (int j = 0; j < 3; ++j) {
    s->col[j] = permutation ? perm[j] : j;
    s->sign[j] = permutation ? R_c(perm[j], j) : 1.0;
  }
  // The permutation's number in run()'s switch: the first column, then whether the other two
  // keep their order.
  s->perm_code = 2 * s->col[0] + (s->col[1] < s->col[2] ? 0 : 1);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) s->m[j][i] = R_c(i, j);
    s->m[3][i] = p_c[i];
  }
}

void sinCosForKinematics(double x, double* s, double* c) {
  const double in[2] = {x, 0.0};
  double so[2], co[2];
  fastSinCosArray(in, so, co, 1);
  *s = so[0];
  *c = co[0];
}

namespace {
std::vector<char> linksWithGeometry(const RobotModel& model, bool all_links) {
  std::vector<char> wanted(model.links.size(), all_links ? 1 : 0);
  for (std::size_t l = 0; l < model.links.size(); ++l)
    wanted[l] |= model.links[l].hasGeometry() ? 1 : 0;
  return wanted;
}
}  // namespace

Kinematics::Kinematics(const RobotModel& model, bool all_links)
    : Kinematics(model, linksWithGeometry(model, all_links)) {}

Kinematics::Kinematics(const RobotModel& model, const std::vector<char>& wanted)
    : root_(model.root_link),
      num_links_(model.links.size()),
      num_active_(model.active_joints.size()) {
  const std::size_t n = model.links.size();
  if (wanted.size() != n)
    throw std::invalid_argument("Kinematics: " + std::to_string(wanted.size()) +
                                " link flags for robot " + model.name + " with " +
                                std::to_string(n) + " links");
  for (const auto& j : model.joints)
    joints_.push_back({j.active_index, j.mimic_active, j.mimic_multiplier, j.mimic_offset});
  // needed[l]: l is wanted or leads to a link that is.
  std::vector<char> needed(n, 0);
  for (std::size_t l = 0; l < n; ++l)
    if (wanted[l])
      for (int k = static_cast<int>(l); k >= 0 && !needed[k]; k = model.links[k].parent_link)
        needed[k] = 1;
  // computed[l]: the pose is written. A needed link is computed when it is wanted, is the
  // root, or its parent joint moves (fixed links on the way are folded away).
  std::vector<char> computed(n, 0);
  for (std::size_t l = 0; l < n; ++l) {
    const RobotLink& link = model.links[l];
    computed[l] = needed[l] && (wanted[l] || link.parent_joint < 0 ||
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
    setConstantFrame(&s, X);
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
    if (joint.type == JointType::kBall) {
      s.motion = Motion::kBall;
    } else if (joint.isMoving()) {
      const bool rot = joint.type != JointType::kPrismatic;
      s.motion = rot ? Motion::kRotAxis : Motion::kTransAxis;
      for (int k = 0; k < 3; ++k) {
        const double a = joint.axis[k];
        if (std::abs(a) == 1.0) {
          s.motion =
              static_cast<Motion>(static_cast<int>(rot ? Motion::kRotX : Motion::kTransX) + k);
          s.multiplier *= a;
          s.offset *= a;
        }
      }
    }
    s.trig = -1;  // set by foldTranslations
    steps_.push_back(s);
    updated_.push_back(s.link);
  }
  foldTranslations(wanted);  // also numbers the axis-aligned rotations (trig_args_)
}

void Kinematics::foldTranslations(const std::vector<char>& wanted) {
  auto identityFrame = [](const Step& s) {
    if (!s.identity_R) return false;
    for (int i = 0; i < 3; ++i)
      if (s.m[3][i] != 0.0) return false;
    return true;
  };
  std::vector<int> uses(wanted.size(), 0);  // steps starting from each link's pose
  for (const Step& s : steps_)
    if (s.ref >= 0) ++uses[std::size_t(s.ref)];
  for (std::size_t i = 0; i + 1 < steps_.size();) {
    Step& a = steps_[i];
    Step& b = steps_[i + 1];
    const bool axis =
        a.motion == Motion::kTransX || a.motion == Motion::kTransY || a.motion == Motion::kTransZ;
    if (!axis || wanted[std::size_t(a.link)] || uses[std::size_t(a.link)] != 1 || b.ref != a.link ||
        !identityFrame(b) || a.num_shifts + 1 + b.num_shifts > 3) {
      ++i;
      continue;
    }
    Step merged = a;  // a's reference and constant frame
    merged.num_shifts = 0;
    for (int k = 0; k < a.num_shifts; ++k) merged.shifts[merged.num_shifts++] = a.shifts[k];
    merged.shifts[merged.num_shifts++] = {
        a.q_index, static_cast<int>(a.motion) - static_cast<int>(Motion::kTransX), a.multiplier,
        a.offset};
    for (int k = 0; k < b.num_shifts; ++k) merged.shifts[merged.num_shifts++] = b.shifts[k];
    // b's link and motion.
    merged.link = b.link;
    merged.motion = b.motion;
    merged.axis = b.axis;
    merged.q_index = b.q_index;
    merged.multiplier = b.multiplier;
    merged.offset = b.offset;
    updated_.erase(std::find(updated_.begin(), updated_.end(), a.link));
    steps_[i + 1] = merged;
    steps_.erase(steps_.begin() + std::ptrdiff_t(i));
  }
  trig_args_.clear();
  for (Step& s : steps_) {
    const int axis = s.motion == Motion::kRotX   ? 0
                     : s.motion == Motion::kRotY ? 1
                     : s.motion == Motion::kRotZ ? 2
                                                 : -1;
    s.trig = axis >= 0 ? static_cast<int>(trig_args_.size()) : -1;
    if (axis >= 0) trig_args_.push_back({s.q_index, s.multiplier, s.offset});
    s.perm_rotation = s.perm && s.num_shifts == 0 && axis >= 0 ? 3 * s.perm_code + axis : -1;
  }
  trig_first_ = trig_args_.empty() ? 0 : trig_args_.front().q_index;
  trig_run_ = trig_args_.size() <= std::size_t(kTrigBlock);
  for (std::size_t t = 0; t < trig_args_.size(); ++t) {
    const TrigArg& a = trig_args_[t];
    trig_run_ =
        trig_run_ && a.q_index == trig_first_ + int(t) && a.multiplier == 1.0 && a.offset == 0.0;
  }
}

double Kinematics::jointValue(const double* q, int joint) const {
  const JointRef& j = joints_[joint];
  if (j.active_index >= 0) return q[j.active_index];
  if (j.mimic_active >= 0) return j.mimic_multiplier * q[j.mimic_active] + j.mimic_offset;
  return 0.0;
}

namespace {

// A column of a pose, (x, y, z, w), as four doubles. Quad is the compiler's vector: one AVX
// register in a function compiled for AVX2, two SSE2 registers otherwise (each operation split
// in two, element by element). ScalarQuad is a plain struct with the same element-wise
// operations. Every path forms the same products and sums in the same order (and never a fused
// multiply-add), so the poses are the same to the bit.
using Quad = double __attribute__((vector_size(32)));
using QuadBits = std::int64_t __attribute__((vector_size(32)));

struct ScalarQuad {
  double v[4];
};
inline ScalarQuad operator+(ScalarQuad a, const ScalarQuad& b) {
  for (int i = 0; i < 4; ++i) a.v[i] += b.v[i];
  return a;
}
inline ScalarQuad operator-(ScalarQuad a, const ScalarQuad& b) {
  for (int i = 0; i < 4; ++i) a.v[i] -= b.v[i];
  return a;
}
inline ScalarQuad operator*(ScalarQuad a, double f) {
  for (int i = 0; i < 4; ++i) a.v[i] *= f;
  return a;
}
inline ScalarQuad operator*(double f, ScalarQuad a) {
  for (int i = 0; i < 4; ++i) a.v[i] = f * a.v[i];
  return a;
}
inline ScalarQuad& operator+=(ScalarQuad& a, const ScalarQuad& b) { return a = a + b; }

// Two SSE2 registers: (x, y) and (z, w).
struct PairColumn {
  Pair lo, hi;
};
inline PairColumn operator+(const PairColumn& a, const PairColumn& b) {
  return {a.lo + b.lo, a.hi + b.hi};
}
inline PairColumn operator-(const PairColumn& a, const PairColumn& b) {
  return {a.lo - b.lo, a.hi - b.hi};
}
inline PairColumn operator*(const PairColumn& a, double f) { return {a.lo * f, a.hi * f}; }
inline PairColumn operator*(double f, const PairColumn& a) { return {f * a.lo, f * a.hi}; }
inline PairColumn& operator+=(PairColumn& a, const PairColumn& b) { return a = a + b; }

// Columns are passed and returned by value (by address the compiler would keep them in memory
// rather than in registers). These helpers and Kinematics::run are always inlined: no call
// passes a 32-byte vector, whose calling convention would depend on the instruction set (GCC's
// -Wpsabi note about it, silenced down to the AVX2 wrapper, does not apply).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
template <class Column>
__attribute__((always_inline)) inline Column loadColumn(const double* p) {
  Column v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <>
__attribute__((always_inline)) inline PairColumn loadColumn<PairColumn>(const double* p) {
  return {loadPair(p), loadPair(p + 2)};
}
// The fourth element (w) of a column.
// (Masks with constants: assigning the element alone takes an extract and an insert.)
__attribute__((always_inline)) inline void setLast(Quad& v, double w) {
  v = (Quad)(((QuadBits)v & QuadBits{-1, -1, -1, 0}) | (QuadBits)Quad{0.0, 0.0, 0.0, w});
}
__attribute__((always_inline)) inline void setLast(PairColumn& v, double w) {
  v.hi = (Pair)(((PairBits)v.hi & PairBits{-1, 0}) | (PairBits)Pair{0.0, w});
}
__attribute__((always_inline)) inline void setLast(ScalarQuad& v, double w) { v.v[3] = w; }
template <class Column>
__attribute__((always_inline)) inline void storeColumn(double* p, Column v) {
  std::memcpy(p, &v, sizeof v);
}
template <>
__attribute__((always_inline)) inline void storeColumn<PairColumn>(double* p, PairColumn v) {
  storePair(p, v.lo);
  storePair(p + 2, v.hi);
}

// Columns P0, P1, P2 of a times the signs, then the rotation about axis kAxis: the same
// products and sums as the general step (a permutation, then rotate()).
template <int P0, int P1, int P2, int kAxis, class Column>
__attribute__((always_inline)) inline void permRotate(const Column* a, const double* sign,
                                                      double sv, double cv, Column* c) {
  c[0] = a[P0] * sign[0], c[1] = a[P1] * sign[1], c[2] = a[P2] * sign[2];
  constexpr int ca = (kAxis + 1) % 3, cb = (kAxis + 2) % 3;
  const Column x = c[ca], y = c[cb];
  c[ca] = cv * x + sv * y;
  c[cb] = cv * y - sv * x;
}

}  // namespace

template <class Column>
__attribute__((always_inline)) inline void Kinematics::run(const double* q,
                                                           Eigen::Isometry3d* X_WL) const {
  // The sines and cosines of the axis-aligned revolute joints first, all together (see
  // fastSinCosArray), in blocks of kTrigBlock.
  double v[kTrigBlock], sn[kTrigBlock], cs[kTrigBlock];
  const int num_trig = static_cast<int>(trig_args_.size());
  X_WL[root_] = X_WR_;
  int block_begin = 0, block_end = 0;
  // A pose as 4 columns of the column-major 4x4 matrix. The pose of the previous step stays in
  // c when it is the next step's reference (a chain), so that it comes from registers rather
  // than from the stores just made.
  Column c[4] = {};
  int prev_link = -2;
  // The step array and its size are read once: the stores into X_WL below would otherwise make
  // the compiler reload them every step.
  const Step* const steps = steps_.data();
  const std::size_t num_steps = steps_.size();
  const TrigArg* const trig_args = trig_args_.data();
  for (std::size_t i = 0; i < num_steps; ++i) {
    const Step& s = steps[i];
    if (s.trig >= block_end) {
      block_begin = block_end;
      const int n = std::min(kTrigBlock, num_trig - block_begin);
      if (trig_run_) {
        // 1 * x + 0 is x + 0 (the sign of a zero as the general formula gives it).
        const double* const qt = q + trig_first_;
        for (int t = 0; t < n; ++t) v[t] = qt[t] + 0.0;
      } else {
        for (int t = 0; t < n; ++t) {
          const TrigArg& ta = trig_args[block_begin + t];
          v[t] = ta.multiplier * q[ta.q_index] + ta.offset;
        }
      }
      for (int t = n; t < kTrigBlock && t % 4 != 0; ++t) v[t] = 0.0;  // whole lanes
      if (std::is_same<Column, Quad>::value)
        fastSinCosLanes<Quad, QuadBits>(v, sn, cs, n);
      else
        fastSinCosArray(v, sn, cs, n);
      block_end = block_begin + n;
    }
    Column a[4];
    auto refPose = [&] { return (s.ref < 0 ? X_WR_ : X_WL[s.ref]).matrix().data(); };
    if (s.ref == prev_link) {
      std::copy(c, c + 4, a);
    } else {
      const double* const A_ref = refPose();
      for (int k = 0; k < 4; ++k) a[k] = loadColumn<Column>(A_ref + 4 * k);
    }
    // The pose c of s.link stored. The bottom row is written exactly (0 0 0 1), whatever the
    // products gave it: set in the columns before they are stored (a separate store into a
    // column just stored would make a later load of the whole column wait for both).
    auto storePose = [&] {
      double* X = X_WL[s.link].matrix().data();
      for (int k = 0; k < 4; ++k) {
        setLast(c[k], k == 3 ? 1.0 : 0.0);
        storeColumn(X + 4 * k, c[k]);
      }
      prev_link = s.link;
    };
    if (s.perm_rotation >= 0 && !std::is_same<Column, ScalarQuad>::value) {
      // The usual step of an arm (a joint origin turned by multiples of pi/2, a revolute
      // joint about one of its axes) in one switch, each case with constant columns; the
      // translation first, from a.
      c[3] = ((a[3] + a[0] * s.m[3][0]) + a[1] * s.m[3][1]) + a[2] * s.m[3][2];
      const double sv = sn[s.trig - block_begin], cv = cs[s.trig - block_begin];
      switch (s.perm_rotation) {
#define DSS_PERM_ROTATION(code, P0, P1, P2)          \
  case 3 * code:                                     \
    permRotate<P0, P1, P2, 0>(a, s.sign, sv, cv, c); \
    break;                                           \
  case 3 * code + 1:                                 \
    permRotate<P0, P1, P2, 1>(a, s.sign, sv, cv, c); \
    break;                                           \
  case 3 * code + 2:                                 \
    permRotate<P0, P1, P2, 2>(a, s.sign, sv, cv, c); \
    break;
        DSS_PERM_ROTATION(0, 0, 1, 2)
        DSS_PERM_ROTATION(1, 0, 2, 1)
        DSS_PERM_ROTATION(2, 1, 0, 2)
        DSS_PERM_ROTATION(3, 1, 2, 0)
        DSS_PERM_ROTATION(4, 2, 0, 1)
        DSS_PERM_ROTATION(5, 2, 1, 0)
#undef DSS_PERM_ROTATION
      }
      storePose();
      continue;
    }
    // [c | p] = [a | at] [R_c | p_c]; the sums in the order a0 * m0 + a1 * m1 + a2 * m2 (+ at
    // first for p). A signed permutation selects columns: for finite poses sign * column is
    // exactly the sum the general product forms with its exact zeros and ones (up to the sign
    // of a zero). The columns are picked from registers by a switch over the six permutations
    // (an index known only at run time would send them through memory: a store and a reload
    // on the chain from one link to the next).
    if (s.identity_R) {
      c[0] = a[0], c[1] = a[1], c[2] = a[2];
    } else if (s.perm && std::is_same<Column, ScalarQuad>::value) {
      // The scalar path reads the columns back from memory (its columns live there anyway; a
      // switch of struct copies costs it a fifth of its time).
      const double* const A_ref = refPose();
      for (int j = 0; j < 3; ++j) c[j] = loadColumn<Column>(A_ref + 4 * s.col[j]) * s.sign[j];
    } else if (s.perm) {
      // The columns picked from registers, each permutation with constant indices.
      Column p0, p1, p2;
      switch (s.perm_code) {
        case 0:  // (0, 1, 2)
          p0 = a[0], p1 = a[1], p2 = a[2];
          break;
        case 1:  // (0, 2, 1)
          p0 = a[0], p1 = a[2], p2 = a[1];
          break;
        case 2:  // (1, 0, 2)
          p0 = a[1], p1 = a[0], p2 = a[2];
          break;
        case 3:  // (1, 2, 0)
          p0 = a[1], p1 = a[2], p2 = a[0];
          break;
        case 4:  // (2, 0, 1)
          p0 = a[2], p1 = a[0], p2 = a[1];
          break;
        default:  // (2, 1, 0)
          p0 = a[2], p1 = a[1], p2 = a[0];
          break;
      }
      c[0] = p0 * s.sign[0], c[1] = p1 * s.sign[1], c[2] = p2 * s.sign[2];
    } else {
      for (int j = 0; j < 3; ++j) c[j] = a[0] * s.m[j][0] + a[1] * s.m[j][1] + a[2] * s.m[j][2];
    }
    c[3] = ((a[3] + a[0] * s.m[3][0]) + a[1] * s.m[3][1]) + a[2] * s.m[3][2];
    // Rotation about axis k mixes columns k + 1 and k + 2: x' = cos x + sin y, y' = cos y - sin x.
    auto rotate = [&c](int ca, int cb, double sv, double cv) {
      const Column x = c[ca], y = c[cb];
      c[ca] = cv * x + sv * y;
      c[cb] = cv * y - sv * x;
    };
    // A general rotation M of the joint frame: column j becomes sum_i M(i, j) column i.
    auto turn = [&c](const Eigen::Matrix3d& M) {
      const Column x0 = c[0], x1 = c[1], x2 = c[2];
      for (int j = 0; j < 3; ++j) c[j] = x0 * M(0, j) + x1 * M(1, j) + x2 * M(2, j);
    };
    // Translation along column k: p += d c_k.
    auto translate = [&c](int k, double d) { c[3] += d * c[k]; };
    // (Each column by a constant index: an index known only at run time would keep the pose
    // in memory rather than in registers.)
    for (int k = 0; k < s.num_shifts; ++k) {
      const Step::Shift& sh = s.shifts[k];
      const double d = sh.multiplier * q[sh.q_index] + sh.offset;
      switch (sh.col) {
        case 0:
          translate(0, d);
          break;
        case 1:
          translate(1, d);
          break;
        default:
          translate(2, d);
          break;
      }
    }
    switch (s.motion) {
      case Motion::kNone:
        break;
      case Motion::kRotX:
        rotate(1, 2, sn[s.trig - block_begin], cs[s.trig - block_begin]);
        break;
      case Motion::kRotY:
        rotate(2, 0, sn[s.trig - block_begin], cs[s.trig - block_begin]);
        break;
      case Motion::kRotZ:
        rotate(0, 1, sn[s.trig - block_begin], cs[s.trig - block_begin]);
        break;
      case Motion::kRotAxis:
        turn(Eigen::AngleAxisd(s.multiplier * q[s.q_index] + s.offset, s.axis).toRotationMatrix());
        break;
      case Motion::kBall: {
        // A quaternion of (nearly) zero or non-finite norm has no rotation: the pose becomes
        // NaN, which every checker answers as invalid input. Otherwise the rotation of the
        // quaternion scaled to unit norm, from its squared norm (one division, no square
        // root). The products come first and the scale last, so that the division runs beside
        // them rather than before them.
        const double x = q[s.q_index], y = q[s.q_index + 1], z = q[s.q_index + 2],
                     w = q[s.q_index + 3];
        Eigen::Matrix3d M;
        if (quaternionNormValid(x, y, z, w)) {
          const double xx = x * x, yy = y * y, zz = z * z, ww = w * w;
          const double xy = x * y, xz = x * z, yz = y * z, wx = w * x, wy = w * y, wz = w * z;
          const double f = 2.0 / ((xx + yy) + (zz + ww));
          M << 1.0 - f * (yy + zz), f * (xy - wz), f * (xz + wy),  //
              f * (xy + wz), 1.0 - f * (xx + zz), f * (yz - wx),   //
              f * (xz - wy), f * (yz + wx), 1.0 - f * (xx + yy);
        } else {
          M.setConstant(std::numeric_limits<double>::quiet_NaN());
        }
        turn(M);
        break;
      }
      case Motion::kTransX:
        translate(0, s.multiplier * q[s.q_index] + s.offset);
        break;
      case Motion::kTransY:
        translate(1, s.multiplier * q[s.q_index] + s.offset);
        break;
      case Motion::kTransZ:
        translate(2, s.multiplier * q[s.q_index] + s.offset);
        break;
      case Motion::kTransAxis: {
        const double d = s.multiplier * q[s.q_index] + s.offset;
        c[3] += d * (c[0] * s.axis.x() + c[1] * s.axis.y() + c[2] * s.axis.z());
        break;
      }
    }
    storePose();
  }
}

void Kinematics::computeScalar(const double* q, Eigen::Isometry3d* X_WL) const {
  run<ScalarQuad>(q, X_WL);
}

void Kinematics::computeSse2(const double* q, Eigen::Isometry3d* X_WL) const {
  run<PairColumn>(q, X_WL);
}

DSS_TARGET_AVX2 void Kinematics::computeAvx2(const double* q, Eigen::Isometry3d* X_WL) const {
  run<Quad>(q, X_WL);
}
#pragma GCC diagnostic pop

void Kinematics::computeOn(SimdPath path, const double* q, Eigen::Isometry3d* X_WL) const {
  switch (path) {
    case SimdPath::kAvx2:
      computeAvx2(q, X_WL);
      break;
    case SimdPath::kSse2:
      computeSse2(q, X_WL);
      break;
    case SimdPath::kScalar:
      computeScalar(q, X_WL);
      break;
  }
}

void Kinematics::computeLinkPoses(const double* q, Eigen::Isometry3d* X_WL) const {
  computeOn(path_, q, X_WL);
}

void Kinematics::computeLinkPoses(const double* q, Eigen::Isometry3d* X_WL, SimdPath path) const {
  computeOn(simdPathAvailable(path) ? path : bestSimdPath(), q, X_WL);
}

std::vector<Eigen::Isometry3d> Kinematics::linkPoses(const std::vector<double>& q) const {
  std::vector<Eigen::Isometry3d> X(num_links_, Eigen::Isometry3d::Identity());
  computeLinkPoses(q.data(), X.data());
  return X;
}

}  // namespace dss
