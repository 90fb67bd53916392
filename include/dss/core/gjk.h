// Decision GJK (Gilbert and Foo 1990) and the paper's Hybrid (Hornus 2017, section 6.5.1),
// with the options and result of DSS, for comparison.
//
// GJK moves v, the point of a simplex in P = A - B closest to the origin, and tests -v: a
// support point w with v.w > 0 proves -v separating. Its decisions are plain floating-point
// signs in every mode (Mode::kExact runs it in double): the comparison is with the method
// as it is used in practice. The Hybrid lets GJK choose the first four test directions and
// then continues with DSS; every decision of the Hybrid is made by the DSS machinery, so in
// Mode::kExact it carries the exact mode's guarantee.
#pragma once

#include "dss/core/dss.h"
#include "dss/core/simplex.h"

namespace dss {
namespace detail {

template <class W, class A, class B>
Result runGjk(const A& a, const B& b, int max_iterations) {
  Result result;
  const Difference<A, B, W, false> diff(a, b);
  Vec3<W> ca, cb;
  diff.centers(ca, cb);
  Vec3<W> v = ca - cb;
  if (!v.allFinite()) {
    result.status = Status::kInvalidInput;
    return result;
  }
  Vec3<W> simplex[4];
  int size = 0;
  const W eps = W(16) * std::numeric_limits<W>::epsilon();
  for (;;) {
    if (v.isZero(0)) return result;  // origin in the simplex
    if (result.iterations >= max_iterations) {
      result.status = Status::kIterationLimit;
      return result;
    }
    ++result.iterations;
    Vec3<W> pa, pb;
    diff.support(Vec3<W>(-v), pa, pb);
    const Vec3<W> w = pa - pb;
    if (!w.allFinite()) {
      result.status = Status::kInvalidInput;
      return result;
    }
    if (v.dot(w) > W(0)) {
      result.intersect = false;
      result.separating_direction = (-v).template cast<double>();
      return result;
    }
    simplex[size++] = w;
    v = closestOnSimplex(simplex, size);
    if (size == 4) return result;  // tetrahedron around the origin
    // The closest point is at the origin within rounding of the simplex's points.
    W scale = W(0);
    for (int i = 0; i < size; ++i) scale = std::max(scale, simplex[i].squaredNorm());
    if (v.squaredNorm() <= eps * eps * scale) return result;
  }
}

}  // namespace detail

/// Decision GJK, same contract as dss::intersect (Mode::kFloat runs in float, else double).
template <class A, class B>
Result intersectGjk(const A& a, const B& b, const Options& opt = {}) {
  if (opt.mode == Mode::kFloat) return detail::runGjk<float>(a, b, opt.max_iterations);
  return detail::runGjk<double>(a, b, opt.max_iterations);
}

/// Hybrid: four GJK-directed steps, then DSS on the polygon they built.
template <class A, class B>
Result intersectHybrid(const A& a, const B& b, const Options& opt = {}) {
  constexpr int kGjkSteps = 4;
  switch (opt.mode) {
    case Mode::kExact:
      return detail::runDss<double, true, A, B, true>(a, b, opt.max_iterations, kGjkSteps);
    case Mode::kDouble:
      return detail::runDss<double, false, A, B, true>(a, b, opt.max_iterations, kGjkSteps);
    case Mode::kFloat:
      return detail::runDss<float, false, A, B, true>(a, b, opt.max_iterations, kGjkSteps);
  }
  return {};
}

}  // namespace dss
