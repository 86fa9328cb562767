// Constant-strain triangle with finite strain (docs/theory.md §3, spec §3.1).
#pragma once

#include <array>

#include <limits>
#include <vector>

#include "fdem/exact_sum.hpp"
#include "fdem/model.hpp"
#include "fdem/state.hpp"

namespace fdem {

/// Result of one internal-force pass, reduced over all triangles.
struct ElementPass {
    Real strain_energy = 0;  ///< sum A0 W(F) at the current positions [J/m]
    Real viscous_power = 0;  ///< sum A eta D:D [W/m], >= 0
    Real min_jacobian = std::numeric_limits<Real>::infinity();  ///< smallest det F seen
    TriId min_jacobian_tri = kNone;
};

/// Add internal forces f_i = 1/2 sigma n_i (theory eq. 3.3) of triangles [begin, end) to f,
/// serially in triangle order. sigma includes the viscous part eta D (theory eq. 2.4) from
/// velocities v. Triangles of fixed bodies are skipped (they never move).
ElementPass add_internal_forces(const Model& m, const Vec2* x, const Vec2* v, Vec2* f, TriId begin,
                                TriId end);

/// Internal forces of every non-fixed triangle added to s.f (positions s.x, velocities s.v), in
/// parallel over m.element_schedule. Bitwise identical for every OpenMP thread count: each node
/// receives its triangles' forces in the schedule's fixed order, and the energies are summed per
/// chunk and then over chunks in chunk order (docs/performance.md). Uses s.scratch_sums (sized on
/// first use, so it allocates only once). The strain energy is summed only when s.need_energy
/// (otherwise 0); the forces are bitwise the same either way.
ElementPass add_internal_forces(const Model& m, State& s);

/// The element pass of the serial step: add_internal_forces(m, s), except that the chunks of
/// ElementSchedule::chunk_first store the forces of their nodes (0 + f_i, the bits of a cleared f
/// plus f_i) instead of adding them, so s.f need not be cleared there first: the caller zeros
/// only ElementSchedule::clear_runs (docs/performance.md "Stop 49"). Same forces, energies and
/// smallest det F as clearing every node and calling add_internal_forces(m, s).
ElementPass first_internal_forces(const Model& m, State& s);

/// A subset of the element schedule for one process of a distributed run (issue #15, spec
/// parallel-and-python.md D7.1 "owner computes"): every chunk that holds a triangle of a node the
/// process owns, in schedule order (so color by color), and which of them the process counts in
/// the energies and the smallest det F (each chunk exactly one process: the owner of its first
/// triangle's first node). Running these chunks adds to every owned node the forces of all its
/// triangles in the serial order, so an owned node's force is bitwise the serial one; forces on
/// the other nodes are partial and belong to their owners.
///
/// Within a chunk only the triangles of owned nodes are needed for the forces: `runs` lists them
/// as ranges of consecutive ids (a node's force is the fold of its triangles' forces in triangle
/// order, which skipping triangles without the node does not change). A chunk runs whole only
/// where its sums are needed: the chunks the process counts, on steps that evaluate the strain
/// energy or (viscous materials) the viscous power; and composite chunks always (the composite's
/// pressure couples its sub-triangles). The smallest det F is taken over every triangle a
/// process runs (each triangle is run by the owners of its nodes), keyed by (chunk, triangle).
struct ElementSubset {
    std::vector<int32_t> chunks;  ///< schedule chunk ids, ascending
    /// the entries of chunks by unit of the schedule (ElementSchedule::unit_begin): unit u of the
    /// subset is entries [unit_begin[u], unit_begin[u + 1]), its units of color c
    /// [color_units[c], color_units[c + 1])
    std::vector<int32_t> unit_begin;
    std::vector<int32_t> color_units;
    std::vector<uint8_t> counts_energy;  ///< per entry of chunks: 1 = this process sums it
    /// per entry of chunks: its runs [run_begin[i], run_begin[i + 1]) of `runs`
    std::vector<int32_t> run_begin;
    std::vector<std::array<TriId, 2>> runs;  ///< [first, end) triangles of owned nodes
};

/// The subset of `rank` for an assignment of every node to a process (node_owner[n] in
/// [0, processes)). Nodes of fixed bodies may have any owner (their bodies have no chunks).
ElementSubset element_subset(const Model& m, const std::vector<int32_t>& node_owner, int32_t rank);

/// What a process's subset pass reports: exact sums, so that adding those of all processes
/// (Comm::sum) and rounding gives the serial pass's bits (theory §4.4), and the smallest det F
/// with its chunk, the key that makes the minimum over processes the serial one (the first in
/// chunk order).
struct ElementSubsetPass {
    ExactSum strain_energy;  ///< over the counted chunks (0 without s.need_energy)
    ExactSum viscous_power;
    Real min_jacobian = std::numeric_limits<Real>::infinity();
    TriId min_jacobian_tri = kNone;
    int32_t min_jacobian_chunk = -1;
};

/// add_internal_forces(m, s) over the chunks of `subset` only: the same kernel, colors and
/// per-chunk partial sums; energies over the chunks it counts (whole when s.need_energy or
/// `viscous_power`), the smallest det F over the triangles it runs. first: as
/// first_internal_forces(), the chunk_first chunks store their nodes' forces (a distributed
/// step, whose StepPlan::clear_f leaves out the nodes of those chunks' runs).
ElementSubsetPass add_internal_forces(const Model& m, State& s, const ElementSubset& subset,
                                      bool viscous_power = true, bool first = false);

/// Cut the triangles of the non-fixed bodies into chunks, group consecutive chunks into units
/// (element_unit_chunks()) and color the units so that units of one color share no node
/// (greedy, in unit order). Depends only on the model, never on the thread count. Called by
/// finalize_model().
ElementSchedule build_element_schedule(const Model& m);

/// Chunks per unit of a schedule of `chunks` chunks: the largest power of two up to 16 that
/// leaves at least 256 units (1 below 512 chunks, 16 from 4096 chunks, about 10^6 triangles).
int32_t element_unit_chunks(int32_t chunks);

/// Kernel for the CST triangles (elastic and viscous): Auto = the AVX-512 kernel when the CPU has
/// it (element/cst_simd.cpp), else the AVX2 kernel when it has AVX2 (the same file), else the
/// portable loops (baseline SSE2); Portable = always the portable loops; Avx2 = the AVX2 kernel
/// even on a CPU with AVX-512 (when it has AVX2), so that tests reach it on every CPU. All give
/// bitwise the same forces, smallest J, strain energy and viscous power
/// (tests/unit/element/cst_simd_test.cpp). Process-wide; do not change it while a pass runs.
enum class CstKernel { Auto, Portable, Avx2 };
void set_cst_kernel(CstKernel k);

/// The kernel the next pass uses for CST triangles: "avx512", "avx2" or "portable".
const char* cst_kernel_name();

/// true when this build has the AVX2 loops and the CPU runs them.
bool cst_avx2_available();

/// Deformation gradient F = Ds Dm^-1 of triangle t (theory eq. 3.1).
inline Mat2 deformation_gradient(const Model& m, const Vec2* x, TriId t) {
    const auto& n = m.tri_nodes[t];
    return columns(x[n[1]] - x[n[0]], x[n[2]] - x[n[0]]) * m.tri_dm_inv[t];
}

/// Rate of deformation D = sym(L), L = [v_b - v_a, v_c - v_a] Ds^-1 of triangle (a, b, c) with
/// current edge matrix Ds (theory eqs. 3.2, 2.4); the viscous stress is eta D.
inline Mat2 rate_of_deformation(const Vec2* v, NodeId a, NodeId b, NodeId c, const Mat2& Ds) {
    const Mat2 L = columns(v[b] - v[a], v[c] - v[a]) * inverse(Ds);
    const Real dxy = 0.5 * (L.xy + L.yx);
    return {L.xx, dxy, dxy, L.yy};
}

/// Nodal forces f_i += 1/2 sigma n_i of triangle (a, b, c) at current positions (xa, xb, xc),
/// n_i the outward normal of the edge opposite node i scaled by its length (theory eq. 3.3).
/// kFirst: the triangle's nodes are its own (ElementSchedule::chunk_first), so their forces are
/// stored as 0 + f_i, the bits of a cleared f plus f_i, without reading f.
template <bool kFirst = false>
inline void add_triangle_forces(Vec2* __restrict f, NodeId a, NodeId b, NodeId c, Vec2 xa, Vec2 xb,
                                Vec2 xc, const Mat2& sigma) {
    const Vec2 na = {xc.y - xb.y, xb.x - xc.x};
    const Vec2 nb = {xa.y - xc.y, xc.x - xa.x};
    const Vec2 nc = {xb.y - xa.y, xa.x - xb.x};
    if constexpr (kFirst) {
        f[a] = Vec2{0, 0} + 0.5 * (sigma * na);
        f[b] = Vec2{0, 0} + 0.5 * (sigma * nb);
        f[c] = Vec2{0, 0} + 0.5 * (sigma * nc);
    } else {
        f[a] += 0.5 * (sigma * na);
        f[b] += 0.5 * (sigma * nb);
        f[c] += 0.5 * (sigma * nc);
    }
}

/// Critical time step of one triangle: smallest altitude / P-wave speed (theory eq. 5.3).
Real element_critical_dt(const Model& m, TriId t);

}  // namespace fdem
