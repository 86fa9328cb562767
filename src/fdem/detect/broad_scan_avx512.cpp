// AVX-512VL version of the broad-phase scan (detect/broad_scan.hpp). The build targets baseline
// x86-64, so only this file is compiled for AVX-512 (function attribute, no global flag) and
// detect/broad_phase.cpp calls it when the CPU supports it.
//
// Per row of the 3x3 block (one contiguous run of cell-ordered entries), 4 entries at a time in
// 256-bit registers with a tail mask: masked loads (no fault past the run), dx * dx + dy * dy <
// r2 as in the portable loop (same operations, same order, no FMA), the role test on the body
// key, and the ids of the hits compressed in a register and stored as 4 lanes at the end of the
// list (kScanSlack). No gather (slow on this CPU family, see element/cst_simd.cpp). Tried and
// dropped (docs/performance.md): 512-bit registers with 8 entries, a sorting network for the
// hits and a whole node loop without data-dependent branches; all measured slower than this.
#include <immintrin.h>

#include "detect/broad_scan.hpp"

#define FDEM_AVX512 __attribute__((target("avx512f,avx512vl,popcnt")))

namespace fdem::detail {

bool scan_avx512_supported() {
    static const bool ok = __builtin_cpu_supports("avx512f") &&
                           __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("popcnt");
    return ok;
}

FDEM_AVX512 int32_t scan_block_avx512(const CellTris& a, const Block& q, int32_t* hits) {
    const __m256d px = _mm256_set1_pd(q.xj.x), py = _mm256_set1_pd(q.xj.y);
    const __m128i pt = _mm_set1_epi32(q.role.t), plo = _mm_set1_epi32(q.role.lo),
                  phi = _mm_set1_epi32(q.role.hi);
    int32_t n = 0;
    for (int32_t cy = q.cy0; cy <= q.cy1; ++cy) {
        const int32_t k1 = a.start[cy * a.nx + q.cx1 + 1];
        for (int32_t k = a.start[cy * a.nx + q.cx0]; k < k1; k += 4) {
            const int32_t left = k1 - k;
            const __mmask8 m = left >= 4 ? __mmask8(0xF) : __mmask8((1u << left) - 1u);
            const __m256d dx = _mm256_sub_pd(px, _mm256_maskz_loadu_pd(m, a.cx + k));
            const __m256d dy = _mm256_sub_pd(py, _mm256_maskz_loadu_pd(m, a.cy + k));
            const __m256d d2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
            __mmask8 hit =
                _mm256_mask_cmp_pd_mask(m, d2, _mm256_maskz_loadu_pd(m, a.r2 + k), _CMP_LT_OQ);
            const __m128i key = _mm_maskz_loadu_epi32(m, a.key + k);
            hit = _mm_mask_cmpneq_epi32_mask(hit, key, pt) &
                  (_mm_cmplt_epi32_mask(key, plo) | _mm_cmpge_epi32_mask(key, phi));
            const __m128i ids = _mm_maskz_compress_epi32(hit, _mm_maskz_loadu_epi32(m, a.item + k));
            _mm_storeu_si128(reinterpret_cast<__m128i*>(hits + n), ids);
            n += __builtin_popcount(hit);
        }
    }
    return n;
}

}  // namespace fdem::detail
