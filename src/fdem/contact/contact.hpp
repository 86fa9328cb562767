// Contact entry points called by the step pipeline and by finalize_model().
#pragma once

#include <algorithm>
#include <span>
#include <type_traits>
#include <utility>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "fdem/model.hpp"
#include "fdem/state.hpp"
#include "parallel/comm.hpp"

namespace fdem {

/// Resolve the contact parameters of m (every default filled in: pair laws per material class,
/// penalty, tangential penalty, buffer, m_bar, h_min). Called by finalize_model(); throws
/// InputError for parameters out of range.
void resolve_contact_params(Model& m);

/// Prepare contact state for a fresh run: builds s.topology (build_topology()) and sizes the
/// buffers (no allocation later).
void init_contact_state(const Model& m, State& s);

/// After joints broke (fracture, docs/theory.md §6.15): rebuild s.topology for the bodies
/// `dirty` with the state's sectors (rebuild_topology(m, dirty, s.node_sector, s.topology)),
/// resize the virtual-node buffers, move the pair histories of edge targets to the new ids of
/// the same edges (their ids shift with the virtual nodes and boundary edges before them; real
/// node targets and contactor bodies keep theirs) and mark the broad phase for rebuild.
/// Allocates: for steps with breaks only.
void rebuild_contact_topology(const Model& m, State& s, std::span<const BodyId> dirty);

/// Add contact forces to s.f and s.f_contact for positions s.x and velocities s.v (v^{n-1/2});
/// update pair history, contact energy and contact dissipation in s.energy / s.contact.
void add_contact_forces(const Model& m, State& s);

/// Bytes of one pair-in-contact record of a distributed run (target node, contactor body,
/// PairResult): every process sends those of its targets every step to the processes that add
/// the pair's forces to a node (add_contact_forces() with a plan). Keyed by (node, body), the
/// order of the serial pair loop, not by an index into a candidate list: each process holds
/// only its own targets' candidates.
/// What the receiver adds (eq. 20): the key, the located sub-triangle, its barycentric
/// coordinates and the force. The pair's history stays with its owner (56 bytes; until
/// 2026-12-03 a record was the key and the whole PairResult, 152 bytes).
struct ContactRecord {
    NodeId node = kNone;  ///< target node
    BodyId body = kNone;  ///< contactor body
    int32_t tri = -1;     ///< PairResult::tri
    int32_t pad = 0;      ///< (zero: every byte of a record is defined)
    Real N[3] = {0, 0, 0};
    Vec2 f;
};
static_assert(sizeof(ContactRecord) == 56 && std::is_trivially_copyable_v<ContactRecord>);
inline constexpr size_t kContactRecordBytes = sizeof(ContactRecord);

/// The contact sums a distributed step reduces with its other exact sums (ContactShare::sums).
inline constexpr int kContactSums = 5;

/// ContactShare::need bits: the process adds contact forces to f_contact / to f at the node.
inline constexpr uint8_t kNeedContact = 1;
inline constexpr uint8_t kNeedForce = 2;

/// Scratch of a process's share of the narrow phase in a distributed run (StepPlan::contact).
struct ContactShare {
    /// Nodes whose f_contact or f a process other than their owner reads every step, as
    /// (node, process) pairs, ascending: the nodes of the bodies.csv sets that process sums
    /// (Simulation). The pairs touching them are sent to that process too. Set it with
    /// set_force_readers().
    std::vector<std::pair<NodeId, int32_t>> force_readers;
    /// The entries of force_readers whose f the process reads too (a fixed body's reaction,
    /// eq. 8.2): only there does it clear f and add contact forces to f beside f_contact.
    std::vector<std::pair<NodeId, int32_t>> f_readers;

