// StateBatch: the states of a batch proven free by the cheap stages in float lanes (see
// dss/checker/state_batch.h).
#include "dss/checker/state_batch.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "dss/checker/sphere_chain.h"
#include "dss/core/lanes.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace dss {

namespace {
// The grid's threshold for a sphere of radius r (metres): a bound of more than this many quanta
// proves it clear; INT_MAX when no stored bound can.
int gridThreshold(double r) {
  const double t = std::floor(r / ClearanceGrid::kQuantum);
  return t < 255.0 ? static_cast<int>(t) : 0x7fffffff;
}
}  // namespace

StateBatch::StateBatch(const CollisionModel& model, double scene_padding, double self_padding)
    : model_(&model), self_padding_(self_padding), kin_(model.sweepKinematics()) {
  num_links_ = model.robot().links.size();
  enabled_ = kin_.supported() && model.baseTable().slots().empty();
  if (!enabled_) return;
  const auto& slots = model.slots();
  const auto& elements = model.elements();
  // Each slot's cover: the chains of balls of its elements (sphere_chain.h), in its pose
  // link's frame, where they are tighter than its sphere (and few enough to pay).
  constexpr int kMaxCoverElements = 8, kMaxCoverBalls = 24;
  struct RawBall {
    Eigen::Vector3d c;
    double r;
  };
  std::vector<std::vector<RawBall>> covers(slots.size());
  for (std::size_t k = 0; k < slots.size(); ++k) {
    const auto& s = slots[k];
    if (s.num_elements > kMaxCoverElements) continue;
    std::vector<RawBall> balls;
    bool tighter = false;
    for (int e = s.first_element; e < s.first_element + s.num_elements; ++e) {
      const CollisionModel::Element& el = elements[std::size_t(e)];
      const SphereChain& chain = model.elementChain(e);
      for (int i = 0; i < chain.num_points; ++i) {
        balls.push_back({el.X_PS * chain.center_S[i], chain.outer[i]});
        tighter = tighter || chain.outer[i] < s.radius * (1.0 - 1e-6);
      }
    }
    if (tighter && balls.size() <= std::size_t(kMaxCoverBalls)) covers[k] = std::move(balls);
  }
  // The margin: the poses' error at the farthest centre, plus the float roundings of a centre
  // (its products and sums) and of the grid's voxel coordinates.
  double far = 0.0;
  for (std::size_t k = 0; k < slots.size(); ++k) {
    far = std::max(far, slots[k].center_P.norm());
    for (const RawBall& b : covers[k]) far = std::max(far, b.c.norm());
  }
  const ClearanceGrid& grid = model.clearanceGrid();
  const ClearanceGrid::Lookup g = grid.lookup();
  const double voxels = double(std::max({g.count[0], g.count[1], g.count[2]}));
  constexpr double u = 0x1p-24;
  margin_ = kin_.positionError() + kin_.rotationError() * far + 16.0 * u * (far + 1.0) +
            8.0 * u * (voxels + 2.0) * grid.voxelSize() + 1e-6;
  // A radius grown for the self pairs: the margin and half the self padding, rounded up.
  const auto grown = [&](double r) {
    return static_cast<float>((r + margin_ + 0.5 * self_padding) * (1.0 + 1e-6));
  };
  // The oriented boxes of the obstacles of each slot checked against the scene (at most
  // kMaxBoxes: beyond that the grid alone), and the float roundings of a point's distance to
  // one near the threshold (a point within a radius of the box): a few per coordinate of the
  // point, the box's centre, its turn and its extent.
  constexpr std::size_t kMaxBoxes = 16;
  const std::vector<Obb>& obbs = model.obstacleObbs();
  double world = 0.0, largest = 0.0;
  for (const auto& s : slots)
    if (s.obstacles.size() <= kMaxBoxes) {
      largest = std::max(largest, s.radius + scene_padding + margin_);
      for (int o : s.obstacles) {
        const Obb& b = obbs[std::size_t(o)];
        world = std::max(world, b.c.norm() + b.h.sum());
      }
    }
  const double box_slack = 32.0 * u * (2.0 * world + largest + 1.0);
  // The squared distance beyond which a ball of radius r is clear of a box, rounded up.
  const auto reach2 = [&](double r) {
    const double d = r + scene_padding + margin_ + box_slack;
    return static_cast<float>(d * d * (1.0 + 1e-5));
  };
  for (std::size_t k = 0; k < slots.size(); ++k) {
    const auto& s = slots[k];
    slot_link_.push_back(s.pose_link);
    for (int i = 0; i < 3; ++i) slot_center_.push_back(static_cast<float>(s.center_P[i]));
    slot_grown_.push_back(grown(s.radius));
    Cover cover{static_cast<int>(balls_.size()), static_cast<int>(covers[k].size())};
    for (const RawBall& b : covers[k])
      balls_.push_back({{float(b.c.x()), float(b.c.y()), float(b.c.z())},
                        grown(b.r),
                        gridThreshold(b.r + scene_padding + margin_),
                        reach2(b.r)});
    cover_.push_back(cover);
    if (s.obstacles.empty()) continue;  // not checked against the scene
    SceneSlot scene{static_cast<int>(k), gridThreshold(s.radius + scene_padding + margin_),
                    reach2(s.radius)};
    if (s.obstacles.size() <= kMaxBoxes) {
      scene.first_box = static_cast<int>(boxes_.size());
      scene.num_boxes = static_cast<int>(s.obstacles.size());
      for (int o : s.obstacles) {
        const Obb& b = obbs[std::size_t(o)];
        Box f;
        for (int j = 0; j < 3; ++j) {
          for (int i = 0; i < 3; ++i) f.r[3 * j + i] = static_cast<float>(b.R(i, j));
          f.c[j] = static_cast<float>(b.c[j]);
          f.h[j] = static_cast<float>(b.h[j]);
        }
        boxes_.push_back(f);
      }
    }
    scene_.push_back(scene);
  }
  for (const auto& p : model.selfPairs()) pairs_.push_back({p.a, p.b, p.table});
  // The elements' local boxes (slots with at most kMaxBoxElements elements), each with the
  // error of its float world placement: the poses' error at its farthest point (a point p of
  // the pose link's frame lies within sqrt(3) (positionError + rotationError |p|_1) of its
  // exact place), plus the roundings of its axes and centre; twice that.
  constexpr int kMaxBoxElements = 4;
  for (const auto& sl : slots) {
    SlotBoxes sb;
    if (sl.num_elements > 0 && sl.num_elements <= kMaxBoxElements) {
      sb.first = static_cast<int>(element_boxes_.size());
      sb.count = sl.num_elements;
      for (int e = sl.first_element; e < sl.first_element + sl.num_elements; ++e) {
        const CollisionModel::Element& el = elements[std::size_t(e)];
        const Eigen::Matrix3d R = el.X_PS.linear();
        const Eigen::Vector3d c = el.X_PS * el.box_center_S;
        ElementBox b;
        double reach = c.cwiseAbs().sum();
        for (int j = 0; j < 3; ++j) {
          for (int i = 0; i < 3; ++i) b.r[3 * j + i] = static_cast<float>(R(i, j));
          b.c[j] = static_cast<float>(c[j]);
          b.h[j] = static_cast<float>(el.box_half[j] * (1.0 + 1e-6));
          reach += el.box_half[j] * R.col(j).cwiseAbs().sum();
        }
        const double error =
            std::sqrt(3.0) * (kin_.positionError() + kin_.rotationError() * reach) +
            64.0 * u * (reach + 1.0);
        b.error = static_cast<float>(2.0 * error);
        element_boxes_.push_back(b);
      }
    }
    slot_boxes_.push_back(sb);
  }
}

