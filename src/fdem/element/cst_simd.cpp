// AVX-512 kernel of the elastic constant-strain triangle (docs/theory.md §2-3).
//
// Why (docs/performance.md, round 4): the portable kernel (element/cst.cpp) is compute-bound at
// ~40 cycles per triangle with SSE2, two triangles per instruction. The build targets baseline
// x86-64, so this file compiles only its kernel for AVX-512 (function attribute, no global flag)
// and element/cst.cpp calls it when the CPU supports it.
//
// Bitwise the same as the portable kernel: every value is the same IEEE add, sub, mul or div of
// the same operands in the same order (-ffp-contract=off, so no fused multiply-add), only 8
// triangles at a time; the forces are scattered, the smallest J tracked and the strain energy
// summed in triangle order, as there. tests/unit/element/cst_simd_test.cpp compares the bits.
//
// Per group of 8 triangles: (1) the corners are loaded as 16-byte Vec2 (no gather instruction:
// on this CPU family the microcode mitigation of "gather data sampling" makes them slow) and
// de-interleaved into x and y vectors; Dm^-1 of the 8 triangles is transposed in registers;
// (2) F, J, sigma and the three nodal forces as 8-wide vectors; (3) the forces, interleaved
// back into Vec2, are added to f triangle by triangle (neighbouring triangles share nodes, so
// this stays scalar and ordered).
#include "element/cst_simd.hpp"

#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "material/hyperelastic.hpp"

// GCC 12 warns inside its own avx512fintrin.h about the undefined upper half of
// _mm512_castpd256_pd512 (filled by the next insert) and in _mm512_reduce_min_pd: false positives
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#define FDEM_AVX512 __attribute__((target("avx512f")))

namespace fdem::detail {

bool cst_avx512_supported() {
    static const bool ok = __builtin_cpu_supports("avx512f");
    return ok;
}

namespace {

constexpr int kLanes = 8;

// Material constants broadcast to all lanes.
struct Consts {
    __m512d mu, half_lambda, one, half;
};

// -a, as the unary minus of the portable kernel: flips the sign bit only (0 - a would turn +0
// into +0 instead of -0). AVX-512F has no floating-point xor, hence the integer one.
FDEM_AVX512 inline __m512d neg(__m512d a) {
    return _mm512_castsi512_pd(_mm512_xor_si512(
        _mm512_castpd_si512(a), _mm512_set1_epi64(static_cast<int64_t>(0x8000000000000000ull))));
}

// Viscous inputs of a group (kViscous): node velocities, and eta and A0 of the 8 triangles.
struct ViscousIn {
    const double* vd;
    const double* eta;
    const double* area0;
};

// The scalar parts of a range, shared by the AVX-512 and AVX2 kernels (baseline SSE2 code without
// a target attribute, so it inlines into either).

// f[node] += (v[0], v[1]); kFirst (a chunk_first chunk: the node is this triangle's alone):
// f[node] = 0 + (v[0], v[1]), the bits of a cleared f plus v, without reading f
template <bool kFirst>
inline void add_force(double* fd, int32_t node, const double* v) {
    double* p = fd + 2 * static_cast<ptrdiff_t>(node);
    const __m128d base = kFirst ? _mm_setzero_pd() : _mm_loadu_pd(p);
    _mm_storeu_pd(p, _mm_add_pd(base, _mm_load_pd(v)));
}

// the forces of lane i of a group (corner k at fo[16 k + 2 i]) added to its three nodes
template <bool kFirst>
[[gnu::always_inline]] inline void add_lane_forces(double* fd, const int32_t* q, const double* fo,
                                                   int i) {
    add_force<kFirst>(fd, q[3 * i], fo + 2 * i);
    add_force<kFirst>(fd, q[3 * i + 1], fo + 16 + 2 * i);
    add_force<kFirst>(fd, q[3 * i + 2], fo + 32 + 2 * i);
}

// Last group of a range (n < kLanes triangles from t0): the missing lanes repeat its last triangle
// (computed, unused); q, dm and vi then point at the padded copies.
template <bool kViscous>
[[gnu::always_inline]] inline void pad_group(int n, TriId t0, const Real* eta, const Real* area0,
                                             const int32_t*& q, const double*& dm, ViscousIn& vi,
                                             int32_t* pad_q, double* pad_dm, double* pad_eta,
                                             double* pad_area) {
    for (int i = 0; i < kLanes; ++i) {
        const int src = std::min(i, n - 1);
        std::copy_n(q + 3 * src, 3, pad_q + 3 * i);
        std::copy_n(dm + 4 * src, 4, pad_dm + 4 * i);
        if constexpr (kViscous) {
            pad_eta[i] = eta[t0 + src];
            pad_area[i] = area0[t0 + src];
        }
    }
    q = pad_q;
    dm = pad_dm;
    vi.eta = pad_eta;
    vi.area0 = pad_area;
}

// A whole group without an inverted triangle (its smallest J already taken): the forces in
// triangle order and (kViscous) the viscous power of the lanes with eta > 0, as the portable sum.
template <bool kViscous, bool kFirst>
[[gnu::always_inline]] inline void commit_group(double* fd, const int32_t* q, const double* fo,
                                                const Real* eta, TriId t0, const double* pw,
                                                Real& power) {
    for (int i = 0; i < kLanes; ++i)
        add_lane_forces<kFirst>(fd, q, fo, i);
    if constexpr (kViscous) {
        for (int i = 0; i < kLanes; ++i) {
            if (eta[t0 + i] > 0) power += pw[i];
        }
    }
}

// Lanes [0, n) of a group, as the portable kernel, triangle by triangle: the smallest J (jg) with
// a strict <, no force from an inverted triangle (reported by the caller; kFirst: zeros stored at
// its nodes, what the clear would have left), the viscous power.
template <bool kViscous, bool kFirst>
[[gnu::always_inline]] inline void commit_checked(int n, double* fd, const int32_t* q,
                                                  const double* fo, const double* jg,
                                                  const Real* eta, TriId t0, const double* pw,
                                                  Real& power, Real& min_j, TriId& min_t) {
    for (int i = 0; i < n; ++i) {
        const Real Ji = jg[i];
        if (Ji < min_j) {
            min_j = Ji;
            min_t = t0 + i;
        }
        if (!(Ji > 0)) {
            if constexpr (kFirst) {
                for (int k = 0; k < 3; ++k)
                    _mm_storeu_pd(fd + 2 * static_cast<ptrdiff_t>(q[3 * i + k]), _mm_setzero_pd());
            }
            continue;
        }
        if constexpr (kViscous) {
            if (eta[t0 + i] > 0) power += pw[i];
        }
        add_lane_forces<kFirst>(fd, q, fo, i);
    }
}

// x and y of corner k (0, 1, 2) of the 8 triangles whose node ids are q[3 i + k].
FDEM_AVX512 inline void load_corner(const double* xd, const int32_t* q, int k, __m512d& X,
                                    __m512d& Y) {
    const auto at = [](const double* p, const int32_t* q3, int i, int k3) {
        return p + 2 * static_cast<ptrdiff_t>(q3[3 * i + k3]);
    };
    const __m256d l0 = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(at(xd, q, 0, k))),
                                            _mm_loadu_pd(at(xd, q, 1, k)), 1);
    const __m256d l1 = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(at(xd, q, 2, k))),
                                            _mm_loadu_pd(at(xd, q, 3, k)), 1);
    const __m256d h0 = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(at(xd, q, 4, k))),
                                            _mm_loadu_pd(at(xd, q, 5, k)), 1);
    const __m256d h1 = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(at(xd, q, 6, k))),
                                            _mm_loadu_pd(at(xd, q, 7, k)), 1);
    // z0 = x0 y0 x1 y1 x2 y2 x3 y3, z1 = x4 y4 ... x7 y7
    const __m512d z0 = _mm512_insertf64x4(_mm512_castpd256_pd512(l0), l1, 1);
    const __m512d z1 = _mm512_insertf64x4(_mm512_castpd256_pd512(h0), h1, 1);
    X = _mm512_permutex2var_pd(z0, _mm512_setr_epi64(0, 2, 4, 6, 8, 10, 12, 14), z1);
    Y = _mm512_permutex2var_pd(z0, _mm512_setr_epi64(1, 3, 5, 7, 9, 11, 13, 15), z1);
}

