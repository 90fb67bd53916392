// Decision Sphere Search: do two convex shapes intersect? (Hornus 2017, Algorithm 2.)
//
// A and B intersect iff the origin lies in P = A - B, iff h_P(n) >= 0 for every direction n.
// The search keeps a spherical polygon S (see spherical_polygon.h) that contains every
// separating direction. Each step tests the centre n of S: the support point q = S_A(n) -
// S_B(-n) either proves n separating (n.q < 0: "disjoint", n is the certificate) or removes
// the hemisphere {w : w.q >= 0} from S. An empty S proves "intersect".
//
// Only two kinds of signs decide anything: n.q < 0 and the 3x3 determinants of the polygon
// update. In Mode::kExact both are exact: the polygon signs by a floating-point filter with an
// exact fallback, the separation test by a certified bound on h_A(n) + h_B(-n) (and, for
// shapes given by world-coordinate vertices, an exact evaluation of it). The next test
// direction only steers the search and needs no exactness.
//
// The computation runs in a frame centred on one of the shapes (see chooseShift) so that
// large common offsets cancel before rounding. Touching counts as intersecting. No
// allocation, no virtual call, no shared state: safe to call from many threads.
#pragma once

#include <cmath>
#include <limits>
#include <type_traits>

#include "dss/core/any_shape.h"
#include "dss/core/exact_predicates.h"
#include "dss/core/posed.h"
#include "dss/core/ref.h"
#include "dss/core/result.h"
#include "dss/core/simplex.h"
#include "dss/core/spherical_polygon.h"

namespace dss {
namespace detail {

template <class S>
using ScalarOf = std::decay_t<decltype(std::declval<const S&>().magnitude())>;

/// The frame origin for a pair: shapes given by world vertices must not be shifted (their
/// points are the exact inputs), so the shift is zero unless both shapes carry a pose.
template <class A, class B>
DSS_INLINE Vec3d chooseShift(const A& a, const B& b) {
  const Vec3d ta = a.anchor().template cast<double>();
  const Vec3d tb = b.anchor().template cast<double>();
  if (isZero3(ta) || isZero3(tb)) return Vec3d(0.0, 0.0, 0.0);
  return tb;
}

/// The Minkowski difference A - B seen from the working scalar W.
template <class A, class B, class W, bool Exact = true>
struct Difference {
  using SA = ScalarOf<A>;
  using SB = ScalarOf<B>;
  const A& a;
  const B& b;
  Vec3<SA> shift_a;
  Vec3<SB> shift_b;
  W scale;      // bounds |p|_1 for every point p of A - B in the working frame (exact mode)
  W sep_scale;  // |n|_1 * sep_scale bounds the rounding of fl(n.q), q = S_A(n) - S_B(-n)

  Difference(const A& sa, const B& sb) : a(sa), b(sb) {
    const Vec3d c = chooseShift(sa, sb);
    shift_a = c.template cast<SA>();
    shift_b = c.template cast<SB>();
    scale = W(0);
    sep_scale = W(0);
    if constexpr (!Exact) return;
    // 1-norms bound the distances without a square root on the query's critical path.
    const Vec3d da = sa.anchor().template cast<double>() - c,
                db = sb.anchor().template cast<double>() - c;
    const double mag =
        (double(sa.magnitude()) + double(sb.magnitude())) + (norm1_3(da) + norm1_3(db));
    // |x - c|_1 <= sqrt(3) |x - anchor| + |anchor - c|_1 for x in a shape; 2 leaves room for
    // the rounding of the support points.
    scale = W(2 * mag);
    // Each support value h(n) = n.x is off by a few ulps of |n| (|x_S| + |t|): rotations of
    // the direction and of the point, normalisations, the translation and the dot product.
    // 32 u covers them with margin for both shapes (float supports use float's u); the dot
    // product's rounding adds 4u |n|_1 |q|_1 <= 4u |n|_1 scale = 8u |n|_1 mag.
    constexpr double u = std::max(double(std::numeric_limits<SA>::epsilon()),
                                  double(std::numeric_limits<SB>::epsilon())) /
                         2;
    constexpr double kSep = 32 * u + 8 * (double(std::numeric_limits<W>::epsilon()) / 2);
    // The absolute term covers roundings among subnormal numbers (shapes near 1e-300).
    sep_scale = W(kSep * mag) + W(64) * std::numeric_limits<W>::denorm_min();
  }