    // --- the exchange of the pairs in contact (local apply; grow-only buffers) ---
    /// the records to the other processes, by destination (doubles: kContactRecordBytes / 8
    /// per record), and those received, by source, each part in pair order
    mutable std::vector<double> send, recv;
    mutable std::vector<int> send_counts, send_displs, recv_counts, recv_displs;
    /// the received records' keys and results, in the order received
    mutable std::vector<NodeId> rec_node;
    mutable std::vector<BodyId> rec_body;
    mutable std::vector<PairResult> rec_out;
    /// every pair whose forces this process adds, in pair order: k >= 0 its own pair k of the
    /// narrow phase's output, k < 0 received record -k - 1
    mutable std::vector<int32_t> order;
    /// destinations of the own records that have one: the pair of the narrow phase's output
    /// index dest_pair[i] goes to dest[dest_end[i - 1] .. dest_end[i]) (from 0 for i = 0)
    mutable std::vector<int32_t> dest, dest_pair, dest_end;
    /// the own candidate pairs whose record may have a destination (ascending; listed with
    /// the neighbours, once per broad phase or plan)
    mutable std::vector<int32_t> send_cand;
    mutable std::vector<int64_t> stamp;         ///< per process (scratch)
    mutable int64_t tick = 0;                   ///< stamp of the current record
    mutable std::vector<int32_t> own_k, heads;  ///< the merge's scratch
    /// a threaded merged apply: thread t adds at the real nodes [thread_lo[t], thread_lo[t + 1])
    mutable std::vector<NodeId> thread_lo;
    /// a one-thread apply: the own pairs whose forces reach a node a received record reaches
    /// (left for the merge), and those nodes (per node) and their bodies (per body) marked (sized
    /// with need and body_all, zero between steps)
    mutable std::vector<int32_t> deferred;
    mutable std::vector<uint8_t> exposed, exposed_body;
    /// per real node: the arrays this process adds contact forces to there, kNeedContact
    /// (f_contact: it owns the node or reads its contact force) | kNeedForce (f: it owns the node
    /// or reads its f, ContactShare::f_readers); 0: neither
    mutable std::vector<uint8_t> need;
    /// per body: the processes that need a node of it (body_rank[body_rank_begin[b] ..
    /// body_rank_begin[b + 1]), ascending)
    mutable std::vector<int32_t> body_rank_begin, body_rank;
    /// per body: this process needs all of its nodes
    mutable std::vector<uint8_t> body_all;
    mutable std::vector<int32_t> neighbours;  ///< processes it may exchange records with
    mutable bool dest_valid = false;          ///< the lists above match the plan and candidates
    /// cs.active may hold other processes' pairs (the serial list after a restore, a
    /// distribute() or gather_active()): the next step keeps its own targets' pairs only
    mutable bool active_full = true;
    /// this process's contact sums of the step (stored energy, dissipation of the step, pairs
    /// in contact, deep and lost pairs), pending: step() reduces them (finish_contact_sums())
    mutable ExactSum sums[kContactSums];
    mutable bool sums_pending = false;
    mutable int64_t own_records = 0;       ///< pairs of its targets in contact at its last step
    mutable int64_t records_sent = 0;      ///< record copies it sent at its last step
    mutable int64_t records_received = 0;  ///< records it received at its last step
    /// candidate pairs of every process at the last broad phase (the serial list's length; a
    /// process holds only its own targets' pairs)
    mutable int64_t total_candidates = 0;
    /// the contactors of the process's candidate pairs: the only body boxes it computes
    mutable std::vector<BodyId> box_bodies;
    mutable std::vector<uint8_t> body_mark;
    mutable bool boxes_valid = false;  ///< box_bodies lists the current candidates' contactors
};

struct StepPlan;  // parallel/distributed.hpp

/// One node in kSparseContactForceRatio at most in ContactState::fc_nodes (the capacity the
/// first full clear reserves); an apply that would list more clears every node next step.
inline constexpr NodeId kSparseContactForceRatio = 16;

/// Step 2's clear of f_contact, the part ContactState::fc_nodes allows: with fc_sparse, zeroes
/// f_contact at the listed nodes, empties the list and returns true (f_contact is clear);
/// else returns false, and the caller must zero f_contact at every node it reads: the list is
/// then exact (empty, fc_sparse), its capacity reserved on the first call (num_nodes /
/// kSparseContactForceRatio).
bool clear_listed_contact_forces(State& s, NodeId num_nodes);

/// The largest |v_i|^2 over the nodes of runs ([first, second) ranges): the skin trigger's
/// speed (spec §2.3); exact and independent of the order, so a maximum over processes of
/// their own nodes' values is the serial value.
Real max_speed2(const Vec2* v, std::span<const std::pair<NodeId, NodeId>> runs);

/// add_contact_forces() as one process of a distributed run (issue #15, docs/parallel.md): the
/// process's broad phase queries only the targets it owns (its real node, or the first end
/// node of an edge target: spec D5.3), so s.contact.cand holds their pairs only (a subsequence
/// of the serial list); it evaluates them (narrow phase and law, the expensive part) and keeps
/// their histories (s.contact.active: its own pairs). Each pair in contact goes as a record
/// keyed by (node, body) to the processes that need one of the nodes its forces reach (the
/// owners, and the readers of ContactShare::force_readers); each process merges its own and the
/// received records in that order and adds their forces to the nodes it needs only, as the
/// serial loop does: bitwise the serial f and f_contact there (elsewhere they are not
/// computed). Energies, counts and the deepest lost pair are reduced over the processes (exact
/// sums, maxima), so they are the serial values on every process. The skin trigger is the
/// maximum over the processes' own nodes; a broad-phase rebuild all-gathers x and v first and
/// rebuilds the ghost lists (plan.ghosts). Collective.
void add_contact_forces(const Model& m, State& s, const StepPlan& plan, const Comm& comm);

/// After a distributed add_contact_forces(): the contact sums of every process (totals: the
/// exact sums over the processes of ContactShare::sums) into s: energies, pairs in contact,
/// deep and lost pairs and their run totals; on a step that lost a pair also the largest depth
/// ratio and the deepest lost pair (more reductions then). Collective.
void finish_contact_sums(State& s, const StepPlan& plan, const Comm& comm, const ExactSum* totals);

/// Replace every process's list of pairs in contact (s.contact.active, its own targets' pairs
/// only during a run) by the serial one, and the largest depth ratios (each process keeps its
/// own during a run) by the maxima over the processes, e.g. before a checkpoint is written or a
/// new partition is made. Collective; allocates.
void gather_active(State& s, const StepPlan& plan, const Comm& comm);

/// The nodes whose forces a process other than their owner reads (ContactShare::force_readers
/// and f_readers), from the sets each process sums: contact_nodes[k] (f_contact) and
/// force_nodes[k] (f) of set k are read by process set_rank[k] (Resultants::contact_read_nodes()
/// and force_read_nodes()). Every process must pass the same lists. Not collective.
void set_force_readers(StepPlan& plan, std::span<const std::vector<NodeId>> contact_nodes,
                       std::span<const std::vector<NodeId>> force_nodes,
                       std::span<const int32_t> set_rank);

/// The exchange of contact records that plan's process makes at a step of state s (fdem
/// decompose, parallel/decompose.hpp): to[q] (resized to plan.procs) = the records it sends
/// process q (its targets' pairs in s.contact.active, each to every other process that needs a
/// node the pair's forces reach), and may_send[q] = 1 for the processes its targets' candidate
/// pairs may send to (its neighbours, with those that may send to it). Not collective.
void contact_exchange_counts(const Model& m, const State& s, const StepPlan& plan,
                             std::vector<int64_t>& to, std::vector<uint8_t>& may_send);

/// Replace every process's own candidate list by the serial one (all of them merged in (node,
/// body) order), e.g. before a checkpoint is written: the file holds the serial list whatever
/// the process count. The filters by target owner keep a distributed step correct on it.
/// Collective; allocates.
void gather_candidates(State& s, const StepPlan& plan, const Comm& comm);

/// The contactor bodies of plan's process's candidate pairs (those of its targets), ascending:
/// the only body boxes it computes and the bodies whose every node it reads (its ghosts). Listed
/// once per candidate list (ContactShare::boxes_valid, cleared by a broad-phase rebuild).
const std::vector<BodyId>& contactor_bodies(const Model& m, const State& s, const StepPlan& plan);

/// Positions and velocities of the virtual contact nodes (s.contact.xv, vv) from s.x, s.v
/// (spec §4.4-2). add_contact_forces() calls it first; exposed for tests and output.
void update_virtual_nodes(const Model& m, State& s);

/// Narrow-phase early reject, exposed for tests: box[b] for every body b < nbodies from the
/// positions of its contactor sub-triangles' vertices (x real, xv virtual), widened by a tiny
/// margin, or infinite where the reject is not proven exact (contact.cpp has the proof).
/// Reads the body's distinct contact nodes (ContactTopology::body_cnode) once each; a model
/// without that list (hand-made in tests) or a body with many nodes takes the reference path.
/// Bitwise the same boxes as body_boxes_reference() (proof at body_boxes(), tested).
void body_boxes(const ContactTopology& cm, const Vec2* x, const Vec2* xv, BodyBox* box,
                int32_t nbodies);

/// The specification of body_boxes(), for tests: the same boxes from the vertices of every
/// sub-triangle in turn (three position reads per sub-triangle). Serial.
void body_boxes_reference(const ContactTopology& cm, const Vec2* x, const Vec2* xv, BodyBox* box,
                          int32_t nbodies);

/// Fill ContactTopology::body_cnode, body_cnode_begin, body_cnode_nreal and sub_local from
/// sub_tri and body_sub_begin (build_topology() calls it; so can tests that build a
/// ContactTopology by hand).
void build_body_contact_nodes(ContactTopology& cm);

/// true: a target node at p is provably in none of the sub-triangles of the body of box b:
/// the locate test of the narrow phase would reject every one of them (contact.cpp
/// body_boxes()). Only points within 1e6 (W_x + W_y) of the box are rejected (the bound on the
/// rounding of the edge functions grows with the distance). The reference formula; box_rejects()
/// is the same operations on SSE2 pairs where available (tested to give the same answer).
inline bool box_rejects_scalar(const BodyBox& b, Vec2 p) {
    constexpr Real kBoxFar = 1e6;
    const Real dx = std::max(b.lo.x - p.x, p.x - b.hi.x);
    const Real dy = std::max(b.lo.y - p.y, p.y - b.hi.y);
    const Real d = std::max(dx, dy);
    return (d > 0) & (d <= kBoxFar * ((b.hi.x - b.lo.x) + (b.hi.y - b.lo.y)));  // no branch
}

inline bool box_rejects(const BodyBox& b, Vec2 p) {
#ifdef __SSE2__
    // (x, y) lanes. std::max(a, c) = (a < c) ? c : a is _mm_max_pd(c, a) (c > a ? c : a, the
    // second operand on NaN), so every value below is that of box_rejects_scalar()
    const __m128d lo = _mm_loadu_pd(&b.lo.x), hi = _mm_loadu_pd(&b.hi.x), q = _mm_loadu_pd(&p.x);
    const __m128d e = _mm_max_pd(_mm_sub_pd(q, hi), _mm_sub_pd(lo, q));  // (dx, dy)
    const Real d = _mm_cvtsd_f64(_mm_max_sd(_mm_unpackhi_pd(e, e), e));  // std::max(dx, dy)
    const __m128d w = _mm_sub_pd(hi, lo);
    const Real far = 1e6 * _mm_cvtsd_f64(_mm_add_sd(w, _mm_unpackhi_pd(w, w)));
    return (d > 0) & (d <= far);
#else
    return box_rejects_scalar(b, p);
#endif
}

/// Largest stable dt [s] imposed by the contact penalty (spec §3.4); +inf without contact.
Real contact_stable_dt(const Model& m, const ContactTopology& t);

}  // namespace fdem
