// Fuzz target: the core decision (dss::intersect on AnyShape, plain, padded and swept), on
// shapes, poses and a power-of-two scale exponent decoded from the fuzz bytes, each answer
// checked against a property that holds by construction. The first byte picks one of four
// scenarios: (0) exact construction -- shapes on a dyadic grid scaled by 2^k, k in
// [-1000, 1000], posed by signed permutations, placed so that a chosen point of each (a vertex,
// a pole, a rim or an interior grid point) is the same world point: exact mode, padded and
// swept alike, must never answer "disjoint"; (1) arbitrary rotations with the shapes' centres
// on a common world point, asserted only where each centre sits deeper inside its shape than
// the rounding of the poses can move it; (2) world-vertex hulls of integer points scaled by
// 2^k: the exact answer must equal an exact separating-axis reference in 128-bit integers, and
// stay the same under argument swap and vertex permutation, and a hull that climbs (qhull
// adjacency, 48 points or more) must answer as the linear scan; (3) raw doubles, NaN and Inf
// included: a non-finite shape parameter, pose entry or padding answers "intersect" with
// status invalid_input, finite input never gives a NaN certificate or a crash, in every mode.
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "dss/core/any_shape_query.h"
#include "dss/core/any_shape_sweep.h"
#include "dss/mesh/mesh.h"
#include "fuzz_support.h"