// Store the 8 Vec2 (fx[i], fy[i]) interleaved at out[0..15].
FDEM_AVX512 inline void store_interleaved(double* out, __m512d fx, __m512d fy) {
    _mm512_store_pd(out,
                    _mm512_permutex2var_pd(fx, _mm512_setr_epi64(0, 8, 1, 9, 2, 10, 3, 11), fy));
    _mm512_store_pd(out + 8,
                    _mm512_permutex2var_pd(fx, _mm512_setr_epi64(4, 12, 5, 13, 6, 14, 7, 15), fy));
}

// Forces of 8 triangles with node ids q[0..23] and Dm^-1 dm[0..31] (8 Mat2, row-major): the
// forces of corner k of lane i go to fo[16 k + 2 i], tr C to trc[i] (kEnergy), the viscous power
// J A0 eta D:D to pw[i] (kViscous; meaningful where eta > 0); returns J.
template <bool kEnergy, bool kViscous>
FDEM_AVX512 inline __m512d group(const double* xd, const int32_t* q, const double* dm,
                                 const Consts& c, const ViscousIn& vi, double* fo, double* trc,
                                 double* pw) {
    __m512d xa, ya, xb, yb, xc, yc;
    load_corner(xd, q, 0, xa, ya);
    load_corner(xd, q, 1, xb, yb);
    load_corner(xd, q, 2, xc, yc);

    // Dm^-1 of the 8 triangles: rows (xx xy yx yy) -> one vector per entry
    const __m512d d0 = _mm512_loadu_pd(dm), d1 = _mm512_loadu_pd(dm + 8);
    const __m512d d2 = _mm512_loadu_pd(dm + 16), d3 = _mm512_loadu_pd(dm + 24);
    const __m512i lo_xx = _mm512_setr_epi64(0, 4, 8, 12, 1, 5, 9, 13);
    const __m512i lo_yx = _mm512_setr_epi64(2, 6, 10, 14, 3, 7, 11, 15);
    const __m512d e0 = _mm512_permutex2var_pd(d0, lo_xx, d1);  // xx t0-3 | xy t0-3
    const __m512d e1 = _mm512_permutex2var_pd(d0, lo_yx, d1);  // yx t0-3 | yy t0-3
    const __m512d e2 = _mm512_permutex2var_pd(d2, lo_xx, d3);  // xx t4-7 | xy t4-7
    const __m512d e3 = _mm512_permutex2var_pd(d2, lo_yx, d3);  // yx t4-7 | yy t4-7
    const __m512i low = _mm512_setr_epi64(0, 1, 2, 3, 8, 9, 10, 11);
    const __m512i high = _mm512_setr_epi64(4, 5, 6, 7, 12, 13, 14, 15);
    const __m512d dxx = _mm512_permutex2var_pd(e0, low, e2);
    const __m512d dxy = _mm512_permutex2var_pd(e0, high, e2);
    const __m512d dyx = _mm512_permutex2var_pd(e1, low, e3);
    const __m512d dyy = _mm512_permutex2var_pd(e1, high, e3);

    // F = Ds Dm^-1, Ds = [xb - xa, xc - xa] (theory eq. 3.1); as Mat2 operator*
    const __m512d e1x = _mm512_sub_pd(xb, xa), e1y = _mm512_sub_pd(yb, ya);
    const __m512d e2x = _mm512_sub_pd(xc, xa), e2y = _mm512_sub_pd(yc, ya);
    const __m512d Fxx = _mm512_add_pd(_mm512_mul_pd(e1x, dxx), _mm512_mul_pd(e2x, dyx));
    const __m512d Fxy = _mm512_add_pd(_mm512_mul_pd(e1x, dxy), _mm512_mul_pd(e2x, dyy));
    const __m512d Fyx = _mm512_add_pd(_mm512_mul_pd(e1y, dxx), _mm512_mul_pd(e2y, dyx));
    const __m512d Fyy = _mm512_add_pd(_mm512_mul_pd(e1y, dxy), _mm512_mul_pd(e2y, dyy));
    const __m512d J = _mm512_sub_pd(_mm512_mul_pd(Fxx, Fyy), _mm512_mul_pd(Fxy, Fyx));

    // sigma = (mu/J)(B - I) + (lambda/2)(J - 1/J) I, B = F F^T (theory eq. 2.2, cauchy_stress);
    // B.yx = Fyx Fxx + Fyy Fxy has the same bits as B.xy (products and the sum commute)
    const __m512d Bxx = _mm512_add_pd(_mm512_mul_pd(Fxx, Fxx), _mm512_mul_pd(Fxy, Fxy));
    const __m512d Bxy = _mm512_add_pd(_mm512_mul_pd(Fxx, Fyx), _mm512_mul_pd(Fxy, Fyy));
    const __m512d Byy = _mm512_add_pd(_mm512_mul_pd(Fyx, Fyx), _mm512_mul_pd(Fyy, Fyy));
    const __m512d a = _mm512_div_pd(c.mu, J);
    const __m512d p = _mm512_mul_pd(c.half_lambda, _mm512_sub_pd(J, _mm512_div_pd(c.one, J)));
    __m512d sxx = _mm512_add_pd(_mm512_mul_pd(a, _mm512_sub_pd(Bxx, c.one)), p);
    __m512d sxy = _mm512_mul_pd(a, Bxy);
    __m512d syy = _mm512_add_pd(_mm512_mul_pd(a, _mm512_sub_pd(Byy, c.one)), p);

    if constexpr (kViscous) {
        // viscous stress eta D, D = sym(L), L = [v_b - v_a, v_c - v_a] Ds^-1 (theory eq. 2.4):
        // rate_of_deformation (element/cst.hpp) with inverse (math.hpp), operation by operation.
        // Ds = columns(e1, e2): Ds.xx = e1x, Ds.xy = e2x, Ds.yx = e1y, Ds.yy = e2y
        __m512d vxa, vya, vxb, vyb, vxc, vyc;
        load_corner(vi.vd, q, 0, vxa, vya);
        load_corner(vi.vd, q, 1, vxb, vyb);
        load_corner(vi.vd, q, 2, vxc, vyc);
        const __m512d inv =
            _mm512_div_pd(c.one, _mm512_sub_pd(_mm512_mul_pd(e1x, e2y), _mm512_mul_pd(e2x, e1y)));
        const __m512d ixx = _mm512_mul_pd(e2y, inv), ixy = _mm512_mul_pd(neg(e2x), inv);
        const __m512d iyx = _mm512_mul_pd(neg(e1y), inv), iyy = _mm512_mul_pd(e1x, inv);
        const __m512d ubx = _mm512_sub_pd(vxb, vxa), uby = _mm512_sub_pd(vyb, vya);
        const __m512d ucx = _mm512_sub_pd(vxc, vxa), ucy = _mm512_sub_pd(vyc, vya);
        // L = columns(u_b, u_c) * Ds^-1 (Mat2 operator*)
        const __m512d Lxx = _mm512_add_pd(_mm512_mul_pd(ubx, ixx), _mm512_mul_pd(ucx, iyx));
        const __m512d Lxy = _mm512_add_pd(_mm512_mul_pd(ubx, ixy), _mm512_mul_pd(ucx, iyy));
        const __m512d Lyx = _mm512_add_pd(_mm512_mul_pd(uby, ixx), _mm512_mul_pd(ucy, iyx));
        const __m512d Lyy = _mm512_add_pd(_mm512_mul_pd(uby, ixy), _mm512_mul_pd(ucy, iyy));
        const __m512d Dxy = _mm512_mul_pd(c.half, _mm512_add_pd(Lxy, Lyx));
        // sigma + eta D only in the lanes with eta > 0 (the portable branch); sigma.yx + eta D.yx
        // has the bits of sigma.xy + eta D.xy, so sxy serves both
        const __m512d eta = _mm512_loadu_pd(vi.eta);
        const __mmask8 visc = _mm512_cmp_pd_mask(eta, _mm512_setzero_pd(), _CMP_GT_OQ);
        sxx = _mm512_mask_add_pd(sxx, visc, sxx, _mm512_mul_pd(eta, Lxx));
        sxy = _mm512_mask_add_pd(sxy, visc, sxy, _mm512_mul_pd(eta, Dxy));
        syy = _mm512_mask_add_pd(syy, visc, syy, _mm512_mul_pd(eta, Lyy));
        // J A0 eta ddot(D, D), ddot summed xx, xy, yx, yy (math.hpp)
        const __m512d dd = _mm512_add_pd(
            _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(Lxx, Lxx), _mm512_mul_pd(Dxy, Dxy)),
                          _mm512_mul_pd(Dxy, Dxy)),
            _mm512_mul_pd(Lyy, Lyy));
        const __m512d jae = _mm512_mul_pd(_mm512_mul_pd(J, _mm512_loadu_pd(vi.area0)), eta);
        _mm512_store_pd(pw, _mm512_mul_pd(jae, dd));
    }

    // f_i = 1/2 sigma n_i, n_i the scaled outward normal of the edge opposite i (theory eq. 3.3)
    const __m512d nx[3] = {_mm512_sub_pd(yc, yb), _mm512_sub_pd(ya, yc), _mm512_sub_pd(yb, ya)};
    const __m512d ny[3] = {_mm512_sub_pd(xb, xc), _mm512_sub_pd(xc, xa), _mm512_sub_pd(xa, xb)};
    for (int k = 0; k < 3; ++k) {
        const __m512d fx = _mm512_mul_pd(
            c.half, _mm512_add_pd(_mm512_mul_pd(sxx, nx[k]), _mm512_mul_pd(sxy, ny[k])));
        const __m512d fy = _mm512_mul_pd(
            c.half, _mm512_add_pd(_mm512_mul_pd(sxy, nx[k]), _mm512_mul_pd(syy, ny[k])));
        store_interleaved(fo + 16 * k, fx, fy);
    }
    if constexpr (kEnergy) {
        // tr C in the order of trace_right_cauchy_green (theory eq. 2.1)
        const __m512d trC = _mm512_add_pd(
            _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(Fxx, Fxx), _mm512_mul_pd(Fxy, Fxy)),
                          _mm512_mul_pd(Fyx, Fyx)),
            _mm512_mul_pd(Fyy, Fyy));
        _mm512_store_pd(trc, trC);
    }
    return J;
}

