// SlotSpheres: the slots' centres and the grid's verdicts in one pass (see the header).
#include "dss/checker/slot_spheres.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace dss {

namespace {

// A pose column or a centre, (x, y, z, w): one AVX register in a function compiled for AVX2,
// two SSE2 registers otherwise (element by element either way).
using Quad = double __attribute__((vector_size(32)));

// The grid's lookup (ClearanceGrid::lookup), read once per four-lane pass (into registers).
using GridView = ClearanceGrid::Lookup;

struct Pass {
  std::size_t n;
  const int* link;
  const double* center;  // four per sphere
  const double* radius;
  const Eigen::Isometry3d* X_WL;
  double padding;
  Eigen::Vector3d* centers;
  std::uint64_t* clear;
};

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
__attribute__((always_inline)) inline Quad load(const double* p) {
  Quad v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// One sphere at a time (Coord: double for the scalar path, Quad for SSE2), each looked up by
// the grid itself. The fields are read into locals once: the stores of centres could
// otherwise alias them and force reloads. Each word of bits is kept in a register until it is
// full.
template <class Coord>
__attribute__((always_inline)) inline void placeAll(const Pass& pass, const ClearanceGrid& grid) {
  const std::size_t n = pass.n;
  const int* const link = pass.link;
  const double* const center = pass.center;
  const double* const radius = pass.radius;
  const Eigen::Isometry3d* const X_WL = pass.X_WL;
  const double padding = pass.padding;
  Eigen::Vector3d* const centers = pass.centers;
  std::uint64_t* const clear = pass.clear;
  std::uint64_t bits = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double* M = X_WL[link[k]].data();  // column-major 4 x 4
    const double* c = center + 4 * k;
    if constexpr (std::is_same_v<Coord, double>) {
      for (int i = 0; i < 3; ++i)
        centers[k][i] = ((M[i] * c[0] + M[4 + i] * c[1]) + M[8 + i] * c[2]) + M[12 + i];
    } else {
      const Quad w = ((load(M) * c[0] + load(M + 4) * c[1]) + load(M + 8) * c[2]) + load(M + 12);
      std::memcpy(centers[k].data(), &w, 3 * sizeof(double));
    }
    const bool free = grid.clear(centers[k], radius[k] + padding);
    bits |= std::uint64_t(free) << (k % 64);
    if (k % 64 == 63 || k + 1 == n) {
      clear[k / 64] = bits;
      bits = 0;
    }
  }
}

void placeScalar(const Pass& p, const ClearanceGrid& g) { placeAll<double>(p, g); }
void placeSse2(const Pass& p, const ClearanceGrid& g) { placeAll<Quad>(p, g); }

#if defined(__x86_64__) || defined(__i386__)
// Four slots at a time: their centres as placeAll forms them (each stored as four doubles, the
// fourth into the next centre or the padding), transposed to x, y and z of the four, then the
// four lookups side by side. The voxel index is formed in 32 bits (placeOn takes this path only
// for grids of fewer than 2^31 voxels, where it is exact); a lane outside the grid reads voxel 0
// (placeOn takes it only for a grid with voxels) and its bit is masked off. The slots are padded
// to a multiple of four with spheres that are never clear.
DSS_TARGET_AVX2 void placeAvx2(const Pass& pass, const ClearanceGrid& grid) {
  const GridView g = grid.lookup();
  const std::size_t n = pass.n;
  const int* const link = pass.link;
  const double* const center = pass.center;
  const double* const radius = pass.radius;
  const Eigen::Isometry3d* const X_WL = pass.X_WL;
  Eigen::Vector3d* const centers = pass.centers;
  std::uint64_t* const clear = pass.clear;
  const std::uint8_t* const bound = g.bound;
  const __m256d padding = _mm256_set1_pd(pass.padding);
  const __m256d inv = _mm256_set1_pd(g.inv_size), quantum = _mm256_set1_pd(ClearanceGrid::kQuantum);
  const __m256d bx = _mm256_set1_pd(g.below[0]), by = _mm256_set1_pd(g.below[1]),
                bz = _mm256_set1_pd(g.below[2]);
  const __m128i bias = _mm_set1_epi32(INT32_MIN), one = _mm_set1_epi32(1);
  const __m128i cx = _mm_set1_epi32(static_cast<int>(g.count[0] ^ 0x80000000u)),
                cy = _mm_set1_epi32(static_cast<int>(g.count[1] ^ 0x80000000u)),
                cz = _mm_set1_epi32(static_cast<int>(g.count[2] ^ 0x80000000u));
  const __m128i sy = _mm_set1_epi32(static_cast<int>(g.stride_y)),
                sz = _mm_set1_epi32(static_cast<int>(g.stride_z));
  std::uint64_t bits = 0;
  for (std::size_t k = 0; k < n; k += 4) {
    __m256d w[4];
    for (std::size_t j = 0; j < 4; ++j) {
      const double* M = X_WL[link[k + j]].data();
      const double* c = center + 4 * (k + j);
      __m256d v = _mm256_mul_pd(_mm256_loadu_pd(M), _mm256_broadcast_sd(c));
      v = _mm256_add_pd(v, _mm256_mul_pd(_mm256_loadu_pd(M + 4), _mm256_broadcast_sd(c + 1)));
      v = _mm256_add_pd(v, _mm256_mul_pd(_mm256_loadu_pd(M + 8), _mm256_broadcast_sd(c + 2)));
      w[j] = _mm256_add_pd(v, _mm256_loadu_pd(M + 12));
      _mm256_storeu_pd(centers[k + j].data(), w[j]);
    }
    const __m256d t0 = _mm256_unpacklo_pd(w[0], w[1]), t1 = _mm256_unpackhi_pd(w[0], w[1]),
                  t2 = _mm256_unpacklo_pd(w[2], w[3]), t3 = _mm256_unpackhi_pd(w[2], w[3]);
    const __m256d x = _mm256_permute2f128_pd(t0, t2, 0x20),
                  y = _mm256_permute2f128_pd(t1, t3, 0x20),
                  z = _mm256_permute2f128_pd(t0, t2, 0x31);
    // toIndex(u) - 1 per lane, then the unsigned range test as a signed one on biased values.
    const __m128i ix = _mm_sub_epi32(_mm256_cvttpd_epi32(_mm256_mul_pd(_mm256_sub_pd(x, bx), inv)),
                                     one),
                  iy = _mm_sub_epi32(_mm256_cvttpd_epi32(_mm256_mul_pd(_mm256_sub_pd(y, by), inv)),
                                     one),
                  iz = _mm_sub_epi32(_mm256_cvttpd_epi32(_mm256_mul_pd(_mm256_sub_pd(z, bz), inv)),
                                     one);
    const __m128i inside =
        _mm_and_si128(_mm_and_si128(_mm_cmplt_epi32(_mm_xor_si128(ix, bias), cx),
                                    _mm_cmplt_epi32(_mm_xor_si128(iy, bias), cy)),
                      _mm_cmplt_epi32(_mm_xor_si128(iz, bias), cz));
    const __m128i index = _mm_and_si128(
        _mm_add_epi32(_mm_add_epi32(_mm_mullo_epi32(iz, sz), _mm_mullo_epi32(iy, sy)), ix), inside);
    const __m128i b =
        _mm_setr_epi32(bound[_mm_extract_epi32(index, 0)], bound[_mm_extract_epi32(index, 1)],
                       bound[_mm_extract_epi32(index, 2)], bound[_mm_extract_epi32(index, 3)]);
    const __m256d r = _mm256_add_pd(_mm256_loadu_pd(radius + k), padding);
    const __m256d far = _mm256_cmp_pd(_mm256_mul_pd(_mm256_cvtepi32_pd(b), quantum), r, _CMP_GT_OQ);
    const unsigned lanes = static_cast<unsigned>(_mm256_movemask_pd(far)) &
                           static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(inside)));
    bits |= std::uint64_t(lanes) << (k % 64);
    if (k % 64 == 60 || k + 4 >= n) {
      clear[k / 64] = bits;
      bits = 0;
    }
  }
}
#else
void placeAvx2(const Pass& p, const ClearanceGrid& g) { placeAll<Quad>(p, g); }
#endif
#pragma GCC diagnostic pop

}  // namespace

