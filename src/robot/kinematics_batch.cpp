// Forward kinematics in eight float lanes (see dss/robot/kinematics_batch.h).
#include "dss/robot/kinematics_batch.h"

#include <cmath>
#include <cstdint>
#include <cstring>

#include "dss/core/lanes.h"

namespace dss {

KinematicsBatch::KinematicsBatch(const Kinematics& kin) : updated_(kin.updated_), root_(kin.root_) {
  supported_ = true;
  const Eigen::Isometry3d& X_WR = kin.X_WR_;
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i) base_[k][i] = static_cast<float>(X_WR.matrix()(i, k));
  double reach = X_WR.translation().norm();
  for (const Kinematics::Step& s : kin.steps_) {
    Step b;
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i) b.m[k][i] = static_cast<float>(s.m[k][i]);
    b.link = s.link;
    b.ref = s.ref;
    b.perm = s.perm;
    for (int j = 0; j < 3; ++j) {
      b.col[j] = s.col[j];
      b.flip[j] = s.sign[j] < 0.0 ? std::int32_t(0x80000000u) : 0;
    }
    reach += std::sqrt(s.m[3][0] * s.m[3][0] + s.m[3][1] * s.m[3][1] + s.m[3][2] * s.m[3][2]);
    if (s.num_shifts > 0) supported_ = false;
    using M = Kinematics::Motion;
    switch (s.motion) {
      case M::kNone:
        break;
      case M::kRotX:
      case M::kRotY:
      case M::kRotZ: {
        const Kinematics::TrigArg& t = kin.trig_args_[std::size_t(s.trig)];
        b.motion = s.motion == M::kRotX ? 1 : s.motion == M::kRotY ? 2 : 3;
        b.q_index = t.q_index;
        b.multiplier = t.multiplier;
        b.offset = t.offset;
        break;
      }
      case M::kRotAxis:
        b.motion = 4;
        b.q_index = s.q_index;
        b.multiplier = s.multiplier;
        b.offset = s.offset;
        for (int i = 0; i < 3; ++i) b.axis[i] = static_cast<float>(s.axis[i]);
        break;
      default:  // prismatic, ball: not in the batch
        supported_ = false;
        break;
    }
    steps_.push_back(b);
  }
  // Per step, a rotation's error (spectral norm) grows by at most about 10 float roundings
  // (the constant frame's entries, the three-term products, the sine and cosine, the turn) and
  // a translation's by that error times the step's offset plus a few roundings of the
  // position: over n steps at most 10 n u and 16 n u times the reach. Eight times that.
  constexpr double u = 0x1p-24;
  const double n = double(steps_.size()) + 1.0;
  rotation_error_ = 8.0 * 10.0 * n * u;
  position_error_ = 8.0 * 16.0 * n * u * (reach + 1.0);
}

namespace {

using lanes::D4;
using lanes::F8;
using lanes::I8;
using lanes::kLanes;
using lanes::L4;

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

// The angles of one joint in the lanes, reduced by pi/2 in double (the kinematics' split of
// pi/2), four lanes at a time: r in [-pi/4, pi/4] as floats and the quadrant k mod 4; NaN
// beyond 1e5 rad (and for NaN). `wide`: compiled for AVX2 (lanes.h).
__attribute__((always_inline)) inline void reduceAngles(const double* q, double multiplier,
                                                        double offset, float* r, std::int32_t* k,
                                                        bool wide) {
  constexpr double kPio2Hi = 0x1.921fb544p+0;
  constexpr double kPio2Mid = 0x1.0b46p-34;
  constexpr double kPio2Lo = 6.123233995736766e-17;
  constexpr double kRound = 0x1.8p52;  // adding it rounds to an integer (|x| < 2^51)
  for (int h = 0; h < kLanes; h += 4) {
    D4 x;
    std::memcpy(&x, q + h, sizeof x);
    x = x * multiplier + offset;
    const D4 shifted = x * (2.0 / M_PI) + kRound;
    const D4 kd = shifted - kRound;
    const D4 rd = ((x - kd * kPio2Hi) - kd * kPio2Mid) - kd * kPio2Lo;
    const L4 ok = lanes::lessEqual(lanes::abs(x), D4{} + 1e5, wide);  // false for NaN
    const D4 rs = lanes::select(ok, rd, D4{} + NAN, wide);
    const L4 quadrant = (L4)shifted & ok;  // the low bits of the integer
    for (int l = 0; l < 4; ++l) {
      r[h + l] = static_cast<float>(rs[l]);
      k[h + l] = static_cast<std::int32_t>(quadrant[l]);
    }
  }
}

// sin and cos of r in [-pi/4, pi/4] turned to quadrant k: Taylor polynomials (truncation
// below 2e-9).
__attribute__((always_inline)) inline void sinCos(const float* r_in, const std::int32_t* k_in,
                                                  F8& s_out, F8& c_out) {
  const F8 r = lanes::load(r_in);
  I8 k;
  std::memcpy(&k, k_in, sizeof k);
  const F8 r2 = r * r;
  const F8 s =
      r + r * r2 * (-1.0f / 6 + r2 * (1.0f / 120 + r2 * (-1.0f / 5040 + r2 * (1.0f / 362880))));
  const F8 c =
      1.0f + r2 * (-0.5f + r2 * (1.0f / 24 +
                                 r2 * (-1.0f / 720 + r2 * (1.0f / 40320 - r2 * (1.0f / 3628800)))));
  // Quadrant q = k mod 4: sin = (s, c, -s, -c)[q], cos = (c, -s, -c, s)[q].
  const I8 odd = 0 - (k & 1), half = 0 - ((k >> 1) & 1), sign = I8{} + std::int32_t(0x80000000u);
  const I8 sb = (I8)s, cb = (I8)c;
  s_out = (F8)(((cb & odd) | (sb & ~odd)) ^ (sign & half));
  c_out = (F8)(((sb & odd) | (cb & ~odd)) ^ (sign & (half ^ odd)));
}

#pragma GCC diagnostic pop

}  // namespace

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