template <bool kEnergy, bool kViscous, bool kFirst>
FDEM_AVX512 void range(const Model& m, const Vec2* x, const Vec2* v, Vec2* f, TriId begin,
                       TriId end, Real lambda, Real mu, ElementPass& out) {
    const auto* tn = reinterpret_cast<const int32_t*>(m.tri_nodes.data());
    const auto* dmd = reinterpret_cast<const double*>(m.tri_dm_inv.data());
    const Real* area0 = m.tri_area0.data();
    const Real* eta = m.tri_eta.data();
    const auto* vd = reinterpret_cast<const double*>(v);
    const auto* xd = reinterpret_cast<const double*>(x);
    auto* fd = reinterpret_cast<double*>(f);
    static_assert(sizeof(m.tri_nodes[0]) == 3 * sizeof(int32_t) &&
                  sizeof(Mat2) == 4 * sizeof(Real));
    static_assert(sizeof(Vec2) == 2 * sizeof(double));

    // the strain energy is summed per block of kBlock triangles after their forces: first all
    // their logs (a call clobbers every vector register, so calls between vector groups cost
    // reloads, and a running sum across calls would live on the stack), then the sum in
    // triangle order, as the portable kernel
    constexpr int kBlock = 256;
    static_assert(kBlock % kLanes == 0);
    const Consts c{_mm512_set1_pd(mu), _mm512_set1_pd(0.5 * lambda), _mm512_set1_pd(1.0),
                   _mm512_set1_pd(0.5)};
    alignas(64) double fo[3 * 2 * kLanes];
    alignas(64) double jac[kEnergy ? kBlock : kLanes], trc[kEnergy ? kBlock : kLanes];
    alignas(64) double lnj[kEnergy ? kBlock : 1], wa[kEnergy ? kBlock : 1];
    alignas(64) int32_t pad_q[3 * kLanes];
    alignas(64) double pad_dm[4 * kLanes];
    alignas(64) double pad_eta[kLanes], pad_area[kLanes], pw[kLanes];
    Real energy = 0, power = 0;
    Real min_j = out.min_jacobian;
    TriId min_t = out.min_jacobian_tri;

    for (TriId b0 = begin; b0 < end; b0 += kBlock) {
        const TriId b1 = std::min<TriId>(end, b0 + kBlock);
        for (TriId t0 = b0; t0 < b1; t0 += kLanes) {
            const int n = static_cast<int>(std::min<TriId>(kLanes, b1 - t0));
            const int32_t* q = tn + 3 * static_cast<ptrdiff_t>(t0);
            const double* dm = dmd + 4 * static_cast<ptrdiff_t>(t0);
            ViscousIn vi{vd, eta + t0, area0 + t0};
            if (n < kLanes) {
                pad_group<kViscous>(n, t0, eta, area0, q, dm, vi, pad_q, pad_dm, pad_eta, pad_area);
            }
            double* jg = kEnergy ? jac + (t0 - b0) : jac;
            const __m512d J =
                group<kEnergy, kViscous>(xd, q, dm, c, vi, fo, kEnergy ? trc + (t0 - b0) : trc, pw);
            _mm512_store_pd(jg, J);
            const __mmask8 positive = _mm512_cmp_pd_mask(J, _mm512_setzero_pd(), _CMP_GT_OQ);
            if (n == kLanes && positive == 0xff) {
                // no inverted triangle: the first lane holding the group's smallest J is the one
                // the triangle-order scan with a strict < would keep
                const double gmin = _mm512_reduce_min_pd(J);
                if (gmin < min_j) {
                    const __mmask8 at = _mm512_cmp_pd_mask(J, _mm512_set1_pd(gmin), _CMP_EQ_OQ);
                    min_j = gmin;
                    min_t = t0 + std::countr_zero(static_cast<unsigned>(at));
                }
                commit_group<kViscous, kFirst>(fd, q, fo, eta, t0, pw, power);
                continue;
            }
            commit_checked<kViscous, kFirst>(n, fd, q, fo, jg, eta, t0, pw, power, min_j, min_t);
        }
        if constexpr (kEnergy) {
            const int nb = static_cast<int>(b1 - b0);
            for (int i = 0; i < nb; ++i)
                lnj[i] = jac[i] > 0 ? std::log(jac[i]) : 0.0;
            // A0 W, W = (mu/2)(tr C - 2 - 2 ln J) + (lambda/4)(J^2 - 1 - 2 ln J) (theory eq. 2.1):
            // strain_energy_density(lambda, mu, J, trC, lnJ) operation by operation, 8 at a time
            const __m512d hmu = _mm512_set1_pd(0.5 * mu), qlambda = _mm512_set1_pd(0.25 * lambda);
            const __m512d two = _mm512_set1_pd(2.0);
            for (int i = 0; i < nb; i += kLanes) {
                const __mmask8 in = static_cast<__mmask8>((1u << std::min(kLanes, nb - i)) - 1);
                const __m512d J = _mm512_maskz_load_pd(in, jac + i);
                const __m512d T = _mm512_maskz_load_pd(in, trc + i);
                const __m512d L2 = _mm512_mul_pd(two, _mm512_maskz_load_pd(in, lnj + i));
                const __m512d W = _mm512_add_pd(
                    _mm512_mul_pd(hmu, _mm512_sub_pd(_mm512_sub_pd(T, two), L2)),
                    _mm512_mul_pd(qlambda,
                                  _mm512_sub_pd(_mm512_sub_pd(_mm512_mul_pd(J, J), c.one), L2)));
                _mm512_store_pd(wa + i,
                                _mm512_mul_pd(_mm512_maskz_loadu_pd(in, area0 + b0 + i), W));
            }
            for (int i = 0; i < nb; ++i) {  // in triangle order; inverted triangles have none
                if (jac[i] > 0) energy += wa[i];
            }
        }
    }
    if constexpr (kEnergy) out.strain_energy += energy;
    if constexpr (kViscous) {
        out.viscous_power += power;  // summed with or without the energy, as element_range
    } else if constexpr (kEnergy) {
        out.viscous_power += 0.0;  // as element_range<false, true>
    }
    out.min_jacobian = min_j;
    out.min_jacobian_tri = min_t;
}