unsigned StateBatch::freeLanes(const double* lanes, int n, SimdPath path) const {
  if (!enabled_ || n <= 0 || path == SimdPath::kScalar) return 0;
  n = std::min(n, kLanes);
  const CollisionModel& m = *model_;
  // The tests in double, as the checker runs them: bounds and held joints, then the tables
  // (per table, bit l: lane l's free flag).
  unsigned valid = m.boundedHeldLanes(lanes, path) & ((1u << n) - 1u);
  if (!valid) return 0;
  const std::size_t tables = m.selfTables().size();
  thread_local std::vector<unsigned> skip;
  if (skip.size() < tables) skip.resize(tables);
  std::fill(skip.begin(), skip.begin() + static_cast<std::ptrdiff_t>(tables), 0u);
  valid &= ~m.selfTables().readLanes(lanes, valid, self_padding_, skip.data(), path);
  if (!valid) return 0;
  return valid & provenFree(lanes, valid, skip.data(), path);
}

unsigned StateBatch::provenFree(const double* qs, unsigned valid, const unsigned* skip,
                                SimdPath path) const {
  if (path == SimdPath::kAvx2 && simdPathAvailable(SimdPath::kAvx2))
    return runAvx2(qs, valid, skip);
  return runGeneric(qs, valid, skip);
}

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace {
using lanes::F8;
using lanes::I8;
using lanes::kLanes;

// A point in the lanes.
struct Point {
  F8 x, y, z;
};

// X p for the lanes' poses X and a point p of the link's frame.
__attribute__((always_inline)) inline Point place(const KinematicsBatch::Pose& X, const float* p) {
  auto e = [&X](int k) { return lanes::load(X.v[k]); };
  return {((e(9) + e(0) * p[0]) + e(3) * p[1]) + e(6) * p[2],
          ((e(10) + e(1) * p[0]) + e(4) * p[1]) + e(7) * p[2],
          ((e(11) + e(2) * p[0]) + e(5) * p[1]) + e(8) * p[2]};
}

#if defined(__x86_64__) || defined(__i386__)
// The lanes l of `in` where bound[at[l]] > threshold, by one gather (the grid keeps
// ClearanceGrid::kReadPast readable bytes past its last voxel; the lanes outside it read voxel
// 0).
DSS_TARGET_AVX2 inline unsigned gatherAbove(const std::uint8_t* bound, const std::int32_t* at,
                                            unsigned in, int threshold) {
  const __m256i index = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(at));
  const __m256i v =
      _mm256_and_si256(_mm256_i32gather_epi32(reinterpret_cast<const int*>(bound), index, 1),
                       _mm256_set1_epi32(0xff));
  const __m256i above = _mm256_cmpgt_epi32(v, _mm256_set1_epi32(threshold));
  return unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(above))) & in;
}
#endif

