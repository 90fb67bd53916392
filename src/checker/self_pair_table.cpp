// Self-pair tables: building, packing and reading (see self_pair_table.h).
#include "dss/checker/self_pair_table.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

#include "dss/checker/motion_bounds.h"
#include "dss/core/any_shape_query.h"

namespace dss {

namespace {
std::vector<int> ancestors(const RobotModel& m, int link) {
  std::vector<int> out;
  for (int l = link; l >= 0; l = m.links[l].parent_link) out.push_back(l);
  return out;
}
}  // namespace

std::optional<SelfPairTable> buildSelfPairTable(const RobotModel& m, const Kinematics& kin,
                                                const std::vector<double>& held,
                                                const std::vector<char>& in_group,
                                                const SelfPairSide& sa, const SelfPairSide& sb,
                                                int cells_1d, int cells_2d, double padding) {
  const std::vector<int> up_a = ancestors(m, sa.link), up_b = ancestors(m, sb.link);
  int common = -1;
  for (int l : up_a)
    if (std::find(up_b.begin(), up_b.end(), l) != up_b.end()) {
      common = l;
      break;
    }
  if (common < 0) return std::nullopt;
  // Bounds on how far a point of B moves (relative to A) per unit change of each joint on the
  // path between them: B-side joints turn B about their origins; an A-side joint turns B (rigid
  // to the common ancestor for that joint's motion) about its own origin, which lies within
  // the origin offsets between it and the common ancestor.
  struct Term {
    const ChainTerm* chain;
    double per_unit;
  };
  double reach_b = 0.0;  // B's geometry from the common ancestor's origin
  const std::vector<ChainTerm> path_b = chainAbove(m, sb.link, common, sb.radius, held, &reach_b);
  const std::vector<ChainTerm> path_a = chainAbove(m, sa.link, common, 0.0, held);
  std::vector<Term> terms;
  for (const ChainTerm& t : path_b) terms.push_back({&t, t.prismatic ? 1.0 : t.reach});
  for (const ChainTerm& t : path_a)
    terms.push_back(
        {&t, t.prismatic
                 ? 1.0
                 : originOffsetBound(m, m.joints[t.joint].child_link, common, held) + reach_b});

  // Variables: the group joints the path joints read (mimic joints through their leader).
  // Joints outside the group keep their held value: the table records it and answers only for
  // states that have it.
  SelfPairTable t;
  double per_var[2] = {0.0, 0.0};
  for (const Term& term : terms) {
    const int v = term.chain->active;
    if (v < 0 || term.chain->ball || !std::isfinite(term.per_unit)) return std::nullopt;
    if (!in_group[v]) {
      int f = 0;
      while (f < t.num_fixed && t.fixed_var[f] != v) ++f;
      if (f == t.num_fixed) {
        if (t.num_fixed == SelfPairTable::kMaxFixed) return std::nullopt;
        t.fixed_var[t.num_fixed] = v;
        t.fixed_value[t.num_fixed++] = held[v];
      }
      continue;
    }
    int k = 0;
    while (k < t.num_vars && t.var[k] != v) ++k;
    if (k == t.num_vars) {
      if (t.num_vars == 2) return std::nullopt;
      t.var[t.num_vars++] = v;
    }
    per_var[k] += std::abs(term.chain->multiplier) * term.per_unit;
  }
  if (t.num_vars == 0) return std::nullopt;
  const int n = t.num_vars == 1 ? cells_1d : cells_2d;
  if (n <= 0) return std::nullopt;
  const double pi = 3.141592653589793;
  for (int k = 0; k < t.num_vars; ++k) {
    const RobotJoint& L = m.joints[m.active_joints[t.var[k]]];
    if (L.type == JointType::kContinuous ||
        (L.type == JointType::kRevolute && !L.limits.has_position_limits)) {
      t.wrap[k] = true;
      t.lo[k] = -pi;
      t.hi[k] = pi;
    } else if (L.limits.has_position_limits && L.limits.lower < L.limits.upper) {
      t.lo[k] = L.limits.lower;
      t.hi[k] = L.limits.upper;
    } else {
      return std::nullopt;
    }
    t.cells[k] = n;
    t.inv_width[k] = double(n) / (t.hi[k] - t.lo[k]);
  }
  t.padding = padding;
  t.cell_state.assign(std::size_t(t.cells[0]) * std::size_t(t.cells[1]), SelfPairTable::kUnknown);

  std::vector<Eigen::Isometry3d> X(m.links.size(), Eigen::Isometry3d::Identity());
  std::vector<double> q = held;
  Options exact;
  exact.mode = Mode::kExact;
  // Certify the block [i0, i1) x [j0, j1) of cells; split it until its cells are decided.
  const double width[2] = {(t.hi[0] - t.lo[0]) / t.cells[0],
                           t.num_vars > 1 ? (t.hi[1] - t.lo[1]) / t.cells[1] : 0.0};
  auto certify = [&](auto&& self, int i0, int i1, int j0, int j1) -> void {
    double moved = 0.0;
    const int lo_idx[2] = {i0, j0}, hi_idx[2] = {i1, j1};
    for (int k = 0; k < t.num_vars; ++k) {
      const double a = t.lo[k] + lo_idx[k] * width[k];
      const double b = hi_idx[k] == t.cells[k] ? t.hi[k] : t.lo[k] + hi_idx[k] * width[k];
      q[t.var[k]] = 0.5 * (a + b);
      // Half-width, grown so that a value whose cell index rounds into this block is covered.
      const double half = 0.5 * (b - a) * (1.0 + 1e-6) + 1e-12 * (1.0 + std::abs(b) + std::abs(a));
      moved += per_var[k] * half;
    }
    kin.computeLinkPoses(q.data(), X.data());
    const double pad = t.padding + moved * (1.0 + 1e-9) + 1e-12;
    auto mark = [&](unsigned char value) {
      for (int i = i0; i < i1; ++i)
        for (int j = j0; j < j1; ++j) t.cell_state[std::size_t(i) * t.cells[1] + j] = value;
    };
    // Free: every element pair farther apart than pad.
    bool free = true;
    for (std::size_t ea = 0; ea < sa.elements.size() && free; ++ea)
      for (std::size_t eb = 0; eb < sb.elements.size() && free; ++eb) {
        const CollisionElement& A = *sa.elements[ea];
        const CollisionElement& B = *sb.elements[eb];
        const Result r =
            intersect(A.shape, X[sa.link] * A.X_LS, B.shape, X[sb.link] * B.X_LS, exact, pad);
        free = !r.intersect && r.status == Status::kDecided;
      }
    if (free) return mark(SelfPairTable::kFree);
    // Colliding: some element pair intersects under the six translations by sqrt(3) L (and a
    // 1e-9 margin for the rounding of the poses) along the axes, hence under any motion within
    // the cell. (At a self padding above the table's, colliding stays colliding.)
    const double reach = std::sqrt(3.0) * (moved * (1.0 + 1e-9) + 1e-9);
    for (const CollisionElement* A : sa.elements)
      for (const CollisionElement* B : sb.elements) {
        const Eigen::Isometry3d XA = X[sa.link] * A->X_LS;
        bool all = true;
        for (int axis = 0; axis < 6 && all; ++axis) {
          Eigen::Isometry3d XB = X[sb.link] * B->X_LS;
          XB.translation()[axis / 2] += (axis % 2 ? -reach : reach);
          // Only a decided intersection certifies: an answer at the cap or on invalid input
          // (a pose that is not finite) says "intersect" without proving it.
          const Result r = intersect(A->shape, XA, B->shape, XB, exact);
          all = r.intersect && r.status == Status::kDecided;
        }
        if (all) return mark(SelfPairTable::kColliding);
      }
    if (i1 - i0 <= 1 && j1 - j0 <= 1) return;
    const int im = i1 - i0 > 1 ? (i0 + i1) / 2 : i1;
    const int jm = j1 - j0 > 1 ? (j0 + j1) / 2 : j1;
    self(self, i0, im, j0, jm);
    if (jm < j1) self(self, i0, im, jm, j1);
    if (im < i1) {
      self(self, im, i1, j0, jm);
      if (jm < j1) self(self, im, i1, jm, j1);
    }
  };
  certify(certify, 0, t.cells[0], 0, t.cells[1]);
  for (unsigned char c : t.cell_state) {
    t.num_free += c == SelfPairTable::kFree;
    t.num_colliding += c == SelfPairTable::kColliding;
  }
  if (t.num_free == 0 && t.num_colliding == 0) return std::nullopt;
  return t;
}

SelfPairTables::SelfPairTables(std::vector<SelfPairTable> tables, double padding,
                               std::vector<int>* new_index)
    : padding_(padding) {
  // Tables on the same grid next to each other, at most four per group.
  new_index->assign(tables.size(), -1);
  for (std::size_t i = 0; i < tables.size(); ++i) {
    if ((*new_index)[i] >= 0) continue;
    Group g;
    g.first = int(tables_.size());
    for (std::size_t j = i; j < tables.size() && g.count < 4; ++j) {
      if ((*new_index)[j] >= 0 || (j != i && !tables[j].sameGrid(tables_[g.first]))) continue;
      (*new_index)[j] = int(tables_.size());
      tables_.push_back(std::move(tables[j]));
      ++g.count;
    }
    g.packed.assign(tables_[g.first].cell_state.size(), 0);
    for (int k = 0; k < g.count; ++k) {
      const std::vector<unsigned char>& cells = tables_[g.first + k].cell_state;
      for (std::size_t c = 0; c < cells.size(); ++c)
        g.packed[c] |= static_cast<std::uint8_t>(cells[c] << (2 * k));
    }
    // The coarse grid: a block's byte keeps the free bits common to all its cells.
    const SelfPairTable& t0 = tables_[std::size_t(g.first)];
    const int nv = t0.num_vars;
    for (int k = 0; k < nv; ++k) g.blocks[k] = (t0.cells[k] + kBlock - 1) / kBlock;
    g.coarse.assign(std::size_t(g.blocks[0]) * std::size_t(g.blocks[1]), 0x55u);
    for (int i = 0; i < t0.cells[0]; ++i)
      for (int j = 0; j < (nv == 2 ? t0.cells[1] : 1); ++j) {
        const std::size_t c =
            nv == 2 ? std::size_t(i) * std::size_t(t0.cells[1]) + std::size_t(j) : std::size_t(i);
        const std::size_t b =
            nv == 2 ? std::size_t(i / kBlock) * std::size_t(g.blocks[1]) + std::size_t(j / kBlock)
                    : std::size_t(i / kBlock);
        g.coarse[b] &= static_cast<std::uint8_t>(free(g.packed[c]));
      }
    groups_.push_back(std::move(g));
  }
}

bool SelfPairTables::read(const double* q, bool held_match, double self_padding,
                          unsigned char* skip, bool colliding_cells) const {
  const bool use_colliding = colliding_cells && self_padding >= padding_,
             use_free = self_padding <= padding_;
  for (const Group& g : groups_) {
    const int idx = tables_[g.first].index(q);
    const unsigned byte = idx < 0 ? 0u : g.packed[idx];
    if (held_match) {
      // Every table was built at the held values: a cell applies as it is, and the two-bit
      // cells of a group are read as masks.
      if (use_colliding && colliding(byte)) return true;
      const unsigned f = use_free ? free(byte) : 0u;
      for (int k = 0; k < g.count; ++k) skip[g.first + k] = (f >> (2 * k)) & 1u;
      continue;
    }
    for (int k = 0; k < g.count; ++k) {
      const int ti = g.first + k;
      const unsigned c = (byte >> (2 * k)) & 3u;
      const bool applies = c != SelfPairTable::kUnknown && tables_[ti].heldMatch(q);
      if (c == SelfPairTable::kColliding && applies && use_colliding) return true;
      skip[ti] = c == SelfPairTable::kFree && applies && use_free;
    }
  }
  return false;
}

#if defined(__x86_64__) || defined(__i386__)
namespace {
// SelfPairTable::indexOf for eight lanes (value j of lane l at lanes[8 var[j] + l]), four at a
// time in AVX2: the same double operations (the wrap's division, floor, product and
// difference, the truncation toward zero), so the same index; -1 outside the range or for NaN.
DSS_TARGET_AVX2 void laneIndicesAvx2(const SelfPairTable& t, const double* lanes,
                                     std::int32_t* idx) {
  for (int h = 0; h < 8; h += 4) {
    __m128i index = _mm_setzero_si128();
    __m128i in = _mm_set1_epi32(-1);
    for (int k = 0; k < t.num_vars; ++k) {
      __m256d v = _mm256_loadu_pd(lanes + std::size_t(t.var[k]) * 8 + std::size_t(h));
      if (t.wrap[k]) {
        const __m256d turn = _mm256_set1_pd(6.283185307179586);
        const __m256d turns = _mm256_floor_pd(
            _mm256_div_pd(_mm256_add_pd(v, _mm256_set1_pd(3.141592653589793)), turn));
        v = _mm256_sub_pd(v, _mm256_mul_pd(turn, turns));
      }
      const __m256d lo = _mm256_set1_pd(t.lo[k]);
      const __m256d ok = _mm256_and_pd(_mm256_cmp_pd(v, lo, _CMP_GE_OQ),
                                       _mm256_cmp_pd(v, _mm256_set1_pd(t.hi[k]), _CMP_LE_OQ));
      // The four comparison masks narrowed to 32 bits (each 64-bit mask is all ones or zero).
      const __m256i ok32 = _mm256_permutevar8x32_epi32(_mm256_castpd_si256(ok),
                                                       _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7));
      in = _mm_and_si128(in, _mm256_castsi256_si128(ok32));
      __m128i i =
          _mm256_cvttpd_epi32(_mm256_mul_pd(_mm256_sub_pd(v, lo), _mm256_set1_pd(t.inv_width[k])));
      i = _mm_min_epi32(i, _mm_set1_epi32(t.cells[k] - 1));
      index = _mm_add_epi32(_mm_mullo_epi32(index, _mm_set1_epi32(t.cells[k])), i);
    }
    index = _mm_or_si128(_mm_and_si128(in, index), _mm_andnot_si128(in, _mm_set1_epi32(-1)));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(idx + h), index);
  }
}