// ---------------------------------------------------------------------------------------------
// The same kernel for CPUs with AVX2 but without AVX-512 (AMD Zen 1-3, many desktop Intel CPUs):
// 8 triangles per group as two 4-wide halves (V8 below), the same expressions in the same order
// (no FMA: the target adds none and the build has -ffp-contract=off), so the same bits as the
// portable kernel and the AVX-512 one. Only the data movement differs: corners and Dm^-1 are
// de-interleaved per half by unpacks and 128-bit lane permutes, masks are vectors (blends).

#define FDEM_AVX2 __attribute__((target("avx2")))

// 8 lanes as two __m256d: lanes 0-3 in lo, 4-7 in hi
struct V8 {
    __m256d lo, hi;
};

FDEM_AVX2 inline V8 operator+(V8 a, V8 b) {
    return {_mm256_add_pd(a.lo, b.lo), _mm256_add_pd(a.hi, b.hi)};
}
FDEM_AVX2 inline V8 operator-(V8 a, V8 b) {
    return {_mm256_sub_pd(a.lo, b.lo), _mm256_sub_pd(a.hi, b.hi)};
}
FDEM_AVX2 inline V8 operator*(V8 a, V8 b) {
    return {_mm256_mul_pd(a.lo, b.lo), _mm256_mul_pd(a.hi, b.hi)};
}
FDEM_AVX2 inline V8 operator/(V8 a, V8 b) {
    return {_mm256_div_pd(a.lo, b.lo), _mm256_div_pd(a.hi, b.hi)};
}
FDEM_AVX2 inline V8 splat(double a) {
    return {_mm256_set1_pd(a), _mm256_set1_pd(a)};
}
// -a: the sign bit flipped, as the portable unary minus
FDEM_AVX2 inline V8 negate(V8 a) {
    const __m256d s = _mm256_set1_pd(-0.0);
    return {_mm256_xor_pd(a.lo, s), _mm256_xor_pd(a.hi, s)};
}
FDEM_AVX2 inline V8 load8(const double* p) {
    return {_mm256_loadu_pd(p), _mm256_loadu_pd(p + 4)};
}
FDEM_AVX2 inline void store8(double* p, V8 a) {
    _mm256_store_pd(p, a.lo);
    _mm256_store_pd(p + 4, a.hi);
}
// b in the lanes of the masks (mlo, mhi: all bits set), a elsewhere
FDEM_AVX2 inline V8 blend8(V8 a, V8 b, __m256d mlo, __m256d mhi) {
    return {_mm256_blendv_pd(a.lo, b.lo, mlo), _mm256_blendv_pd(a.hi, b.hi, mhi)};
}
// lanes where a > 0 (ordered: NaN is not), as a bit mask of 8
FDEM_AVX2 inline unsigned positive_mask(V8 a) {
    const __m256d z = _mm256_setzero_pd();
    return static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(a.lo, z, _CMP_GT_OQ))) |
           (static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(a.hi, z, _CMP_GT_OQ))) << 4);
}

