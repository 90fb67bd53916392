// ContinuousMotionChecker: padded swept hulls per element, halving each sub-motion and
// re-testing only the units its parent could not clear (see continuous_motion.h).
#include "dss/checker/continuous_motion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

#include "dss/core/any_shape_sweep.h"

namespace dss {

namespace {

// Rounding margin of the swept box stage, relative to the coordinates' size.
constexpr double kBoxMargin = 1e-9;
// A unit whose padding over a sub-motion exceeds this fraction of its element's radius (the
// smaller one's, for a self pair) skips its swept test while the sub-motion can still be
// halved: such tests mostly fail, and a failing test costs more than the halving.
constexpr double kDeferRatio = 0.5;

struct Interval {
  double ta, tb;
  std::size_t begin, end;  // its units: Scratch::work[begin, end)
  int pa, pb;              // the link poses at ta and tb: Scratch::pool slots
};
// One element over the current sub-motion: its sphere's centre at both ends, the ball around
// its swept sphere (centre `mid`; radius `reach`: half the chord of its centre, its radius and
// its slot's padding), its shape poses at both ends, and whether the clearance grid clears
// that ball (-1: not asked yet).
struct ElementSweep {
  std::uint64_t stamp = 0;  // the sub-motion these are for (Scratch::stamp)
  Eigen::Vector3d c0, c1;   // its sphere's centre at both ends
  Eigen::Vector3d mid;
  double reach = 0.0;
  Eigen::Isometry3d XS0, XS1;  // its shape poses at both ends, once has_poses
  bool has_poses = false;
  int grid = -1;
};
// A slot's padding in an ancestor's frame (ContinuousMotionChecker::rel_chains_) over the
// current sub-motion.
struct RelativePad {
  std::uint64_t stamp = 0;
  double pad = 0.0;
};
// The inverse pose of a pair frame's link at both ends of the current sub-motion.
struct FrameInverse {
  std::uint64_t stamp = 0;
  Eigen::Isometry3d X0, X1;
};
struct Scratch {
  std::vector<ElementSweep> sweeps;         // per model element
  std::vector<FrameInverse> frame_inverse;  // per robot link
  std::vector<RelativePad> rel_pads;        // per relative chain
  std::uint64_t stamp = 0;
  // Link poses of sub-motion ends, one slot of num-links poses each, shared by the intervals
  // that end there and released when none does.
  std::vector<Eigen::Isometry3d> pool;
  std::vector<int> refs, free_slots;
  int acquire(std::size_t nl) {
    if (free_slots.empty()) {
      free_slots.push_back(int(refs.size()));
      refs.push_back(0);
      pool.resize(refs.size() * nl, Eigen::Isometry3d::Identity());
    }
    const int slot = free_slots.back();
    free_slots.pop_back();
    refs[std::size_t(slot)] = 1;
    return slot;
  }
  void release(int slot) {
    if (--refs[std::size_t(slot)] == 0) free_slots.push_back(slot);
  }
  // Per sub-motion: the travel of each active value (jointTravel), and each slot's padding,
  // computed when a unit first needs it (pad_stamp == stamp).
  std::vector<double> travel, pad, qa, qb;
  std::vector<std::uint64_t> pad_stamp;
  std::vector<int> turning;  // the ball joints whose quaternion differs at the motion's ends
  std::vector<unsigned char> free_along;  // per self-pair table, for the current sub-motion
  std::vector<int> work;                  // unit indices, a stack of lists (see clear())
  std::vector<Interval> stack;
};
Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

// Every point of a set whose path is bounded by b stays within this of its chord (see
// continuous_motion.h), with a rounding margin.
double chordPadding(const MotionBound& b) {
  return std::min(0.5 * b.length, 0.125 * b.bend) * (1.0 + 1e-9) + (b.length > 0 ? 1e-12 : 0.0);
}

// Grows [lo, hi] (in the frame F: x_F = Rf^T (x_W - o)) by the element box (centre bc, half
// extents bh in the shape frame) at shape pose X.
void growByBox(const Eigen::Matrix3d& Rf, const Eigen::Vector3d& o, const Eigen::Isometry3d& X,
               const Eigen::Vector3d& bc, const Eigen::Vector3d& bh, Eigen::Vector3d* lo,
               Eigen::Vector3d* hi) {
  const Eigen::Matrix3d R = Rf.transpose() * X.linear();
  const Eigen::Vector3d c = Rf.transpose() * (X * bc - o);
  const Eigen::Vector3d e = R.cwiseAbs() * bh;
  *lo = lo->cwiseMin(c - e);
  *hi = hi->cwiseMax(c + e);
}
// The axis-aligned box in frame (Rf, o) around an element's local box at two poses.
void sweptBox(const Eigen::Matrix3d& Rf, const Eigen::Vector3d& o, const Eigen::Isometry3d& X0,
              const Eigen::Isometry3d& X1, const Eigen::Vector3d& bc, const Eigen::Vector3d& bh,
              Eigen::Vector3d* lo, Eigen::Vector3d* hi) {
  *lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  *hi = -*lo;
  growByBox(Rf, o, X0, bc, bh, lo, hi);
  growByBox(Rf, o, X1, bc, bh, lo, hi);
}
// [lo_a, hi_a] and [lo_b, hi_b] apart by more than gap along one axis (a NaN never is).
bool boxesApart(const Eigen::Vector3d& lo_a, const Eigen::Vector3d& hi_a,
                const Eigen::Vector3d& lo_b, const Eigen::Vector3d& hi_b, double gap) {
  for (int k = 0; k < 3; ++k)
    if (lo_b[k] - hi_a[k] > gap || lo_a[k] - hi_b[k] > gap) return true;
  return false;
}

}  // namespace

ContinuousMotionChecker::ContinuousMotionChecker(std::shared_ptr<const DssChecker> checker,
                                                 double min_fraction)
    : checker_(std::move(checker)), min_fraction_(min_fraction) {
  if (!(min_fraction_ > 0.0 && min_fraction_ <= 1.0))
    throw std::invalid_argument("ContinuousMotionChecker: min_fraction " +
                                std::to_string(min_fraction_) + " is not in (0, 1]");
  const CollisionModel& m = checker_->model();
  chains_.resize(m.slots().size());
  for (std::size_t k = 0; k < m.slots().size(); ++k) {
    const auto& s = m.slots()[k];
    if (s.moves)
      chains_[k] = chainAbove(m.robot(), s.link, -1, s.center_L.norm() + s.radius, m.held());
  }
  for (std::size_t a = 0; a < m.robot().numActiveJoints(); ++a) {
    const RobotJoint& j = m.robot().joints[m.robot().active_joints[a]];
    if (j.type == JointType::kBall && j.active_index == int(a)) balls_.push_back(int(a));
  }
  // Units in the order of the state sweep: robot vs scene, then self pairs.
  for (const auto& s : m.slots()) {
    if (!s.moves) continue;
    for (int e = s.first_element; e < s.first_element + s.num_elements; ++e)
      for (int o : s.obstacles) units_.push_back({e, o, false, -1, -1, s.base_bit});
  }
  const RobotModel& robot = m.robot();
  std::vector<char> computed(robot.links.size(), 0);
  for (int l : m.kinematics().updatedLinks()) computed[std::size_t(l)] = 1;
  std::map<std::pair<int, int>, int> rel_index;  // (slot, ancestor) -> rel_chains_
  for (const auto& p : m.selfPairs()) {
    const auto& sa = m.slots()[p.a];
    const auto& sb = m.slots()[p.b];
    // The world frame when the common ancestor's pose is not computed (it does not move: the
    // joints above it are fixed or held).
    const int lca = lowestCommonAncestor(robot, sa.link, sb.link);
    PairFrame f;
    f.frame = lca >= 0 && computed[std::size_t(lca)] ? lca : -1;
    auto chainIndex = [&](int slot) {
      const auto key = std::make_pair(slot, lca);
      auto it = rel_index.find(key);
      if (it == rel_index.end()) {
        const auto& s = m.slots()[std::size_t(slot)];
        it = rel_index.emplace(key, int(rel_chains_.size())).first;
        rel_chains_.push_back(
            chainAbove(robot, s.link, lca, s.center_L.norm() + s.radius, m.held()));
      }
      return it->second;
    };
    f.chain_a = chainIndex(p.a);
    f.chain_b = chainIndex(p.b);
    f.still_a = rel_chains_[std::size_t(f.chain_a)].empty();
    f.still_b = rel_chains_[std::size_t(f.chain_b)].empty();
    const int pair_index = int(pairs_.size());
    pairs_.push_back(std::move(f));
    for (int ea = sa.first_element; ea < sa.first_element + sa.num_elements; ++ea)
      for (int eb = sb.first_element; eb < sb.first_element + sb.num_elements; ++eb)
        units_.push_back({ea, eb, true, p.table, pair_index});
  }
}

void ContinuousMotionChecker::paddings(const double* qa, const double* qb, double* pad) const {
  std::vector<double> travel(checker_->model().robot().numActiveJoints());
  jointTravel(qa, qb, travel.size(), balls_, travel.data());
  for (std::size_t k = 0; k < chains_.size(); ++k)
    pad[k] = chordPadding(motionBound(chains_[k], travel.data()));
}

bool ContinuousMotionChecker::unitClear(const Unit& u, const Eigen::Isometry3d* XA,
                                        const Eigen::Isometry3d* XB, bool may_defer,
                                        std::uint64_t* tests) const {
  const CollisionModel& m = checker_->model();
  const DssCheckerSettings& set = checker_->settings();
  const auto& el = m.elements();
  Scratch& sc = scratch();
  // A slot's padding over the sub-motion, computed once per sub-motion.
  auto pad = [&](int slot) {
    const std::size_t k = std::size_t(slot);
    if (sc.pad_stamp[k] != sc.stamp) {
      sc.pad[k] = chordPadding(motionBound(chains_[k], sc.travel.data()));
      sc.pad_stamp[k] = sc.stamp;
    }
    return sc.pad[k];
  };
  // An element's sphere and shape poses over the sub-motion, computed once per sub-motion.
  auto swept = [&](int e) -> ElementSweep& {
    ElementSweep& s = sc.sweeps[std::size_t(e)];
    if (s.stamp == sc.stamp) return s;
    const CollisionModel::Element& x = el[std::size_t(e)];
    const Eigen::Isometry3d& X0 = XA[x.link];
    const Eigen::Isometry3d& X1 = XB[x.link];
    s.c0 = X0 * x.center_L, s.c1 = X1 * x.center_L;
    s.mid = 0.5 * (s.c0 + s.c1);
    s.reach = 0.5 * (s.c1 - s.c0).norm() + x.radius + pad(x.slot);
    s.has_poses = false;
    s.grid = -1;
    s.stamp = sc.stamp;
    return s;
  };
  // ... and its shape poses, when a stage after the spheres needs them.
  auto posed = [&](int e) -> const ElementSweep& {
    ElementSweep& s = sc.sweeps[std::size_t(e)];
    if (!s.has_poses) {
      const CollisionModel::Element& x = el[std::size_t(e)];
      s.XS0 = x.identity_LS ? XA[x.link] : XA[x.link] * x.source->X_LS;
      s.XS1 = x.identity_LS ? XB[x.link] : XB[x.link] * x.source->X_LS;
      s.has_poses = true;
    }
    return s;
  };
  const auto& ea = el[u.a];
  ElementSweep& sa = swept(u.a);
  if (!u.self) {
    const double p = pad(ea.slot) + set.scene_padding;
    const double r = sa.reach + set.scene_padding;
    // One clearance-grid lookup clears the element against every obstacle at once.
    if (sa.grid < 0) sa.grid = m.clearanceGrid().clear(sa.mid, r) ? 1 : 0;
    if (sa.grid) return true;
    if (detail::sqDistPointAabb(sa.mid, m.obstacleBoxes()[u.b]) > r * r) return true;
    // A turned obstacle: the swept sphere against its oriented box.
    const Obb& ob = m.obstacleObbs()[u.b];
    if (!ob.axis_aligned && ballApartObb(sa.mid, r, ob)) return true;
    // The element's local box at both ends, bounded in the obstacle's box frame, grown by the
    // padding: apart along one of the frame's axes, the swept hull is apart too.
    posed(u.a);
    Eigen::Vector3d lo, hi;
    sweptBox(ob.R, ob.c, sa.XS0, sa.XS1, ea.box_center_S, ea.box_half, &lo, &hi);
    const double margin = kBoxMargin * (1.0 + ob.c.norm() + ob.h.norm() + r);
    if (boxesApart(lo, hi, -ob.h, ob.h, p + margin)) return true;
    if (may_defer && p > kDeferRatio * ea.radius) return false;
    ++*tests;
    const Obstacle& o = m.scene().obstacles[u.b];
    return !intersectSwept(ea.source->shape, sa.XS0, sa.XS1, p, o.shape, o.X_WO, set.options)
                .intersect;
  }
  const auto& eb = el[u.b];
  // In the pair's frame F: poses relative to F at both ends, paddings from the joints below F.
  const PairFrame& f = pairs_[std::size_t(u.pair)];
  auto relativePad = [&](int chain) {
    RelativePad& rp = sc.rel_pads[std::size_t(chain)];
    if (rp.stamp != sc.stamp) {
      rp.pad = chordPadding(motionBound(rel_chains_[std::size_t(chain)], sc.travel.data()));
      rp.stamp = sc.stamp;
    }
    return rp.pad;
  };
  // Sphere centres in F at both ends (F's inverse computed once per sub-motion), then the
  // shape poses in F for the stages after the spheres.
  const ElementSweep& sb = swept(u.b);
  // Both swept spheres in the world first (computed once per element and sub-motion): apart,
  // the pair is apart at every instant, whatever moves it.
  {
    const double rw = sa.reach + sb.reach + set.self_padding;
    if ((sa.mid - sb.mid).squaredNorm() > rw * rw) return true;
  }
  const Eigen::Isometry3d* F0 = nullptr;
  const Eigen::Isometry3d* F1 = nullptr;
  if (f.frame >= 0) {
    FrameInverse& fi = sc.frame_inverse[std::size_t(f.frame)];
    if (fi.stamp != sc.stamp) {
      fi.X0 = XA[f.frame].inverse();
      fi.X1 = XB[f.frame].inverse();
      fi.stamp = sc.stamp;
    }
    F0 = &fi.X0, F1 = &fi.X1;
  }
  const double p = relativePad(f.chain_a) + relativePad(f.chain_b) + set.self_padding;
  const Eigen::Vector3d a0 = F0 ? *F0 * sa.c0 : sa.c0, a1 = F1 ? *F1 * sa.c1 : sa.c1;
  const Eigen::Vector3d b0 = F0 ? *F0 * sb.c0 : sb.c0, b1 = F1 ? *F1 * sb.c1 : sb.c1;
  const double r = 0.5 * (a1 - a0).norm() + 0.5 * (b1 - b0).norm() + ea.radius + eb.radius + p;
  if ((0.5 * (a0 + a1) - 0.5 * (b0 + b1)).squaredNorm() > r * r) return true;
  posed(u.a);
  posed(u.b);
  const Eigen::Isometry3d YA0 = F0 ? *F0 * sa.XS0 : sa.XS0, YA1 = F1 ? *F1 * sa.XS1 : sa.XS1;
  const Eigen::Isometry3d YB0 = F0 ? *F0 * sb.XS0 : sb.XS0, YB1 = F1 ? *F1 * sb.XS1 : sb.XS1;
  // Both elements' local boxes at both ends, bounded in a's shape frame at the start.
  const Eigen::Matrix3d& Rf = YA0.linear();
  const Eigen::Vector3d& of = YA0.translation();
  Eigen::Vector3d lo_a, hi_a, lo_b, hi_b;
  sweptBox(Rf, of, YA0, YA1, ea.box_center_S, ea.box_half, &lo_a, &hi_a);
  sweptBox(Rf, of, YB0, YB1, eb.box_center_S, eb.box_half, &lo_b, &hi_b);
  const double margin = kBoxMargin * (1.0 + of.norm() + r);
  if (boxesApart(lo_a, hi_a, lo_b, hi_b, p + margin)) return true;
  if (may_defer && p > kDeferRatio * std::min(ea.radius, eb.radius)) return false;
  ++*tests;
  // A link that is the frame itself (the common ancestor) does not move there: only the other
  // one is swept, at half the support cost.
  if (f.still_a)
    return !intersectSwept(eb.source->shape, YB0, YB1, p, ea.source->shape, YA0, set.options)
                .intersect;
  if (f.still_b)
    return !intersectSwept(ea.source->shape, YA0, YA1, p, eb.source->shape, YB0, set.options)
                .intersect;
  return !intersectSwept(ea.source->shape, YA0, YA1, p, eb.source->shape, YB0, YB1, set.options)
              .intersect;
}

bool ContinuousMotionChecker::clear(const double* q0, const double* q1, double* last,
                                    MotionOrder kind) const {
  // Without a last valid fraction to report, a colliding state decides the motion at once: when
  // the whole motion is not cleared at once, two states are checked before the first midpoint,
  // the first two of the discrete check's order (discrete_motion.h).
  bool probe = last == nullptr;
  double last_storage = 0.0;
  if (!last) last = &last_storage;
  *last = 0.0;
  const CollisionModel& m = checker_->model();
  // The shared counters are updated once per motion, not per test: threads checking motions
  // concurrently would otherwise fight over their cache line.
  std::uint64_t intervals = 1, tests = 0;
  struct Flush {
    const ContinuousMotionChecker* c;
    const std::uint64_t& intervals;
    const std::uint64_t& tests;
    ~Flush() {
      c->sub_motions_.fetch_add(intervals, std::memory_order_relaxed);
      c->unit_tests_.fetch_add(tests, std::memory_order_relaxed);
    }
  } flush{this, intervals, tests};
  // The bounds hold for states within the model's bounds; the set of such states is convex
  // (a box), so the whole motion is within them when both ends are.
  if (!m.withinBounds(q0) || !m.withinBounds(q1)) return false;
  // Depth-first halving, left half first. `work` is a stack of unit lists: an interval owns
  // work[begin, end), written by its parent; the units it leaves for its halves (the first one
  // it fails to clear and those after it) are appended after `end` and shared by both. When an
  // interval is popped, everything after its own list belongs to intervals already finished, so
  // the list is cut back to `end` first.
  const std::size_t n = m.robot().numActiveJoints();
  Scratch& sc = scratch();
  const std::size_t nl = m.robot().links.size();
  if (sc.pool.size() != sc.refs.size() * nl) sc.pool.clear(), sc.refs.clear();  // another model
  sc.free_slots.clear();
  for (std::size_t k = 0; k < sc.refs.size(); ++k) sc.refs[k] = 0, sc.free_slots.push_back(int(k));
  if (sc.pad.size() < m.slots().size())
    sc.pad.resize(m.slots().size()), sc.pad_stamp.resize(m.slots().size(), 0);
  if (sc.sweeps.size() < m.elements().size()) sc.sweeps.resize(m.elements().size());
  if (sc.rel_pads.size() < rel_chains_.size()) sc.rel_pads.resize(rel_chains_.size());
  if (sc.frame_inverse.size() < nl) sc.frame_inverse.resize(nl);
  if (sc.qa.size() < n) sc.qa.resize(n), sc.qb.resize(n), sc.travel.resize(n);
  if (sc.free_along.size() < m.selfTables().size()) sc.free_along.resize(m.selfTables().size());
  sc.work.resize(units_.size());
  for (std::size_t u = 0; u < units_.size(); ++u) sc.work[u] = static_cast<int>(u);
  sc.stack.clear();
  // A ball joint the motion holds (the same quaternion at both ends) is interpolated linearly
  // like the other values, which keeps it exactly; only the others are slerped.
  sc.turning.clear();
  for (int a : balls_)
    if (!sameQuaternion(q0 + a, q1 + a)) sc.turning.push_back(a);
  const int p0 = sc.acquire(nl), p1 = sc.acquire(nl);
  m.kinematics().computeLinkPoses(q0, sc.pool.data() + std::size_t(p0) * nl);
  m.kinematics().computeLinkPoses(q1, sc.pool.data() + std::size_t(p1) * nl);
  sc.stack.push_back({0.0, 1.0, 0, units_.size(), p0, p1});
  double* qa = sc.qa.data();
  double* qb = sc.qb.data();
  bool first = true;
  while (!sc.stack.empty()) {
    const Interval iv = sc.stack.back();
    sc.stack.pop_back();
    sc.work.resize(iv.end);
    intervals += !first;
    first = false;
    for (std::size_t i = 0; i < n; ++i) {
      qa[i] = q0[i] + iv.ta * (q1[i] - q0[i]);
      qb[i] = q0[i] + iv.tb * (q1[i] - q0[i]);
    }
    for (int a : sc.turning) {  // quaternions: slerp along the shorter arc, as OMPL's SO(3)
      slerpQuaternion(q0 + a, q1 + a, iv.ta, qa + a);
      slerpQuaternion(q0 + a, q1 + a, iv.tb, qb + a);
    }
    const Eigen::Isometry3d* XA = sc.pool.data() + std::size_t(iv.pa) * nl;
    const Eigen::Isometry3d* XB = sc.pool.data() + std::size_t(iv.pb) * nl;
    jointTravel(qa, qb, n, sc.turning, sc.travel.data());
    ++sc.stamp;  // every element's sweep and every slot's padding is stale
    bool tables_read = false, base_read = false;
    std::uint8_t base_along = 0;
    const bool may_defer = iv.tb - iv.ta > min_fraction_;
    for (std::size_t w = iv.begin; w < iv.end; ++w) {
      const int u = sc.work[w];
      const Unit& unit = units_[u];
      if (unit.table >= 0) {
        if (!tables_read) {
          m.selfTables().freeAlong(qa, qb, checker_->settings().self_padding, sc.free_along.data());
          tables_read = true;
        }
        if (sc.free_along[std::size_t(unit.table)]) continue;  // certified over [ta, tb]
      }
      // A planar base's link certified free in every table cell the sub-motion crosses.
      const std::uint8_t base_bit = unit.base_bit;
      if (base_bit) {
        if (!base_read) {
          base_along = m.baseTable().freeAlong(qa, qb, checker_->settings().scene_padding);
          base_read = true;
        }
        if (base_along & base_bit) continue;
      }
      // The most frequent answers without the call, from sweeps already computed in this
      // sub-motion: an element the clearance grid has cleared or whose swept sphere misses the
      // obstacle's box, and a self pair whose world swept spheres are apart (unitClear's first
      // tests).
      if (!unit.self) {
        const ElementSweep& e = sc.sweeps[std::size_t(unit.a)];
        if (e.stamp == sc.stamp && e.grid >= 0) {
          if (e.grid == 1) continue;
          const double r = e.reach + checker_->settings().scene_padding;
          if (detail::sqDistPointAabb(e.mid, m.obstacleBoxes()[std::size_t(unit.b)]) > r * r)
            continue;
        }
      } else {
        const ElementSweep& a = sc.sweeps[std::size_t(unit.a)];
        const ElementSweep& b = sc.sweeps[std::size_t(unit.b)];
        if (a.stamp == sc.stamp && b.stamp == sc.stamp) {
          const double rw = a.reach + b.reach + checker_->settings().self_padding;
          if ((a.mid - b.mid).squaredNorm() > rw * rw) continue;
        }
      }
      if (unitClear(unit, XA, XB, may_defer, &tests)) continue;  // cleared for [ta, tb]
      // The first unit not cleared decides that [ta, tb] is split: it goes first in the
      // halves' list (near a contact it fails again at once), followed by the units not yet
      // tested here. Testing those here too would clear some for both halves with one test,
      // but on long motions most fail at the upper levels and the tests would be wasted.
      sc.work.push_back(u);
      for (std::size_t x = w + 1; x < iv.end; ++x) {
        const int rest = sc.work[x];
        sc.work.push_back(rest);
      }
      break;
    }
    if (sc.work.size() == iv.end) {  // every unit cleared over [ta, tb]
      sc.release(iv.pa);
      sc.release(iv.pb);
      continue;
    }
    if (iv.tb - iv.ta <= min_fraction_) {
      *last = iv.ta;
      return false;
    }
    // The state at fraction t into qa and its poses into a pool slot acquired for them (the
    // pool may move: XA and XB are not used below).
    auto posesAt = [&](double t) {
      for (std::size_t i = 0; i < n; ++i) qa[i] = q0[i] + t * (q1[i] - q0[i]);
      for (int a : sc.turning) slerpQuaternion(q0 + a, q1 + a, t, qa + a);
      const int slot = sc.acquire(nl);
      m.kinematics().computeLinkPoses(qa, sc.pool.data() + std::size_t(slot) * nl);
      return slot;
    };
    if (probe) {  // the two states (above)
      probe = false;
      auto collidesAt = [&](double t) {
        const int slot = posesAt(t);
        const bool hit = checker_->collidesWithPoses(qa, sc.pool.data() + std::size_t(slot) * nl);
        sc.release(slot);
        return hit;
      };
      if (kind == MotionOrder::kEndLast
              ? collidesAt(0.75) || collidesAt(0.9)
              : checker_->collidesWithPoses(q1, sc.pool.data() + std::size_t(p1) * nl) ||
                    collidesAt(0.75))
        return false;
    }
    const double tm = 0.5 * (iv.ta + iv.tb);
    const int pm = posesAt(tm);
    if (checker_->collidesWithPoses(qa, sc.pool.data() + std::size_t(pm) * nl)) {
      *last = iv.ta;  // a colliding state on the motion: done
      return false;
    }
    // The halves take over the parent's ends; the midpoint serves both.
    sc.refs[std::size_t(pm)] = 2;
    sc.stack.push_back({tm, iv.tb, iv.end, sc.work.size(), pm, iv.pb});
    sc.stack.push_back({iv.ta, tm, iv.end, sc.work.size(), iv.pa, pm});
  }
  return true;
}

}  // namespace dss
