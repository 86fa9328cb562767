// Broad phase of the triangle-to-node contact (spec §2.5, docs/theory.md §6.8): candidate
// (target boundary node, contactor sub-triangle) couples whose bounding objects are closer than
// the buffer b, on a uniform grid filled by counting sort (linear time, NBS-like).
#pragma once

#include "fdem/candidates.hpp"
#include "fdem/contact_topology.hpp"
#include "fdem/model.hpp"

namespace fdem {

/// Inner loop of find_candidates: Auto = AVX-512 when the CPU has it, else portable; Scalar =
/// always the portable loop (tests compare the two).
enum class BroadKernel { Auto, Scalar };

/// The circle scan find_candidates runs with BroadKernel::Auto: "avx512" or "portable" (printed
/// by `fdem run`).
const char* broad_scan_kernel_name();

/// Rebuild the candidate list out of topology ct from current positions: x = real node positions,
/// xv = virtual node positions (ContactState::xv). A couple (node j, sub-triangle tau) is accepted
/// when is_contactor_for(body(tau), body(j)) and |x_j - c_tau| < r_tau + b, with c_tau the centroid
/// and r_tau the largest centroid-vertex distance. Output is sorted by (node, body, tri) and does
/// not depend on threading. Writes only out and its own grid scratch g (both grow only); the
/// caller (contact/contact.cpp) decides when to run it and owns both.
void find_candidates(const Model& m, const ContactTopology& ct, const Vec2* x, const Vec2* xv,
                     Candidates& out, BroadPhaseScratch& g, BroadKernel kernel = BroadKernel::Auto);

/// The same with the contactors' real vertices at xc and the targets at x: a welded topology
/// (docs/theory.md §6.15, eq. 6.23) evaluates its sub-triangles on the sectors' mean positions
/// (ContactState::xw), so the bounding circles are taken there, the positions the narrow phase
/// locates in. xc = x gives the form above.
void find_candidates(const Model& m, const ContactTopology& ct, const Vec2* x, const Vec2* xc,
                     const Vec2* xv, Candidates& out, BroadPhaseScratch& g,
                     BroadKernel kernel = BroadKernel::Auto);

/// The targets of one process of a distributed run (spec D5.3: a pair belongs to the owner of
/// its target node; an edge target's node is its first end node, target_node()): target j is
/// queried when owner[target_node(ct, j)] == rank. owner = nullptr: every target.
struct TargetOwner {
    const int32_t* owner = nullptr;
    int32_t rank = 0;
};

/// find_candidates for the targets own selects only: the subsequence of the full list made of
/// those targets' pairs (each target's pairs depend on the positions only, never on the other
/// targets), so a process's pairs are the serial ones. The grid is still built over every
/// sub-triangle (they need current positions: the caller gathers x first).
void find_candidates(const Model& m, const ContactTopology& ct, const Vec2* x, const Vec2* xc,
                     const Vec2* xv, Candidates& out, BroadPhaseScratch& g, TargetOwner own,
                     BroadKernel kernel = BroadKernel::Auto);

/// O(N_nodes * N_tris) reference implementation of find_candidates (tests, T11).
void find_candidates_brute_force(const Model& m, const ContactTopology& ct, const Vec2* x,
                                 const Vec2* xv, Candidates& out, BroadPhaseScratch& g);
/// ... with contactor vertices at xc (as find_candidates above).
void find_candidates_brute_force(const Model& m, const ContactTopology& ct, const Vec2* x,
                                 const Vec2* xc, const Vec2* xv, Candidates& out,
                                 BroadPhaseScratch& g);

}  // namespace fdem