// x and y of corner k of triangles 4h .. 4h + 3 (node ids q[3 i + k]): a = (p0, p2), b = (p1, p3)
// as Vec2 pairs, so the unpacks give x and y in lane order
FDEM_AVX2 inline void load_corner_half(const double* xd, const int32_t* q, int k, int h, __m256d& X,
                                       __m256d& Y) {
    const auto at = [&](int i) {
        return _mm_loadu_pd(xd + 2 * static_cast<ptrdiff_t>(q[3 * (4 * h + i) + k]));
    };
    const __m256d a = _mm256_insertf128_pd(_mm256_castpd128_pd256(at(0)), at(2), 1);
    const __m256d b = _mm256_insertf128_pd(_mm256_castpd128_pd256(at(1)), at(3), 1);
    X = _mm256_unpacklo_pd(a, b);
    Y = _mm256_unpackhi_pd(a, b);
}

FDEM_AVX2 inline void load_corner_avx2(const double* xd, const int32_t* q, int k, V8& X, V8& Y) {
    load_corner_half(xd, q, k, 0, X.lo, Y.lo);
    load_corner_half(xd, q, k, 1, X.hi, Y.hi);
}

// Dm^-1 of triangles 4h .. 4h + 3 (rows xx xy yx yy at dm + 16 h): a 4 x 4 transpose
FDEM_AVX2 inline void load_dm_half(const double* dm, int h, __m256d& xx, __m256d& xy, __m256d& yx,
                                   __m256d& yy) {
    const double* p = dm + 16 * h;
    const __m256d r0 = _mm256_loadu_pd(p), r1 = _mm256_loadu_pd(p + 4);
    const __m256d r2 = _mm256_loadu_pd(p + 8), r3 = _mm256_loadu_pd(p + 12);
    const __m256d t0 = _mm256_unpacklo_pd(r0, r1);  // xx0 xx1 yx0 yx1
    const __m256d t1 = _mm256_unpackhi_pd(r0, r1);  // xy0 xy1 yy0 yy1
    const __m256d t2 = _mm256_unpacklo_pd(r2, r3);  // xx2 xx3 yx2 yx3
    const __m256d t3 = _mm256_unpackhi_pd(r2, r3);  // xy2 xy3 yy2 yy3
    xx = _mm256_permute2f128_pd(t0, t2, 0x20);
    yx = _mm256_permute2f128_pd(t0, t2, 0x31);
    xy = _mm256_permute2f128_pd(t1, t3, 0x20);
    yy = _mm256_permute2f128_pd(t1, t3, 0x31);
}