// A group's packed cells for eight lanes on AVX2 (cells of table t, the group's first): bit l
// of *colliding where lane l's byte has a colliding cell, bit l of free_bits[k] where table k's
// cell is free (bytes as SelfPairTables::colliding and free read them; a lane outside the
// range reads nothing).
DSS_TARGET_AVX2 void groupLanesAvx2(const SelfPairTable& t, const std::uint8_t* packed, int count,
                                    const double* lanes, unsigned* colliding, unsigned* free_bits) {
  std::int32_t idx[8];
  laneIndicesAvx2(t, lanes, idx);
  std::int32_t b[8];
  for (int l = 0; l < 8; ++l) b[l] = idx[l] < 0 ? 0 : packed[std::size_t(idx[l])];
  const __m256i v = _mm256_setr_epi32(b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]);
  const __m256i zero = _mm256_setzero_si256();
  // byte & 0xAA & ~(byte << 1), and byte & 0x55 & ~(byte >> 1).
  const __m256i coll =
      _mm256_andnot_si256(_mm256_slli_epi32(v, 1), _mm256_and_si256(v, _mm256_set1_epi32(0xAA)));
  const __m256i fr =
      _mm256_andnot_si256(_mm256_srli_epi32(v, 1), _mm256_and_si256(v, _mm256_set1_epi32(0x55)));
  *colliding =
      ~unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(coll, zero)))) & 0xFFu;
  for (int k = 0; k < count; ++k) {
    const __m256i bit = _mm256_set1_epi32(1 << (2 * k));
    free_bits[k] = unsigned(_mm256_movemask_ps(
        _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(fr, bit), bit))));
  }
}
}  // namespace
#endif

