// AVX-512 node update (integrate/node_update.hpp): gravity and mass damping, the central
// difference v^{n+1/2} = v^{n-1/2} + dt f/m, the energies at t^n and x^{n+1} = x^n + dt v^{n+1/2}
// (docs/theory.md §4-5) for 8 nodes per instruction. Same IEEE operations on the same operands
// in the same order as the portable loop in integrate/step.cpp (-ffp-contract=off: no fused
// multiply-add), so x and v are bitwise the same; the per-node energy terms are summed in node
// order afterwards, so the sums are too. Compiled for AVX-512 by a function attribute only (the
// build targets baseline x86-64); step.cpp calls it when the CPU supports it.
#include <immintrin.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "integrate/node_update.hpp"

#define FDEM_AVX512 __attribute__((target("avx512f")))

namespace fdem::detail {

namespace {

// 8 Vec2 at p (masked: lanes of `lanes`) as x and y vectors
FDEM_AVX512 inline void load_vec2(const double* p, __mmask8 lo, __mmask8 hi, __m512d& X,
                                  __m512d& Y) {
    const __m512d z0 = _mm512_maskz_loadu_pd(lo, p);      // x0 y0 ... x3 y3
    const __m512d z1 = _mm512_maskz_loadu_pd(hi, p + 8);  // x4 y4 ... x7 y7
    X = _mm512_permutex2var_pd(z0, _mm512_setr_epi64(0, 2, 4, 6, 8, 10, 12, 14), z1);
    Y = _mm512_permutex2var_pd(z0, _mm512_setr_epi64(1, 3, 5, 7, 9, 11, 13, 15), z1);
}

FDEM_AVX512 inline void store_vec2(double* p, __mmask8 lo, __mmask8 hi, __m512d X, __m512d Y) {
    _mm512_mask_storeu_pd(
        p, lo, _mm512_permutex2var_pd(X, _mm512_setr_epi64(0, 8, 1, 9, 2, 10, 3, 11), Y));
    _mm512_mask_storeu_pd(
        p + 8, hi, _mm512_permutex2var_pd(X, _mm512_setr_epi64(4, 12, 5, 13, 6, 14, 7, 15), Y));
}

// lane mask (4 lanes) -> mask of their 8 doubles (x, y per lane)
constexpr __mmask8 spread(unsigned m4) {
    __mmask8 r = 0;
    for (int i = 0; i < 4; ++i) {
        if (m4 & (1u << i)) r = static_cast<__mmask8>(r | (3u << (2 * i)));
    }
    return r;
}

template <bool kGravity, bool kDamped, bool kEnergy>
FDEM_AVX512 void block(const NodeArrays& a, const NodeUpdate& u, int32_t begin, int32_t end,
                       Real* sums) {
    constexpr __mmask8 kSpread[16] = {spread(0),  spread(1),  spread(2),  spread(3),
                                      spread(4),  spread(5),  spread(6),  spread(7),
                                      spread(8),  spread(9),  spread(10), spread(11),
                                      spread(12), spread(13), spread(14), spread(15)};
    const __m512d gx = _mm512_set1_pd(u.g.x), gy = _mm512_set1_pd(u.g.y);
    const __m512d dt = _mm512_set1_pd(u.dt), dt_v = _mm512_set1_pd(u.dt_v);
    const __m512d c = _mm512_set1_pd(u.c), half = _mm512_set1_pd(0.5);
    const bool first = u.first;
    auto* xd = reinterpret_cast<double*>(a.x);
    auto* vd = reinterpret_cast<double*>(a.v);
    const auto* fd = reinterpret_cast<const double*>(a.f);
    const auto* x0d = reinterpret_cast<const double*>(a.x0);
    alignas(64) double kin_t[8], grav_t[8], damp_t[8];

    for (int32_t g0 = begin; g0 < end; g0 += kNodeGroup, sums += 3) {
        const int32_t g_end = std::min<int32_t>(end, g0 + kNodeGroup);
        Real kin = 0, grav = 0, damp = 0;
        for (int32_t i0 = g0; i0 < g_end; i0 += 8) {
            const int n = static_cast<int>(std::min<int32_t>(8, g_end - i0));
            const __mmask8 in = static_cast<__mmask8>((1u << n) - 1);
            const __m512d inv = _mm512_maskz_loadu_pd(in, a.inv_mass + i0);
            const __m512d mi = _mm512_maskz_loadu_pd(in, a.mass + i0);
            // nodes of fixed bodies (inv == 0) are skipped, as `continue` in the portable loop
            const __mmask8 active =
                _mm512_mask_cmp_pd_mask(in, inv, _mm512_setzero_pd(), _CMP_NEQ_UQ);
            const __mmask8 lo = kSpread[active & 15u], hi = kSpread[active >> 4];
            const ptrdiff_t o = 2 * static_cast<ptrdiff_t>(i0);
            __m512d vx, vy, fx, fy, xx, xy;
            load_vec2(vd + o, lo, hi, vx, vy);
            load_vec2(fd + o, lo, hi, fx, fy);
            load_vec2(xd + o, lo, hi, xx, xy);

            // fi = f + m g (- c m v_old); v_new = v_old + (dt_v inv) fi
            __m512d fix = _mm512_add_pd(fx, _mm512_mul_pd(mi, gx));
            __m512d fiy = _mm512_add_pd(fy, _mm512_mul_pd(mi, gy));
            if constexpr (kDamped) {
                const __m512d cm = _mm512_mul_pd(c, mi);
                fix = _mm512_sub_pd(fix, _mm512_mul_pd(cm, vx));
                fiy = _mm512_sub_pd(fiy, _mm512_mul_pd(cm, vy));
            }
            const __m512d s = _mm512_mul_pd(dt_v, inv);
            const __m512d wx = _mm512_add_pd(vx, _mm512_mul_pd(s, fix));
            const __m512d wy = _mm512_add_pd(vy, _mm512_mul_pd(s, fiy));
            // v^n (theory eq. 5.2)
            const __m512d nx = first ? vx : _mm512_mul_pd(half, _mm512_add_pd(vx, wx));
            const __m512d ny = first ? vy : _mm512_mul_pd(half, _mm512_add_pd(vy, wy));
            if constexpr (kEnergy) {
                _mm512_store_pd(kin_t, _mm512_mul_pd(mi, _mm512_add_pd(_mm512_mul_pd(nx, nx),
                                                                       _mm512_mul_pd(ny, ny))));
            }
            if constexpr (kGravity && kEnergy) {
                // work of gravity up to x^n: the exact potential change (theory eq. 4.2)
                __m512d x0x, x0y;
                load_vec2(x0d + o, lo, hi, x0x, x0y);
                const __m512d d = _mm512_add_pd(_mm512_mul_pd(gx, _mm512_sub_pd(xx, x0x)),
                                                _mm512_mul_pd(gy, _mm512_sub_pd(xy, x0y)));
                _mm512_store_pd(grav_t, _mm512_mul_pd(mi, d));
            }
            if constexpr (kDamped) {
                const __m512d d = _mm512_add_pd(_mm512_mul_pd(vx, nx), _mm512_mul_pd(vy, ny));
                _mm512_store_pd(damp_t, _mm512_mul_pd(_mm512_mul_pd(c, mi), d));
            }
            store_vec2(vd + o, lo, hi, wx, wy);
            store_vec2(xd + o, lo, hi, _mm512_add_pd(xx, _mm512_mul_pd(dt, wx)),
                       _mm512_add_pd(xy, _mm512_mul_pd(dt, wy)));

            // sums in node order
            if constexpr (kEnergy || kDamped) {
                if (active == 0xff) {
                    for (int i = 0; i < 8; ++i) {
                        if constexpr (kEnergy) kin += kin_t[i];
                        if constexpr (kGravity && kEnergy) grav += grav_t[i];
                        if constexpr (kDamped) damp += damp_t[i];
                    }
                } else {
                    for (int i = 0; i < n; ++i) {
                        if (!(active & (1u << i))) continue;
                        if constexpr (kEnergy) kin += kin_t[i];
                        if constexpr (kGravity && kEnergy) grav += grav_t[i];
                        if constexpr (kDamped) damp += damp_t[i];
                    }
                }
            }
        }
        sums[0] = kin;
        sums[1] = grav;
        sums[2] = damp;
    }
}

template <bool kEnergy>
void dispatch(const NodeArrays& a, const NodeUpdate& u, bool gravity, bool damped, int32_t begin,
              int32_t end, Real* sums) {
    if (gravity && damped) {
        block<true, true, kEnergy>(a, u, begin, end, sums);
    } else if (gravity) {
        block<true, false, kEnergy>(a, u, begin, end, sums);
    } else if (damped) {
        block<false, true, kEnergy>(a, u, begin, end, sums);
    } else {
        block<false, false, kEnergy>(a, u, begin, end, sums);
    }
}

}  // namespace

void node_block_avx512(const NodeArrays& a, const NodeUpdate& u, bool gravity, bool damped,
                       bool energy, int32_t begin, int32_t end, Real* sums) {
    if (energy) {
        dispatch<true>(a, u, gravity, damped, begin, end, sums);
    } else {
        dispatch<false>(a, u, gravity, damped, begin, end, sums);
    }
}

}  // namespace fdem::detail