// the 8 Vec2 (fx[i], fy[i]) interleaved at out[0..15]
FDEM_AVX2 inline void store_interleaved_avx2(double* out, V8 fx, V8 fy) {
    const __m256d a = _mm256_unpacklo_pd(fx.lo, fy.lo), b = _mm256_unpackhi_pd(fx.lo, fy.lo);
    const __m256d c = _mm256_unpacklo_pd(fx.hi, fy.hi), d = _mm256_unpackhi_pd(fx.hi, fy.hi);
    _mm256_store_pd(out, _mm256_permute2f128_pd(a, b, 0x20));
    _mm256_store_pd(out + 4, _mm256_permute2f128_pd(a, b, 0x31));
    _mm256_store_pd(out + 8, _mm256_permute2f128_pd(c, d, 0x20));
    _mm256_store_pd(out + 12, _mm256_permute2f128_pd(c, d, 0x31));
}

// group() with V8: the same expressions, operation by operation
template <bool kEnergy, bool kViscous>
FDEM_AVX2 inline V8 group_avx2(const double* xd, const int32_t* q, const double* dm, double mu,
                               double half_lambda, const ViscousIn& vi, double* fo, double* trc,
                               double* pw) {
    const V8 one = splat(1.0), half = splat(0.5);
    V8 xa, ya, xb, yb, xc, yc;
    load_corner_avx2(xd, q, 0, xa, ya);
    load_corner_avx2(xd, q, 1, xb, yb);
    load_corner_avx2(xd, q, 2, xc, yc);
    V8 dxx, dxy, dyx, dyy;
    load_dm_half(dm, 0, dxx.lo, dxy.lo, dyx.lo, dyy.lo);
    load_dm_half(dm, 1, dxx.hi, dxy.hi, dyx.hi, dyy.hi);

    // F = Ds Dm^-1, Ds = [xb - xa, xc - xa] (theory eq. 3.1); as Mat2 operator*
    const V8 e1x = xb - xa, e1y = yb - ya;
    const V8 e2x = xc - xa, e2y = yc - ya;
    const V8 Fxx = e1x * dxx + e2x * dyx;
    const V8 Fxy = e1x * dxy + e2x * dyy;
    const V8 Fyx = e1y * dxx + e2y * dyx;
    const V8 Fyy = e1y * dxy + e2y * dyy;
    const V8 J = Fxx * Fyy - Fxy * Fyx;

    // sigma = (mu/J)(B - I) + (lambda/2)(J - 1/J) I, B = F F^T (theory eq. 2.2, cauchy_stress)
    const V8 Bxx = Fxx * Fxx + Fxy * Fxy;
    const V8 Bxy = Fxx * Fyx + Fxy * Fyy;
    const V8 Byy = Fyx * Fyx + Fyy * Fyy;
    const V8 a = splat(mu) / J;
    const V8 p = splat(half_lambda) * (J - one / J);
    V8 sxx = a * (Bxx - one) + p;
    V8 sxy = a * Bxy;
    V8 syy = a * (Byy - one) + p;

    if constexpr (kViscous) {
        // viscous stress eta D (theory eq. 2.4), as the AVX-512 group
        V8 vxa, vya, vxb, vyb, vxc, vyc;
        load_corner_avx2(vi.vd, q, 0, vxa, vya);
        load_corner_avx2(vi.vd, q, 1, vxb, vyb);
        load_corner_avx2(vi.vd, q, 2, vxc, vyc);
        const V8 inv = one / (e1x * e2y - e2x * e1y);
        const V8 ixx = e2y * inv, ixy = negate(e2x) * inv;
        const V8 iyx = negate(e1y) * inv, iyy = e1x * inv;
        const V8 ubx = vxb - vxa, uby = vyb - vya;
        const V8 ucx = vxc - vxa, ucy = vyc - vya;
        const V8 Lxx = ubx * ixx + ucx * iyx;
        const V8 Lxy = ubx * ixy + ucx * iyy;
        const V8 Lyx = uby * ixx + ucy * iyx;
        const V8 Lyy = uby * ixy + ucy * iyy;
        const V8 Dxy = half * (Lxy + Lyx);
        // sigma + eta D only in the lanes with eta > 0 (the portable branch)
        const V8 eta = load8(vi.eta);
        const __m256d z = _mm256_setzero_pd();
        const __m256d vlo = _mm256_cmp_pd(eta.lo, z, _CMP_GT_OQ);
        const __m256d vhi = _mm256_cmp_pd(eta.hi, z, _CMP_GT_OQ);
        sxx = blend8(sxx, sxx + eta * Lxx, vlo, vhi);
        sxy = blend8(sxy, sxy + eta * Dxy, vlo, vhi);
        syy = blend8(syy, syy + eta * Lyy, vlo, vhi);
        // J A0 eta ddot(D, D), ddot summed xx, xy, yx, yy (math.hpp)
        const V8 dd = ((Lxx * Lxx + Dxy * Dxy) + Dxy * Dxy) + Lyy * Lyy;
        store8(pw, ((J * load8(vi.area0)) * eta) * dd);
    }

    // f_i = 1/2 sigma n_i, n_i the scaled outward normal of the edge opposite i (theory eq. 3.3)
    const V8 nx[3] = {yc - yb, ya - yc, yb - ya};
    const V8 ny[3] = {xb - xc, xc - xa, xa - xb};
    for (int k = 0; k < 3; ++k) {
        const V8 fx = half * (sxx * nx[k] + sxy * ny[k]);
        const V8 fy = half * (sxy * nx[k] + syy * ny[k]);
        store_interleaved_avx2(fo + 16 * k, fx, fy);
    }
    if constexpr (kEnergy) {
        // tr C in the order of trace_right_cauchy_green (theory eq. 2.1)
        store8(trc, ((Fxx * Fxx + Fxy * Fxy) + Fyx * Fyx) + Fyy * Fyy);
    }
    return J;
}