unsigned SelfPairTables::readLanes(const double* lanes, unsigned states, double self_padding,
                                   unsigned* skip, SimdPath path) const {
  constexpr int kLanes = 8;
  const bool use_colliding = self_padding >= padding_, use_free = self_padding <= padding_;
#if defined(__x86_64__) || defined(__i386__)
  const bool avx2 = path == SimdPath::kAvx2 && simdPathAvailable(SimdPath::kAvx2);
#else
  const bool avx2 = false;
  (void)path;
#endif
  unsigned colliding_states = 0;
  for (const Group& g : groups_) {
    const SelfPairTable& t = tables_[std::size_t(g.first)];
    unsigned free_bits[4] = {0, 0, 0, 0};  // per table of the group, bit l for state l
#if defined(__x86_64__) || defined(__i386__)
    if (avx2) {
      unsigned coll = 0;
      groupLanesAvx2(t, g.packed.data(), g.count, lanes, &coll, free_bits);
      if (use_colliding) colliding_states |= coll & states;
      if (use_free)
        for (int k = 0; k < g.count; ++k) skip[g.first + k] |= free_bits[k] & states;
      continue;
    }
#endif
    for (unsigned left = states; left; left &= left - 1) {
      const int l = __builtin_ctz(left);
      double v[2];
      for (int k = 0; k < t.num_vars; ++k) v[k] = lanes[std::size_t(t.var[k]) * kLanes + l];
      const int idx = t.indexOf(v);
      const unsigned byte = idx < 0 ? 0u : g.packed[std::size_t(idx)];
      if (use_colliding && colliding(byte)) colliding_states |= 1u << l;
      const unsigned f = use_free ? free(byte) : 0u;
      for (int k = 0; k < g.count; ++k) free_bits[k] |= ((f >> (2 * k)) & 1u) << l;
    }
    for (int k = 0; k < g.count; ++k) skip[g.first + k] |= free_bits[k];
  }
  return colliding_states;
}