SlotSpheres::SlotSpheres(const std::vector<Sphere>& own, const std::vector<Sphere>& folded)
    : path_(activeSimdPath()), size_(own.size()) {
  if (own.size() != folded.size())
    throw std::invalid_argument("SlotSpheres: " + std::to_string(own.size()) + " own spheres, " +
                                std::to_string(folded.size()) + " on pose links");
  // Padding spheres (to a multiple of four) on the first sphere's link, never clear.
  const std::size_t padded = (size_ + 3) / 4 * 4;
  const std::vector<Sphere>* sets[2] = {&own, &folded};
  for (int f = 0; f < 2; ++f)
    for (std::size_t k = 0; k < padded; ++k) {
      const Sphere& s = k < size_ ? (*sets[f])[k] : (*sets[f])[0];
      link_[f].push_back(s.link);
      const Eigen::Vector3d c = k < size_ ? s.center : Eigen::Vector3d::Zero();
      center_[f].insert(center_[f].end(), {c.x(), c.y(), c.z(), 0.0});
    }
  scene_.assign(words(), 0);
  for (std::size_t k = 0; k < padded; ++k) {
    radius_.push_back(k < size_ ? own[k].radius : std::numeric_limits<double>::infinity());
    if (k < size_) scene_[k / 64] |= std::uint64_t(own[k].scene) << (k % 64);
  }
}

void SlotSpheres::place(SimdPath path, bool pose_links, const Eigen::Isometry3d* X_WL,
                        const ClearanceGrid& grid, double padding, Eigen::Vector3d* centers,
                        std::uint64_t* clear) const {
  placeOn(simdPathAvailable(path) ? path : bestSimdPath(), pose_links, X_WL, grid, padding, centers,
          clear);
}

void SlotSpheres::placeOn(SimdPath path, bool pose_links, const Eigen::Isometry3d* X_WL,
                          const ClearanceGrid& grid, double padding, Eigen::Vector3d* centers,
                          std::uint64_t* clear) const {
  const int f = pose_links ? 1 : 0;
  Pass p{size_, link_[f].data(), center_[f].data(), radius_.data(), X_WL, padding, centers, clear};
  // The four-lane pass needs a grid with voxels, fewer than 2^31 of them.
  if (path == SimdPath::kAvx2 && (grid.empty() || grid.voxels() >= (std::size_t(1) << 31)))
    path = SimdPath::kSse2;
  switch (path) {
    case SimdPath::kAvx2:
      p.n = radius_.size();
      placeAvx2(p, grid);
      break;
    case SimdPath::kSse2:
      placeSse2(p, grid);
      break;
    case SimdPath::kScalar:
      placeScalar(p, grid);
      break;
  }
}

}  // namespace dss