// The lanes where the grid's lower bound at point c exceeds `threshold` quanta (never outside
// the grid or for NaN). `gather`: the bounds by gatherAbove (AVX2, a grid with voxels);
// `wide`: compiled for AVX2 (lanes.h).
__attribute__((always_inline)) inline unsigned gridClear(const ClearanceGrid::Lookup& g,
                                                         const float* below, float inv,
                                                         const Point& c, int threshold, bool gather,
                                                         bool wide) {
  // Voxel coordinates, clamped so that the conversion is defined: NaN and values below 0
  // become -1 (outside), huge ones 1e7 (outside).
  auto coord = [inv, wide](F8 v, float b) {
    F8 u = (v - b) * inv;
    u = lanes::select(lanes::greater(u, F8{}, wide), u, lanes::broadcast(-1.0f), wide);
    u = lanes::select(lanes::less(u, lanes::broadcast(1e7f), wide), u, lanes::broadcast(1e7f),
                      wide);
    return __builtin_convertvector(u, I8) - 1;
  };
  // Inside: 0 <= i < count per coordinate.
  auto within = [wide](I8 i, std::size_t count) {
    return lanes::greater(i, I8{} - 1, wide) & lanes::less(i, I8{} + std::int32_t(count), wide);
  };
  const I8 x = coord(c.x, below[0]), y = coord(c.y, below[1]), z = coord(c.z, below[2]);
  const I8 inside = within(x, g.count[0]) & within(y, g.count[1]) & within(z, g.count[2]);
  const I8 index = (z * std::int32_t(g.stride_z) + y * std::int32_t(g.stride_y) + x) & inside;
  std::int32_t at[kLanes];
  std::memcpy(at, &index, sizeof at);
  const unsigned in = lanes::laneBits(inside);
#if defined(__x86_64__) || defined(__i386__)
  if (gather) return gatherAbove(g.bound, at, in, threshold);
#else
  (void)gather;
#endif
  unsigned clear = 0;
  for (int l = 0; l < kLanes; ++l)
    clear |= unsigned(((in >> l) & 1u) && g.bound[at[l]] > threshold) << l;
  return clear;
}
// The lanes where point c is farther than sqrt(reach2) from every box of boxes[0, count)
// (never for NaN). `wide`: compiled for AVX2 (lanes.h).
template <class Box>
__attribute__((always_inline)) inline unsigned boxesClear(const Box* boxes, int count,
                                                          const Point& c, float reach2, bool wide) {
  I8 clear = I8{} - 1;
  for (int b = 0; b < count; ++b) {
    const Box& x = boxes[b];
    const F8 dx = c.x - x.c[0], dy = c.y - x.c[1], dz = c.z - x.c[2];
    F8 d2 = F8{};
    for (int j = 0; j < 3; ++j) {
      const F8 l = (dx * x.r[3 * j] + dy * x.r[3 * j + 1]) + dz * x.r[3 * j + 2];
      F8 e = lanes::abs(l) - x.h[j];
      e = lanes::select(lanes::less(e, F8{}, wide), F8{}, e, wide);  // NaN stays NaN
      d2 = d2 + e * e;
    }
    clear &= lanes::greater(d2, lanes::broadcast(reach2), wide);
  }
  return lanes::laneBits(clear);
}

