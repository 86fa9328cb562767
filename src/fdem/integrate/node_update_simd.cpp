// AVX-512 and AVX2 node updates (integrate/node_update.hpp): gravity and mass damping, the central
// difference v^{n+1/2} = v^{n-1/2} + dt f/m, the energies at t^n and x^{n+1} = x^n + dt v^{n+1/2}
// (docs/theory.md §4-5) for 8 nodes per instruction. Same IEEE operations on the same operands
// in the same order as the portable loop in integrate/step.cpp (-ffp-contract=off: no fused
// multiply-add), so x and v are bitwise the same; the per-node energy terms are summed in node
// order afterwards, so the sums are too. Compiled for AVX-512 (AVX2) by a function attribute only
// (the build targets baseline x86-64); step.cpp calls one when the CPU supports it.
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

// The same block with AVX2, 4 nodes per instruction, for CPUs without AVX-512. The two 32-byte
// halves of 4 Vec2 (x0 y0 x1 y1 | x2 y2 x3 y3) are unpacked into X = (x0 x2 x1 x3) and
// Y = (y0 y2 y1 y3), so the per-node arrays are loaded in that lane order too (one lane permute)
// and the energy terms are summed back in node order; the unpack back to Vec2 restores the order.
// Lanes of fixed nodes (1/m = 0) and past the end are loaded as zeros and not stored (masked
// moves), as the AVX-512 block's masks. Same operations and order: same bits.
#define FDEM_AVX2 __attribute__((target("avx2")))

// node order of lane i: (0 2 1 3)
constexpr int kAvx2Order[4] = {0, 2, 1, 3};

// lanes (node order) of a 4-bit mask -> masks of the two halves of their 8 doubles
FDEM_AVX2 inline void spread_avx2(unsigned m4, __m256i& lo, __m256i& hi) {
    const auto bit = [&](int i) { return (m4 >> i) & 1u ? int64_t{-1} : int64_t{0}; };
    lo = _mm256_setr_epi64x(bit(0), bit(0), bit(1), bit(1));
    hi = _mm256_setr_epi64x(bit(2), bit(2), bit(3), bit(3));
}

FDEM_AVX2 inline void load_vec2_avx2(const double* p, bool all, __m256i lo, __m256i hi, __m256d& X,
                                     __m256d& Y) {
    const __m256d z0 = all ? _mm256_loadu_pd(p) : _mm256_maskload_pd(p, lo);
    const __m256d z1 = all ? _mm256_loadu_pd(p + 4) : _mm256_maskload_pd(p + 4, hi);
    X = _mm256_unpacklo_pd(z0, z1);
    Y = _mm256_unpackhi_pd(z0, z1);
}

FDEM_AVX2 inline void store_vec2_avx2(double* p, bool all, __m256i lo, __m256i hi, __m256d X,
                                      __m256d Y) {
    const __m256d z0 = _mm256_unpacklo_pd(X, Y), z1 = _mm256_unpackhi_pd(X, Y);
    if (all) {
        _mm256_storeu_pd(p, z0);
        _mm256_storeu_pd(p + 4, z1);
    } else {
        _mm256_maskstore_pd(p, lo, z0);
        _mm256_maskstore_pd(p + 4, hi, z1);
    }
}

// 4 doubles at p (n of them, the rest 0) in the lane order of load_vec2_avx2
FDEM_AVX2 inline __m256d load_lanes_avx2(const double* p, int n) {
    const __m256d z =
        n == 4 ? _mm256_loadu_pd(p)
               : _mm256_maskload_pd(p, _mm256_setr_epi64x(-1, n > 1 ? -1 : 0, n > 2 ? -1 : 0, 0));
    return _mm256_permute4x64_pd(z, 0xD8);
}