__attribute__((always_inline)) inline void KinematicsBatch::run(const double* q, Pose* X,
                                                                bool wide) const {
  float r[kLanes];
  std::int32_t k[kLanes];
  for (int e = 0; e < 12; ++e) lanes::store(X[root_].v[e], lanes::broadcast(base_[e / 3][e % 3]));
  for (const Step& s : steps_) {
    // [c | p] = [a | at] [R_c | p_c], then the joint's rotation. The parent's pose is read
    // from X (the base pose from X[root_]), entry by entry where it is used.
    const Pose& A = X[s.ref < 0 ? root_ : s.ref];
    auto a = [&A](int col, int i) { return lanes::load(A.v[3 * col + i]); };
    F8 c[4][3];
    if (s.perm) {
      // A signed permutation (kinematics.h): columns selected, no product; a negated column's
      // sign bits flipped, as negation does.
      for (int j = 0; j < 3; ++j) {
        const I8 flip = I8{} + s.flip[j];
        for (int i = 0; i < 3; ++i) c[j][i] = (F8)((I8)a(s.col[j], i) ^ flip);
      }
    } else {
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
          c[j][i] = a(0, i) * s.m[j][0] + a(1, i) * s.m[j][1] + a(2, i) * s.m[j][2];
    }
    // The translation's zero terms left out: adding a zero product leaves a finite sum as it is.
    for (int i = 0; i < 3; ++i) c[3][i] = a(3, i);
    for (int k = 0; k < 3; ++k)
      if (s.m[3][k] != 0.0f)
        for (int i = 0; i < 3; ++i) c[3][i] = c[3][i] + a(k, i) * s.m[3][k];
    if (s.motion != 0) {
      reduceAngles(q + s.q_index * kLanes, s.multiplier, s.offset, r, k, wide);
      F8 sn, cs;
      sinCos(r, k, sn, cs);
      // About axis x, y or z: columns (1, 2), (2, 0) or (0, 1) mix (each case with its own
      // columns, so that c stays in registers).
      auto turn = [&cs, &sn](F8* x, F8* y) {
        for (int i = 0; i < 3; ++i) {
          const F8 u = x[i], v = y[i];
          x[i] = cs * u + sn * v;
          y[i] = cs * v - sn * u;
        }
      };
      switch (s.motion) {
        case 1:
          turn(c[1], c[2]);
          break;
        case 2:
          turn(c[2], c[0]);
          break;
        case 3:
          turn(c[0], c[1]);
          break;
        default: {
          // About a unit axis: M = cos I + sin [axis]x + (1 - cos) axis axis^T; column j of
          // the pose becomes sum_i M(i, j) column i.
          const float ax = s.axis[0], ay = s.axis[1], az = s.axis[2];
          const F8 t = 1.0f - cs;
          F8 M[3][3];
          M[0][0] = cs + t * (ax * ax), M[1][1] = cs + t * (ay * ay), M[2][2] = cs + t * (az * az);
          M[0][1] = t * (ax * ay) - sn * az, M[1][0] = t * (ax * ay) + sn * az;
          M[0][2] = t * (ax * az) + sn * ay, M[2][0] = t * (ax * az) - sn * ay;
          M[1][2] = t * (ay * az) - sn * ax, M[2][1] = t * (ay * az) + sn * ax;
          F8 x[3][3];
          for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) x[j][i] = c[j][i];
          for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i)
              c[j][i] = x[0][i] * M[0][j] + x[1][i] * M[1][j] + x[2][i] * M[2][j];
          break;
        }
      }
    }
    Pose& C = X[s.link];
    for (int e = 0; e < 12; ++e) lanes::store(C.v[e], c[e / 3][e % 3]);
  }
}

void KinematicsBatch::computeGeneric(const double* q, Pose* X) const { run(q, X, false); }

DSS_TARGET_AVX2 void KinematicsBatch::computeAvx2(const double* q, Pose* X) const {
  run(q, X, true);
}

#pragma GCC diagnostic pop

void KinematicsBatch::compute(const double* q, Pose* X, SimdPath path) const {
  if (path == SimdPath::kAvx2 && simdPathAvailable(SimdPath::kAvx2))
    computeAvx2(q, X);
  else
    computeGeneric(q, X);
}

}  // namespace dss
