// Mutable contact data: broad-phase candidates, per-pair history and scratch buffers.
// Everything is sized by init_contact_state() and grows only (no allocation in a step after
// warm-up).
#pragma once

#include <cstdint>
#include <vector>

#include "fdem/candidates.hpp"
#include "fdem/exact_sum.hpp"
#include "fdem/math.hpp"

namespace fdem {

/// History of one (target node, contactor body) pair (spec §4.5-4, -6). Keyed by the body, not
/// the contactor element, so that crossing an element edge keeps the tangential spring.
struct PairHistory {
    Real s = 0;            ///< tangential spring elongation s (eq. 17) [m]
    Real d_max = 0;        ///< largest depth of this contact episode [m]
    Real d_prev = 0;       ///< depth at the previous step [m]
    Real stored = 0;       ///< stored energy of the pair at the previous step [J/m]
    Vec2 f_damp;           ///< damping force gamma v_r of the previous step, unscaled [N/m]
    Real depth_ratio = 0;  ///< d / largest nodal distance of the triangle, previous step [-]
    /// birth depth: the law sees d - d0 (theory eq. 9.25); d0 = d when a self pair (rule X) is
    /// born, then min(d0, d); 0 for pairs of two bodies [m]
    Real d0 = 0;
    int8_t unloading = 0;  ///< literal law: 1 while on the unloading branch
    /// contactor sub-triangle of the last evaluation, counted from the body's first
    /// (ContactTopology::body_sub_begin); -1 before the first. Bodies with fracture continue
    /// the law depth where it changes (theory eq. 9.27)
    int32_t sub = -1;
};

/// A pair's law depth d - d0 at x^n under the contact topology before this step's breaks
/// (theory eq. 9.26): what the rebuilt topology's pair continues from.
struct RebaseEntry {
    NodeId node = kNone;  ///< target node (id in the rebuilt topology)
    BodyId body = kNone;  ///< contactor body
    Real d_law = 0;       ///< d - d0 of the old topology at x^n [m]
    Real normal = 0;      ///< its normal potential scale k_n psi (released if the pair ends) [J/m]
};

/// One active contact (in contact at the last evaluation), sorted by (node, body).
struct ActiveContact {
    NodeId node = kNone;  ///< target node (real id)
    BodyId body = kNone;  ///< contactor body
    PairHistory h;
};

/// Narrow-phase result of one candidate pair in one step: scratch of add_contact_forces(), which
/// evaluates all pairs in parallel into this buffer and then applies them serially in pair
/// order (bitwise the same for any thread count). Meaningless between steps.
struct PairResult {
    int32_t hist = -1;      ///< index into ContactState::active of the pair's history, -1: new
    int32_t tri = -1;       ///< located contactor sub-triangle; -1: not in contact
    Real N[3] = {0, 0, 0};  ///< barycentric coordinates of the target in tri
    Vec2 f;                 ///< force on the target node [N/m]
    PairHistory h;          ///< history after this step
    Real stored = 0;        ///< stored energy of the pair [J/m]
    Real dissipated = 0;    ///< energy dissipated by the evaluation [J/m]
};

/// Axis-aligned box of a contactor body's sub-triangles at the current step, widened by a small
/// margin, for the exact early reject of the narrow phase (contact.cpp body_boxes()); an infinite
/// box (lo = -inf, hi = +inf) where the reject is not proven safe. Per-step scratch.
struct BodyBox {
    Vec2 lo, hi;
};

/// A candidate couple of mesh triangles of different bodies for baseline A (spec §1.2,
/// docs/theory.md §7.3), a < b, with the sliding distances of its 6 edges (friction history,
/// spec §1.2 step 9; kept while the couple stays a candidate, so it survives the edge leaving
/// and re-entering). Edge k of a is node k -> k+1 of a ([0..3)), then the edges of b ([3..6)).
struct LegacyCouple {
    TriId a = kNone, b = kNone;
    Real slide[6] = {0, 0, 0, 0, 0, 0};  ///< sliding distance per edge [m]
};

/// Mutable data of baseline A (contact/legacy_triangle.hpp): candidate couples (sorted by
/// (a, b)) and grid scratch. Grows only, so steps after warm-up do not allocate.
struct LegacyTriangleState {
    std::vector<LegacyCouple> couples;
    std::vector<LegacyCouple> next;  ///< scratch of the rebuild (history merge)
    Real skin_used = 0;              ///< accumulated 2 dt max|v| since the last rebuild [m]
    bool need_rebuild = true;
    int64_t rebuilds = 0;
    int32_t active = 0;  ///< couples with a nonzero force at the last evaluation