template <bool kGravity, bool kDamped, bool kEnergy>
FDEM_AVX2 void block_avx2(const NodeArrays& a, const NodeUpdate& u, int32_t begin, int32_t end,
                          Real* sums) {
    const __m256d gx = _mm256_set1_pd(u.g.x), gy = _mm256_set1_pd(u.g.y);
    const __m256d dt = _mm256_set1_pd(u.dt), dt_v = _mm256_set1_pd(u.dt_v);
    const __m256d c = _mm256_set1_pd(u.c), half = _mm256_set1_pd(0.5);
    const bool first = u.first;
    auto* xd = reinterpret_cast<double*>(a.x);
    auto* vd = reinterpret_cast<double*>(a.v);
    const auto* fd = reinterpret_cast<const double*>(a.f);
    const auto* x0d = reinterpret_cast<const double*>(a.x0);
    alignas(32) double kin_t[4], grav_t[4], damp_t[4];

    for (int32_t g0 = begin; g0 < end; g0 += kNodeGroup, sums += 3) {
        const int32_t g_end = std::min<int32_t>(end, g0 + kNodeGroup);
        Real kin = 0, grav = 0, damp = 0;
        for (int32_t i0 = g0; i0 < g_end; i0 += 4) {
            const int n = static_cast<int>(std::min<int32_t>(4, g_end - i0));
            const __m256d inv = load_lanes_avx2(a.inv_mass + i0, n);
            const __m256d mi = load_lanes_avx2(a.mass + i0, n);
            // nodes of fixed bodies (inv == 0) are skipped, as `continue` in the portable loop
            const unsigned lane_active = static_cast<unsigned>(
                _mm256_movemask_pd(_mm256_cmp_pd(inv, _mm256_setzero_pd(), _CMP_NEQ_UQ)));
            unsigned active = 0;  // in node order
            for (int l = 0; l < 4; ++l)
                active |= ((lane_active >> l) & 1u) << kAvx2Order[l];
            active &= (1u << n) - 1;
            const bool all = active == 15u;
            __m256i lo = _mm256_setzero_si256(), hi = _mm256_setzero_si256();
            if (!all) spread_avx2(active, lo, hi);
            const ptrdiff_t o = 2 * static_cast<ptrdiff_t>(i0);
            __m256d vx, vy, fx, fy, xx, xy;
            load_vec2_avx2(vd + o, all, lo, hi, vx, vy);
            load_vec2_avx2(fd + o, all, lo, hi, fx, fy);
            load_vec2_avx2(xd + o, all, lo, hi, xx, xy);

            // fi = f + m g (- c m v_old); v_new = v_old + (dt_v inv) fi
            __m256d fix = _mm256_add_pd(fx, _mm256_mul_pd(mi, gx));
            __m256d fiy = _mm256_add_pd(fy, _mm256_mul_pd(mi, gy));
            if constexpr (kDamped) {
                const __m256d cm = _mm256_mul_pd(c, mi);
                fix = _mm256_sub_pd(fix, _mm256_mul_pd(cm, vx));
                fiy = _mm256_sub_pd(fiy, _mm256_mul_pd(cm, vy));
            }
            const __m256d s = _mm256_mul_pd(dt_v, inv);
            const __m256d wx = _mm256_add_pd(vx, _mm256_mul_pd(s, fix));
            const __m256d wy = _mm256_add_pd(vy, _mm256_mul_pd(s, fiy));
            // v^n (theory eq. 5.2)
            const __m256d nx = first ? vx : _mm256_mul_pd(half, _mm256_add_pd(vx, wx));
            const __m256d ny = first ? vy : _mm256_mul_pd(half, _mm256_add_pd(vy, wy));
            if constexpr (kEnergy) {
                _mm256_store_pd(kin_t, _mm256_mul_pd(mi, _mm256_add_pd(_mm256_mul_pd(nx, nx),
                                                                       _mm256_mul_pd(ny, ny))));
            }
            if constexpr (kGravity && kEnergy) {
                // work of gravity up to x^n: the exact potential change (theory eq. 4.2)
                __m256d x0x, x0y;
                load_vec2_avx2(x0d + o, all, lo, hi, x0x, x0y);
                const __m256d d = _mm256_add_pd(_mm256_mul_pd(gx, _mm256_sub_pd(xx, x0x)),
                                                _mm256_mul_pd(gy, _mm256_sub_pd(xy, x0y)));
                _mm256_store_pd(grav_t, _mm256_mul_pd(mi, d));
            }
            if constexpr (kDamped) {
                const __m256d d = _mm256_add_pd(_mm256_mul_pd(vx, nx), _mm256_mul_pd(vy, ny));
                _mm256_store_pd(damp_t, _mm256_mul_pd(_mm256_mul_pd(c, mi), d));
            }
            store_vec2_avx2(vd + o, all, lo, hi, wx, wy);
            store_vec2_avx2(xd + o, all, lo, hi, _mm256_add_pd(xx, _mm256_mul_pd(dt, wx)),
                            _mm256_add_pd(xy, _mm256_mul_pd(dt, wy)));

            // sums in node order: node i is in lane kAvx2Order[i] (the order is its own inverse)
            if constexpr (kEnergy || kDamped) {
                for (int i = 0; i < n; ++i) {
                    if (!(active & (1u << i))) continue;
                    const int l = kAvx2Order[i];
                    if constexpr (kEnergy) kin += kin_t[l];
                    if constexpr (kGravity && kEnergy) grav += grav_t[l];
                    if constexpr (kDamped) damp += damp_t[l];
                }
            }
        }
        sums[0] = kin;
        sums[1] = grav;
        sums[2] = damp;
    }
}

template <bool kAvx2, bool kEnergy>
void dispatch(const NodeArrays& a, const NodeUpdate& u, bool gravity, bool damped, int32_t begin,
              int32_t end, Real* sums) {
    if (gravity && damped) {
        kAvx2 ? block_avx2<true, true, kEnergy>(a, u, begin, end, sums)
              : block<true, true, kEnergy>(a, u, begin, end, sums);
    } else if (gravity) {
        kAvx2 ? block_avx2<true, false, kEnergy>(a, u, begin, end, sums)
              : block<true, false, kEnergy>(a, u, begin, end, sums);
    } else if (damped) {
        kAvx2 ? block_avx2<false, true, kEnergy>(a, u, begin, end, sums)
              : block<false, true, kEnergy>(a, u, begin, end, sums);
    } else {
        kAvx2 ? block_avx2<false, false, kEnergy>(a, u, begin, end, sums)
              : block<false, false, kEnergy>(a, u, begin, end, sums);
    }
}

}  // namespace

void node_block_avx512(const NodeArrays& a, const NodeUpdate& u, bool gravity, bool damped,
                       bool energy, int32_t begin, int32_t end, Real* sums) {
    if (energy) {
        dispatch<false, true>(a, u, gravity, damped, begin, end, sums);
    } else {
        dispatch<false, false>(a, u, gravity, damped, begin, end, sums);
    }
}

void node_block_avx2(const NodeArrays& a, const NodeUpdate& u, bool gravity, bool damped,
                     bool energy, int32_t begin, int32_t end, Real* sums) {
    if (energy) {
        dispatch<true, true>(a, u, gravity, damped, begin, end, sums);
    } else {
        dispatch<true, false>(a, u, gravity, damped, begin, end, sums);
    }
}

}  // namespace fdem::detail