unsigned SelfPairTables::walkFree(const Group& g, const double* a, const double* b, bool fine,
                                  unsigned mask) const {
  const SelfPairTable& tb = tables_[std::size_t(g.first)];
  const int nv = tb.num_vars;
  int count[2] = {1, 1};
  double inv[2] = {0, 0};
  int pieces = 1;
  for (int k = 0; k < nv; ++k) {
    count[k] = fine ? tb.cells[k] : g.blocks[k];
    inv[k] = fine ? tb.inv_width[k] : tb.inv_width[k] / kBlock;
    const double span = std::abs(b[k] - a[k]) * inv[k];
    if (!(span < kMaxPieces)) return 0;
    pieces = std::max(pieces, int(span) + 1);
  }
  const std::vector<std::uint8_t>& bytes = fine ? g.packed : g.coarse;
  // The cells of [v0, v1] (sorted) along variable k, widened by a margin of 1e-9 cell.
  auto cellRange = [&](int k, double v0, double v1, int* i0, int* i1) {
    const double x0 = (std::min(v0, v1) - tb.lo[k]) * inv[k] - 1e-9;
    const double x1 = (std::max(v0, v1) - tb.lo[k]) * inv[k] + 1e-9;
    *i0 = std::clamp(int(std::floor(x0)), 0, count[k] - 1);
    *i1 = std::clamp(int(std::floor(x1)), 0, count[k] - 1);
  };
  for (int p = 0; p < pieces && mask; ++p) {
    const double s0 = double(p) / pieces, s1 = double(p + 1) / pieces;
    int lo_i[2] = {0, 0}, hi_i[2] = {0, 0};
    for (int k = 0; k < nv; ++k)
      cellRange(k, a[k] + s0 * (b[k] - a[k]), a[k] + s1 * (b[k] - a[k]), &lo_i[k], &hi_i[k]);
    for (int i = lo_i[0]; i <= hi_i[0]; ++i)
      for (int j = lo_i[1]; j <= hi_i[1]; ++j) {
        const std::uint8_t byte =
            bytes[nv == 2 ? std::size_t(i) * std::size_t(count[1]) + std::size_t(j)
                          : std::size_t(i)];
        mask &= fine ? free(byte) : byte;
      }
  }
  return mask;
}

