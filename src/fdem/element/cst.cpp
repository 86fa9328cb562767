// Constant-strain triangle kernel (docs/theory.md §3). Reference: Munjiza 2004 §4.6, spec §3.1.
//
// Performance notes (docs/performance.md): the loop runs over chunks of contiguous triangles of
// one body, so the material constants are hoisted out of it and fixed bodies never enter it;
// the viscous branch is a template parameter decided per chunk. Chunks are colored so that a
// color's chunks share no node and can scatter their forces concurrently without atomics, in an
// order that does not depend on the thread count. On CPUs with AVX-512 or AVX2, the CST triangles
// (elastic and viscous) go to the kernels in element/cst_simd.cpp (8 triangles per group, bitwise
// the same results); other CPUs (and CstKernel::Portable) use the loops below.
#include "element/cst.hpp"

#include "fdem/exact_sum.hpp"

#include <omp.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "element/composite.hpp"
#include "element/cst_simd.hpp"
#include "material/hyperelastic.hpp"

namespace fdem {

namespace {

/// Triangles per chunk. Small enough that a 16k-triangle (cache-resident) mesh still gives two
/// threads enough chunks per color, large enough that the per-chunk overhead is negligible.
constexpr TriId kChunkTris = 256;
// chunks start at a body's first triangle and hold a multiple of 4 triangles (or the rest of
// the body), so they never split a composite element (model.hpp layout)
static_assert(kChunkTris % 4 == 0);

/// Below this many chunks (8192 triangles) the pass runs on one thread: a fork/join and one
/// barrier per color cost more than the work they would share.
constexpr int32_t kMinParallelChunks = 32;

/// Units (element_unit_chunks()): at most this many chunks each, and at least kMinUnits units
/// where there are enough chunks. Why (docs/performance.md "Stop 50"): run color after color,
/// one-chunk units make the pass jump through the triangle and node arrays every 256 triangles;
/// at 10^6 triangles that cost the pass 40-50 % against a pass in triangle order, and units of
/// 16 chunks (4 096 triangles, ~200 KB of triangle data streamed at a time) recover nearly all
/// of it while a 10^6-triangle model keeps ~40 units per color for the threads.
constexpr int32_t kMaxUnitChunks = 16;
constexpr int32_t kMinUnits = 256;

/// Partial sums stored per chunk in State::scratch_sums.
constexpr size_t kChunkSlots = 4;

/// Kernel of the elastic triangles (set_cst_kernel).
CstKernel g_kernel = CstKernel::Auto;

// Triangles [begin, end) of one body with Lame constants (lambda, mu). kViscous: some triangle
// of the range has eta > 0 (theory eq. 2.4); otherwise the viscous code is compiled out.
// kEnergy: sum the strain energy (one std::log per triangle); the forces do not depend on it.
// kFirst: the range is a chunk_first chunk: its nodes' forces are stored (add_triangle_forces),
// an inverted triangle's as zeros (what the clear would have left).
template <bool kViscous, bool kEnergy, bool kFirst = false>
void element_range(const Model& m, const Vec2* __restrict x, const Vec2* __restrict v,
                   Vec2* __restrict f, TriId begin, TriId end, Real lambda, Real mu,
                   ElementPass& out) {
    const auto* __restrict tri = m.tri_nodes.data();
    const Mat2* __restrict dm_inv = m.tri_dm_inv.data();
    const Real* __restrict area0 = m.tri_area0.data();
    const Real* __restrict eta = m.tri_eta.data();
    Real energy = 0, power = 0;
    Real min_j = out.min_jacobian;
    TriId min_t = out.min_jacobian_tri;

    for (TriId t = begin; t < end; ++t) {
        const auto [a, b, c] = tri[t];
        const Vec2 xa = x[a], xb = x[b], xc = x[c];

        // current edge matrix and deformation gradient (theory eq. 3.1)
        const Mat2 Ds = columns(xb - xa, xc - xa);
        const Mat2 F = Ds * dm_inv[t];
        const Real J = det(F);
        if (J < min_j) {
            min_j = J;
            min_t = t;
        }
        if (!(J > 0)) {  // inverted: reported by the caller, no force from a log of < 0
            if constexpr (kFirst) f[a] = f[b] = f[c] = Vec2{0, 0};
            continue;
        }

        // elastic Cauchy stress and strain energy (theory eqs. 2.1, 2.2)
        Mat2 sigma = cauchy_stress(lambda, mu, F);
        if constexpr (kEnergy) energy += area0[t] * strain_energy_density(lambda, mu, F);

        // viscous stress eta D, D = sym(L), L = [v1-v0, v2-v0] Ds^-1 (theory eq. 2.4)
        if constexpr (kViscous) {
            if (eta[t] > 0) {
                const Mat2 D = rate_of_deformation(v, a, b, c, Ds);
                sigma = sigma + eta[t] * D;
                power += J * area0[t] * eta[t] * ddot(D, D);
            }
        }

        // nodal forces f_i = 1/2 sigma n_i (theory eq. 3.3)
        add_triangle_forces<kFirst>(f, a, b, c, xa, xb, xc, sigma);
    }
    out.strain_energy += energy;
    out.viscous_power += power;
    out.min_jacobian = min_j;
    out.min_jacobian_tri = min_t;
}

// Elastic (non-viscous) triangles [begin, end) without the strain energy, in blocks of kBlock
// (docs/performance.md): (1) gather the corner positions into local arrays, (2) F, J, sigma and
// the three nodal forces of every triangle of the block in a loop without indirection or
// branches, which the compiler vectorises (two triangles per SSE2 instruction), (3) in triangle
// order: smallest J and the scatter of the forces. Every value is the same expression as in
// element_range (same helpers, same order of operations, -ffp-contract=off), so the forces are
// bitwise those of the scalar loop; an inverted triangle (J <= 0) computes throw-away values in
// (2) and is skipped in (3) exactly as there. kFirst: as element_range.
template <bool kFirst = false>
void elastic_range(const Model& m, const Vec2* __restrict x, Vec2* __restrict f, TriId begin,
                   TriId end, Real lambda, Real mu, ElementPass& out) {
    constexpr int kBlock = 64;
    const auto* __restrict tri = m.tri_nodes.data();
    const Mat2* __restrict dm_inv = m.tri_dm_inv.data();
    alignas(64) Real ax[kBlock], ay[kBlock], bx[kBlock], by[kBlock], cx[kBlock], cy[kBlock];
    alignas(64) Real fax[kBlock], fay[kBlock], fbx[kBlock], fby[kBlock], fcx[kBlock], fcy[kBlock];
    alignas(64) Real jac[kBlock];
    Real min_j = out.min_jacobian;
    TriId min_t = out.min_jacobian_tri;

    for (TriId t0 = begin; t0 < end; t0 += kBlock) {
        const int n = static_cast<int>(std::min<TriId>(kBlock, end - t0));
        // (1) gather
        for (int i = 0; i < n; ++i) {
            const auto& q = tri[t0 + i];
            ax[i] = x[q[0]].x;
            ay[i] = x[q[0]].y;
            bx[i] = x[q[1]].x;
            by[i] = x[q[1]].y;
            cx[i] = x[q[2]].x;
            cy[i] = x[q[2]].y;
        }
        // (2) F (theory eq. 3.1), sigma (eq. 2.2), f_i = 1/2 sigma n_i (eq. 3.3)
        for (int i = 0; i < n; ++i) {
            const Vec2 xa = {ax[i], ay[i]}, xb = {bx[i], by[i]}, xc = {cx[i], cy[i]};
            const Mat2 F = columns(xb - xa, xc - xa) * dm_inv[t0 + i];
            const Mat2 sigma = cauchy_stress(lambda, mu, F);
            const Vec2 na = {xc.y - xb.y, xb.x - xc.x};
            const Vec2 nb = {xa.y - xc.y, xc.x - xa.x};
            const Vec2 nc = {xb.y - xa.y, xa.x - xb.x};
            const Vec2 fa = 0.5 * (sigma * na), fb = 0.5 * (sigma * nb), fc = 0.5 * (sigma * nc);
            fax[i] = fa.x;
            fay[i] = fa.y;
            fbx[i] = fb.x;
            fby[i] = fb.y;
            fcx[i] = fc.x;
            fcy[i] = fc.y;
            jac[i] = det(F);
        }
        // (3) in triangle order
        for (int i = 0; i < n; ++i) {
            const TriId t = t0 + i;
            const Real J = jac[i];
            if (J < min_j) {
                min_j = J;
                min_t = t;
            }
            const auto& q = tri[t];
            if (!(J > 0)) {  // inverted: reported by the caller, no force
                if constexpr (kFirst) f[q[0]] = f[q[1]] = f[q[2]] = Vec2{0, 0};
                continue;
            }
            if constexpr (kFirst) {  // 0 + f_i: the bits of a cleared f plus f_i
                f[q[0]] = Vec2{0, 0} + Vec2{fax[i], fay[i]};
                f[q[1]] = Vec2{0, 0} + Vec2{fbx[i], fby[i]};
                f[q[2]] = Vec2{0, 0} + Vec2{fcx[i], fcy[i]};
            } else {
                f[q[0]] += Vec2{fax[i], fay[i]};
                f[q[1]] += Vec2{fbx[i], fby[i]};
                f[q[2]] += Vec2{fcx[i], fcy[i]};
            }
        }
    }
    out.min_jacobian = min_j;
    out.min_jacobian_tri = min_t;
}

// the AVX2 kernel (element/cst_simd.cpp): Auto without AVX-512, or Avx2
bool use_avx2() {
    return (g_kernel == CstKernel::Auto && !detail::cst_avx512_supported() &&
            cst_avx2_available()) ||
           (g_kernel == CstKernel::Avx2 && cst_avx2_available());
}

// The portable loops for a range (kFirst: of a chunk_first chunk).
template <bool kFirst>
void portable_range(const Model& m, const Vec2* x, const Vec2* v, Vec2* f, TriId begin, TriId end,
                    const Material& mt, bool viscous, bool with_energy, ElementPass& out) {
    if (viscous && with_energy) {
        element_range<true, true, kFirst>(m, x, v, f, begin, end, mt.lambda, mt.mu, out);
    } else if (viscous) {
        element_range<true, false, kFirst>(m, x, v, f, begin, end, mt.lambda, mt.mu, out);
    } else if (with_energy) {
        // the blocked kernel measured no faster here: the std::log and the energy sum dominate
        element_range<false, true, kFirst>(m, x, v, f, begin, end, mt.lambda, mt.mu, out);
    } else {
        elastic_range<kFirst>(m, x, f, begin, end, mt.lambda, mt.mu, out);
    }
}

// Dispatch a range of triangles of one material on whether any of them is viscous. first: the
// range is a chunk_first chunk (its nodes' forces are stored, not added; CST only).
void material_range(const Model& m, const Vec2* x, const Vec2* v, Vec2* f, TriId begin, TriId end,
                    bool with_energy, ElementPass& out, bool first = false) {
    // composite bodies: selective-integration kernel (theory §3.5); chunks never mix kinds
    if (m.bodies[m.tri_body[begin]].element == ElementKind::Composite6) {
        add_composite_forces(m, x, v, f, begin, end, with_energy, out);
        return;
    }
    const Material& mt = m.materials[m.tri_material[begin]];
    // tri_eta = eta + 2 h xi sqrt(E rho) (theory eq. 2.6) is > 0 exactly when the material has a
    // viscosity or a damping ratio: decided per material, without reading tri_eta
    const bool viscous = mt.viscosity > 0 || mt.damping_ratio > 0;
    if (g_kernel == CstKernel::Auto && detail::cst_avx512_supported()) {
        // 8 triangles per instruction, bitwise the same forces, energy and viscous power
        // (element/cst_simd.cpp)
        detail::cst_range_avx512(m, x, v, f, begin, end, mt.lambda, mt.mu, viscous, with_energy,
                                 out, first);
    } else if (use_avx2()) {
        // the same with AVX2, 4 triangles per instruction (element/cst_simd.cpp)
        detail::cst_range_avx2(m, x, v, f, begin, end, mt.lambda, mt.mu, viscous, with_energy, out,
                               first);
    } else if (first) {
        portable_range<true>(m, x, v, f, begin, end, mt, viscous, with_energy, out);
    } else {
        portable_range<false>(m, x, v, f, begin, end, mt, viscous, with_energy, out);
    }
}

// The element units of each color c, [color_units[c], color_units[c+1]), one color after the
// other (implicit barrier at the end of each omp for); unit u is the entries [unit_begin[u],
// unit_begin[u + 1]), run in order by one thread; run_entry(i, x, v, f, with_energy, p) runs
// entry i (material_range() over its triangles) and it leaves its partials in the returned
// array at kChunkSlots * i (strain energy, viscous power, smallest det F, its triangle). The
// units of a color touch disjoint nodes, so their scatter needs no atomics; dynamic scheduling
// only changes which thread runs a unit, never the order in which a node is updated. Uses
// s.scratch_sums (sized on first use).
template <class RunEntry>
const Real* run_chunks(State& s, const int32_t* color_units, int32_t ncolors,
                       const int32_t* unit_begin, int32_t n, RunEntry run_entry) {
    if (s.scratch_sums.size() < kChunkSlots * static_cast<size_t>(n)) {
        s.scratch_sums.resize(kChunkSlots * static_cast<size_t>(n));  // first call only
    }
    Real* part = s.scratch_sums.data();
    const Vec2* x = s.x.data();
    const Vec2* v = s.v.data();
    Vec2* f = s.f.data();
    const bool with_energy = s.need_energy;
#pragma omp parallel if (n >= kMinParallelChunks)
    for (int32_t c = 0; c < ncolors; ++c) {
#pragma omp for schedule(dynamic, 1)
        for (int32_t u = color_units[c]; u < color_units[c + 1]; ++u) {
            for (int32_t i = unit_begin[u]; i < unit_begin[u + 1]; ++i) {
                ElementPass p;
                run_entry(i, x, v, f, with_energy, p);
                Real* slot = part + kChunkSlots * static_cast<size_t>(i);
                slot[0] = p.strain_energy;
                slot[1] = p.viscous_power;
                slot[2] = p.min_jacobian;
                slot[3] = static_cast<Real>(p.min_jacobian_tri);
            }
        }
    }
    return part;
}

}  // namespace

void set_cst_kernel(CstKernel k) {
    g_kernel = k;
}

const char* cst_kernel_name() {
    if (g_kernel == CstKernel::Auto && detail::cst_avx512_supported()) return "avx512";
    return use_avx2() ? "avx2" : "portable";
}

bool cst_avx2_available() {
    static const bool ok = __builtin_cpu_supports("avx2");
    return ok;
}

ElementPass add_internal_forces(const Model& m, const Vec2* x, const Vec2* v, Vec2* f, TriId begin,
                                TriId end) {
    ElementPass out;
    for (BodyId b = 0; b < m.num_bodies(); ++b) {
        const Body& body = m.bodies[b];
        TriId lo = std::max(begin, body.tri_begin);
        const TriId hi = std::min(end, body.tri_end);
        if (body.fixed) continue;
        // runs of one material (normally the whole body)
        while (lo < hi) {
            TriId run = lo + 1;
            while (run < hi && m.tri_material[run] == m.tri_material[lo])
                ++run;
            material_range(m, x, v, f, lo, run, true, out);
            lo = run;
        }
    }
    return out;
}

namespace {

// add_internal_forces(m, s) (first: first_internal_forces(m, s))
ElementPass schedule_pass(const Model& m, State& s, bool first) {
    const ElementSchedule& sc = m.element_schedule;
    const int32_t nc = sc.num_chunks();
    const int32_t ncolors = static_cast<int32_t>(sc.color_units.size()) - 1;
    const Real* part = run_chunks(
        s, sc.color_units.data(), ncolors, sc.unit_begin.data(), nc,
        [&](int32_t k, const Vec2* x, const Vec2* v, Vec2* f, bool with_energy, ElementPass& p) {
            material_range(m, x, v, f, sc.chunk_tris[k][0], sc.chunk_tris[k][1], with_energy, p,
                           first && sc.chunk_first[static_cast<size_t>(k)] != 0);
        });

    // the chunk partials combined exactly (theory §4.4): the same sums whatever the thread count
    // or grouping of the chunks; the smallest det F in chunk order (the first of equal ones)
    ElementPass out;
    ExactSum strain, viscous;
    for (int32_t k = 0; k < nc; ++k) {
        const Real* slot = part + kChunkSlots * static_cast<size_t>(k);
        strain.add(slot[0]);
        viscous.add(slot[1]);
        if (slot[2] < out.min_jacobian) {
            out.min_jacobian = slot[2];
            out.min_jacobian_tri = static_cast<TriId>(slot[3]);
        }
    }
    out.strain_energy = strain.value();
    out.viscous_power = viscous.value();
    return out;
}

}  // namespace

ElementPass add_internal_forces(const Model& m, State& s) {
    return schedule_pass(m, s, false);
}

ElementPass first_internal_forces(const Model& m, State& s) {
    return schedule_pass(m, s, true);
}

ElementSubset element_subset(const Model& m, const std::vector<int32_t>& node_owner, int32_t rank) {
    const ElementSchedule& sc = m.element_schedule;
    const int32_t ncolors = static_cast<int32_t>(sc.color_units.size()) - 1;
    ElementSubset out;
    out.color_units.push_back(0);
    out.unit_begin.push_back(0);
    out.run_begin.push_back(0);
    for (int32_t c = 0; c < ncolors; ++c) {
        for (int32_t u = sc.color_units[c]; u < sc.color_units[c + 1]; ++u) {
            for (int32_t k = sc.unit_begin[u]; k < sc.unit_begin[u + 1]; ++k) {
                const TriId b = sc.chunk_tris[k][0], e = sc.chunk_tris[k][1];
                const size_t first_run = out.runs.size();
                for (TriId t = b; t < e; ++t) {
                    bool mine = false;
                    for (NodeId n : m.tri_nodes[t])
                        mine = mine || node_owner[n] == rank;
                    if (!mine) continue;
                    if (out.runs.size() > first_run && out.runs.back()[1] == t) {
                        ++out.runs.back()[1];
                    } else {
                        out.runs.push_back({t, t + 1});
                    }
                }
                if (out.runs.size() == first_run) continue;  // no triangle of an owned node
                // a composite's sub-triangles are coupled by its pressure: the chunk whole
                if (m.bodies[m.tri_body[b]].element == ElementKind::Composite6) {
                    out.runs.resize(first_run);
                    out.runs.push_back({b, e});
                }
                out.chunks.push_back(k);
                out.counts_energy.push_back(node_owner[m.tri_nodes[b][0]] == rank ? 1 : 0);
                out.run_begin.push_back(static_cast<int32_t>(out.runs.size()));
            }
            // the unit's chunks that have triangles of owned nodes, run in order as in the serial
            // pass
            if (static_cast<int32_t>(out.chunks.size()) > out.unit_begin.back())
                out.unit_begin.push_back(static_cast<int32_t>(out.chunks.size()));
        }
        out.color_units.push_back(static_cast<int32_t>(out.unit_begin.size()) - 1);
    }
    return out;
}

ElementSubsetPass add_internal_forces(const Model& m, State& s, const ElementSubset& subset,
                                      bool viscous_power, bool first) {
    const ElementSchedule& sc = m.element_schedule;
    const int32_t nk = static_cast<int32_t>(subset.chunks.size());
    const int32_t ncolors = static_cast<int32_t>(subset.color_units.size()) - 1;
    // the counted chunks whole where their sums are read; otherwise the runs of a chunk in
    // triangle order (the fold of each owned node unchanged)
    const bool whole_counted = s.need_energy || viscous_power;
    const Real* part = run_chunks(
        s, subset.color_units.data(), ncolors, subset.unit_begin.data(), nk,
        [&](int32_t i, const Vec2* x, const Vec2* v, Vec2* f, bool with_energy, ElementPass& p) {
            const int32_t k = subset.chunks[static_cast<size_t>(i)];
            const bool store = first && sc.chunk_first[static_cast<size_t>(k)] != 0;
            if (whole_counted && subset.counts_energy[static_cast<size_t>(i)]) {
                material_range(m, x, v, f, sc.chunk_tris[k][0], sc.chunk_tris[k][1], with_energy, p,
                               store);
                return;
            }
            for (int32_t r = subset.run_begin[i]; r < subset.run_begin[i + 1]; ++r) {
                const auto& run = subset.runs[static_cast<size_t>(r)];
                material_range(m, x, v, f, run[0], run[1], with_energy, p, store);
            }
        });
    // the counted chunks' partials, exactly (theory §4.4); the smallest det F over every
    // triangle run, the first in (chunk, triangle) order: over the processes the serial one
    ElementSubsetPass out;
    for (int32_t i = 0; i < nk; ++i) {
        const Real* slot = part + kChunkSlots * static_cast<size_t>(i);
        if (subset.counts_energy[static_cast<size_t>(i)]) {
            out.strain_energy.add(slot[0]);
            out.viscous_power.add(slot[1]);
        }
        if (slot[2] < out.min_jacobian) {
            out.min_jacobian = slot[2];
            out.min_jacobian_tri = static_cast<TriId>(slot[3]);
            out.min_jacobian_chunk = subset.chunks[static_cast<size_t>(i)];
        }
    }
    return out;
}

ElementSchedule build_element_schedule(const Model& m) {
    // chunks: at most kChunkTris contiguous triangles of one material of one non-fixed body.
    // Runs of small bodies (fewer than kChunkTris triangles each, e.g. particles or blocks of a
    // granular pack) share a chunk when they are adjacent in triangle ids and of one material:
    // a chunk per 2-triangle body would make the pass mostly scheduling overhead. Every node
    // still receives its triangles' forces in triangle order within one chunk, so the forces
    // are the same bits as with one chunk per body.
    std::vector<std::array<TriId, 2>> chunks;
    std::vector<BodyId> chunk_body;
    bool open_small = false;  // the last chunk is a run of small bodies that may grow
    for (BodyId b = 0; b < m.num_bodies(); ++b) {
        const Body& body = m.bodies[b];
        if (body.fixed) {
            open_small = false;
            continue;
        }
        const TriId n = body.tri_end - body.tri_begin;
        if (n > 0 && n < kChunkTris &&
            std::all_of(m.tri_material.begin() + body.tri_begin,
                        m.tri_material.begin() + body.tri_end,
                        [&](int32_t mt) { return mt == m.tri_material[body.tri_begin]; })) {
            if (open_small && chunks.back()[1] == body.tri_begin &&
                chunks.back()[1] - chunks.back()[0] + n <= kChunkTris &&
                m.tri_material[chunks.back()[0]] == m.tri_material[body.tri_begin] &&
                m.bodies[chunk_body.back()].element == body.element) {
                chunks.back()[1] = body.tri_end;
            } else {
                chunks.push_back({body.tri_begin, body.tri_end});
                chunk_body.push_back(b);
                open_small = true;
            }
            continue;
        }
        open_small = false;
        TriId t = body.tri_begin;
        while (t < body.tri_end) {
            TriId e = t + 1;
            while (e < body.tri_end && e - t < kChunkTris &&
                   m.tri_material[e] == m.tri_material[t]) {
                ++e;
            }
            chunks.push_back({t, e});
            chunk_body.push_back(b);
            t = e;
        }
    }

    // units: runs of `per` consecutive chunks (element_unit_chunks), unit k / per of chunk k
    const size_t n_chunks = chunks.size();
    const int32_t per = element_unit_chunks(static_cast<int32_t>(n_chunks));
    const size_t n_units = (n_chunks + static_cast<size_t>(per) - 1) / static_cast<size_t>(per);
    const auto unit_chunks = [&](size_t u) {
        return std::pair{u * static_cast<size_t>(per),
                         std::min(n_chunks, (u + 1) * static_cast<size_t>(per))};
    };

    // greedy coloring in unit order: node_colors[n] holds a bit per color of the units already
    // colored that touch node n; a unit takes the lowest color none of its nodes has
    std::vector<int32_t> color(n_units, 0);
    std::vector<uint64_t> node_colors(static_cast<size_t>(m.num_nodes()), 0);
    int32_t ncolors = 0;
    bool overflow = false;
    for (size_t u = 0; u < n_units && !overflow; ++u) {
        // a unit's chunks may leave out fixed bodies' triangles between them: visit each chunk
        uint64_t used = 0;
        const auto [k0, k1] = unit_chunks(u);
        for (size_t k = k0; k < k1; ++k) {
            for (TriId t = chunks[k][0]; t < chunks[k][1]; ++t) {
                for (NodeId n : m.tri_nodes[t])
                    used |= node_colors[static_cast<size_t>(n)];
            }
        }
        if (used == ~uint64_t{0}) {
            overflow = true;  // more than 64 colors: never seen in 2-D meshes
            break;
        }
        const int c = std::countr_one(used);
        color[u] = c;
        ncolors = std::max(ncolors, c + 1);
        for (size_t k = k0; k < k1; ++k) {
            for (TriId t = chunks[k][0]; t < chunks[k][1]; ++t) {
                for (NodeId n : m.tri_nodes[t])
                    node_colors[static_cast<size_t>(n)] |= uint64_t{1} << c;
            }
        }
    }
    if (overflow) {
        // still correct and deterministic, only serial: one unit per color
        for (size_t u = 0; u < n_units; ++u)
            color[u] = static_cast<int32_t>(u);
        ncolors = static_cast<int32_t>(n_units);
    }

    // order the units by (color, unit index) (counting sort), each unit's chunks in order
    ElementSchedule sc;
    sc.color_units.assign(static_cast<size_t>(ncolors) + 1, 0);
    for (size_t u = 0; u < n_units; ++u)
        ++sc.color_units[static_cast<size_t>(color[u]) + 1];
    for (int32_t c = 0; c < ncolors; ++c)
        sc.color_units[c + 1] += sc.color_units[c];
    std::vector<int32_t> next(sc.color_units.begin(), sc.color_units.end() - 1);
    std::vector<size_t> unit_at(n_units);  // the unit in schedule position p
    for (size_t u = 0; u < n_units; ++u)
        unit_at[static_cast<size_t>(next[static_cast<size_t>(color[u])]++)] = u;
    sc.chunk_tris.reserve(n_chunks);
    sc.chunk_body.reserve(n_chunks);
    sc.unit_begin.push_back(0);
    for (size_t p = 0; p < n_units; ++p) {
        const auto [k0, k1] = unit_chunks(unit_at[p]);
        for (size_t k = k0; k < k1; ++k) {
            sc.chunk_tris.push_back(chunks[k]);
            sc.chunk_body.push_back(chunk_body[k]);
        }
        sc.unit_begin.push_back(static_cast<int32_t>(sc.chunk_tris.size()));
    }

    // first writers (first_internal_forces): chunks of CST triangles each of whose nodes is used
    // by that triangle alone (over every triangle of the model, fixed bodies' included); the
    // serial step clears every other node
    std::vector<uint8_t> uses(static_cast<size_t>(m.num_nodes()), 0);
    for (const auto& q : m.tri_nodes) {
        for (NodeId n : q)
            uses[static_cast<size_t>(n)] =
                static_cast<uint8_t>(std::min(2, uses[static_cast<size_t>(n)] + 1));
    }
    std::vector<uint8_t> written(static_cast<size_t>(m.num_nodes()), 0);
    sc.chunk_first.assign(n_chunks, 0);
    for (size_t k = 0; k < n_chunks; ++k) {
        const auto [b, e] = sc.chunk_tris[k];
        bool own = true;
        for (TriId t = b; t < e && own; ++t) {
            own = m.bodies[m.tri_body[t]].element == ElementKind::Cst;
            for (NodeId n : m.tri_nodes[t])
                own = own && uses[static_cast<size_t>(n)] == 1;
        }
        if (!own) continue;
        sc.chunk_first[k] = 1;
        for (TriId t = b; t < e; ++t) {
            for (NodeId n : m.tri_nodes[t])
                written[static_cast<size_t>(n)] = 1;
        }
    }
    for (NodeId n = 0; n < m.num_nodes(); ++n) {
        if (written[static_cast<size_t>(n)]) continue;
        if (!sc.clear_runs.empty() && sc.clear_runs.back()[1] == n) {
            ++sc.clear_runs.back()[1];
        } else {
            sc.clear_runs.push_back({n, n + 1});
        }
    }
    return sc;
}

int32_t element_unit_chunks(int32_t chunks) {
    int32_t per = 1;
    while (per < kMaxUnitChunks && chunks / (2 * per) >= kMinUnits)
        per *= 2;
    return per;
}

Real element_critical_dt(const Model& m, TriId t) {
    const auto& n = m.tri_nodes[t];
    const Vec2 p0 = m.node_x0[n[0]], p1 = m.node_x0[n[1]], p2 = m.node_x0[n[2]];
    const Real l01 = norm(p1 - p0), l12 = norm(p2 - p1), l20 = norm(p0 - p2);
    const Real lmax = std::max({l01, l12, l20});
    const Real h_min = 2.0 * m.tri_area0[t] / lmax;  // smallest altitude
    const Material& mt = m.materials[m.tri_material[t]];
    const Real cp = std::sqrt((mt.lambda + 2.0 * mt.mu) / mt.density);
    Real dt = h_min / cp;  // theory eq. 5.3: omega_max ~ 2 c_p / h_min, dt <= 2/omega_max
    // viscous damping lowers the limit: dt <= (2/omega)(sqrt(1+xi^2) - xi), theory eq. 5.4
    const Real eta = m.tri_eta[t];
    if (eta > 0) {
        const Real omega = 2.0 * cp / h_min;
        // damping ratio of the highest mode: xi = eta omega / (2 (lambda + 2 mu))
        const Real xi = eta * omega / (2.0 * (mt.lambda + 2.0 * mt.mu));
        dt *= std::sqrt(1.0 + xi * xi) - xi;
    }
    return dt;
}

}  // namespace fdem