    // grid scratch (contents meaningless between steps)
    std::vector<Vec2> center;
    std::vector<Real> radius;
    std::vector<int32_t> cell;
    std::vector<int32_t> cell_start;
    std::vector<int32_t> cell_items;
    std::vector<int32_t> cursor;
    std::vector<TriId> query;

    /// per-couple forces of the last evaluation (6 nodes: a's then b's) and per-couple stored
    /// and dissipated energy; filled in parallel, scattered serially in couple order
    std::vector<Vec2> couple_force;
    std::vector<Real> couple_stored;
    std::vector<Real> couple_dissipated;
};

/// One share of the apply of the pairs in contact (add_contact_forces() step 3b with 2+ threads:
/// a segment of ContactApplyLists, or a thread's slice in a distributed run): its energies
/// (exact sums: any split gives the same bits) and diagnostics, combined in pair order
/// afterwards. Per-step scratch.
struct alignas(64) ContactApplyPart {
    ExactSum stored, dissipated;
    Real max_depth_ratio = 0;
    int64_t deep = 0, lost = 0;
    NodeId lost_node = kNone;
    BodyId lost_body = kNone;
    Real lost_depth_ratio = 0;
};

/// The apply of the pairs in contact with T >= 2 threads (add_contact_forces() step 3b): thread
/// u adds the forces of the real nodes [N u / T, N (u + 1) / T). Its share of the bookkeeping is
/// two segments of the candidates: those whose target lies in that range, and the edge targets
/// whose edge starts there (the candidates ascend by target, edge targets last), so most pairs
/// add their forces in the bookkeeping's own loop; a pair whose force span leaves its thread's
/// range is added by every other range it meets from that range's foreign list, walked in pair
/// order around the thread's own segments: every node receives its forces in pair order. A
/// function of the candidates and T, built by the first apply after a broad phase. Scratch, not
/// saved: threads = 0 (not built) wherever the candidates are written.
struct ContactApplyLists {
    int32_t threads = 0;                 ///< T the lists were built for; 0: not built
    std::vector<NodeId> range_lo;        ///< T + 1: thread u adds at [range_lo[u], range_lo[u + 1])
    std::vector<int32_t> first;          ///< 2 T + 1: the first candidate of each segment, then all
    std::vector<uint8_t> inside;         ///< per candidate: its forces stay in its thread's range
    std::vector<int32_t> foreign_begin;  ///< T + 1: range u's foreign list, CSR
    std::vector<int32_t> foreign;        ///< candidates (ascending per range)
    std::vector<int32_t> fill;           ///< T: the build's fill positions
};

struct ContactState {
    int32_t active_contacts = 0;  ///< pairs in contact after the last step

    // ---- penetration diagnostics (spec §4.6): the engine may warn or fail on them ---------
    int32_t deep_penetrations = 0;        ///< pairs this step with d / layer > deep_ratio_limit
    int32_t lost_inside = 0;              ///< pairs lost this step with the node inside the body
    NodeId lost_node = kNone;             ///< deepest of those target nodes this step
    BodyId lost_body = kNone;             ///< the body lost_node went into
    Real lost_depth_ratio = 0;            ///< d / layer of lost_node when it was last in contact
    Real max_depth_ratio = 0;             ///< largest d / layer this step [-]
    int64_t total_deep_penetrations = 0;  ///< running sums of the two counters above
    int64_t total_lost_inside = 0;
    Real max_depth_ratio_ever = 0;

    // ---- broad phase (detect/broad_phase.hpp): when to run it, and its output --
    int64_t rebuilds = 0;  ///< number of broad-phase runs
    Real skin_used = 0;    ///< accumulated 2 dt max|v| since the last rebuild [m]
    bool need_rebuild = true;
    Candidates cand;          ///< written by the broad phase, read by the narrow phase
    BroadPhaseScratch broad;  ///< the broad phase's grid scratch
    /// scratch of the narrow phase: the candidate pairs in contact (ascending within each of
    /// its fixed chunks of pairs, at the front of the chunk's range; pair_out holds their
    /// results at the same places)
    std::vector<int32_t> in_contact;