void SelfPairTables::freeAlong(const double* qa, const double* qb, double self_padding,
                               unsigned char* free_along) const {
  std::fill(free_along, free_along + tables_.size(), 0);
  if (!(self_padding <= padding_)) return;
  for (const Group& g : groups_) {
    const SelfPairTable& tb = tables_[std::size_t(g.first)];
    const int nv = tb.num_vars;
    double a[2], b[2];
    bool ok = true;
    for (int k = 0; k < nv && ok; ++k) {
      a[k] = qa[tb.var[k]], b[k] = qb[tb.var[k]];
      ok = !tb.wrap[k] && a[k] >= tb.lo[k] && a[k] <= tb.hi[k] && b[k] >= tb.lo[k] &&
           b[k] <= tb.hi[k];
    }
    if (!ok) continue;
    // Tables of the group whose held joints match at both ends, as a mask of their free bits.
    unsigned mask = 0;
    for (int k = 0; k < g.count; ++k)
      if (tables_[std::size_t(g.first + k)].heldMatch(qa) &&
          tables_[std::size_t(g.first + k)].heldMatch(qb))
        mask |= 1u << (2 * k);
    // Blocks first; the cells only for the tables some block along the way does not clear.
    const unsigned coarse = walkFree(g, a, b, false, mask);
    const unsigned fine = coarse == mask ? mask : coarse | walkFree(g, a, b, true, mask & ~coarse);
    for (int k = 0; k < g.count; ++k) free_along[g.first + k] = (fine >> (2 * k)) & 1u;
  }
}

}  // namespace dss