// The lanes where the boxes A and B (local boxes posed by the lanes' poses XA and XB) are
// proven apart by more than `gap`, by any of the 15 axes of the separating-axis test. Each
// float box is the image of its local box under the float pose, within A.error (B.error) of
// the exact one; an axis L separates the exact boxes by more than gap when the centres'
// distance along it exceeds the two projection radii plus |L| (gap + both errors), all
// grown for the roundings of the test (|L|_1 bounds |L|). A degenerate axis (parallel
// edges) proves nothing; nor does NaN. `wide`: compiled for AVX2 (lanes.h).
template <class ElementBox>
__attribute__((always_inline)) inline unsigned elementBoxesApart(const KinematicsBatch::Pose& XA,
                                                                 const ElementBox& A,
                                                                 const KinematicsBatch::Pose& XB,
                                                                 const ElementBox& B, float gap,
                                                                 bool wide) {
  auto worldAxes = [](const KinematicsBatch::Pose& X, const ElementBox& E, F8(*w)[3]) {
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k)
        w[i][k] = (lanes::load(X.v[k]) * E.r[3 * i] + lanes::load(X.v[3 + k]) * E.r[3 * i + 1]) +
                  lanes::load(X.v[6 + k]) * E.r[3 * i + 2];
  };
  F8 aw[3][3], bw[3][3];
  worldAxes(XA, A, aw);
  worldAxes(XB, B, bw);
  const Point ac = place(XA, A.c), bc = place(XB, B.c);
  const F8 d[3] = {bc.x - ac.x, bc.y - ac.y, bc.z - ac.z};
  using lanes::abs;
  const F8 spread = (abs(d[0]) + abs(d[1])) + abs(d[2]) + ((A.h[0] + A.h[1]) + A.h[2]) +
                    ((B.h[0] + B.h[1]) + B.h[2]) + 1.0f;
  const F8 extra = (gap + A.error + B.error) + 1e-5f * spread;
  I8 apart = I8{};
  auto test = [&](const F8* l) {
    auto dot = [l](const F8* v) { return (l[0] * v[0] + l[1] * v[1]) + l[2] * v[2]; };
    const F8 s = abs(dot(d));
    const F8 ra = (A.h[0] * abs(dot(aw[0])) + A.h[1] * abs(dot(aw[1]))) + A.h[2] * abs(dot(aw[2]));
    const F8 rb = (B.h[0] * abs(dot(bw[0])) + B.h[1] * abs(dot(bw[1]))) + B.h[2] * abs(dot(bw[2]));
    const F8 norm1 = (abs(l[0]) + abs(l[1])) + abs(l[2]);
    apart |= lanes::greater(s, ((ra + rb) + norm1 * extra) * (1.0f + 1e-5f), wide);
  };
  for (int i = 0; i < 3; ++i) test(aw[i]);
  for (int j = 0; j < 3; ++j) test(bw[j]);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const F8* x = aw[i];
      const F8* y = bw[j];
      const F8 l[3] = {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2],
                       x[0] * y[1] - x[1] * y[0]};
      test(l);
    }
  return lanes::laneBits(apart);
}
}  // namespace