  /// The centres of A and B (points of the shapes), in the working frame.
  DSS_INLINE void centers(Vec3<W>& ca, Vec3<W>& cb) const {
    ca = (a.center() - shift_a).template cast<W>();
    cb = (b.center() - shift_b).template cast<W>();
  }

  /// Support point pa = S_A(n).
  DSS_INLINE void supportA(const Vec3<W>& n, Vec3<W>& pa) const {
    if constexpr (std::is_same<SA, W>::value) {
      pa = a.support(n, shift_a);
    } else {
      pa = a.support(n.template cast<SA>(), shift_a).template cast<W>();
    }
  }

  /// Support points pa = S_A(n) and pb = S_B(-n); q = pa - pb is a point of A - B.
  DSS_INLINE void support(const Vec3<W>& n, Vec3<W>& pa, Vec3<W>& pb) const {
    supportA(n, pa);
    if constexpr (std::is_same<SB, W>::value) {
      pb = b.support(neg3(n), shift_b);
    } else {
      pb = b.support(neg3(n).template cast<SB>(), shift_b).template cast<W>();
    }
  }

  /// The rounding error of hi = fl(x - y), so that hi + lo = x - y exactly (exact mode; zero
  /// otherwise). Computed only when a pole enters the polygon: a separating step needs none.
  static DSS_INLINE Vec3<W> error(const Vec3<W>& x, const Vec3<W>& y) {
    Vec3<W> lo;
    if constexpr (Exact && std::is_same<W, double>::value) {
      for (int k = 0; k < 3; ++k) {
        W hi;
        exact::twoDiff(x[k], y[k], hi, lo[k]);
      }
    } else {
      lo.setZero();
    }
    return lo;
  }
};

/// Exact sign of h_A(n) + h_B(-n) for two world-vertex hulls; on return (if >= 0) pa, pb are
/// exact maximisers. Candidates are the vertices within the floating-point error of the best.
template <class A, class B>
int exactSeparationSign(const A& a, const B& b, const Vec3d& n, Vec3d& pa, Vec3d& pb) {
  const double u = std::numeric_limits<double>::epsilon() / 2;
  auto best = [&](const auto& hull, const Vec3d& d) {
    const auto& pts = hull.points();
    double top = -std::numeric_limits<double>::infinity();
    for (const auto& p : pts) top = std::max(top, d.dot(p));
    const double slack = 8 * u * d.lpNorm<1>() * hull.magnitude();
    int arg = -1;
    for (int i = 0; i < int(pts.size()); ++i) {
      if (d.dot(pts[i]) < top - slack) continue;
      if (arg < 0 || exact::dotDiffSign(d.data(), pts[i].data(), pts[arg].data()) > 0) arg = i;
    }
    return pts[arg];
  };
  pa = best(a, n);
  pb = best(b, Vec3d(-n));
  return exact::dotDiffSign(n.data(), pa.data(), pb.data());
}

enum class Step { kContinue, kDone, kGiveUp };

/// A posed ball (a sphere with a pose, held by value or by reference): its support point
/// c + r d/|d| needs a square root and a division on the search's critical path, which the
/// plain search avoids (see testBallDirection).
template <class S>
struct IsPosedBall : std::false_type {};
template <class S>
struct IsPosedBall<Posed<S>> {
  static constexpr bool value =
      std::is_same<std::decay_t<decltype(unref(std::declval<const S&>()))>,
                   SphereT<ScalarOf<S>>>::value;
  static ScalarOf<S> radius(const Posed<S>& ball) { return unref(ball.shape).radius; }
};

/// The plain double search's test of direction n when B is a ball of centre c and radius r (in the
/// working frame): h_A(n) + h_B(-n) = n.(S_A(n) - c) + r |n|, one square root and no division,
/// and the pole |n| (S_A(n) - S_B(-n)) = |n| (S_A(n) - c) + r n, a positive multiple of the
/// support point (the polygon only uses poles' directions). Returns false (nothing done) when
/// |n|^2 is outside [1e-30, 1e30], where the general test takes over.
template <class B, class W, class Diff, class PoleT>
DSS_INLINE bool testBallDirection(const B& ball, const Diff& diff, const Vec3<W>& n, Vec3<W>& pa,
                                  PoleT& pole, Step& step, Result& result) {
  const W n2 = dot3(n, n);
  if (!(n2 > W(1e-30) && n2 < W(1e30))) return false;
  const W len = std::sqrt(n2);
  diff.supportA(n, pa);
  const Vec3<W> core = diff3(pa, diff3(ball.p_WS, diff.shift_b));
  const W r = IsPosedBall<B>::radius(ball);
  const W t = dot3(n, core) + r * len;
  if (!std::isfinite(t)) {
    result.status = Status::kInvalidInput;
    step = Step::kDone;
    return true;
  }
  if (t < W(0)) {
    result.intersect = false;
    result.separating_direction = n.template cast<double>();
    step = Step::kDone;
    return true;
  }
  pole.hi = sum3(scaled3(core, len), scaled3(n, r));
  step = Step::kContinue;
  return true;
}

/// One test of direction n: q = S_A(n) - S_B(-n) into pole (and pa, pb). kDone when n is
/// proved separating or the input is invalid (result set), kGiveUp when the filtered search
/// cannot certify a separating sign, kContinue when q must clip the polygon.
template <bool Exact, bool Filter, bool kHybrid, class A, class B, class W, class Diff, class PoleT>
DSS_INLINE Step testDirection(const A& a, const B& b, const Diff& diff, const Vec3<W>& n,
                              Vec3<W>& pa, Vec3<W>& pb, PoleT& pole, Result& result) {
  (void)a, (void)b;
  // In double only: with float shapes the general test is the faster one.
  if constexpr (!Filter && !kHybrid && IsPosedBall<B>::value && std::is_same<W, double>::value &&
                std::is_same<ScalarOf<B>, W>::value) {
    Step step;
    if (testBallDirection<B>(b, diff, n, pa, pole, step, result)) return step;
  }
  diff.support(n, pa, pb);
  pole.hi = diff3(pa, pb);
  const W t = dot3(n, pole.hi);
  if (!std::isfinite(t)) {  // a NaN or Inf anywhere in n or q shows here
    // The filtered search hands an overflow over to the exact search, whose directions and
    // poles are scaled to stay in range; there (and in the plain modes) it is invalid input.
    if constexpr (Filter && !Exact) return Step::kGiveUp;
    result.status = Status::kInvalidInput;
    return Step::kDone;
  }
  if (!(t < W(0))) return Step::kContinue;
  if constexpr (!Filter) {
    result.intersect = false;
    result.separating_direction = n.template cast<double>();
    return Step::kDone;
  } else {
    // Certified when even the rounding of both supports and of the dot cannot lift t to 0.
    // (|n|_1 bounds |n| without a square root.)
    if (t + norm1_3(n) * diff.sep_scale < W(0)) {
      result.intersect = false;
      result.separating_direction = n;
      return Step::kDone;
    }
    if constexpr (!Exact) return Step::kGiveUp;
    if constexpr (A::kExactVertices && B::kExactVertices) {
      Vec3d xa, xb;
      if (exactSeparationSign(a, b, n, xa, xb) < 0) {
        result.intersect = false;
        result.separating_direction = n;
        return Step::kDone;
      }
      pa = xa, pb = xb;
      pole.hi = diff3(pa, pb);
    }
    // Otherwise the direction is not certifiably separating (a gap within rounding of the
    // supports): keep searching with q, which is a point of P up to rounding.
    return Step::kContinue;
  }
}

/// Scales an exact pole (hi and lo alike) by the power of two that brings its largest |hi|
/// component into [1, 2): the polygon only uses the poles' directions, and at any scale of the
/// shapes its signs (products of up to three poles) then stay in the double range. A pole
/// whose error part would fall out of the normal range is left as it is.
template <class W>
void scalePole(Pole<W, true>& p) {
  const W m = std::max(std::abs(p.hi.x()), std::max(std::abs(p.hi.y()), std::abs(p.hi.z())));
  if (!(m > W(0)) || !std::isfinite(m)) return;
  const int e = std::ilogb(m);
  if (e == 0) return;
  for (int k = 0; k < 3; ++k)
    if (p.lo[k] != W(0) && std::ilogb(p.lo[k]) - e < std::numeric_limits<W>::min_exponent) return;
  for (int k = 0; k < 3; ++k) {
    p.hi[k] = std::ldexp(p.hi[k], -e);
    p.lo[k] = std::ldexp(p.lo[k], -e);
  }
}

/// The polygon update of the exact search, out of line: the exact search runs only for the
/// queries the filtered search cannot decide, and its clip (exact predicates included) is then
/// compiled once per translation unit instead of once per pair of shape types.
template <class Poly, class PoleT>
DSS_NOINLINE ClipResult clipOutOfLine(Poly& poly, const PoleT& pole) {
  return poly.clip(pole);
}

/// One search, one function per instantiation (its supports and the polygon update inlined).
/// Sign policies as in SphericalPolygon: plain (Exact = Filter = false), filtered (Filter
/// only: returns false, leaving `result` meaningless, as soon as a sign or the final
/// separation cannot be certified) and exact (both). Returns true with the answer in `result`.
template <class W, bool Exact, bool Filter, class A, class B, bool kHybrid>
DSS_NOINLINE bool searchDss(const A& a, const B& b, int max_iterations, int gjk_steps,
                            Result& result) {
  constexpr bool kOnlyFilter = Filter && !Exact;
  const Difference<A, B, W, Filter> diff(a, b);
  using Poly = SphericalPolygon<W, Exact, Filter>;
  Vec3<W> start_a, start_b;
  diff.centers(start_a, start_b);
  const Vec3<W> c = diff3(start_a, start_b);
  if (!c.allFinite()) {
    result.status = Status::kInvalidInput;
    return true;
  }
  // fl(a - b) is zero only when a == b: the centres coincide (and the rounding error is zero).
  if (isZero3(c)) return true;
  if (max_iterations < 1) {
    result.status = Status::kIterationLimit;
    return true;
  }

  // Scales whose cubes (a lune's direction is cubic in the poles) or whose products with
  // such directions would leave the double range go straight to the exact search.
  if constexpr (kOnlyFilter) {
    if (!(diff.scale > W(1e-60) && diff.scale < W(1e60))) return false;
  }

  // The first step, from A's centre towards B's, is taken before anything else is set up:
  // at low collision density most queries end here. The exact search scales its directions
  // and poles by powers of two (exactly) so that nothing it computes leaves the double range,
  // whatever the shapes' scale.
  Vec3<W> n = neg3(c);
  if constexpr (Exact) n = powerOfTwoScaled(n);
  Vec3<W> pa, pb;
  Pole<W, Exact> pole;
  result.iterations = 1;
  const Step first_step =
      testDirection<Exact, Filter, kHybrid>(a, b, diff, n, pa, pb, pole, result);
  if (first_step == Step::kDone) return true;
  if (first_step == Step::kGiveUp) return false;

  // The polygon starts as the hemisphere of the centres' difference; that pole's rounding
  // error is computed only now.
  Poly poly;
  if constexpr (kOnlyFilter) poly.setScale(diff.scale);
  {
    Pole<W, Exact> first;
    first.hi = c;
    if constexpr (Exact) {
      first.lo = diff.error(start_a, start_b);
      scalePole(first);
      first.norm = Poly::normBound(first.hi);
    }
    poly.init(first);
  }
  // Hybrid: GJK's simplex (closest point to the origin) steers the first steps.
  Vec3<W> simplex[4];
  int simplex_size = 0;
  Vec3<W> v = c;  // GJK's current point of P closest to the origin

  for (;;) {
    if constexpr (Exact) {
      pole.lo = diff.error(pa, pb);
      scalePole(pole);
      pole.norm = Poly::normBound(pole.hi);
    }
    ClipResult clipped;
    if constexpr (Exact) {
      clipped = clipOutOfLine(poly, pole);
    } else {
      clipped = poly.clip(pole);
    }
    switch (clipped) {
      case ClipResult::kEmpty:
        return true;
      case ClipResult::kOverflow:
        result.status = Status::kIterationLimit;
        return true;
      case ClipResult::kUnsure:
        return false;
      default:
        break;
    }
    if (kHybrid && gjk_steps > 0) {
      // GJK step: add q to the simplex and move v to its point closest to the origin.
      simplex[simplex_size++] = pole.hi;
      v = closestOnSimplex(simplex, simplex_size);
    }
    if (kHybrid && result.iterations < gjk_steps && !isZero3(v)) {
      n = neg3(v);
    } else {
      gjk_steps = 0;
      n = poly.center();
    }
    if (result.iterations >= max_iterations) {
      result.status = Status::kIterationLimit;
      return true;
    }
    ++result.iterations;
    const Step step = testDirection<Exact, Filter, kHybrid>(a, b, diff, n, pa, pb, pole, result);
    if (step == Step::kDone) return true;
    if (step == Step::kGiveUp) return false;
  }
}

/// The search in one of the three modes. The exact mode first runs the filtered search, which
/// makes the exact search's decisions at the plain search's cost (no rounding errors carried,
/// one bound per sign), and reruns the query exactly only when a sign was too close to call.
template <class W, bool Exact, class A, class B, bool kHybrid = false>
Result runDss(const A& a, const B& b, int max_iterations, int gjk_steps = 0) {
  Result result;
  if constexpr (Exact) {
    if (searchDss<W, false, true, A, B, kHybrid>(a, b, max_iterations, gjk_steps, result))
      return result;
    result = Result{};
    searchDss<W, true, true, A, B, kHybrid>(a, b, max_iterations, gjk_steps, result);
  } else {
    searchDss<W, false, false, A, B, kHybrid>(a, b, max_iterations, gjk_steps, result);
  }
  return result;
}

/// The exact search alone, without the filtered first pass (for tests).
template <class A, class B>
Result runDssExactOnly(const A& a, const B& b, int max_iterations) {
  Result result;
  searchDss<double, true, true, A, B, false>(a, b, max_iterations, 0, result);
  return result;
}

}  // namespace detail

/// Decides whether A and B intersect (touching counts). A and B: any core shape types.
template <class A, class B>
Result intersect(const A& a, const B& b, const Options& opt = {}) {
  using SA = detail::ScalarOf<A>;
  using SB = detail::ScalarOf<B>;
  constexpr bool kFloatShapes = std::is_same<SA, float>::value && std::is_same<SB, float>::value;
  if (opt.mode == Mode::kFloat || kFloatShapes) {
    if (opt.mode == Mode::kExact && kFloatShapes)
      return detail::runDss<double, true>(a, b, opt.max_iterations);
    if (opt.mode == Mode::kDouble && kFloatShapes)
      return detail::runDss<double, false>(a, b, opt.max_iterations);
    return detail::runDss<float, false>(a, b, opt.max_iterations);
  }
  if (opt.mode == Mode::kExact) return detail::runDss<double, true>(a, b, opt.max_iterations);
  return detail::runDss<double, false>(a, b, opt.max_iterations);
}

}  // namespace dss