// range() with group_avx2: the same blocks, scatter, smallest-J rule and energy sums
template <bool kEnergy, bool kViscous, bool kFirst>
FDEM_AVX2 void range_avx2(const Model& m, const Vec2* x, const Vec2* v, Vec2* f, TriId begin,
                          TriId end, Real lambda, Real mu, ElementPass& out) {
    const auto* tn = reinterpret_cast<const int32_t*>(m.tri_nodes.data());
    const auto* dmd = reinterpret_cast<const double*>(m.tri_dm_inv.data());
    const Real* area0 = m.tri_area0.data();
    const Real* eta = m.tri_eta.data();
    const auto* vd = reinterpret_cast<const double*>(v);
    const auto* xd = reinterpret_cast<const double*>(x);
    auto* fd = reinterpret_cast<double*>(f);

    constexpr int kBlock = 256;
    alignas(64) double fo[3 * 2 * kLanes];
    alignas(64) double jac[kEnergy ? kBlock : kLanes], trc[kEnergy ? kBlock : kLanes];
    alignas(64) double wa[kEnergy ? kBlock : 1];
    alignas(64) int32_t pad_q[3 * kLanes];
    alignas(64) double pad_dm[4 * kLanes];
    alignas(64) double pad_eta[kLanes], pad_area[kLanes], pw[kLanes];
    Real energy = 0, power = 0;
    Real min_j = out.min_jacobian;
    TriId min_t = out.min_jacobian_tri;

    for (TriId b0 = begin; b0 < end; b0 += kBlock) {
        const TriId b1 = std::min<TriId>(end, b0 + kBlock);
        for (TriId t0 = b0; t0 < b1; t0 += kLanes) {
            const int n = static_cast<int>(std::min<TriId>(kLanes, b1 - t0));
            const int32_t* q = tn + 3 * static_cast<ptrdiff_t>(t0);
            const double* dm = dmd + 4 * static_cast<ptrdiff_t>(t0);
            ViscousIn vi{vd, eta + t0, area0 + t0};
            if (n < kLanes) {
                pad_group<kViscous>(n, t0, eta, area0, q, dm, vi, pad_q, pad_dm, pad_eta, pad_area);
            }
            double* jg = kEnergy ? jac + (t0 - b0) : jac;
            const V8 J = group_avx2<kEnergy, kViscous>(xd, q, dm, mu, 0.5 * lambda, vi, fo,
                                                       kEnergy ? trc + (t0 - b0) : trc, pw);
            store8(jg, J);
            if (n == kLanes && positive_mask(J) == 0xffu) {
                // no inverted triangle: the first lane holding the group's smallest J is the one
                // the triangle-order scan with a strict < would keep (min is exact: any order)
                double gmin = jg[0];
                for (int i = 1; i < kLanes; ++i)
                    gmin = jg[i] < gmin ? jg[i] : gmin;
                if (gmin < min_j) {
                    int first = 0;
                    while (jg[first] != gmin)
                        ++first;
                    min_j = gmin;
                    min_t = t0 + first;
                }
                commit_group<kViscous, kFirst>(fd, q, fo, eta, t0, pw, power);
                continue;
            }
            commit_checked<kViscous, kFirst>(n, fd, q, fo, jg, eta, t0, pw, power, min_j, min_t);
        }
        if constexpr (kEnergy) {
            // A0 W, W = (mu/2)(tr C - 2 - 2 ln J) + (lambda/4)(J^2 - 1 - 2 ln J) (theory eq. 2.1):
            // strain_energy_density operation by operation, as the AVX-512 kernel
            const int nb = static_cast<int>(b1 - b0);
            const Real hmu = 0.5 * mu, qlambda = 0.25 * lambda;
            for (int i = 0; i < nb; ++i) {
                const Real J = jac[i];
                const Real L2 = 2.0 * (J > 0 ? std::log(J) : 0.0);
                wa[i] =
                    area0[b0 + i] * (hmu * ((trc[i] - 2.0) - L2) + qlambda * ((J * J - 1.0) - L2));
            }
            for (int i = 0; i < nb; ++i) {  // in triangle order; inverted triangles have none
                if (jac[i] > 0) energy += wa[i];
            }
        }
    }
    if constexpr (kEnergy) out.strain_energy += energy;
    if constexpr (kViscous) {
        out.viscous_power += power;  // summed with or without the energy, as element_range
    } else if constexpr (kEnergy) {
        out.viscous_power += 0.0;  // as element_range<false, true>
    }
    out.min_jacobian = min_j;
    out.min_jacobian_tri = min_t;
}