// The test out of line (it runs rarely, and inlined it would crowd the batch's registers), once
// per path.
template <class ElementBox>
__attribute__((noinline)) unsigned elementBoxesApartGeneric(const KinematicsBatch::Pose& XA,
                                                            const ElementBox& A,
                                                            const KinematicsBatch::Pose& XB,
                                                            const ElementBox& B, float gap) {
  return elementBoxesApart(XA, A, XB, B, gap, false);
}
template <class ElementBox>
DSS_TARGET_AVX2 __attribute__((noinline)) unsigned elementBoxesApartAvx2(
    const KinematicsBatch::Pose& XA, const ElementBox& A, const KinematicsBatch::Pose& XB,
    const ElementBox& B, float gap) {
  return elementBoxesApart(XA, A, XB, B, gap, true);
}

__attribute__((always_inline)) inline unsigned StateBatch::run(const double* qs, unsigned valid,
                                                               const unsigned* skip,
                                                               SimdPath path) const {
  thread_local std::vector<KinematicsBatch::Pose> poses;
  thread_local std::vector<float> centers;  // per slot x, y, z in lanes
  if (poses.size() < num_links_) poses.resize(num_links_);
  if (centers.size() < slot_link_.size() * 3 * kLanes)
    centers.resize(slot_link_.size() * 3 * kLanes);
  KinematicsBatch::Pose* const X = poses.data();
  float* const centre = centers.data();
  kin_.compute(qs, X, path);
  for (std::size_t k = 0; k < slot_link_.size(); ++k) {
    const Point p = place(X[slot_link_[k]], &slot_center_[3 * k]);
    lanes::store(centre + (3 * k) * kLanes, p.x);
    lanes::store(centre + (3 * k + 1) * kLanes, p.y);
    lanes::store(centre + (3 * k + 2) * kLanes, p.z);
  }
  auto c = [centre](int k) -> Point {
    const float* p = centre + 3 * std::size_t(k) * kLanes;
    return {lanes::load(p), lanes::load(p + kLanes), lanes::load(p + 2 * kLanes)};
  };
  // The world centres of a slot's cover balls, placed when first needed.
  thread_local std::vector<float> ball_store;
  thread_local std::vector<char> placed;
  if (ball_store.size() < balls_.size() * 3 * kLanes) ball_store.resize(balls_.size() * 3 * kLanes);
  if (placed.size() < cover_.size()) placed.resize(cover_.size());
  std::fill(placed.begin(), placed.begin() + static_cast<std::ptrdiff_t>(cover_.size()), 0);
  float* const ball_centre = ball_store.data();
  auto ball = [ball_centre](int i) -> Point {
    const float* p = ball_centre + 3 * std::size_t(i) * kLanes;
    return {lanes::load(p), lanes::load(p + kLanes), lanes::load(p + 2 * kLanes)};
  };
  auto placeCover = [&](int k) {
    if (placed[std::size_t(k)]) return;
    placed[std::size_t(k)] = 1;
    const Cover& cv = cover_[std::size_t(k)];
    for (int i = cv.first; i < cv.first + cv.count; ++i) {
      const Point p = place(X[slot_link_[std::size_t(k)]], balls_[std::size_t(i)].c);
      float* const out = ball_centre + 3 * std::size_t(i) * kLanes;
      lanes::store(out, p.x);
      lanes::store(out + kLanes, p.y);
      lanes::store(out + 2 * kLanes, p.z);
    }
  };
  unsigned open = valid;  // lanes not yet failed
  // Robot vs scene: each sphere's lookup, then its cover's balls for the lanes it leaves.
  const ClearanceGrid::Lookup g = model_->clearanceGrid().lookup();
  const float below[3] = {float(g.below[0]), float(g.below[1]), float(g.below[2])};
  const float inv = float(g.inv_size);
  const bool wide = path == SimdPath::kAvx2;  // compiled for AVX2 (runAvx2)
  const bool gather = wide && !model_->clearanceGrid().empty();
  for (const SceneSlot& s : scene_) {
    const Point sc = c(s.slot);
    unsigned left = open & ~gridClear(g, below, inv, sc, s.threshold, gather, wide);
    if (!left) continue;
    const Box* const boxes = boxes_.data() + s.first_box;
    if (s.num_boxes > 0) left &= ~boxesClear(boxes, s.num_boxes, sc, s.reach2, wide);
    if (!left) continue;
    const Cover& cv = cover_[std::size_t(s.slot)];
    unsigned all = cv.count > 0 ? left : 0u;
    if (all) placeCover(s.slot);
    for (int i = cv.first; i < cv.first + cv.count && all; ++i) {
      const Ball& b = balls_[std::size_t(i)];
      const Point bc = ball(i);
      unsigned ok = gridClear(g, below, inv, bc, b.threshold, gather, wide);
      if ((all & ~ok) && s.num_boxes > 0) ok |= boxesClear(boxes, s.num_boxes, bc, b.reach2, wide);
      all &= ok;
    }
    open &= ~(left & ~all);
    if (!open) return 0;
  }
  // Self pairs: the pair's table flag, or the slot spheres apart, or every ball of one cover
  // apart from the other's sphere or from every ball of its cover.
  auto apart = [wide](const Point& a, float ra, const Point& b, float rb) {
    const F8 dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
    const F8 d2 = (dx * dx + dy * dy) + dz * dz;
    const float r = ra + rb;
    return lanes::laneBits(lanes::greater(d2, lanes::broadcast(r * r * (1.0f + 1e-5f)), wide));
  };
  // The lanes of `lanes` where every element box of slot a is apart from every one of slot b.
  const float box_gap = static_cast<float>(self_padding_ * (1.0 + 1e-6));
  auto boxesApart = [&](int a, int b, unsigned lanes_in) {
    const SlotBoxes& sa = slot_boxes_[std::size_t(a)];
    const SlotBoxes& sb = slot_boxes_[std::size_t(b)];
    if (sa.count == 0 || sb.count == 0) return 0u;
    const KinematicsBatch::Pose& XA = X[slot_link_[std::size_t(a)]];
    const KinematicsBatch::Pose& XB = X[slot_link_[std::size_t(b)]];
    unsigned all = lanes_in;
    for (int i = sa.first; i < sa.first + sa.count && all; ++i)
      for (int j = sb.first; j < sb.first + sb.count && all; ++j)
        all &= path == SimdPath::kAvx2
                   ? elementBoxesApartAvx2(XA, element_boxes_[std::size_t(i)], XB,
                                           element_boxes_[std::size_t(j)], box_gap)
                   : elementBoxesApartGeneric(XA, element_boxes_[std::size_t(i)], XB,
                                              element_boxes_[std::size_t(j)], box_gap);
    return all;
  };
  for (const SelfPair& p : pairs_) {
    // The table's flags first: where they cover every open lane, no sphere test.
    const unsigned untabled = p.table >= 0 ? open & ~skip[p.table] : open;
    if (!untabled) continue;
    const unsigned near = untabled & ~apart(c(p.a), slot_grown_[std::size_t(p.a)], c(p.b),
                                            slot_grown_[std::size_t(p.b)]);
    if (!near) continue;
    // The side with a cover goes ball by ball (a, else b).
    int a = p.a, b = p.b;
    if (cover_[std::size_t(a)].count == 0) std::swap(a, b);
    const Cover& ca = cover_[std::size_t(a)];
    const Cover& cb = cover_[std::size_t(b)];
    if (ca.count == 0) {
      open &= ~(near & ~boxesApart(a, b, near));
    } else {
      placeCover(a);
      if (cb.count > 0) placeCover(b);
      const Point sb = c(b);
      const float rb = slot_grown_[std::size_t(b)];
      unsigned ok = near;
      for (int i = ca.first; i < ca.first + ca.count && ok; ++i) {
        const Point bi = ball(i);
        const float ri = balls_[std::size_t(i)].grown;
        const unsigned by_sphere = apart(bi, ri, sb, rb);
        unsigned by_balls = cb.count > 0 ? ok & ~by_sphere : 0u;
        for (int j = cb.first; j < cb.first + cb.count && by_balls; ++j)
          by_balls &= apart(bi, ri, ball(j), balls_[std::size_t(j)].grown);
        ok &= by_sphere | by_balls;
      }
      if (near & ~ok) ok |= boxesApart(a, b, near & ~ok);
      open &= ~(near & ~ok);
    }
    if (!open) return 0;
  }
  return open;
}

unsigned StateBatch::runGeneric(const double* qs, unsigned valid, const unsigned* skip) const {
  return run(qs, valid, skip, SimdPath::kSse2);
}

DSS_TARGET_AVX2 unsigned StateBatch::runAvx2(const double* qs, unsigned valid,
                                             const unsigned* skip) const {
  return run(qs, valid, skip, SimdPath::kAvx2);
}

#pragma GCC diagnostic pop

}  // namespace dss