namespace {

using dss::AnyShape;
using dss::Vec3d;
using Iso = Eigen::Isometry3d;
using I128 = __int128;

const char* const kTypeNames[] = {"sphere", "box",       "capsule", "cylinder",
                                  "cone",   "ellipsoid", "convex"};

std::string describe(const AnyShape& a, const Iso& X_A, const AnyShape& b, const Iso& X_B) {
  auto one = [](const AnyShape& s, const Iso& X) {
    std::string out = kTypeNames[s.index()];
    char buf[64];
    std::snprintf(buf, sizeof buf, " magnitude %.17g at ", dss::shapeMagnitude(s));
    out += buf;
    for (int i = 0; i < 3; ++i) {
      std::snprintf(buf, sizeof buf, "%.17g ", X.translation()[i]);
      out += buf;
    }
    return out;
  };
  return one(a, X_A) + "/ " + one(b, X_B);
}

// ---------------------------------------------------------------- scenario 0: exact grid

// A signed permutation: exact rotation of any vector.
Eigen::Matrix3d signedPermutation(int code) {
  static const int kPerms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                   {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const int* p = kPerms[code % 6];
  int signs = (code / 6) % 8;
  Eigen::Matrix3d R = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) R(i, p[i]) = (signs >> i) & 1 ? -1.0 : 1.0;
  // A reflection is not a rotation: flip one row's sign back when the determinant is -1.
  if (R.determinant() < 0) R.row(0) *= -1.0;
  return R;
}

struct GridShape {
  AnyShape shape;
  Vec3d point;  // a point of the shape (exactly)
};

// Lengths are integers times the unit 2^(k-20); |integer| <= 2^20 for sizes, so that every sum
// the construction forms is exact.
GridShape gridShape(FuzzedDataProvider& in, double unit) {
  const int kMax = 1 << 20;
  auto len = [&] { return in.ConsumeIntegralInRange<int>(0, kMax) * unit; };
  auto within = [&](double h) {  // a grid value in [-h, h] (h on the grid)
    const int n = static_cast<int>(h / unit);
    switch (in.ConsumeIntegralInRange<int>(0, 3)) {
      case 0:
        return -h;
      case 1:
        return h;
      case 2:
        return 0.0;
      default:
        return in.ConsumeIntegralInRange<int>(-n, n) * unit;
    }
  };
  auto sign = [&] { return in.ConsumeBool() ? 1.0 : -1.0; };
  GridShape g;
  const int type = in.ConsumeIntegralInRange<int>(0, 6);
  switch (type) {
    case 0: {
      const double r = len();
      g.shape = dss::Sphere{r};
      g.point = Vec3d::Zero();
      if (in.ConsumeBool()) g.point[in.ConsumeIntegralInRange<int>(0, 2)] = sign() * r;
      break;
    }
    case 1: {
      const Vec3d h(len(), len(), len());
      g.shape = dss::Box{h};
      g.point = Vec3d(within(h.x()), within(h.y()), within(h.z()));
      break;
    }
    case 2:
    case 3: {
      const double r = len(), h = len();
      if (type == 2)
        g.shape = dss::Capsule{r, h};
      else
        g.shape = dss::Cylinder{r, h};
      g.point = Vec3d(0, 0, within(h));
      if (in.ConsumeBool()) g.point[in.ConsumeIntegralInRange<int>(0, 1)] = within(r);
      if (type == 2 && in.ConsumeBool()) g.point = Vec3d(0, 0, sign() * (h + r));
      break;
    }
    case 4: {
      const double r = len(), h = len();
      g.shape = dss::Cone{r, h};
      if (in.ConsumeBool()) {  // on the base disc
        g.point = Vec3d(0, 0, -h);
        g.point[in.ConsumeIntegralInRange<int>(0, 1)] = within(r);
      } else {  // on the axis, apex included
        g.point = Vec3d(0, 0, within(h));
      }
      break;
    }
    case 5: {
      const Vec3d radii(len(), len(), len());
      g.shape = dss::Ellipsoid{radii};
      g.point = Vec3d::Zero();
      const int axis = in.ConsumeIntegralInRange<int>(0, 2);
      g.point[axis] = within(radii[axis]);
      break;
    }
    default: {
      const int n = in.ConsumeIntegralInRange<int>(1, 8);
      std::vector<Vec3d> pts;
      for (int i = 0; i < n; ++i)
        pts.emplace_back(in.ConsumeIntegralInRange<int>(-kMax, kMax) * unit,
                         in.ConsumeIntegralInRange<int>(-kMax, kMax) * unit,
                         in.ConsumeIntegralInRange<int>(-kMax, kMax) * unit);
      const Vec3d& v0 = pts[in.ConsumeIntegralInRange<int>(0, n - 1)];
      const Vec3d& v1 = pts[in.ConsumeIntegralInRange<int>(0, n - 1)];
      // A vertex, or the midpoint of two (exact: one more bit of the grid).
      g.point = in.ConsumeBool() ? v0 : Vec3d(0.5 * (v0 + v1));
      g.shape = dss::ConvexHull(std::move(pts));
      break;
    }
  }
  return g;
}

Vec3d gridVector(FuzzedDataProvider& in, double unit, int max) {
  return Vec3d(in.ConsumeIntegralInRange<int>(-max, max) * unit,
               in.ConsumeIntegralInRange<int>(-max, max) * unit,
               in.ConsumeIntegralInRange<int>(-max, max) * unit);
}

void scenarioExactGrid(FuzzedDataProvider& in) {
  const int k = in.ConsumeIntegralInRange<int>(-1000, 1000);
  const double unit = std::ldexp(1.0, k - 20);
  const GridShape a = gridShape(in, unit), b = gridShape(in, unit);
  const Vec3d c = gridVector(in, unit, 1 << 22);  // the common world point
  auto place = [&](const GridShape& g) {
    Iso X = Iso::Identity();
    if (in.ConsumeBool()) X.linear() = signedPermutation(in.ConsumeIntegralInRange<int>(0, 47));
    X.translation() = c - X.linear() * g.point;  // exact: a permutation and grid sums
    return X;
  };
  const Iso X_A = place(a), X_B = place(b);
  dss::Options opt;
  opt.max_iterations = in.ConsumeBool() ? 64 : in.ConsumeIntegralInRange<int>(1, 200);
  const double padding = in.ConsumeBool() ? 0.0 : in.ConsumeIntegralInRange<int>(0, 1 << 20) * unit;
  auto fail = [&](const char* what, const dss::Result& r) {
    dss_fuzz::propertyFailed(std::string(what) + ": a pair sharing a point called disjoint (" +
                             describe(a.shape, X_A, b.shape, X_B) + ", k " + std::to_string(k) +
                             ", " + std::to_string(r.iterations) + " iterations)");
  };
  for (const bool swap : {false, true}) {
    const AnyShape& s = swap ? b.shape : a.shape;
    const AnyShape& t = swap ? a.shape : b.shape;
    const Iso& X_S = swap ? X_B : X_A;
    const Iso& X_T = swap ? X_A : X_B;
    dss::Result r = dss::intersect(s, X_S, t, X_T, opt);
    if (!r.intersect) fail("exact", r);
    r = dss::intersect(s, X_S, t, X_T, opt, padding);
    if (!r.intersect) fail("exact padded", r);
    // A swept shape contains its start pose: still intersecting, whatever the end pose.
    Iso X_S1 = Iso::Identity();
    X_S1.linear() = signedPermutation(in.ConsumeIntegralInRange<int>(0, 47));
    X_S1.translation() = gridVector(in, unit, 1 << 22);
    r = dss::intersectSwept(s, X_S, X_S1, padding, t, X_T, opt);
    if (!r.intersect) fail("exact swept", r);
    r = dss::intersectSwept(s, X_S1, X_S, padding, t, X_T, X_S1, opt);
    if (!r.intersect) fail("exact swept both", r);
  }
}

// ------------------------------------------------- scenario 1: arbitrary rotations, robust

struct CentredShape {
  AnyShape shape;
  Vec3d centre;   // local point placed on the common world point
  double margin;  // its distance to the shape's boundary (a lower bound); 0 when unknown
};

CentredShape centredShape(FuzzedDataProvider& in, double scale) {
  // Lengths in [2^-10, 1] times the scale.
  auto len = [&] {
    return scale * std::ldexp(1.0 + in.ConsumeProbability<double>(),
                              -in.ConsumeIntegralInRange<int>(1, 10));
  };
  CentredShape g;
  g.centre = Vec3d::Zero();
  switch (in.ConsumeIntegralInRange<int>(0, 6)) {
    case 0: {
      const double r = len();
      g.shape = dss::Sphere{r};
      g.margin = r;
      break;
    }
    case 1: {
      const Vec3d h(len(), len(), len());
      g.shape = dss::Box{h};
      g.margin = h.minCoeff();
      break;
    }
    case 2: {
      const double r = len(), h = len();
      g.shape = dss::Capsule{r, h};
      g.margin = r;
      break;
    }
    case 3: {
      const double r = len(), h = len();
      g.shape = dss::Cylinder{r, h};
      g.margin = std::min(r, h);
      break;
    }
    case 4: {
      // The centroid (0, 0, -h/2): h/2 above the base, 0.75 r cos(half angle) from the side.
      const double r = len(), h = len();
      g.shape = dss::Cone{r, h};
      g.centre = Vec3d(0, 0, -h / 2);
      g.margin = std::min(h / 2, 0.75 * r * (2 * h / std::hypot(2 * h, r)));
      break;
    }
    case 5: {
      const Vec3d radii(len(), len(), len());
      g.shape = dss::Ellipsoid{radii};
      g.margin = radii.minCoeff();
      break;
    }
    default: {
      std::vector<Vec3d> pts;
      const int n = in.ConsumeIntegralInRange<int>(1, 12);
      for (int i = 0; i < n; ++i)
        pts.push_back(Vec3d(len(), len(), len()) - Vec3d::Constant(0.5 * scale));
      g.shape = dss::ConvexHull(std::move(pts));
      g.margin = 0.0;
      break;
    }
  }
  return g;
}

Eigen::Matrix3d rotation(FuzzedDataProvider& in) {
  Eigen::Quaterniond q(
      in.ConsumeFloatingPointInRange<double>(-1, 1), in.ConsumeFloatingPointInRange<double>(-1, 1),
      in.ConsumeFloatingPointInRange<double>(-1, 1), in.ConsumeFloatingPointInRange<double>(-1, 1));
  if (!(q.norm() > 1e-3)) q = Eigen::Quaterniond::Identity();
  return q.normalized().toRotationMatrix();
}

void scenarioRotated(FuzzedDataProvider& in) {
  const int k = in.ConsumeIntegralInRange<int>(-1000, 1000);
  const double scale = std::ldexp(1.0, k);
  const CentredShape a = centredShape(in, scale), b = centredShape(in, scale);
  const Vec3d c = scale * Vec3d(in.ConsumeFloatingPointInRange<double>(-4, 4),
                                in.ConsumeFloatingPointInRange<double>(-4, 4),
                                in.ConsumeFloatingPointInRange<double>(-4, 4));
  auto place = [&](const CentredShape& g, double& slack) {
    Iso X = Iso::Identity();
    X.linear() = rotation(in);
    X.translation() = c - X.linear() * g.centre;
    // The exact image of the centre is c up to the rounding of R centre and of the
    // subtraction: a few ulps of the magnitudes involved (plus subnormal spacing).
    slack = 16 * std::numeric_limits<double>::epsilon() *
                (c.norm() + g.centre.norm() + X.translation().norm()) +
            64 * std::numeric_limits<double>::denorm_min();
    return X;
  };
  double slack_a = 0, slack_b = 0;
  const Iso X_A = place(a, slack_a), X_B = place(b, slack_b);
  dss::Options opt;
  const double padding = in.ConsumeBool() ? 0.0 : scale * in.ConsumeProbability<double>();
  const bool robust = a.margin > slack_a && b.margin > slack_b;
  for (const dss::Mode mode : {dss::Mode::kExact, dss::Mode::kDouble, dss::Mode::kFloat}) {
    opt.mode = mode;
    for (const bool swap : {false, true}) {
      const dss::Result r = swap ? dss::intersect(b.shape, X_B, a.shape, X_A, opt, padding)
                                 : dss::intersect(a.shape, X_A, b.shape, X_B, opt, padding);
      if (!r.separating_direction.allFinite())
        dss_fuzz::propertyFailed("a NaN certificate for finite input");
      if (mode == dss::Mode::kExact && robust && !r.intersect)
        dss_fuzz::propertyFailed(
            "exact: shapes sharing their centres' world point called "
            "disjoint (" +
            describe(a.shape, X_A, b.shape, X_B) + ", k " + std::to_string(k) + ")");
      if (mode == dss::Mode::kExact && r.status == dss::Status::kInvalidInput)
        dss_fuzz::propertyFailed("exact: finite input in range called invalid (" +
                                 describe(a.shape, X_A, b.shape, X_B) + ", k " + std::to_string(k) +
                                 ")");
    }
  }
}

// ------------------------------------------------------ scenario 2: integer world hulls

struct IVec {
  I128 x, y, z;
};
IVec sub(const IVec& a, const IVec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
IVec cross(const IVec& a, const IVec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
I128 dot(const IVec& a, const IVec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

bool separates(const IVec& n, const std::vector<IVec>& a, const std::vector<IVec>& b) {
  if (n.x == 0 && n.y == 0 && n.z == 0) return false;
  I128 amin = dot(n, a[0]), amax = amin, bmin = dot(n, b[0]), bmax = bmin;
  for (const auto& p : a) {
    const I128 v = dot(n, p);
    amin = std::min(amin, v), amax = std::max(amax, v);
  }
  for (const auto& p : b) {
    const I128 v = dot(n, p);
    bmin = std::min(bmin, v), bmax = std::max(bmax, v);
  }
  return amax < bmin || bmax < amin;
}

// Exact intersection of conv(a) and conv(b), touching included, for |coordinates| <= 2^20:
// every separating-axis candidate of convex polytopes of any dimension (face normals as
// crosses of difference vectors, edge-edge crosses, and for lower-dimensional sets the
// connecting directions and their crosses with edges, which give the in-plane normals).
bool referenceIntersect(const std::vector<IVec>& a, const std::vector<IVec>& b) {
  std::vector<IVec> ea, eb;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = i + 1; j < a.size(); ++j) ea.push_back(sub(a[j], a[i]));
  for (std::size_t i = 0; i < b.size(); ++i)
    for (std::size_t j = i + 1; j < b.size(); ++j) eb.push_back(sub(b[j], b[i]));
  for (const auto* e : {&ea, &eb})
    for (std::size_t i = 0; i < e->size(); ++i)
      for (std::size_t j = i + 1; j < e->size(); ++j)
        if (separates(cross((*e)[i], (*e)[j]), a, b)) return false;
  for (const auto& u : ea)
    for (const auto& v : eb)
      if (separates(cross(u, v), a, b)) return false;
  for (const auto& p : a)
    for (const auto& q : b) {
      const IVec d = sub(q, p);
      if (separates(d, a, b)) return false;
      for (const auto* e : {&ea, &eb})
        for (const auto& u : *e) {
          const IVec c = cross(u, d);
          if (separates(c, a, b) || separates(cross(c, u), a, b)) return false;
        }
    }
  return true;
}

void scenarioIntegerHulls(FuzzedDataProvider& in) {
  const int k = in.ConsumeIntegralInRange<int>(-1000, 1000);
  const bool many = in.ConsumeIntegralInRange<int>(0, 7) == 0;  // climbing hulls
  auto points = [&](std::vector<IVec>& ints) {
    const int kMax = many ? (1 << 10) : (1 << 20);
    const int n =
        many ? in.ConsumeIntegralInRange<int>(48, 96) : in.ConsumeIntegralInRange<int>(1, 8);
    const IVec o{in.ConsumeIntegralInRange<int>(-kMax, kMax),
                 in.ConsumeIntegralInRange<int>(-kMax, kMax),
                 in.ConsumeIntegralInRange<int>(-kMax, kMax)};
    const int spread = in.ConsumeIntegralInRange<int>(0, kMax);
    for (int i = 0; i < n; ++i)
      ints.push_back({o.x + in.ConsumeIntegralInRange<int>(-spread, spread),
                      o.y + in.ConsumeIntegralInRange<int>(-spread, spread),
                      o.z + in.ConsumeIntegralInRange<int>(-spread, spread)});
  };
  std::vector<IVec> ia, ib;
  points(ia);
  points(ib);
  auto toDouble = [k](const std::vector<IVec>& ints) {
    std::vector<Vec3d> out;
    for (const IVec& p : ints)
      out.emplace_back(std::ldexp(double(p.x), k), std::ldexp(double(p.y), k),
                       std::ldexp(double(p.z), k));
    return out;
  };
  std::vector<Vec3d> pa = toDouble(ia), pb = toDouble(ib);
  const AnyShape a = dss::ConvexHull(pa), b = dss::ConvexHull(pb);
  const Iso I = Iso::Identity();
  dss::Options opt;
  const dss::Result ab = dss::intersect(a, I, b, I, opt), ba = dss::intersect(b, I, a, I, opt);
  for (const dss::Result* r : {&ab, &ba})
    if (r->status == dss::Status::kInvalidInput)
      dss_fuzz::propertyFailed("integer hulls called invalid input, k " + std::to_string(k));
  if (ab.status == dss::Status::kDecided && ba.status == dss::Status::kDecided &&
      ab.intersect != ba.intersect)
    dss_fuzz::propertyFailed("world hulls: the answer changes under swap, k " + std::to_string(k));
  if (!many) {
    const bool truth = referenceIntersect(ia, ib);
    for (const dss::Result* r : {&ab, &ba})
      if (r->status == dss::Status::kDecided && r->intersect != truth)
        dss_fuzz::propertyFailed(std::string("world hulls: exact answer ") +
                                 (r->intersect ? "intersect" : "disjoint") +
                                 " against the reference, k " + std::to_string(k));
    // The same sets with their points in another order.
    std::rotate(pa.begin(), pa.begin() + in.ConsumeIntegralInRange<std::size_t>(0, pa.size() - 1),
                pa.end());
    std::reverse(pb.begin(), pb.end());
    const dss::Result perm = dss::intersect(dss::ConvexHull(pa), I, dss::ConvexHull(pb), I, opt);
    if (perm.status == dss::Status::kDecided && perm.intersect != truth)
      dss_fuzz::propertyFailed("world hulls: the answer changes under vertex permutation, k " +
                               std::to_string(k));
    return;
  }
  // Hulls that climb (qhull adjacency) against the same sets scanned linearly.
  const AnyShape ca = dss::mesh::convexHull(pa, "fuzz a"), cb = dss::mesh::convexHull(pb, "fuzz b");
  const dss::Result climbed = dss::intersect(ca, I, cb, I, opt);
  if (climbed.status == dss::Status::kDecided && ab.status == dss::Status::kDecided &&
      climbed.intersect != ab.intersect)
    dss_fuzz::propertyFailed("world hulls: climbing and scanning hulls disagree, k " +
                             std::to_string(k));
}

// ----------------------------------------------------------- scenario 3: raw doubles

double rawDouble(FuzzedDataProvider& in) {
  std::uint64_t bits = in.ConsumeIntegral<std::uint64_t>();
  double x;
  std::memcpy(&x, &bits, sizeof x);
  return x;
}

struct RawShape {
  AnyShape shape;
  bool finite = true;
  double magnitude = 0;  // largest |parameter|
};

RawShape rawShape(FuzzedDataProvider& in) {
  RawShape g;
  std::vector<double> used;
  auto v = [&] {
    const double x = std::abs(rawDouble(in));
    used.push_back(x);
    return x;
  };
  switch (in.ConsumeIntegralInRange<int>(0, 6)) {
    case 0:
      g.shape = dss::Sphere{v()};
      break;
    case 1:
      g.shape = dss::Box{Vec3d(v(), v(), v())};
      break;
    case 2:
      g.shape = dss::Capsule{v(), v()};
      break;
    case 3:
      g.shape = dss::Cylinder{v(), v()};
      break;
    case 4:
      g.shape = dss::Cone{v(), v()};
      break;
    case 5:
      g.shape = dss::Ellipsoid{Vec3d(v(), v(), v())};
      break;
    default: {
      std::vector<Vec3d> pts;
      const int n = in.ConsumeIntegralInRange<int>(1, 10);
      for (int i = 0; i < n; ++i) {
        Vec3d p(rawDouble(in), rawDouble(in), rawDouble(in));
        if (!p.allFinite()) p.setZero();  // the ConvexHull constructor refuses them
        for (int j = 0; j < 3; ++j) used.push_back(std::abs(p[j]));
        pts.push_back(p);
      }
      g.shape = dss::ConvexHull(std::move(pts));
      break;
    }
  }
  for (double x : used) {
    g.finite = g.finite && std::isfinite(x);
    if (std::isfinite(x)) g.magnitude = std::max(g.magnitude, x);
  }
  return g;
}

Iso rawPose(FuzzedDataProvider& in, bool& finite, double& magnitude) {
  Iso X = Iso::Identity();
  switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0:
      break;
    case 1:
      X.linear() = rotation(in);
      break;
    case 2: {  // a raw quaternion, normalised (NaN and Inf pass through)
      Eigen::Quaterniond q(rawDouble(in), rawDouble(in), rawDouble(in), rawDouble(in));
      X.linear() = q.normalized().toRotationMatrix();
      break;
    }
    default:  // a raw matrix entry in an otherwise exact rotation
      X.linear()(in.ConsumeIntegralInRange<int>(0, 2), in.ConsumeIntegralInRange<int>(0, 2)) =
          rawDouble(in);
      break;
  }
  if (in.ConsumeBool()) X.translation() = Vec3d(rawDouble(in), rawDouble(in), rawDouble(in));
  finite = X.matrix().allFinite();
  magnitude = finite ? X.translation().cwiseAbs().maxCoeff() : 0.0;
  return X;
}

void scenarioRaw(FuzzedDataProvider& in) {
  const RawShape a = rawShape(in), b = rawShape(in);
  bool fa = true, fb = true;
  double ma = 0, mb = 0;
  const Iso X_A = rawPose(in, fa, ma), X_B = rawPose(in, fb, mb);
  const double padding = in.ConsumeBool() ? 0.0 : rawDouble(in);
  const bool finite = a.finite && b.finite && fa && fb && std::isfinite(padding);
  dss::Options opt;
  opt.max_iterations = in.ConsumeIntegralInRange<int>(0, 100);
  for (const dss::Mode mode : {dss::Mode::kExact, dss::Mode::kDouble, dss::Mode::kFloat}) {
    opt.mode = mode;
    for (const bool swap : {false, true}) {
      const dss::Result r = swap ? dss::intersect(b.shape, X_B, a.shape, X_A, opt, padding)
                                 : dss::intersect(a.shape, X_A, b.shape, X_B, opt, padding);
      if (!finite && (!r.intersect || r.status != dss::Status::kInvalidInput))
        dss_fuzz::propertyFailed(std::string("non-finite input answered ") +
                                 (r.intersect ? "intersect" : "disjoint") + " with status " +
                                 dss::toString(r.status) + " in " + dss::toString(mode) +
                                 " mode (" + describe(a.shape, X_A, b.shape, X_B) + ")");
      if (!r.separating_direction.allFinite()) dss_fuzz::propertyFailed("a non-finite certificate");
    }
    const dss::Result s = dss::intersectSwept(a.shape, X_A, X_B, padding, b.shape, X_B, opt);
    if (!finite && (!s.intersect || s.status != dss::Status::kInvalidInput))
      dss_fuzz::propertyFailed("swept: non-finite input not answered invalid");
    if (!s.separating_direction.allFinite()) dss_fuzz::propertyFailed("swept: a NaN certificate");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0:
      scenarioExactGrid(in);
      break;
    case 1:
      scenarioRotated(in);
      break;
    case 2:
      scenarioIntegerHulls(in);
      break;
    default:
      scenarioRaw(in);
      break;
  }
  return 0;
}