// fn.template operator()<kEnergy, kViscous, kFirst>() for the run-time flags
template <class Fn>
void with_range_flags(bool viscous, bool with_energy, bool first, Fn&& fn) {
    const auto rest = [&]<bool kFirst>() {
        if (viscous && with_energy) {
            fn.template operator()<true, true, kFirst>();
        } else if (viscous) {
            fn.template operator()<false, true, kFirst>();
        } else if (with_energy) {
            fn.template operator()<true, false, kFirst>();
        } else {
            fn.template operator()<false, false, kFirst>();
        }
    };
    if (first) {
        rest.template operator()<true>();
    } else {
        rest.template operator()<false>();
    }
}

}  // namespace

void cst_range_avx512(const Model& m, const Vec2* x, const Vec2* v, Vec2* f, TriId begin, TriId end,
                      Real lambda, Real mu, bool viscous, bool with_energy, ElementPass& out,
                      bool first) {
    with_range_flags(viscous, with_energy, first, [&]<bool kEnergy, bool kViscous, bool kFirst>() {
        range<kEnergy, kViscous, kFirst>(m, x, v, f, begin, end, lambda, mu, out);
    });
}

void cst_range_avx2(const Model& m, const Vec2* x, const Vec2* v, Vec2* f, TriId begin, TriId end,
                    Real lambda, Real mu, bool viscous, bool with_energy, ElementPass& out,
                    bool first) {
    with_range_flags(viscous, with_energy, first, [&]<bool kEnergy, bool kViscous, bool kFirst>() {
        range_avx2<kEnergy, kViscous, kFirst>(m, x, v, f, begin, end, lambda, mu, out);
    });
}

}  // namespace fdem::detail