    // ---- pair history: ping-pong buffers, both sorted by (node, body) ----------------
    std::vector<ActiveContact> active;
    std::vector<ActiveContact> active_next;
    std::vector<PairResult> pair_out;  ///< as in_contact, scratch (see PairResult)
    /// scratch of the apply with 2+ threads: its shares of the bookkeeping (two per thread)
    std::vector<ContactApplyPart> apply_part;
    /// scratch of the apply with T >= 2 threads: the segments and foreign lists of the candidates
    ContactApplyLists apply_lists;
    /// energy continuity through a rebuild of the contact topology (theory eq. 9.26): written
    /// by rebuild_contact_topology() (probe of the old topology at x^n, sorted by (node, body)),
    /// read and cleared by the next add_contact_forces() of the same step; never saved
    std::vector<RebaseEntry> rebase;
    std::vector<uint8_t> rebase_body;  ///< per body: 1 if its topology was rebuilt this step
    bool rebase_pending = false;
    std::vector<BodyBox> body_box;  ///< per body, scratch of add_contact_forces()
    /// the contactor bodies of cand, ascending: the only boxes the narrow phase reads, so only
    /// theirs are computed (one-process runs; a distributed run lists its own pairs' in
    /// ContactShare::box_bodies). Scratch, not saved: box_list_valid (and apply_lists.threads)
    /// is cleared wherever cand is written (broad phase, checkpoint read, gather_candidates())
    std::vector<BodyId> box_bodies;
    std::vector<uint8_t> box_mark;  ///< per body, scratch of the list
    bool box_list_valid = false;
    /// With fc_sparse: every node whose f_contact may be non-zero is in fc_nodes (ascending,
    /// no repeats): the nodes the contact applies reached since step() last cleared f_contact.
    /// A step with few pairs in contact then clears f_contact, and bodies.csv sums it, at those
    /// nodes only (integrate/step.cpp step 2, measure/resultants.cpp). False: the next clear
    /// is of every node (after it, fc_sparse with an empty list). The list never grows beyond
    /// the capacity the first full clear reserves (num_real_nodes / kSparseContactForceRatio):
    /// an apply that would overflow it sets fc_sparse false instead. Scratch, not saved: every
    /// other writer of f_contact (checkpoint read, the all-gather of output steps, baseline A)
    /// sets fc_sparse false
    std::vector<NodeId> fc_nodes;
    /// per real node, 1 while it is in fc_nodes during an apply's listing (all 0 between
    /// calls): the listing keeps each node once before its sort. Scratch, sized with fc_nodes'
    /// capacity
    std::vector<uint8_t> fc_mark;
    bool fc_sparse = false;
    /// false: no body-box reject (every box infinite), for the tests that compare the narrow
    /// phase with and without it; not saved in checkpoints
    bool box_reject = true;

    // ---- kinematics of the virtual nodes this step --------------------------------------
    std::vector<Vec2> xv;  ///< positions [m]
    std::vector<Vec2> vv;  ///< velocities v^{n-1/2} [m/s]
    /// welded topology only (ContactTopology::welded()), per real node: the contactor position
    /// this step (eq. 6.23: the sector mean of a grouped copy, x itself of the other referenced
    /// nodes; entries the contactor geometry does not reference are meaningless). Sized once by
    /// init_contact_state(); empty without a weld. Scratch, not saved in checkpoints.
    std::vector<Vec2> xw;
    /// per contact node (contact id: real, then virtual), the contactor position this step: x
    /// (xw with a weld) of a real node, xv of a virtual one, for the contact nodes of the
    /// bodies the narrow phase evaluates as contactors (box_bodies); the other entries are
    /// meaningless. One load per vertex in the locate loop instead of a real-or-virtual branch
    /// (issue #16). Filled by add_contact_forces() before the narrow phase; scratch, not saved
    /// in checkpoints.
    std::vector<Vec2> xa;

    // ---- baseline A (ContactAlgorithm::LegacyTriangle): couples and their history -------
    LegacyTriangleState legacy;
};

}  // namespace fdem
