// Smooth triangle-to-node contact of Lei et al. 2020 (docs/theory.md §6): per step, virtual-node
// kinematics, broad phase when the skin is used up, narrow phase (locate the target node in a
// contactor sub-triangle), the contact law and the reaction on the contactor (eq. 20).
//
// Pair loop order: candidate pairs sorted by (target node, contactor body), merged with the
// active-contact list of the previous step that is sorted the same way. The pairs are evaluated
// in parallel (OpenMP) into a per-pair buffer and applied in pair order (every node receives its
// forces in that order; the energies are exact sums), so the result is bitwise the same for any
// thread count. Baseline A (ContactAlgorithm::LegacyTriangle) goes
// to legacy_triangle.cpp; baseline B only changes the field (field.hpp evaluate_field).
#include "contact/contact.hpp"
#include "fdem/assert.hpp"
#include "fdem/build.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "contact/field.hpp"
#include "contact/law.hpp"
#include "contact/legacy_triangle.hpp"
#include "detect/broad_phase.hpp"
#include "parallel/distributed.hpp"

namespace fdem {

namespace {

constexpr Real kLocateEps = 1e-12;  // N_i >= -eps counts as inside (spec §4.5-1)
// a pair's last sub-triangle is taken without testing the other candidates when every N_i of
// x_j there exceeds this (evaluate_pair(): temporal coherence)
constexpr Real kCoherentMin = 1e-6;
constexpr Real kLostCheckRatio = 0.1;  // depth ratio above which a lost pair is tested
// early reject of the locate test: c_i < -kRejectMargin |2A| means N_i < -1e-9, far beyond
// -kLocateEps plus the rounding of N_i (~1e-15), and far below any geometric distance
constexpr Real kRejectMargin = 1e-9;
// candidate pairs per step below which the narrow phase runs on one thread (fork/join of a
// parallel region costs about as much as a few thousand pair evaluations)
constexpr int32_t kMinParallelPairs = 2048;
// below this many pairs in contact the apply (step 3b) runs on one thread
constexpr int32_t kMinParallelApply = 4096;
// which forces the apply's bookkeeping adds (contact_forces_impl() step 3b)
constexpr int kNoForces = 0, kAllForces = 1, kSliceForces = 2, kDirectForces = 3;
using NoForces = std::integral_constant<int, kNoForces>;
using AllForces = std::integral_constant<int, kAllForces>;
using SliceForces = std::integral_constant<int, kSliceForces>;
using DirectForces = std::integral_constant<int, kDirectForces>;

// The bookkeeping's forces in a one-thread distributed apply (kDirectForces): every own pair's
// forces at the nodes it needs that no received record reaches (exposed[i] == 0), in pair order
// (only own pairs reach those nodes: the serial order there); a pair that reaches an exposed
// node is listed in deferred, for apply_merged() to add there in the merged order. Whole (one
// add_pair_forces(), no test per node) where every node of the contactor body is needed and
// none is exposed (body_all, exposed_body) and neither is the target.
struct DirectAdds {
    const uint8_t* need;          ///< ContactShare::need
    const uint8_t* exposed;       ///< ContactShare::exposed
    const uint8_t* exposed_body;  ///< ContactShare::exposed_body
    const uint8_t* body_all;      ///< ContactShare::body_all
    int32_t* deferred;            ///< out: the pairs (narrow-phase index k) left for the merge
    int32_t n_deferred = 0;
};
// the narrow phase splits the pairs into this many fixed chunks (independent of the thread
// count); each chunk lists its pairs in contact at the front of its range of cs.in_contact
constexpr int32_t kPairChunks = 64;
constexpr int32_t kBoxPrefetch = 24;  // pairs ahead whose body box pass 1 prefetches

// Body-box reject (body_boxes(), box_rejects() in contact.hpp; proof at body_boxes()):
constexpr Real kBoxMargin = 1e-6;  // box widened by kBoxMargin W (W: larger box extent)
constexpr Real kBoxAspect = 1e-6;  // needs |2A| >= kBoxAspect W^2 for every sub-triangle
constexpr Real kBoxScale = 1e-8;   // needs W >= kBoxScale max |coordinate| of the box
constexpr Real kBoxMinW2 = 1e-200, kBoxMaxW2 = 1e200;  // no under- or overflow in the bound

inline Vec2 cpos(const ContactTopology& ct, const Vec2* x, const Vec2* xv, NodeId i) {
    return i < ct.num_real_nodes ? x[i] : xv[i - ct.num_real_nodes];
}

// even-odd crossing test of p against the boundary edges of body c (handles holes)
bool inside_body(const ContactTopology& ct, BodyId c, const Vec2* x, Vec2 p) {
    bool in = false;
    for (int32_t e = ct.body_bedge_begin[c]; e < ct.body_bedge_begin[c + 1]; ++e) {
        const Vec2 a = x[ct.boundary_edges[e][0]], b = x[ct.boundary_edges[e][1]];
        if ((a.y > p.y) != (b.y > p.y)) {
            const Real xc = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if (p.x < xc) in = !in;
        }
    }
    return in;
}

// The forces of one pair in contact, node by node: visit(i, f) for every real node i and the
// force f it receives, in the order of the serial loop. The apply with 2+ threads
// (add_contact_forces() step 3b) adds them for the nodes of one range only (add_pair_forces with
// a range); the values are the same expressions either way.

// force f on target t: the node, or half to each end node of an edge target (theory §6.12)
template <class Visit>
inline void visit_target_force(const ContactTopology& ct, NodeId t, Vec2 f, Visit&& visit) {
    if (t < ct.num_real_nodes) {
        visit(t, f);
        return;
    }
    const auto& e = ct.boundary_edges[static_cast<size_t>(t - ct.edge_target_base)];
    const Vec2 h = 0.5 * f;
    visit(e[0], h);
    visit(e[1], h);
}

// Welded contactor (docs/theory.md §6.15, eq. 6.23): the mass-weighted mean of group g's copies
// of the values a (positions or velocities), the copies in ascending order (one fixed sum)
inline Vec2 group_mean(const ContactTopology& ct, const Vec2* a, int32_t g) {
    const int32_t b = ct.weld_group_begin[static_cast<size_t>(g)];
    const int32_t e = ct.weld_group_begin[static_cast<size_t>(g) + 1];
    Vec2 sum = ct.weld_share[static_cast<size_t>(b)] * a[ct.weld_copy[static_cast<size_t>(b)]];
    for (int32_t k = b + 1; k < e; ++k)
        sum += ct.weld_share[static_cast<size_t>(k)] * a[ct.weld_copy[static_cast<size_t>(k)]];
    return sum;
}

// the contactor value of real node i: its sector's mean if grouped, else its own (no weld: a[i])
inline Vec2 weld_mean(const ContactTopology& ct, const Vec2* a, NodeId i) {
    if (!ct.welded()) return a[i];
    const int32_t g = ct.weld_group[static_cast<size_t>(i)];
    return g < 0 ? a[i] : group_mean(ct, a, g);
}

// force f on real contactor node i: to the copies of its sector by their mass shares if grouped
// (the chain rule of eq. 6.23), else to i
template <class Visit>
inline void visit_real_force(const ContactTopology& ct, NodeId i, Vec2 f, Visit&& visit) {
    const int32_t g = ct.welded() ? ct.weld_group[static_cast<size_t>(i)] : -1;
    if (g < 0) {
        visit(i, f);
        return;
    }
    for (int32_t k = ct.weld_group_begin[static_cast<size_t>(g)];
         k < ct.weld_group_begin[static_cast<size_t>(g) + 1]; ++k)
        visit(ct.weld_copy[static_cast<size_t>(k)], ct.weld_share[static_cast<size_t>(k)] * f);
}

// force f on contact node i (virtual: to its parents with the frozen weights, spec §4.4-6)
template <class Visit>
inline void visit_node_force(const ContactTopology& ct, NodeId i, Vec2 f, Visit&& visit) {
    if (i < ct.num_real_nodes) {
        visit_real_force(ct, i, f, visit);
        return;
    }
    const size_t v = static_cast<size_t>(i - ct.num_real_nodes);
    for (int k = 0; k < 3; ++k)
        visit_real_force(ct, ct.virt_parent[v][k], ct.virt_weight[v][k] * f, visit);
}

// f on the target, -N_i f on the contactor's vertices (eq. 20): every force of one pair in
// contact, target first, then vertices 0, 1, 2
// (always inlined: the one-process apply loop and apply_merged() both call it; as a call the
// serial loop ran +0.8 % more instructions, callgrind of the saturated pack)
template <class Visit>
[[gnu::always_inline]] inline void visit_pair_forces(const ContactTopology& ct, NodeId j,
                                                     const PairResult& o, Visit&& visit) {
    const auto& q = ct.sub_tri[o.tri];
    visit_target_force(ct, j, o.f, visit);
    for (int k = 0; k < 3; ++k)
        visit_node_force(ct, q[k], -o.N[k] * o.f, visit);
}

// the pair's forces added to f and f_contact (fc): of every node, or of the nodes [lo, hi) only.
// Without welds (the common case) a direct path: the values and order of visit_pair_forces()
// (target, then vertices 0, 1, 2; a virtual vertex to its parents), with the weld test once per
// pair instead of per node, the pair's force and coordinates read once into locals (a force
// store could alias them, so the visits reloaded them after each store) and nothing called
// (issue #16: ~110 instructions per pair in the visits, callgrind of the saturated pack)
[[gnu::always_inline]] inline void add_pair_forces(const ContactTopology& ct, Vec2* f, Vec2* fc,
                                                   NodeId j, const PairResult& o) {
    const auto add = [ f, fc ](NodeId i, Vec2 fi) __attribute__((always_inline)) {
        f[i] += fi;
        fc[i] += fi;
    };
    if (ct.welded()) {
        visit_pair_forces(ct, j, o, add);
        return;
    }
    const NodeId nr = ct.num_real_nodes;
    const Vec2 of = o.f;
    const Real N[3] = {o.N[0], o.N[1], o.N[2]};
    const auto& q = ct.sub_tri[static_cast<size_t>(o.tri)];
    const NodeId q0 = q[0], q1 = q[1], q2 = q[2];
    if (j < nr) {  // (visit_target_force())
        add(j, of);
    } else {
        const auto& e = ct.boundary_edges[static_cast<size_t>(j - ct.edge_target_base)];
        const NodeId e0 = e[0], e1 = e[1];
        const Vec2 h = 0.5 * of;
        add(e0, h);
        add(e1, h);
    }
    // (visit_node_force() without welds; always inlined: as a call it cost ~35 instructions a
    // vertex)
    const auto vertex = [&](NodeId i, Vec2 g) __attribute__((always_inline)) {
        if (i < nr) {
            add(i, g);
            return;
        }
        const size_t v = static_cast<size_t>(i - nr);
        const std::array<NodeId, 3> p = ct.virt_parent[v];
        const std::array<Real, 3> w = ct.virt_weight[v];
        add(p[0], w[0] * g);
        add(p[1], w[1] * g);
        add(p[2], w[2] * g);
    };
    vertex(q0, -N[0] * of);
    vertex(q1, -N[1] * of);
    vertex(q2, -N[2] * of);
}
inline void add_pair_forces(const ContactTopology& ct, Vec2* f, Vec2* fc, NodeId j,
                            const PairResult& o, NodeId lo, NodeId hi) {
    visit_pair_forces(ct, j, o, [f, fc, lo, hi](NodeId i, Vec2 fi) {
        if (i < lo || i >= hi) return;
        f[i] += fi;
        fc[i] += fi;
    });
}

// A distributed step's add at real node i: to f and f_contact as far as this process needs them
// there (ContactShare::need)
inline void add_needed(Vec2* f, Vec2* fc, const uint8_t* need, NodeId i, Vec2 fi) {
    if (need[i] & kNeedForce) f[i] += fi;
    if (need[i] & kNeedContact) fc[i] += fi;
}

// The real nodes of target j: the node (a = b = j), or an edge target's end nodes
inline void target_ends(const ContactTopology& ct, NodeId j, NodeId& a, NodeId& b) {
    a = b = j;
    if (j < ct.num_real_nodes) return;
    const auto& e = ct.boundary_edges[static_cast<size_t>(j - ct.edge_target_base)];
    a = e[0];
    b = e[1];
}

// A distributed step: this process needs f and f_contact at every node the forces of pair
// (target j, contactor c) reach (ContactShare::need, body_all), so the one-process add applies
inline bool all_needed(const ContactTopology& ct, const uint8_t* need, const uint8_t* body_all,
                       NodeId j, BodyId c) {
    constexpr uint8_t kBoth = kNeedContact | kNeedForce;
    NodeId a, b;
    target_ends(ct, j, a, b);
    return body_all[c] && need[a] == kBoth && need[b] == kBoth;
}

// After an apply: the nodes its pairs' forces reached, added to ContactState::fc_nodes (which
// stays ascending without repeats); each(visit) walks visit_pair_forces() of every pair it
// applied. An apply that would overflow the list's reserved capacity (never grown in the step)
// sets fc_sparse false instead: the next clear is of every node.
template <class EachPair>
void note_contact_force_nodes(ContactState& cs, size_t pairs, EachPair&& each) {
    if (!cs.fc_sparse) return;
    std::vector<NodeId>& list = cs.fc_nodes;
    // (a pair reaches at least its target and the contactor's three vertices)
    bool overflow = 4 * pairs > list.capacity() - list.size();
    if (!overflow) {
        // each node once (fc_mark): a welded contactor's pairs reach the same sector copies
        // many times over, and sorting the repeats cost ~1.5 % of a jointed UCS's step
        uint8_t* mark = cs.fc_mark.data();
        for (const NodeId i : list)  // (the earlier applies of this step)
            mark[i] = 1;
        each([&](NodeId i, Vec2) {
            if (mark[i]) return;
            if (list.size() == list.capacity()) {
                overflow = true;
                return;
            }
            mark[i] = 1;
            list.push_back(i);
        });
        for (const NodeId i : list)
            mark[i] = 0;
    }
    if (overflow) {
        cs.fc_sparse = false;
        list.clear();
        return;
    }
    std::sort(list.begin(), list.end());
}

// The smallest real node target j reaches: j itself, or an edge target's smaller end node.
inline NodeId target_low_node(const ContactTopology& ct, NodeId j) {
    if (j < ct.num_real_nodes) return j;
    const auto& e = ct.boundary_edges[static_cast<size_t>(j - ct.edge_target_base)];
    return std::min(e[0], e[1]);
}

// Bounds b[0] = 0 <= b[1] <= ... <= b[T] = N (the real nodes) of T node ranges holding about
// equal numbers of n items (pairs, records) whose targets target(i) gives: quantiles of the
// low nodes (target_low_node) of an even sample of up to kSamples items; equal shares of the
// ids without items. For threads that add at their own node range: any bounds give the same
// bits, these give each thread about the same work wherever the pairs lie in the ids.
template <size_t kSamples, class Target>
void quantile_node_ranges(const ContactTopology& ct, size_t n, int T, Target&& target, NodeId* b) {
    const NodeId nr = ct.num_real_nodes;
    std::array<NodeId, kSamples> sample;
    const size_t ns = std::min(n, kSamples), ts = static_cast<size_t>(T);
    for (size_t q = 0; q < ns; ++q)
        sample[q] = target_low_node(ct, target((2 * q + 1) * n / (2 * ns)));
    std::sort(sample.begin(), sample.begin() + static_cast<ptrdiff_t>(ns));
    b[0] = 0;
    for (size_t u = 1; u < ts; ++u)
        b[u] = ns > 0 ? sample[u * ns / ts] : static_cast<NodeId>(static_cast<int64_t>(nr) * u / T);
    b[ts] = nr;
}

// The real nodes [lo, hi] the forces of pair (target j, contactor c) can reach: the target's
// (an edge target: its end nodes) and body c's node range, which holds every vertex, virtual-node
// parent and welded copy of its contactor geometry (a conservative span, without the walk).
inline void pair_span(const Model& m, const ContactTopology& ct, NodeId j, BodyId c, NodeId& lo,
                      NodeId& hi) {
    const Body& b = m.bodies[static_cast<size_t>(c)];
    const NodeId tl = target_low_node(ct, j);
    NodeId th = j;
    if (j >= ct.num_real_nodes) {
        const auto& e = ct.boundary_edges[static_cast<size_t>(j - ct.edge_target_base)];
        th = std::max(e[0], e[1]);
    }
    lo = std::min(tl, b.node_begin);
    hi = std::max(th, b.node_end - 1);
}

// the order of the per-pair lists (ContactState::active, rebase, the candidates): by (target
// node, contactor body); pair_below: entry a comes before pair (j, c)
template <class T>
inline bool pair_below(const T& a, NodeId j, BodyId c) {
    return a.node < j || (a.node == j && a.body < c);
}

template <class T>
inline bool pair_key_less(const T& a, const T& b) {
    return pair_below(a, b.node, b.body);
}

// the entry of pair (j, c) in a list sorted by pair_key_less (the pair history in cs.active, the
// old topology's law depth in cs.rebase), or nullptr
template <class T>
inline const T* find_pair(const std::vector<T>& list, NodeId j, BodyId c) {
    const auto it = std::partition_point(list.begin(), list.end(),
                                         [j, c](const T& a) { return pair_below(a, j, c); });
    return it != list.end() && it->node == j && it->body == c ? &*it : nullptr;
}

// find_pair() for keys that come in ascending order (the candidates of one chunk of the narrow
// phase): `at` is the cursor into the list, the first entry not below the last key looked up.
// The cursor moves forward entry by entry (the in-contact pairs are mostly the listed pairs, so
// it moves about one entry per lookup, on memory the last lookup brought in) and by a binary
// search over the rest when the gap is long. The same entry as find_pair() (issue #16: the
// binary search over the whole list was ~30 % of contact_at() on the saturated pack).
template <class T>
inline const T* find_pair_from(const std::vector<T>& list, size_t& at, NodeId j, BodyId c) {
    constexpr int kLinearSteps = 8;
    const size_t n = list.size();
    const auto below = [j, c](const T& a) { return pair_below(a, j, c); };
    for (int k = 0; at < n && below(list[at]); ++k, ++at) {
        if (k == kLinearSteps) {
            at = static_cast<size_t>(
                std::partition_point(list.begin() + static_cast<std::ptrdiff_t>(at), list.end(),
                                     below) -
                list.begin());
            break;
        }
    }
    return at < n && list[at].node == j && list[at].body == c ? &list[at] : nullptr;
}

// does the release of active pair a test whether its target went inside the contactor (spec
// §4.6)? Only deep pairs of two bodies
inline bool lost_test_needed(const Model& m, const ContactTopology& ct, const ActiveContact& a) {
    return a.h.depth_ratio > kLostCheckRatio && a.body != m.node_body[target_node(ct, a.node)];
}

// does a pair of contactor c and target body bt continue from cs.rebase in this step (eq. 9.26)?
inline bool rebased(const ContactState& cs, BodyId c, BodyId bt) {
    return cs.rebase_pending && (cs.rebase_body[static_cast<size_t>(c)] != 0 ||
                                 cs.rebase_body[static_cast<size_t>(bt)] != 0);
}

// ContactState::xw sized for the topology (no weld: empty)
void size_weld_positions(const ContactTopology& ct, ContactState& cs) {
    if (ct.welded()) {
        if (cs.xw.size() != static_cast<size_t>(ct.num_real_nodes))
            cs.xw.assign(static_cast<size_t>(ct.num_real_nodes), Vec2{});
    } else {
        cs.xw.clear();
    }
}

}  // namespace

void init_contact_state(const Model& m, State& s) {
    const ContactModel& cm = m.contact;
    build_topology(m, s.node_sector, s.topology);
    const ContactTopology& ct = s.topology;
    ContactState& cs = s.contact;
    cs = ContactState{};
    if (cm.algorithm == ContactAlgorithm::None) return;
    if (cm.algorithm == ContactAlgorithm::LegacyTriangle) {
        // baseline A: couples of boundary triangles; about 8 partners per triangle after
        // warm-up (the grow-only buffers enlarge themselves if a scene needs more)
        LegacyTriangleState& ls = cs.legacy;
        const size_t nt = ct.boundary_tris.size();
        ls.couples.reserve(8 * nt + 16);
        ls.next.reserve(8 * nt + 16);
        ls.couple_force.reserve(6 * (8 * nt + 16));
        ls.couple_stored.reserve(8 * nt + 16);
        ls.couple_dissipated.reserve(8 * nt + 16);
        ls.center.reserve(nt);
        ls.radius.reserve(nt);
        ls.cell.reserve(nt);
        ls.cell_items.reserve(nt);
        ls.cell_start.reserve(4 * nt + 64);
        ls.cursor.reserve(4 * nt + 64);
        ls.query.reserve(nt + 16);
        return;
    }
    const size_t nv = static_cast<size_t>(ct.num_virtual());
    const size_t nb = ct.boundary_nodes.size() + ct.edge_scale.size();  // targets
    const size_t nt = static_cast<size_t>(ct.num_sub_tris());
    cs.xv.assign(nv, Vec2{});
    cs.vv.assign(nv, Vec2{});
    size_weld_positions(ct, cs);
    // reservations: the grow-only buffers rarely need more than this after warm-up
    cs.cand.node.reserve(4 * nb + 16);
    cs.cand.body.reserve(4 * nb + 16);
    cs.cand.begin.reserve(4 * nb + 17);
    cs.cand.tri.reserve(16 * nb + 64);
    cs.pair_out.reserve(4 * nb + 16);
    cs.body_box.assign(static_cast<size_t>(m.num_bodies()), BodyBox{});
    cs.box_bodies.reserve(static_cast<size_t>(m.num_bodies()));
    cs.box_mark.assign(static_cast<size_t>(m.num_bodies()), 0);
    cs.box_list_valid = false;
    cs.apply_lists.threads = 0;
    cs.broad.tri_center.reserve(nt);
    cs.broad.tri_radius.reserve(nt);
    cs.broad.tri_cell.reserve(nt);
    cs.broad.cell_items.reserve(nt);
    cs.broad.cell_start.reserve(4 * nt + 64);
    cs.broad.query.reserve(4 * nt + 64);
    cs.in_contact.reserve(4 * nb + 16);
    cs.active.reserve(2 * nb + 16);
    cs.active_next.reserve(2 * nb + 16);
}

namespace {
void probe_law_depths(const Model& m, State& s, std::span<const BodyId> dirty);
}  // namespace

void rebuild_contact_topology(const Model& m, State& s, std::span<const BodyId> dirty) {
    ContactState& cs = s.contact;
    const NodeId old_base = s.topology.edge_target_base;
    const std::vector<std::array<NodeId, 2>> old_edges = s.topology.boundary_edges;
    const bool smooth = m.contact.algorithm != ContactAlgorithm::None &&
                        m.contact.algorithm != ContactAlgorithm::LegacyTriangle;
    // the law depths of the old topology at x^n, for eq. 9.26 (before it is replaced)
    if (smooth) probe_law_depths(m, s, dirty);
    rebuild_topology(m, dirty, s.node_sector, s.topology);
    const ContactTopology& ct = s.topology;
    if (!smooth) return;
    const size_t nv = static_cast<size_t>(ct.num_virtual());
    cs.xv.assign(nv, Vec2{});
    cs.vv.assign(nv, Vec2{});
    size_weld_positions(ct, cs);

    // an edge target's history follows its edge (the triangle's own copies, oriented): a broken
    // joint adds boundary edges and never removes one, so every old edge is found
    if (ct.num_edge_targets() > 0) {
        std::vector<std::pair<std::array<NodeId, 2>, int32_t>> by_nodes;
        by_nodes.reserve(ct.boundary_edges.size());
        for (size_t e = 0; e < ct.boundary_edges.size(); ++e)
            by_nodes.emplace_back(ct.boundary_edges[e], static_cast<int32_t>(e));
        std::sort(by_nodes.begin(), by_nodes.end());
        // the new id of old target id t, or kNone
        auto new_id = [&](NodeId t) {
            if (t < old_base) return t;
            const auto& e = old_edges[static_cast<size_t>(t - old_base)];
            const auto it =
                std::lower_bound(by_nodes.begin(), by_nodes.end(), std::pair{e, int32_t{-1}});
            if (it == by_nodes.end() || it->first != e) return NodeId{kNone};  // (not expected)
            return ct.edge_target_base + it->second;
        };
        size_t kept = 0;
        for (ActiveContact& a : cs.active) {
            a.node = new_id(a.node);
            if (a.node != kNone) cs.active[kept++] = a;
        }
        cs.active.resize(kept);
        std::sort(cs.active.begin(), cs.active.end(), pair_key_less<ActiveContact>);
        kept = 0;
        for (RebaseEntry& r : cs.rebase) {
            r.node = new_id(r.node);
            if (r.node != kNone) cs.rebase[kept++] = r;
        }
        cs.rebase.resize(kept);
    }
    std::sort(cs.rebase.begin(), cs.rebase.end(), pair_key_less<RebaseEntry>);
    cs.need_rebuild = true;
}

namespace {

// ContactState::xa (contactor positions by contact id, read by the locate loop of
// evaluate_pair()) from the contactor positions xc of the real nodes and cs.xv (update the
// virtual nodes first): the contact nodes of the bodies list[0 .. count), the contactors of the
// pairs about to be evaluated (ContactTopology::body_cnode); every contact node with list ==
// nullptr or in a model without that list. Only those: on a sparse raster most bodies are in no
// candidate pair, and filling all (~155 000 nodes at N = 141) cost ~10 % of its step. Sized here
// when the topology changed (the first step, breaks).
void fill_contact_positions(const ContactTopology& ct, ContactState& cs, const Vec2* xc,
                            const BodyId* list, int32_t count) {
    const NodeId nr = ct.num_real_nodes;
    const size_t n = static_cast<size_t>(ct.num_contact_nodes());
    if (cs.xa.size() != n) cs.xa.resize(n);
    Vec2* xa = cs.xa.data();
    const bool listed = ct.lists_contact_nodes();
    if (list == nullptr || !listed) {
        std::copy(xc, xc + nr, xa);
        std::copy(cs.xv.begin(), cs.xv.end(), xa + nr);
        return;
    }
    const NodeId* cnode = ct.body_cnode.data();
    const Vec2* xv = cs.xv.data();
    for (int32_t k = 0; k < count; ++k) {
        const BodyId b = list[k];
        for (int32_t e = ct.body_cnode_begin[static_cast<size_t>(b)];
             e < ct.body_cnode_begin[static_cast<size_t>(b) + 1]; ++e) {
            const NodeId i = cnode[e];
            xa[i] = cpos(ct, xc, xv, i);
        }
    }
}

}  // namespace

void update_virtual_nodes(const Model&, State& s) {
    const ContactTopology& ct = s.topology;
    ContactState& cs = s.contact;
    const Vec2* x = s.x.data();
    const Vec2* v = s.v.data();
    if (ct.welded()) {
        // welded contactor positions (eq. 6.23): each grouped sector's mean once, to all its
        // copies; the other referenced nodes as they are. Virtual nodes follow these positions
        // and the sector-mean velocities of their parents
        size_weld_positions(ct, cs);
        Vec2* xw = cs.xw.data();
        for (const NodeId i : ct.weld_plain)
            xw[i] = x[i];
        const int32_t ng = static_cast<int32_t>(ct.weld_group_begin.size()) - 1;
        for (int32_t g = 0; g < ng; ++g) {
            const Vec2 xm = group_mean(ct, x, g);
            for (int32_t k = ct.weld_group_begin[static_cast<size_t>(g)];
                 k < ct.weld_group_begin[static_cast<size_t>(g) + 1]; ++k)
                xw[ct.weld_copy[static_cast<size_t>(k)]] = xm;
        }
        for (int32_t k = 0; k < ct.num_virtual(); ++k) {
            const auto& p = ct.virt_parent[k];
            const auto& w = ct.virt_weight[k];
            cs.xv[k] = w[0] * xw[p[0]] + w[1] * xw[p[1]] + w[2] * xw[p[2]];
            cs.vv[k] = w[0] * weld_mean(ct, v, p[0]) + w[1] * weld_mean(ct, v, p[1]) +
                       w[2] * weld_mean(ct, v, p[2]);
        }
        return;
    }
    for (int32_t k = 0; k < ct.num_virtual(); ++k) {
        const auto& p = ct.virt_parent[k];
        const auto& w = ct.virt_weight[k];
        cs.xv[k] = w[0] * x[p[0]] + w[1] * x[p[1]] + w[2] * x[p[2]];
        cs.vv[k] = w[0] * v[p[0]] + w[1] * v[p[1]] + w[2] * v[p[2]];
    }
}

namespace {

// Per-step box of every contactor body, for the exact early reject of a candidate pair whose
// target node lies well outside the body (docs/performance.md, round 4). In the contact-heavy
// pack ~99.8 % of the candidate pairs are not in contact and most of their nodes lie outside the
// contactor's box, so one 32-byte box replaces the sub-triangle vertex gathers of the pair.
//
// Box of body b: [lo, hi] = the bounds of the vertices p of all its sub-triangles (the same
// positions the locate loop uses), widened by delta = kBoxMargin W, W = max(W_x, W_y). The
// box is made infinite (never rejects) unless every sub-triangle has computed |a2| =
// |cross(p1 - p0, p2 - p0)| >= kBoxAspect W^2 > 0, W^2 lies in [kBoxMinW2, kBoxMaxW2] and
// W >= kBoxScale max |coordinate|. Claim: if then x lies outside [lo, hi] by d > 0 along some
// axis, with d the largest such excess and d <= kBoxFar (W_x + W_y), the locate loop rejects
// every sub-triangle of b in its early test (some c_i beyond kRejectMargin |a2| on the outer
// side), so skipping the pair gives bitwise the same result (not in contact).
// Proof sketch (u = 2^-53; ^ marks computed, * exact values):
//  - lo = fl(min - delta) with u |min| <= 0.02 delta (scale guard), so x is outside the
//    unwidened box of every sub-triangle T of b by D >= 0.98 delta along that axis;
//  - exact barycentric N* of x in T sum to 1 and x = sum N*_i p_i, so along that axis
//    -D > x - min_T = sum N*_i (p_i - min_T) >= -2 eta W, eta = largest -N*_i: some
//    c*_i = N*_i A* (A* = exact 2A) has the sign opposite to A* and |c*_i| > D |A*| / (2W);
//  - rounding: |c^_i - c*_i| <= 4.5u * 2 M^2 < 2e-15 M^2 with M = max |p_k - x|_inf <= D + W,
//    |a2^ - A*| < 2e-15 W^2, so |A*| >= 0.99 kBoxAspect W^2 and sign(a2^) = sign(A*);
//  - with t = D / W in [0.98e-6, 2.1e6] and alpha = |A*| / W^2 >= 0.99e-6 the outer-side excess
//    of c^_i is >= (t/2) alpha W^2 - 2e-15 (1 + t)^2 W^2, which exceeds kRejectMargin |a2^|
//    (<= 1.01e-9 alpha W^2) by a factor >= 200 at both ends of the t range, hence in between
//    (the difference is concave in t).
// NaN or infinite positions fail the guards (infinite box); a NaN node never gives d > 0.
}  // namespace

// Cheaper evaluation (round 5): the box is the same function of the same values when the bounds
// run over the body's distinct contact nodes (ContactTopology::body_cnode, each read once, real
// ones from x and virtual ones from xv without a branch) and the areas over sub_local indices into
// those positions: every vertex of a sub-triangle is one of those nodes and vice versa, and the
// areas are computed from the same vertex values in the same order. Only the order of the
// min/max chains changes, and it does not matter: min and max of a set are exact; NaN anywhere
// makes an area NaN (infinite box either way); where the order could pick -0 or +0 the box is
// still the same (lo = +-0 - delta = -delta with delta > 0 on a finite box, the extents and
// |coordinates| do not see the sign; both extents zero fails the W^2 guard).
namespace {

constexpr int32_t kBoxLocalNodes = 32;  // bodies with more distinct nodes take the reference

inline BodyBox finish_box(Real lx, Real ly, Real hx, Real hy, Real amin, bool nonzero) {
    constexpr Real inf = std::numeric_limits<Real>::infinity();
    const Real w = std::max(hx - lx, hy - ly), w2 = w * w;
    const Real c = std::max({std::abs(lx), std::abs(hx), std::abs(ly), std::abs(hy)});
    if (nonzero && w2 >= kBoxMinW2 && w2 <= kBoxMaxW2 && amin >= kBoxAspect * w2 &&
        w >= kBoxScale * c) {
        const Real delta = kBoxMargin * w;
        return BodyBox{{lx - delta, ly - delta}, {hx + delta, hy + delta}};
    }
    return BodyBox{{-inf, -inf}, {inf, inf}};
}

// the specification: bounds and areas over every sub-triangle's vertices in turn
BodyBox reference_box(const ContactTopology& ct, const Vec2* x, const Vec2* xv, BodyId b) {
    constexpr Real inf = std::numeric_limits<Real>::infinity();
    Real lx = inf, ly = inf, hx = -inf, hy = -inf, amin = inf;
    bool nonzero = true;
    for (int32_t t = ct.body_sub_begin[b]; t < ct.body_sub_begin[b + 1]; ++t) {
        const auto& q = ct.sub_tri[t];
        const Vec2 p[3] = {cpos(ct, x, xv, q[0]), cpos(ct, x, xv, q[1]), cpos(ct, x, xv, q[2])};
        // bounds of the sub-triangle first: one min/max per sub-triangle on the chains
        lx = std::min(lx, std::min(p[0].x, std::min(p[1].x, p[2].x)));
        hx = std::max(hx, std::max(p[0].x, std::max(p[1].x, p[2].x)));
        ly = std::min(ly, std::min(p[0].y, std::min(p[1].y, p[2].y)));
        hy = std::max(hy, std::max(p[0].y, std::max(p[1].y, p[2].y)));
        const Real a2 = std::abs(cross(p[1] - p[0], p[2] - p[0]));  // as in evaluate_pair
        nonzero &= a2 > 0;                                          // false for NaN
        amin = std::min(amin, a2);
    }
    return finish_box(lx, ly, hx, hy, amin, nonzero);
}

}  // namespace

void body_boxes_reference(const ContactTopology& ct, const Vec2* x, const Vec2* xv, BodyBox* box,
                          int32_t nbodies) {
    for (BodyId b = 0; b < nbodies; ++b)
        box[b] = reference_box(ct, x, xv, b);
}

namespace {

// body_boxes() for the bodies list[0 .. count) (every body when list is nullptr)
void boxes_of(const ContactTopology& ct, const Vec2* x, const Vec2* xv, BodyBox* box,
              int32_t nbodies, const BodyId* list, int32_t count) {
    constexpr Real inf = std::numeric_limits<Real>::infinity();
    const bool compact = ct.body_cnode_begin.size() == static_cast<size_t>(nbodies) + 1 &&
                         ct.sub_local.size() == ct.sub_tri.size();
    const NodeId* cnode = ct.body_cnode.data();
    const NodeId nreal_nodes = ct.num_real_nodes;
    // bodies are independent: shared among the threads when called in a parallel region
#pragma omp for schedule(static)
    for (int32_t entry = 0; entry < count; ++entry) {
        const BodyId b = list != nullptr ? list[entry] : entry;
        const int32_t nb = compact ? ct.body_cnode_begin[b] : 0;
        const int32_t nn = compact ? ct.body_cnode_begin[b + 1] - nb : kBoxLocalNodes + 1;
        if (nn > kBoxLocalNodes) {
            box[b] = reference_box(ct, x, xv, b);
            continue;
        }
        const int32_t nr = ct.body_cnode_nreal[b];
        Real lx, ly, hx, hy, amin;
        bool nonzero;
#ifdef __SSE2__
        // (x, y) lanes: one min and one max per node; a NaN lane may give another bound than
        // std::min, but a NaN position makes an area NaN and the box infinite either way
        __m128d p[kBoxLocalNodes];  // no initialisation
        __m128d lo = _mm_set1_pd(inf), hi = _mm_set1_pd(-inf);
        for (int32_t k = 0; k < nr; ++k) {
            p[k] = _mm_loadu_pd(&x[cnode[nb + k]].x);
            lo = _mm_min_pd(lo, p[k]);
            hi = _mm_max_pd(hi, p[k]);
        }
        for (int32_t k = nr; k < nn; ++k) {
            p[k] = _mm_loadu_pd(&xv[cnode[nb + k] - nreal_nodes].x);
            lo = _mm_min_pd(lo, p[k]);
            hi = _mm_max_pd(hi, p[k]);
        }
        const __m128d abs_mask = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffffLL));
        __m128d am = _mm_set_sd(inf), ok = _mm_castsi128_pd(_mm_set1_epi64x(-1));
        for (int32_t t = ct.body_sub_begin[b]; t < ct.body_sub_begin[b + 1]; ++t) {
            const auto& q = ct.sub_local[t];
            const __m128d e1 = _mm_sub_pd(p[q[1]], p[q[0]]), e2 = _mm_sub_pd(p[q[2]], p[q[0]]);
            // (e1.x e2.y, e1.y e2.x), then their difference: cross(p1 - p0, p2 - p0) exactly
            const __m128d m = _mm_mul_pd(e1, _mm_shuffle_pd(e2, e2, 1));
            const __m128d a2 = _mm_and_pd(_mm_sub_sd(m, _mm_unpackhi_pd(m, m)), abs_mask);
            ok = _mm_and_pd(ok, _mm_cmpgt_sd(a2, _mm_setzero_pd()));  // false for NaN
            am = _mm_min_sd(a2, am);  // a2 < am ? a2 : am = std::min(am, a2)
        }
        lx = _mm_cvtsd_f64(lo);
        ly = _mm_cvtsd_f64(_mm_unpackhi_pd(lo, lo));
        hx = _mm_cvtsd_f64(hi);
        hy = _mm_cvtsd_f64(_mm_unpackhi_pd(hi, hi));
        amin = _mm_cvtsd_f64(am);
        nonzero = (_mm_movemask_pd(ok) & 1) != 0;
#else
        // the positions, read once
        Real px[kBoxLocalNodes], py[kBoxLocalNodes];
        lx = inf, ly = inf, hx = -inf, hy = -inf, amin = inf;
        for (int32_t k = 0; k < nr; ++k) {
            const Vec2 q = x[cnode[nb + k]];
            px[k] = q.x;
            py[k] = q.y;
        }
        for (int32_t k = nr; k < nn; ++k) {
            const Vec2 q = xv[cnode[nb + k] - nreal_nodes];
            px[k] = q.x;
            py[k] = q.y;
        }
        for (int32_t k = 0; k < nn; ++k) {
            lx = std::min(lx, px[k]);
            hx = std::max(hx, px[k]);
            ly = std::min(ly, py[k]);
            hy = std::max(hy, py[k]);
        }
        nonzero = true;
        for (int32_t t = ct.body_sub_begin[b]; t < ct.body_sub_begin[b + 1]; ++t) {
            const auto& q = ct.sub_local[t];
            // cross(p1 - p0, p2 - p0) of evaluate_pair, the same operations
            const Real e1x = px[q[1]] - px[q[0]], e1y = py[q[1]] - py[q[0]];
            const Real e2x = px[q[2]] - px[q[0]], e2y = py[q[2]] - py[q[0]];
            const Real a2 = std::abs(cross(Vec2{e1x, e1y}, Vec2{e2x, e2y}));
            nonzero &= a2 > 0;  // false for NaN
            amin = std::min(amin, a2);
        }
#endif
        box[b] = finish_box(lx, ly, hx, hy, amin, nonzero);
    }
}

}  // namespace

void body_boxes(const ContactTopology& ct, const Vec2* x, const Vec2* xv, BodyBox* box,
                int32_t nbodies) {
    boxes_of(ct, x, xv, box, nbodies, nullptr, nbodies);
}

namespace {

// The contactor bodies of the candidate pairs of cand, ascending, into list (mark: per-body
// scratch): with owner, only the pairs whose target node the process rank owns (a distributed
// run: ContactShare::box_bodies; its candidates may still hold every process's pairs after a
// restore); without, every pair (one-process runs: ContactState::box_bodies; the narrow phase
// reads no other box, so the others are not computed: on a sparse particle raster most bodies
// have no candidate pair; its mark and list are sized at init: no allocation in the step).
void list_contactors(const Model& m, const ContactTopology& ct, const Candidates& cand,
                     const int32_t* owner, int32_t rank, std::vector<uint8_t>& mark,
                     std::vector<BodyId>& list) {
    mark.assign(static_cast<size_t>(m.num_bodies()), 0);
    for (size_t pr = 0; pr < cand.node.size(); ++pr) {
        if (owner == nullptr || owner[target_node(ct, cand.node[pr])] == rank)
            mark[static_cast<size_t>(cand.body[pr])] = 1;
    }
    list.clear();
    for (BodyId b = 0; b < m.num_bodies(); ++b) {
        if (mark[static_cast<size_t>(b)]) list.push_back(b);
    }
}

// The field of contactor sub-triangle t at x (eq. 3), extended linearly beyond t: its
// barycentric coordinates N (negative outside t) and vertices pt; NaN for a degenerate t.
Real extended_field(const Model& m, const ContactTopology& ct, const Vec2* xc, const Vec2* xv,
                    int32_t t, Vec2 x, Real N[3], Vec2 pt[3]) {
    const auto& q = ct.sub_tri[t];
    for (int k = 0; k < 3; ++k)
        pt[k] = cpos(ct, xc, xv, q[k]);
    FieldSample fs;
    Real inv;
    if (!barycentric(pt[0], pt[1], pt[2], x, fs.N, inv))
        return std::numeric_limits<Real>::quiet_NaN();
    const Real dist[3] = {ct.node_dist[q[0]], ct.node_dist[q[1]], ct.node_dist[q[2]]};
    evaluate_field(m.contact.algorithm, ct, t, pt, dist, inv, fs);
    for (int k = 0; k < 3; ++k)
        N[k] = fs.N[k];
    return fs.d;
}

// Locate rule of a pair with history on a contactor with fracture (theory eq. 9.28): the last
// sub-triangle while it still contains x_j; else, of the candidates that contain x_j, the one
// whose field there is closest to the last sub-triangle's (extended linearly), ties to the larger
// min N_i. Across a crack the faces' triangles overlap and their fields disagree: the rule of the
// largest min N_i would switch faces inside the overlap, the force jumping to the other face's
// gradient (often opposite); each such switch costs the trapezoid rule about |f| |dx| of energy.
// A C0 neighbour (same face) agrees with the extended field and is kept. Returns the chosen
// sub-triangle and rewrites N and pb; without history (or in a rebuild step of the pair's bodies,
// whose sub-triangle ids changed) returns best unchanged. Where it moves the pair away from its
// last sub-triangle, d_last is that sub-triangle's field at x_j (what eq. 9.27 continues from);
// NaN otherwise.
[[gnu::noinline]] int32_t coherent_locate(const Model& m, const ContactTopology& ct,
                                          const ContactState& cs, const Vec2* xc, const Vec2* xv,
                                          const ActiveContact* hist, Vec2 xj, BodyId c, int32_t pr,
                                          int32_t best, Real N[3], Vec2 pb[3], Real& d_last) {
    d_last = std::numeric_limits<Real>::quiet_NaN();
    if (hist == nullptr) return best;
    const int32_t sb = ct.body_sub_begin[static_cast<size_t>(c)];
    const int32_t nsub = ct.body_sub_begin[static_cast<size_t>(c) + 1] - sb;
    if (hist->h.sub < 0 || hist->h.sub >= nsub || sb + hist->h.sub == best) return best;
    const int32_t last = sb + hist->h.sub;
    Real Nl[3];
    Vec2 pl[3];
    const Real dl = extended_field(m, ct, xc, xv, last, xj, Nl, pl);
    if (!(dl == dl)) return best;  // degenerate: keep the plain rule
    if (std::min({Nl[0], Nl[1], Nl[2]}) >= -kLocateEps) {
        for (int k = 0; k < 3; ++k) {
            N[k] = Nl[k];
            pb[k] = pl[k];
        }
        return last;
    }
    // (the last sub-triangle no longer contains x_j, so it is not picked below)
    d_last = dl;
    int32_t pick = best;
    Real pick_gap = std::numeric_limits<Real>::infinity(), pick_min = -kLocateEps;
    for (int32_t k = cs.cand.begin[pr]; k < cs.cand.begin[pr + 1]; ++k) {
        const int32_t t = cs.cand.tri[k];
        Real Nt[3];
        Vec2 pt[3];
        const Real d = extended_field(m, ct, xc, xv, t, xj, Nt, pt);
        const Real mn = std::min({Nt[0], Nt[1], Nt[2]});
        if (!(d == d) || mn < -kLocateEps) continue;
        const Real gap = std::abs(d - dl);
        if (gap < pick_gap || (gap == pick_gap && mn >= pick_min)) {
            pick = t;
            pick_gap = gap;
            pick_min = mn;
            for (int i = 0; i < 3; ++i) {
                N[i] = Nt[i];
                pb[i] = pt[i];
            }
        }
    }
    return pick;
}

// The second part of evaluate_pair: field and law of a pair whose node lies in sub-triangle best
// (vertices pb, barycentric coordinates N). It was out of line while the locate loop tested every
// candidate of every pair; since temporal coherence most pairs in contact skip that loop, and as
// a call (19 arguments) it cost ~22 instructions a pair in contact (issue #16; inlined: -1.7 % of
// the saturated pack's step, callgrind).
[[gnu::always_inline]] inline int32_t contact_at(const Model& m, const ContactTopology& ct,
                                                 const ContactState& cs, const Vec2* xc,
                                                 const Vec2* xv, const Vec2* v, const Vec2* vv,
                                                 Real dt, NodeId j, Vec2 xj, BodyId c, int32_t pr,
                                                 int32_t best, const Real N_in[3],
                                                 const Vec2 pb_in[3], Real inv, PairResult& out,
                                                 bool hist_known, const ActiveContact* hist_in) {
    const ContactModel& cm = m.contact;
    const BodyId bt = m.node_body[target_node(ct, j)];
    // a contactor with fracture: the history first, for the locate rule of a pair with history
    // (eq. 9.28; not in a rebuild step of the pair's bodies, whose sub-triangle ids changed)
    const bool frac = !ct.body_self.empty() && ct.body_self[static_cast<size_t>(c)] != 0;
    const ActiveContact* hist = nullptr;
    Real d_last = std::numeric_limits<Real>::quiet_NaN();  // eq. 9.27, set by coherent_locate()
    Real Nf[3];
    Vec2 pf[3];
    const Real* N = N_in;
    const Vec2* pb = pb_in;
    // the history: the caller's lookup where it made one (evaluate_pair() with a chunk's
    // cursor, before the locate loop), else a search of the whole list
    const auto history = [&]() __attribute__((always_inline))->const ActiveContact* {
        return hist_known ? hist_in : find_pair(cs.active, j, c);
    };
    if (frac) {
        hist = history();
        for (int k = 0; k < 3; ++k) {
            Nf[k] = N_in[k];
            pf[k] = pb_in[k];
        }
        if (!rebased(cs, c, bt))
            best = coherent_locate(m, ct, cs, xc, xv, hist, xj, c, pr, best, Nf, pf, d_last);
        N = Nf;
        pb = pf;
        inv = inverse_double_area(pb[0], pb[1], pb[2]);  // (best may have changed)
    }
    FieldSample fs;
    fs.N[0] = N[0];
    fs.N[1] = N[1];
    fs.N[2] = N[2];
    const auto& q = ct.sub_tri[best];
    const Real dist[3] = {ct.node_dist[q[0]], ct.node_dist[q[1]], ct.node_dist[q[2]]};
    evaluate_field(cm.algorithm, ct, best, pb, dist, inv, fs);
    if (!(fs.d > 0)) return -1;

    // history of the pair in the previous active list (only pairs in contact come here, a few
    // per thousand candidates; a contactor with fracture looked it up above)
    if (!frac) hist = history();
    const bool has_hist = hist != nullptr;
    out.hist = has_hist ? static_cast<int32_t>(hist - cs.active.data()) : -1;

    // the law (eqs. 5-19) with v_r = v_c - v_j, v_c = sum N_i v_i (eq. 13)
    const ContactParams& p = pair_parameters(cm, m.bodies[c].material, m.bodies[bt].material);
    const Real scale = target_scale(ct, j);  // m_j / mbar (eq. 19), l_j / lbar, or eq. 6.19
    Vec2 vc;                                 // (welded contactor: sector-mean velocities, eq. 6.23)
    for (int k = 0; k < 3; ++k)
        vc += fs.N[k] *
              (q[k] < ct.num_real_nodes ? weld_mean(ct, v, q[k]) : vv[q[k] - ct.num_real_nodes]);
    out.h = has_hist ? hist->h : PairHistory{};
    // birth depth (theory eq. 9.25): a self pair (rule X) starts from the depth it is found at,
    // which a break's rebuild, or the node's own-sector triangles it came from, revealed rather
    // than a motion against the field made; d0 only falls, to d, where the law's force and
    // potential are zero. Pairs of two bodies keep d0 = 0 (the law sees d, bitwise).
    // Through a rebuild of the topology of c or of the target's body (eq. 9.26) every pair
    // continues from the law depth the old topology gives at the same positions x^n (0 if the
    // old one did not locate it): the rebuild changes the field, not the pair's energy.
    if (rebased(cs, c, bt)) {
        const RebaseEntry* e = find_pair(cs.rebase, j, c);
        out.h.d0 = fs.d - (e != nullptr ? e->d_law : 0.0);
    } else if (!has_hist) {
        if (c == bt) out.h.d0 = fs.d;
    } else {
        // A body with fracture: where the pair moves to another sub-triangle, the law depth
        // continues from the one the last sub-triangle's field (extended linearly) gives at x_j
        // (eq. 9.27; d_last from coherent_locate(), NaN where the sub-triangle did not change).
        // Across a crack the two faces' fields disagree; a target in the overlap of their
        // triangles would otherwise jump between them with no work done. Where the field is C0
        // (intact body) the two agree but for the kink's O(motion of a step).
        if (d_last == d_last) out.h.d0 += fs.d - d_last;
        if (out.h.d0 > fs.d) out.h.d0 = fs.d;
    }
    // (read by eqs. 9.27-9.28 of contactors with fracture, and as the first guess of
    // evaluate_pair()'s locate loop for the others)
    out.h.sub = best - ct.body_sub_begin[static_cast<size_t>(c)];
    const Real d_law = fs.d - out.h.d0;  // (= d exactly where d0 = 0)
    const LawResult r =
        contact_law(p, d_law, fs.grad, vc - target_point(ct, v, j), scale, dt, out.h);

    // depth diagnostics: d relative to the local layer thickness
    out.h.depth_ratio = fs.layer > 0 ? fs.d / fs.layer : 1.0;
    out.tri = best;
    out.N[0] = fs.N[0];
    out.N[1] = fs.N[1];
    out.N[2] = fs.N[2];
    out.f = r.f;
    out.stored = r.stored;
    out.dissipated = r.dissipated;
    return best;
}

// Narrow phase and law of candidate pair pr (spec §4.5-1 to -7): reads positions, velocities
// and the previous history (looked up in cs.active, sorted by (node, body)); returns the located
// sub-triangle, or -1 when the pair is not in contact, and writes out only in contact.
// Independent of every other pair, so the pairs can be evaluated in any order and on any thread.
//
// Early reject (docs/performance.md): in the contact-heavy pack only ~0.3 % of the candidate
// pairs touch, so the locate loop first tests the signs of the three edge functions
// c_i = cross(p_{i+1} - x, p_{i+2} - x) (N_i = c_i / 2A, eq. 4) against the signed area without
// a division; only a point within a margin of the triangle goes on to barycentric(), which
// computes the same c_i, so the accepted triangle and N are bitwise those of the full test.
int32_t evaluate_pair(const Model& m, const ContactTopology& ct, const ContactState& cs,
                      const Vec2* x, const Vec2* xc, const Vec2* v, const Vec2* xv, const Vec2* vv,
                      Real dt, int32_t pr, PairResult& out, size_t* cursor = nullptr) {
    const NodeId j = cs.cand.node[pr];

    // locate x_j: the candidate sub-triangle with the largest min N_i >= -eps
    const Vec2 xj = target_point(ct, x, j);
    int32_t best = -1;
    Real best_min = -kLocateEps;
    Real bN[3], binv = 0;
    Vec2 pb[3];
    const Vec2* xa = cs.xa.data();  // (= cpos(ct, xc, xv, i) at contact id i)
    const int32_t k0 = cs.cand.begin[pr], k1 = cs.cand.begin[pr + 1];
    // the test of candidate sub-triangle t (the larger min N_i wins, ties to the later one)
    const auto test = [&](int32_t t) __attribute__((always_inline)) {
        const auto& q = ct.sub_tri[t];
        const Vec2 p[3] = {xa[q[0]], xa[q[1]], xa[q[2]]};
        // N_i = c_i * (1 / a2) with |rounding| < 1e-15 relative, so any c_i beyond
        // kRejectMargin |a2| on the outer side gives N_i < -kLocateEps: rejected either way
        // (NaN and a2 == 0 fall through to barycentric(), which decides as before)
        const Real a2 = cross(p[1] - p[0], p[2] - p[0]);
        const Real c0 = cross(p[1] - xj, p[2] - xj), c1 = cross(p[2] - xj, p[0] - xj),
                   c2 = cross(p[0] - xj, p[1] - xj);
        const Real lim = kRejectMargin * std::abs(a2);
        if (a2 > 0 ? std::min({c0, c1, c2}) < -lim : std::max({c0, c1, c2}) > lim) return;
        Real N[3];
        Real inv;
        if (!barycentric(p[0], p[1], p[2], xj, N, inv)) return;
        const Real mn = std::min({N[0], N[1], N[2]});
        if (mn >= best_min) {
            best_min = mn;
            best = t;
            binv = inv;
            bN[0] = N[0];
            bN[1] = N[1];
            bN[2] = N[2];
            pb[0] = p[0];
            pb[1] = p[1];
            pb[2] = p[2];
        }
    };
    // temporal coherence (issue #16): a pair with history tests its last sub-triangle first.
    // If that one is a candidate and holds x_j with every N_i > kCoherentMin, the full test
    // would pick it too: the sub-triangles of a body without fracture do not overlap, so x_j
    // lies outside every other one, by a margin that rounding cannot close (their min N_i is
    // below 0 by about the same share of their height), so none reaches min N_i >= kCoherentMin;
    // best, N and the vertices are those the loop computes for it. Otherwise the full test.
    // (Contactors with fracture: their crack faces' sub-triangles overlap, coherent_locate()
    // applies eq. 9.28 after the plain rule.)
    // (the history looked up here is handed to contact_at())
    bool located = false;
    bool hist_known = false;
    const ActiveContact* h = nullptr;
    if (cursor != nullptr) {
        const BodyId c = cs.cand.body[pr];
        h = find_pair_from(cs.active, *cursor, j, c);
        hist_known = true;
        if (ct.body_self.empty() || ct.body_self[static_cast<size_t>(c)] == 0) {
            const int32_t sb = ct.body_sub_begin[static_cast<size_t>(c)];
            if (h != nullptr && h->h.sub >= 0 &&
                h->h.sub < ct.body_sub_begin[static_cast<size_t>(c) + 1] - sb) {
                const int32_t last = sb + h->h.sub;
                int32_t k = k0;
                while (k < k1 && cs.cand.tri[k] != last)
                    ++k;
                if (k < k1) {  // (a candidate)
                    test(last);
                    located = best >= 0 && best_min > kCoherentMin;
                    if (!located) {
                        best = -1;
                        best_min = -kLocateEps;
                    }
                }
            }
        }
    }
    if (!located) {
        for (int32_t k = k0; k < k1; ++k)
            test(cs.cand.tri[k]);
    } else if constexpr (kAssertsEnabled) {
        // (assert builds: the full test picks the same sub-triangle)
        [[maybe_unused]] const int32_t kept = best;
        best = -1;
        best_min = -kLocateEps;
        for (int32_t k = k0; k < k1; ++k)
            test(cs.cand.tri[k]);
        FDEM_ASSERT(best == kept,
                    "temporal coherence kept a sub-triangle the full test does not pick");
    }
    if (best < 0) return -1;
    return contact_at(m, ct, cs, xc, xv, v, vv, dt, j, xj, cs.cand.body[pr], pr, best, bN, pb, binv,
                      out, hist_known, h);
}

// Theory eq. 9.26: before a rebuild of the bodies `dirty`, the law depth d - d0 (and the
// normal potential) that the old topology gives every pair touching them at the positions x^n
// of this step, into cs.rebase (sorted by (node, body)); rebase_body flags those bodies and
// rebase_pending makes the next add_contact_forces() continue every such pair from it. The
// broad phase runs on the old topology first (the candidates of the last one may not cover
// x^n); the rebuild sets need_rebuild, so the next contact pass runs it again on the new one.
// Serial, allocates: steps with breaks only.
void probe_law_depths(const Model& m, State& s, std::span<const BodyId> dirty) {
    const ContactTopology& ct = s.topology;
    ContactState& cs = s.contact;
    cs.rebase.clear();
    cs.rebase_body.assign(static_cast<size_t>(m.num_bodies()), 0);
    for (const BodyId b : dirty)
        cs.rebase_body[static_cast<size_t>(b)] = 1;
    cs.rebase_pending = false;  // the probe itself evaluates with the rules of the old topology
    if (ct.num_sub_tris() > 0) {
        update_virtual_nodes(m, s);
        const Vec2* x = s.x.data();
        const Vec2* xc = ct.welded() ? cs.xw.data() : x;
        find_candidates(m, ct, x, xc, cs.xv.data(), cs.cand, cs.broad);
        cs.box_list_valid = false;
        cs.apply_lists.threads = 0;
        fill_contact_positions(ct, cs, xc, nullptr, 0);  // (every contact node: a break step)
        const int32_t npairs = static_cast<int32_t>(cs.cand.node.size());
        PairResult out;
        for (int32_t pr = 0; pr < npairs; ++pr) {
            const NodeId j = cs.cand.node[pr];
            const BodyId c = cs.cand.body[pr];
            const BodyId bt = m.node_body[target_node(ct, j)];
            if (cs.rebase_body[static_cast<size_t>(c)] == 0 &&
                cs.rebase_body[static_cast<size_t>(bt)] == 0)
                continue;
            if (evaluate_pair(m, ct, cs, x, xc, s.v.data(), cs.xv.data(), cs.vv.data(), s.dt, pr,
                              out) < 0)
                continue;
            const ContactParams& p =
                pair_parameters(m.contact, m.bodies[c].material, m.bodies[bt].material);
            const Real spring =
                target_scale(ct, j) * 0.5 * p.tangential_penalty * out.h.s * out.h.s;
            cs.rebase.push_back(RebaseEntry{j, c, out.h.d_prev, out.stored - spring});
        }
    }
    cs.rebase_pending = true;
}

// --- Local apply of a distributed run (issue #15, docs/parallel.md "Local apply") ---
// A pair's forces reach its target (an edge target: both end nodes) and nodes of its contactor
// body (vertices, virtual-node parents, welded copies: pair_span()). A process needs a node's
// force if it owns the node or reads it every step (ContactShare::force_readers), so a pair's
// record goes to the processes that need a node of its contactor body or of its target.

// visit(r) for the owner of node i and every process that reads its force
template <class Visit>
inline void node_ranks(const StepPlan& plan, NodeId i, Visit&& visit) {
    visit(plan.node_owner[static_cast<size_t>(i)]);
    const auto& rd = plan.contact.force_readers;
    if (rd.empty()) return;
    auto it = std::lower_bound(rd.begin(), rd.end(), std::pair<NodeId, int32_t>{i, -1});
    for (; it != rd.end() && it->first == i; ++it)
        visit(it->second);
}

// visit(r) for every process that needs a node the forces of pair (j, c) reach (with repeats)
template <class Visit>
inline void pair_ranks(const ContactTopology& ct, const StepPlan& plan, NodeId j, BodyId c,
                       Visit&& visit) {
    const ContactShare& sh = plan.contact;
    for (int32_t k = sh.body_rank_begin[static_cast<size_t>(c)];
         k < sh.body_rank_begin[static_cast<size_t>(c) + 1]; ++k)
        visit(sh.body_rank[static_cast<size_t>(k)]);
    if (j < ct.num_real_nodes) {
        node_ranks(plan, j, visit);
        return;
    }
    const auto& e = ct.boundary_edges[static_cast<size_t>(j - ct.edge_target_base)];
    node_ranks(plan, e[0], visit);
    node_ranks(plan, e[1], visit);
}

// ContactShare::need and the processes that need each body's nodes: from the plan's owners and
// the force readers only (not the candidates), so once per plan or set of readers
void plan_body_ranks(const Model& m, const StepPlan& plan) {
    const ContactShare& sh = plan.contact;
    const NodeId nn = m.num_nodes();
    const int32_t me = plan.rank;
    const auto& rd = sh.force_readers;
    constexpr uint8_t kBoth = kNeedContact | kNeedForce;
    sh.need.assign(static_cast<size_t>(nn), 0);
    for (NodeId i = 0; i < nn; ++i)
        sh.need[static_cast<size_t>(i)] = plan.node_owner[static_cast<size_t>(i)] == me ? kBoth : 0;
    for (const auto& [i, r] : rd) {
        if (r == me) sh.need[static_cast<size_t>(i)] |= kNeedContact;
    }
    // (a node in f_readers is in force_readers: its contact forces reach the reader)
    for (const auto& [i, r] : sh.f_readers) {
        if (r == me) sh.need[static_cast<size_t>(i)] |= kNeedForce;
    }
    const BodyId nb = m.num_bodies();
    sh.stamp.assign(static_cast<size_t>(plan.procs), -1);
    sh.body_rank_begin.assign(static_cast<size_t>(nb) + 1, 0);
    sh.body_rank.clear();
    sh.body_all.assign(static_cast<size_t>(nb), 0);
    for (BodyId b = 0; b < nb; ++b) {
        const Body& body = m.bodies[static_cast<size_t>(b)];
        const auto add = [&](int32_t r) {
            if (sh.stamp[static_cast<size_t>(r)] == b) return;
            sh.stamp[static_cast<size_t>(r)] = b;
            sh.body_rank.push_back(r);
        };
        for (NodeId i = body.node_begin; i < body.node_end; ++i)
            add(plan.node_owner[static_cast<size_t>(i)]);
        if (!rd.empty()) {
            auto it = std::lower_bound(rd.begin(), rd.end(),
                                       std::pair<NodeId, int32_t>{body.node_begin, -1});
            for (; it != rd.end() && it->first < body.node_end; ++it)
                add(it->second);
        }
        const int32_t first = sh.body_rank_begin[static_cast<size_t>(b)];
        std::sort(sh.body_rank.begin() + first, sh.body_rank.end());
        sh.body_rank_begin[static_cast<size_t>(b) + 1] = static_cast<int32_t>(sh.body_rank.size());
        bool all = true;
        for (NodeId i = body.node_begin; i < body.node_end && all; ++i)
            all = sh.need[static_cast<size_t>(i)] == kBoth;
        sh.body_all[static_cast<size_t>(b)] = all;
    }
    sh.stamp.assign(static_cast<size_t>(plan.procs), -1);  // (free for the records' ticks)
    // (the marks of a one-thread apply, cleared after each use)
    sh.exposed.assign(static_cast<size_t>(nn), 0);
    sh.exposed_body.assign(static_cast<size_t>(m.num_bodies()), 0);
}

// mark[q] = 1 for the other processes the records of plan's candidate pairs may go to; with
// send, also the candidates (ascending) whose record has a destination (another process needs a
// node its forces may reach)
void may_send_marks(const Model& m, const State& s, const StepPlan& plan,
                    std::vector<uint8_t>& mark, std::vector<int32_t>* send = nullptr) {
    const ContactShare& sh = plan.contact;
    if (sh.body_rank_begin.size() != static_cast<size_t>(m.num_bodies()) + 1)
        plan_body_ranks(m, plan);
    const ContactTopology& ct = s.topology;
    const Candidates& cand = s.contact.cand;
    const int32_t me = plan.rank;
    mark.assign(static_cast<size_t>(plan.procs), 0);
    for (size_t pr = 0; pr < cand.node.size(); ++pr) {
        const NodeId j = cand.node[pr];
        if (plan.node_owner[static_cast<size_t>(target_node(ct, j))] != me) continue;
        bool other = false;
        pair_ranks(ct, plan, j, cand.body[pr], [&](int32_t r) {
            mark[static_cast<size_t>(r)] = 1;
            other |= r != me;
        });
        if (send != nullptr && other) send->push_back(static_cast<int32_t>(pr));
    }
    mark[static_cast<size_t>(me)] = 0;
}

// The processes this one may exchange records with until the next broad phase: those its own
// candidate pairs may send to, and those whose candidate pairs may send to it (an all-gather
// of the lists). Collective: every process calls it at the same step (after a broad phase or
// with a new plan).
void plan_record_exchange(const Model& m, const State& s, const StepPlan& plan, const Comm& comm) {
    const ContactShare& sh = plan.contact;
    const int32_t me = plan.rank, procs = plan.procs;
    std::vector<uint8_t> mark;
    sh.send_cand.clear();
    may_send_marks(m, s, plan, mark, &sh.send_cand);
    std::vector<int32_t> to;
    for (int32_t r = 0; r < procs; ++r) {
        if (mark[static_cast<size_t>(r)]) to.push_back(r);
    }
    // [count][ranks...] of every process
    std::vector<char> mine((to.size() + 1) * sizeof(int32_t)), all;
    const int32_t n_to = static_cast<int32_t>(to.size());
    std::memcpy(mine.data(), &n_to, sizeof n_to);
    if (n_to > 0) std::memcpy(mine.data() + sizeof n_to, to.data(), to.size() * sizeof(int32_t));
    comm.allgather_bytes(mine, all);
    std::vector<int32_t> w(all.size() / sizeof(int32_t));
    std::memcpy(w.data(), all.data(), w.size() * sizeof(int32_t));
    size_t at = 0;
    for (int32_t q = 0; q < procs; ++q) {
        const int32_t n = w[at++];
        for (int32_t k = 0; k < n; ++k) {
            if (q != me && w[at + static_cast<size_t>(k)] == me) mark[static_cast<size_t>(q)] = 1;
        }
        at += static_cast<size_t>(n);
    }
    sh.neighbours.clear();
    for (int32_t r = 0; r < procs; ++r) {
        if (mark[static_cast<size_t>(r)]) sh.neighbours.push_back(r);
    }
    const size_t p = static_cast<size_t>(procs);
    sh.send_counts.assign(p, 0);
    sh.send_displs.assign(p, 0);
    sh.dest_valid = true;
}

// The forces of the pairs in contact of a distributed step, part 1: this process's own pairs
// (own_k[p]: the narrow phase's output index of its p-th pair in pair order) go as records to
// the processes that need a node they reach; the records of the others arrive, in pair order per
// source, into sh.rec_node, rec_body and rec_out (sh.records_received of them). Part 2,
// apply_merged(), adds their forces. Collective.
template <class InContact>
void exchange_records(const Model& m, const ContactTopology& ct, const StepPlan& plan,
                      const Comm& comm, State& s, InContact&& in_contact_at,
                      const int32_t* in_contact, const PairResult* out) {
    const ContactShare& sh = plan.contact;
    StepTiming& timing = s.timing;
    if (!sh.dest_valid) {
        timing.mark(StepPhase::ContactApply);
        plan_record_exchange(m, s, plan, comm);
        timing.mark(StepPhase::Communication);
    }
    const NodeId* cand_node = s.contact.cand.node.data();
    const BodyId* cand_body = s.contact.cand.body.data();
    const int32_t me = plan.rank, procs = plan.procs;
    static_assert(kContactRecordBytes % sizeof(double) == 0);
    constexpr int kW = static_cast<int>(kContactRecordBytes / sizeof(double));

    // 1. the destinations of the own pairs in contact that may have one (sh.send_cand, listed
    //    once per broad phase: every other pair reaches only nodes no other process needs), and
    //    the records per destination
    int* send_counts = sh.send_counts.data();
    for (const int32_t q : sh.neighbours)
        send_counts[q] = 0;
    // (the pairs with a destination, sh.dest_pair (their index k in out), and the end of each
    // one's destinations in sh.dest, sh.dest_end; grow-only)
    sh.dest.clear();
    sh.dest_pair.clear();
    sh.dest_end.clear();
    int64_t* stamp = sh.stamp.data();
    for (const int32_t pr : sh.send_cand) {
        const int32_t k = in_contact_at(pr);
        if (k < 0) continue;  // (not in contact)
        const size_t before = sh.dest.size();
        const int64_t tick = ++sh.tick;
        pair_ranks(ct, plan, cand_node[pr], cand_body[pr], [&](int32_t r) {
            if (r == me || stamp[r] == tick) return;
            stamp[r] = tick;
            FDEM_ASSERT(std::binary_search(sh.neighbours.begin(), sh.neighbours.end(), r),
                        "a contact record for a process that is not a neighbour");
            sh.dest.push_back(r);
            ++send_counts[r];
        });
        if (sh.dest.size() > before) {
            sh.dest_pair.push_back(k);
            sh.dest_end.push_back(static_cast<int32_t>(sh.dest.size()));
        }
    }
    sh.records_sent = static_cast<int64_t>(sh.dest.size());

    // 2. the records, one message to and from each neighbour (its length tells the count)
    int n_send = 0;
    for (int32_t q = 0; q < procs; ++q) {
        send_counts[q] *= kW;
        sh.send_displs[static_cast<size_t>(q)] = n_send;
        n_send += send_counts[q];
    }
    resize_grow(sh.send, static_cast<size_t>(n_send));
    // (the fill position of each destination: its displacement, advanced per record)
    resize_grow(sh.heads, 2 * static_cast<size_t>(procs));  // (the merge below: 2 per run)
    int32_t* at = sh.heads.data();
    for (int32_t q = 0; q < procs; ++q)
        at[q] = sh.send_displs[static_cast<size_t>(q)];
    for (size_t i = 0, d0 = 0; i < sh.dest_pair.size(); ++i) {
        const int32_t k = sh.dest_pair[i];
        const int32_t pr = in_contact[k];
        const size_t d1 = static_cast<size_t>(sh.dest_end[i]);
        for (size_t d = std::exchange(d0, d1); d < d1; ++d) {
            const int32_t q = sh.dest[d];
            const PairResult& o = out[k];
            ContactRecord rec;
            rec.node = cand_node[pr];
            rec.body = cand_body[pr];
            rec.tri = o.tri;
            rec.N[0] = o.N[0];
            rec.N[1] = o.N[1];
            rec.N[2] = o.N[2];
            rec.f = o.f;
            std::memcpy(sh.send.data() + at[q], &rec, sizeof rec);
            at[q] += kW;
        }
    }
    timing.mark(StepPhase::ContactApply);
    comm.exchange_sized(sh.neighbours, sh.send.data(), sh.send_counts, sh.send_displs, sh.recv,
                        sh.recv_counts, sh.recv_displs);
    timing.mark(StepPhase::Communication);
    int n_recv = 0;
    for (const int32_t q : sh.neighbours)
        n_recv += sh.recv_counts[static_cast<size_t>(q)];
    const size_t n_in = static_cast<size_t>(n_recv / kW);
    sh.records_received = static_cast<int64_t>(n_in);
    resize_grow(sh.rec_node, n_in);
    resize_grow(sh.rec_body, n_in);
    resize_grow(sh.rec_out, n_in);
    NodeId* rnode = sh.rec_node.data();
    BodyId* rbody = sh.rec_body.data();
    PairResult* rout = sh.rec_out.data();
    {
        const char* r = reinterpret_cast<const char*>(sh.recv.data());
        for (size_t k = 0; k < n_in; ++k, r += kContactRecordBytes) {
            ContactRecord rec;
            std::memcpy(&rec, r, sizeof rec);
            rnode[k] = rec.node;
            rbody[k] = rec.body;
            // (what the adds read: tri, N and f; the rest of a PairResult stays with the owner)
            PairResult& o = rout[k];
            o.tri = rec.tri;
            o.N[0] = rec.N[0];
            o.N[1] = rec.N[1];
            o.N[2] = rec.N[2];
            o.f = rec.f;
        }
    }
}

// The received records' nodes (visit_pair_forces(); real nodes) marked in sh.exposed, and their
// bodies in sh.exposed_body; value 1 to mark, 0 to clear the marks again.
void mark_exposed(const Model& m, const ContactTopology& ct, const ContactShare& sh,
                  uint8_t value) {
    const size_t n_in = static_cast<size_t>(sh.records_received);
    uint8_t* node = sh.exposed.data();
    uint8_t* body = sh.exposed_body.data();
    const BodyId* node_body = m.node_body.data();
    for (size_t r = 0; r < n_in; ++r) {
        visit_pair_forces(ct, sh.rec_node[r], sh.rec_out[r], [&](NodeId i, Vec2) {
            node[i] = value;
            body[node_body[i]] = value;
        });
    }
}

// Part 2 of the forces of a distributed step (after exchange_records()): the pairs own_k[0 ..
// n_own) of this process (all its pairs in contact, in pair order) and the received records,
// merged in pair order ((node, body): each pair has one owner, so the keys are distinct); their
// forces are added to the nodes this process needs, in that order: every such node receives the
// adds of the serial loop in its order. With `exposed` (a one-thread apply whose bookkeeping
// added the own pairs' forces at every node no received record reaches, in pair order), own_k
// lists only the own pairs that reach a node a received record reaches (sh.exposed), and the
// forces go to those nodes only; all_k[0 .. n_all) is every own pair (the nodes written).
void apply_merged(const Model& m, const ContactTopology& ct, const StepPlan& plan, State& s,
                  const int32_t* own_k, int32_t n_own, const int32_t* all_k, int32_t n_all,
                  bool exposed, const int32_t* in_contact, const PairResult* out) {
    const ContactShare& sh = plan.contact;
    constexpr int kW = static_cast<int>(kContactRecordBytes / sizeof(double));
    const NodeId* cand_node = s.contact.cand.node.data();
    const BodyId* cand_body = s.contact.cand.body.data();
    const size_t n_in = static_cast<size_t>(sh.records_received);
    const NodeId* rnode = sh.rec_node.data();
    const BodyId* rbody = sh.rec_body.data();
    const PairResult* rout = sh.rec_out.data();
    int32_t* at = sh.heads.data();

    // 3. the merge in pair order: the own records and one sorted run per source (received
    //    in rank order: run q is [recv_displs[q], + recv_counts[q]) / kW)
    const size_t total = static_cast<size_t>(n_own) + n_in;
    resize_grow(sh.order, total);
    int32_t* order = sh.order.data();
    // runs [head, end) of the received records, as pairs in sh.heads (reused)
    int32_t nruns = 0;
    for (const int32_t q : sh.neighbours) {
        const size_t u = static_cast<size_t>(q);
        if (sh.recv_counts[u] == 0) continue;
        at[2 * nruns] = sh.recv_displs[u] / kW;
        at[2 * nruns + 1] = (sh.recv_displs[u] + sh.recv_counts[u]) / kW;
        ++nruns;
    }
    // (the keys are distinct: each pair has one owner. The own records below the smallest
    // received head go in one tight loop; most records are own, the received ones lie along
    // the partition's boundary)
    {
        int32_t p = 0;  // the next own record
        size_t idx = 0;
        while (idx < total) {
            int32_t best = -1;  // the run of the smallest head key
            NodeId bj = 0;
            BodyId bc = 0;
            for (int32_t r = 0; r < nruns; ++r) {
                const int32_t h = at[2 * r];
                if (h == at[2 * r + 1]) continue;
                if (best < 0 || rnode[h] < bj || (rnode[h] == bj && rbody[h] < bc)) {
                    best = r;
                    bj = rnode[h];
                    bc = rbody[h];
                }
            }
            if (best < 0) {  // every received record placed: the rest are own
                std::copy(own_k + p, own_k + n_own, order + idx);
                break;
            }
            for (; p < n_own; ++p) {
                const int32_t pr = in_contact[own_k[p]];
                const NodeId j = cand_node[pr];
                if (j > bj || (j == bj && cand_body[pr] > bc)) break;
                order[idx++] = own_k[p];
            }
            order[idx++] = -1 - at[2 * best]++;
        }
    }

    // 4. the forces, to the nodes this process needs, in pair order (threads: each to its own
    //    range of nodes, as in the one-process apply)
    const uint8_t* need = sh.need.data();
    Vec2* const f = s.f.data();
    Vec2* const fc = s.f_contact.data();
    const auto record = [&](int32_t code, NodeId& j, BodyId& c) -> const PairResult& {
        if (code >= 0) {
            const int32_t pr = in_contact[code];
            j = cand_node[pr];
            c = cand_body[pr];
            return out[code];
        }
        const size_t r = static_cast<size_t>(-1 - code);
        j = rnode[r];
        c = rbody[r];
        return rout[r];
    };
    // (the nodes they reach, needed here or not: a superset of the f_contact entries written;
    // a set, so in any order)
    note_contact_force_nodes(s.contact, static_cast<size_t>(n_all) + n_in, [&](auto&& visit) {
        for (int32_t p = 0; p < n_all; ++p) {
            const int32_t k = all_k[p];
            visit_pair_forces(ct, cand_node[in_contact[k]], out[k], visit);
        }
        for (size_t r = 0; r < n_in; ++r)
            visit_pair_forces(ct, rnode[r], rout[r], visit);
    });
    if (exposed) {
        // (the nodes a received record reaches; the others have their forces from the
        // bookkeeping)
        const uint8_t* ex = sh.exposed.data();
        for (size_t idx = 0; idx < total; ++idx) {
            NodeId j;
            BodyId c;
            const PairResult& o = record(order[idx], j, c);
            visit_pair_forces(ct, j, o, [f, fc, need, ex](NodeId i, Vec2 fi) {
                if (ex[i]) add_needed(f, fc, need, i, fi);
            });
        }
        return;
    }
    // every node the pair reaches is needed here: the one-process add (no test per node)
    const uint8_t* all = sh.body_all.data();
    const int max_threads = omp_get_max_threads();
    if (max_threads < 2 || total < static_cast<size_t>(kMinParallelApply)) {
        for (size_t idx = 0; idx < total; ++idx) {
            NodeId j;
            BodyId c;
            const PairResult& o = record(order[idx], j, c);
            if (all_needed(ct, need, all, j, c)) {
                add_pair_forces(ct, f, fc, j, o);
                continue;
            }
            visit_pair_forces(ct, j, o,
                              [f, fc, need](NodeId i, Vec2 fi) { add_needed(f, fc, need, i, fi); });
        }
        return;
    }
    // Thread t adds at the real nodes [thread_lo[t], thread_lo[t + 1]): ranges of about equal
    // numbers of records, by quantiles of a sample of the records' nodes (a target, or an edge
    // target's smaller node: edge targets come after every real one in pair order). Equal
    // ranges of the whole model's nodes (as the one-process apply) gave a process's nodes,
    // which a spatial partition puts in few of those ranges, mostly to one thread: 84-90 % of
    // the adds (docs/parallel.md, stop 53). Any partition of the nodes gives the same bits:
    // each node is one thread's, and every thread adds in the merged order.
    const NodeId nn = ct.num_real_nodes;
    resize_grow(sh.thread_lo, static_cast<size_t>(max_threads) + 1);
    quantile_node_ranges<512>(
        ct, total, max_threads,
        [&](size_t i) {
            NodeId j;
            BodyId c;
            record(order[i], j, c);
            return j;
        },
        sh.thread_lo.data());
    const NodeId* bounds = sh.thread_lo.data();
#pragma omp parallel num_threads(max_threads)
    {
        const int nt = omp_get_num_threads(), t = omp_get_thread_num();
        // (fewer threads than asked: the last one takes the rest)
        const NodeId lo = bounds[t];
        const NodeId hi = t + 1 == nt ? nn : bounds[t + 1];
        for (size_t idx = 0; idx < total; ++idx) {
            NodeId j;
            BodyId c;
            const PairResult& o = record(order[idx], j, c);
            NodeId a, b;
            pair_span(m, ct, j, c, a, b);
            if (b < lo || a >= hi) continue;
            visit_pair_forces(ct, j, o, [f, fc, need, lo, hi](NodeId i, Vec2 fi) {
                if (i >= lo && i < hi) add_needed(f, fc, need, i, fi);
            });
        }
    }
}

// The node ranges, segments and foreign lists of the apply with T threads (ContactApplyLists) for
// the candidates cand. The candidates ascend by target, real nodes first, then edge targets. The
// T node ranges [range_lo[u], range_lo[u + 1]) hold about equal numbers of candidates: their
// bounds are quantiles of a sample of the candidates' nodes (a target, or an edge target's
// smaller node). (Equal shares of the node ids gave one thread every pair where the contacts
// lie in part of the ids, e.g. a pack beside a large continuum body: 2 threads applied in 1.08
// s what one did in 1.15 s, docs/performance.md, stop 53.) Segment u < T holds the candidates
// whose real target lies in node range u; segment T + u the edge targets whose edge's smaller
// node (its running maximum: the segments must be runs) lies in range u. Thread u runs segments u
// and T + u. A candidate whose force span (pair_span()) leaves its thread's range is on the foreign
// list of every other range the span meets, in ascending order. Serial; run by the first apply with
// T threads after the candidates changed.
void build_apply_lists(const Model& m, const ContactTopology& ct, const Candidates& cand, int T,
                       ContactApplyLists& L) {
    const int32_t np = static_cast<int32_t>(cand.node.size());
    const NodeId nr = ct.num_real_nodes;
    const size_t ts = static_cast<size_t>(T);
    L.range_lo.resize(ts + 1);
    quantile_node_ranges<1024>(
        ct, static_cast<size_t>(np), T, [&](size_t i) { return cand.node[i]; }, L.range_lo.data());
    const auto range_of = [&](NodeId i) {  // the range holding real node i (ranges may be empty)
        const NodeId* b = L.range_lo.data();
        return static_cast<int>(std::upper_bound(b + 1, b + T, i) - (b + 1));
    };
    L.first.assign(2 * ts + 1, np);
    L.inside.resize(static_cast<size_t>(np));
    L.foreign_begin.assign(ts + 1, 0);
    int last = -1;       // the segment of the previous candidate
    NodeId edge_at = 0;  // the running maximum of the edge targets' smaller nodes
    const auto segment = [&](NodeId j) {
        if (j < nr) return range_of(j);
        edge_at = std::max(edge_at, target_low_node(ct, j));
        return T + range_of(edge_at);
    };
    for (int32_t pr = 0; pr < np; ++pr) {
        const NodeId j = cand.node[static_cast<size_t>(pr)];
        const int sg = segment(j);
        FDEM_ASSERT(sg >= last, "the apply's segments are not runs of the candidates");
        while (last < sg)
            L.first[static_cast<size_t>(++last)] = pr;
        const int own = sg % T;
        NodeId a, b;
        pair_span(m, ct, j, cand.body[static_cast<size_t>(pr)], a, b);
        const int ua = range_of(a), ub = range_of(b);
        L.inside[static_cast<size_t>(pr)] = ua == own && ub == own ? 1 : 0;
        for (int u = ua; u <= ub; ++u)
            L.foreign_begin[static_cast<size_t>(u) + 1] += u != own ? 1 : 0;
    }
    for (size_t u = 0; u < ts; ++u)
        L.foreign_begin[u + 1] += L.foreign_begin[u];
    L.foreign.resize(static_cast<size_t>(L.foreign_begin[ts]));
    std::vector<int32_t>& at = L.fill;
    at.assign(L.foreign_begin.begin(), L.foreign_begin.end() - 1);
    int sg = 0;  // the segment of candidate pr
    for (int32_t pr = 0; pr < np; ++pr) {
        while (L.first[static_cast<size_t>(sg) + 1] <= pr)
            ++sg;
        if (L.inside[static_cast<size_t>(pr)]) continue;
        const int own = sg % T;
        NodeId a, b;
        pair_span(m, ct, cand.node[static_cast<size_t>(pr)], cand.body[static_cast<size_t>(pr)], a,
                  b);
        for (int u = range_of(a); u <= range_of(b); ++u) {
            if (u != own) L.foreign[static_cast<size_t>(at[static_cast<size_t>(u)]++)] = pr;
        }
    }
    L.threads = T;
}

// add_contact_forces() with plan == nullptr; else as one process of a distributed run
void contact_forces_impl(const Model& m, State& s, const StepPlan* plan, const Comm* comm) {
    const ContactShare* share = plan != nullptr ? &plan->contact : nullptr;
    const bool ghosts = plan != nullptr && plan->ghosts.active;
    const ContactModel& cm = m.contact;
    const ContactTopology& ct = s.topology;
    ContactState& cs = s.contact;
    cs.deep_penetrations = 0;
    cs.lost_inside = 0;
    cs.lost_node = kNone;
    cs.lost_body = kNone;
    cs.lost_depth_ratio = 0;
    cs.max_depth_ratio = 0;
    if (cm.algorithm == ContactAlgorithm::None || ct.num_sub_tris() == 0) {
        cs.rebase_pending = false;
        s.energy.contact = 0;
        cs.active_contacts = 0;
        return;
    }
    if (cm.algorithm == ContactAlgorithm::LegacyTriangle) {
        // baseline A: triangle-to-triangle edge integration (docs/theory.md §7.2-7.3); its
        // forces do not go through ContactState::fc_nodes
        cs.fc_sparse = false;
        s.energy.contact = add_legacy_triangle_forces(m, s, cs.legacy);
        cs.active_contacts = cs.legacy.active;
        return;
    }
    const Real dt = s.dt;
    const Vec2* x = s.x.data();
    const Vec2* v = s.v.data();
    if (share != nullptr && share->active_full) {
        // (a distributed run keeps the histories of its own targets' pairs only)
        const int32_t* own = plan->node_owner.data();
        const int32_t me = plan->rank;
        std::erase_if(cs.active,
                      [&](const ActiveContact& a) { return own[target_node(ct, a.node)] != me; });
        share->active_full = false;
    }

    // 1. virtual nodes follow their parents (spec §4.4-2); a welded contactor stands at its
    //    sectors' mean positions xc (eq. 6.23), the targets stay at x (no weld: xc = x)
    update_virtual_nodes(m, s);
    const Vec2* xv = cs.xv.data();
    const Vec2* vv = cs.vv.data();
    const Vec2* xc = ct.welded() ? cs.xw.data() : x;

    // 2. skin (spec §2.3): x^n - x^{n-1} = dt v^{n-1/2}; two objects close by at most
    //    2 dt max|v| per step, so the candidates stay complete until the sum exceeds b
    if (!cs.need_rebuild) {
        // (a distributed run: the maximum over the processes' own nodes, reduced with the
        // element pass's smallest det F in step(): the same value, max is exact)
        const std::pair<NodeId, NodeId> all_nodes{0, m.num_nodes()};
        const Real v2 = plan != nullptr ? plan->max_speed2 : max_speed2(v, {&all_nodes, 1});
        cs.skin_used += 2.0 * dt * std::sqrt(v2);
        if (cs.skin_used > cm.buffer) cs.need_rebuild = true;
    }
    if (cs.need_rebuild) {
        if (ghosts) {
            // the broad phase reads every contact node, and the new ghosts' v is read below
            s.timing.mark(StepPhase::BroadPhase);
            gather_nodes(s.x.data(), *plan, *comm);
            gather_nodes(s.v.data(), *plan, *comm);
            s.timing.mark(StepPhase::Communication);
            update_virtual_nodes(m, s);
        }
        if (plan != nullptr) {
            // this process's targets only (a subsequence of the serial list, spec D5.3)
            find_candidates(m, ct, x, xc, xv, cs.cand, cs.broad,
                            TargetOwner{plan->node_owner.data(), plan->rank});
            s.timing.mark(StepPhase::BroadPhase);
            share->total_candidates = comm->sum(static_cast<int64_t>(cs.cand.node.size()));
            s.timing.mark(StepPhase::Communication);
        } else {
            find_candidates(m, ct, x, xc, xv, cs.cand, cs.broad);
        }
        cs.box_list_valid = false;
        cs.apply_lists.threads = 0;
        if (share != nullptr) {
            share->boxes_valid = false;
            share->dest_valid = false;
        }
        if (ghosts) {
            s.timing.mark(StepPhase::BroadPhase);
            rebuild_ghosts(m, s, *plan, *comm);
            s.timing.mark(StepPhase::Communication);
        }
        cs.need_rebuild = false;
        cs.skin_used = 0;
        ++cs.rebuilds;
    }

    // 3a. narrow phase and law of every pair, independent of each other: in parallel into the
    //     buffer pair_out; each of the kPairChunks fixed chunks of pairs lists its pairs in
    //     contact, ascending, at the front of its range of cs.in_contact, and their results at
    //     the same places of pair_out (dense: written in order, not at the pair's index, whose
    //     scattered writes to a buffer of all candidates cost a cache miss each). The body box
    //     rejects most pairs before any sub-triangle is touched (exact: body_boxes()). Below
    //     kMinParallelPairs fork/join dominates.
    const int32_t npairs = static_cast<int32_t>(cs.cand.node.size());
    cs.body_box.resize(static_cast<size_t>(m.num_bodies()));
    if (!cs.box_reject) {
        constexpr Real inf = std::numeric_limits<Real>::infinity();
        std::fill(cs.body_box.begin(), cs.body_box.end(), BodyBox{{-inf, -inf}, {inf, inf}});
    }
    // grow only: a resize that shrinks and grows again value-initialises the regrown part
    if (cs.pair_out.size() < static_cast<size_t>(npairs)) {
        cs.pair_out.resize(static_cast<size_t>(npairs));
        cs.in_contact.resize(static_cast<size_t>(npairs));
    }
    PairResult* out = cs.pair_out.data();
    int32_t* in_contact = cs.in_contact.data();
    int32_t chunk_count[kPairChunks];
    auto chunk_begin = [npairs](int32_t ch) {
        return static_cast<int32_t>(static_cast<int64_t>(npairs) * ch / kPairChunks);
    };
    // a distributed run: only the pairs of this process's targets (spec D5.3), and only the
    // boxes of their contactors (listed again after every broad phase)
    const int32_t* owner = plan != nullptr ? plan->node_owner.data() : nullptr;
    const int32_t my_rank = plan != nullptr ? plan->rank : 0;
    if (plan != nullptr) {
        contactor_bodies(m, s, *plan);  // (lists them after a rebuild)
    } else if (!cs.box_list_valid) {
        list_contactors(m, ct, cs.cand, nullptr, 0, cs.box_mark, cs.box_bodies);
        cs.box_list_valid = true;
    }
    const std::vector<BodyId>& box_bodies = share != nullptr ? share->box_bodies : cs.box_bodies;
    const BodyId* box_list = box_bodies.data();
    const int32_t box_count = static_cast<int32_t>(box_bodies.size());
    // the contactor positions the locate loop reads: those of the listed bodies only
    fill_contact_positions(ct, cs, xc, box_list, box_count);
    s.timing.mark(StepPhase::BroadPhase);
    {
        const ContactState& ccs = cs;
        const NodeId* cand_node = cs.cand.node.data();
        const BodyId* cand_body = cs.cand.body.data();
        BodyBox* box = cs.body_box.data();
        const bool boxes = cs.box_reject;
        const int32_t nbodies = m.num_bodies();
        // one parallel region: the boxes (a worksharing loop inside body_boxes(), whose
        // implicit barrier completes them), then the pairs: the chunks handed out as threads
        // come free (each chunk's results are its own, so any thread may run any chunk; on a
        // shared host a thread slowed for a while takes fewer chunks: the saturated pack's
        // 2-thread step −7 % against round-robin, docs/performance.md "Stop 51")
#pragma omp parallel if (npairs > kMinParallelPairs)
        {
            if (boxes) boxes_of(ct, xc, xv, box, nbodies, box_list, box_count);
#pragma omp for schedule(dynamic, 1) nowait
            for (int32_t ch = 0; ch < kPairChunks; ++ch) {
                const int32_t b = chunk_begin(ch), e = chunk_begin(ch + 1);
                // pass 1, branch-free: the pairs the box does not reject, in order
                int32_t n = b;
                if (owner == nullptr) {
                    for (int32_t pr = b; pr < e; ++pr) {
                        // with body ids far apart in space (shuffled numbering) the box is a
                        // cache miss
                        if (pr + kBoxPrefetch < e)
                            __builtin_prefetch(&box[cand_body[pr + kBoxPrefetch]]);
                        in_contact[n] = pr;
                        n += !box_rejects(box[cand_body[pr]], target_point(ct, x, cand_node[pr]));
                    }
                } else {
                    for (int32_t pr = b; pr < e; ++pr) {
                        const NodeId j = cand_node[pr];
                        if (owner[target_node(ct, j)] != my_rank) continue;
                        in_contact[n] = pr;
                        n += !box_rejects(box[cand_body[pr]], target_point(ct, x, j));
                    }
                }
                // pass 2: locate and law of those; the pairs in contact, compacted in place
                // (ascending pairs: their histories are looked up from a cursor)
                int32_t nc = b;
                size_t cursor = 0;
                for (int32_t k = b; k < n; ++k) {
                    const int32_t pr = in_contact[k];
                    if (evaluate_pair(m, ct, ccs, x, xc, v, xv, vv, dt, pr, out[nc], &cursor) >= 0)
                        in_contact[nc++] = pr;
                }
                chunk_count[ch] = nc - b;
            }
        }
    }

    s.timing.mark(StepPhase::NarrowPhase);
    // the pairs in contact, as spans [span_begin, + chunk_count) of in_contact and out in pair
    // order: the chunks' fronts (a distributed run: its own pairs; the other processes' records
    // come in exchange_records())
    int32_t span_begin[kPairChunks];
    for (int32_t ch = 0; ch < kPairChunks; ++ch)
        span_begin[ch] = chunk_begin(ch);
    // the key (node, body) of the k-th pair in contact: key_node[in_contact[k]]
    const NodeId* key_node = cs.cand.node.data();
    const BodyId* key_body = cs.cand.body.data();

    // 3b. apply: the forces of the pairs in contact (eq. 20) and the bookkeeping, merged with
    //     the previous active list (both sorted by (node, body)), releasing the histories of
    //     pairs that left contact. The pairs in contact take the places 0 .. n_next - 1 in pair
    //     order (their places in the new active list). Every node receives its forces in that
    //     order, so f and f_contact are those of a serial loop; the energies are exact sums
    //     (theory §4.4), the diagnostics counts and maxima, so any split of the bookkeeping
    //     gives the same bits. One thread: one loop does both. T >= 2 threads (at least
    //     kMinParallelApply pairs in contact): thread t owns the real nodes [N t / T,
    //     N (t + 1) / T) and does the bookkeeping of two segments of the pairs: those whose
    //     target lies there and the edge targets whose edge starts there (ContactApplyLists,
    //     built once per broad phase). It adds their forces in the same loop (to its own nodes
    //     only where a pair's node span, pair_span(), leaves the range), and the forces on its
    //     nodes of the other threads' pairs that reach them (the range's foreign list) before,
    //     between and after its segments in pair order: every node gets its forces in pair
    //     order, no barrier.
    int32_t span_pos[kPairChunks + 1];  // the place of each span's first pair
    span_pos[0] = 0;
    for (int32_t sp = 0; sp < kPairChunks; ++sp)
        span_pos[sp + 1] = span_pos[sp] + chunk_count[sp];
    const int32_t n_next = span_pos[kPairChunks];
    // the new active list, written by place (resize value-initialises only the part beyond the
    // previous length)
    cs.active_next.resize(static_cast<size_t>(n_next));
    // calls fn(p, k) for the places p in [p0, p1) in order; k indexes in_contact and out
    auto for_places = [&](int32_t p0, int32_t p1, auto&& fn) {
        if (p0 >= p1) return;
        int32_t sp = 0;
        while (span_pos[sp + 1] <= p0)
            ++sp;
        for (int32_t p = p0; p < p1; ++sp) {
            const int32_t end = std::min(p1, span_pos[sp + 1]);
            const int32_t off = span_begin[sp] - span_pos[sp];
            for (; p < end; ++p)
                fn(p, p + off);
        }
    };
    auto release = [&](const ActiveContact& a, ContactApplyPart& part, ExactSum& dissipated) {
        const BodyId bt = m.node_body[target_node(ct, a.node)];
        const ContactParams& p =
            pair_parameters(cm, m.bodies[a.body].material, m.bodies[bt].material);
        const Real scale = target_scale(ct, a.node);
        bool lost = false;
        // (not for a self-contact pair: the node lies on its own body's boundary, where the
        // crossing test has no meaning)
        if (lost_test_needed(m, ct, a) &&
            inside_body(ct, a.body, xc, target_point(ct, x, a.node))) {
            lost = true;  // left the boundary layer inwards: penetration too deep (spec §4.6)
            ++part.lost;
            // the deepest one (the first of equals in pair order; depth ratios are finite) is
            // named in the failure message (integrate/run_checks.cpp)
            if (part.lost_node < 0 || a.h.depth_ratio > part.lost_depth_ratio) {
                part.lost_node = a.node;
                part.lost_body = a.body;
                part.lost_depth_ratio = a.h.depth_ratio;
            }
        }
        if (rebased(cs, a.body, bt)) {
            // ended by a rebuild (eq. 9.26): the normal potential the old topology gives it at
            // x^n leaves the books here, with its spring and damping as at any separation
            const RebaseEntry* e = find_pair(cs.rebase, a.node, a.body);
            dissipated.add((e != nullptr ? e->normal : 0.0) +
                           release_energy(p, a.h, scale, false, dt));
            return;
        }
        // a pair continued with d0 < 0 (eq. 9.26) separates at d = 0 with d - d0 > 0: its
        // normal potential leaves the books as that of a lost pair
        dissipated.add(release_energy(p, a.h, scale, lost || a.h.d0 < 0, dt));
    };
    // (the old list, the new list and the sums in locals: the force stores could alias members
    // of cs, which the compiler would otherwise reload after each of them)
    const ActiveContact* act = cs.active.data();
    const size_t n_act = cs.active.size();
    ActiveContact* next = cs.active_next.data();
    const Real deep_limit = cm.deep_ratio_limit;
    // the stored energy (an exact sum, ~40 instructions per pair) only on the steps that evaluate
    // the energies (State::need_energy), as the strain and kinetic energies; each pair's own
    // stored energy (h.stored, what a lost pair releases) is kept every step by the law
    const bool energy = s.need_energy;
    Vec2* const f = s.f.data();
    Vec2* const fc = s.f_contact.data();
    // the first old entry not below the pair at place p (n_act for p = n_next)
    auto old_from = [&](int32_t p) -> size_t {
        if (p >= n_next) return n_act;
        size_t at = 0;
        for_places(p, p + 1, [&](int32_t, int32_t k) {
            const NodeId j = key_node[in_contact[k]];
            const BodyId c = key_body[in_contact[k]];
            at = static_cast<size_t>(std::partition_point(act, act + n_act,
                                                          [j, c](const ActiveContact& a) {
                                                              return pair_below(a, j, c);
                                                          }) -
                                     act);
        });
        return at;
    };
    // the bookkeeping of the places [p0, p1) and of the old entries [ia, ia_end) (those below
    // the pair at p1); forces: none (kNoForces), every pair's (kAllForces, one thread), those
    // of the nodes [lo, hi) (kSliceForces: whole where the candidate's forces stay in the range,
    // inside[pr], else node by node), or those of a distributed step's nodes that no received
    // record reaches (kDirectForces, with direct)
    // (captures by value: the force stores could alias anything captured by reference, which
    // the compiler would then reload after each of them)
    auto bookkeeping = [act, next, out, in_contact, key_node, key_body, f, fc, deep_limit, energy,
                        &ct, &release, &span_pos,
                        &span_begin](int32_t p0, int32_t p1, size_t ia, size_t ia_end,
                                     ContactApplyPart& part, auto forces, NodeId lo, NodeId hi,
                                     const uint8_t* inside, DirectAdds* direct) {
        ExactSum stored, dissipated;
        Real max_ratio = 0;
        int64_t deep = 0;
        int32_t sp = 0;  // the span of place p
        int32_t next_span = span_pos[1], off = span_begin[0];
        // only the pairs in contact, in ascending pair order: an old entry that no pair in
        // contact continues is released at its place of the merged order. A pair's history
        // o.hist is the index of the old entry with its key (-1: none; the narrow phase's
        // lookup), so the old entries below it that are not yet passed are the released ones:
        // the merge by keys without comparing them (both lists ascend; the entry of a pair of
        // the places [p0, p1) lies in [ia, ia_end))
        for (int32_t p = p0; p < p1; ++p) {
            while (p >= next_span) {
                ++sp;
                next_span = span_pos[sp + 1];
                off = span_begin[sp] - span_pos[sp];
            }
            const int32_t k = p + off;
            const int32_t pr = in_contact[k];
            const NodeId j = key_node[pr];
            const BodyId c = key_body[pr];
            const PairResult& o = out[k];
            if (o.hist >= 0) {
                const size_t h = static_cast<size_t>(o.hist);
                FDEM_ASSERT(h >= ia && h < ia_end && act[h].node == j && act[h].body == c,
                            "a pair's history is not the old entry of its key in its range");
                while (ia < h)
                    release(act[ia++], part, dissipated);
                ia = h + 1;
            }
            if constexpr (decltype(forces)::value == kAllForces) {
                add_pair_forces(ct, f, fc, j, o);  // f on the target, -N_i f on the contactor
            } else if constexpr (decltype(forces)::value == kSliceForces) {
                if (inside[pr]) {
                    if constexpr (kAssertsEnabled) {
                        visit_pair_forces(ct, j, o, [lo, hi]([[maybe_unused]] NodeId i, Vec2) {
                            FDEM_ASSERT(i >= lo && i < hi,
                                        "a pair's force reaches beyond its thread's range");
                        });
                    }
                    add_pair_forces(ct, f, fc, j, o);
                } else {
                    add_pair_forces(ct, f, fc, j, o, lo, hi);
                }
            } else if constexpr (decltype(forces)::value == kDirectForces) {
                const uint8_t* need = direct->need;
                const uint8_t* ex = direct->exposed;
                NodeId t0, t1;
                target_ends(ct, j, t0, t1);
                if (all_needed(ct, need, direct->body_all, j, c) && !direct->exposed_body[c] &&
                    !ex[t0] && !ex[t1]) {
                    add_pair_forces(ct, f, fc, j, o);
                } else {
                    bool reaches = false;
                    visit_pair_forces(ct, j, o, [f, fc, need, ex, &reaches](NodeId i, Vec2 fi) {
                        if (ex[i]) {
                            reaches = true;
                            return;
                        }
                        add_needed(f, fc, need, i, fi);
                    });
                    if (reaches) direct->deferred[direct->n_deferred++] = k;
                }
            }
            const Real ratio = o.h.depth_ratio;
            max_ratio = std::max(max_ratio, ratio);
            deep += ratio > deep_limit ? 1 : 0;
            if (energy) stored.add(o.stored);
            if (o.dissipated != 0) dissipated.add(o.dissipated);  // (exact: zeros add nothing)
            next[p] = ActiveContact{j, c, o.h};
        }
        while (ia < ia_end)
            release(act[ia++], part, dissipated);
        part.stored.add(stored);  // (exact: a part may take several runs)
        part.dissipated.add(dissipated);
        part.max_depth_ratio = std::max(part.max_depth_ratio, max_ratio);
        part.deep += deep;
    };
    const int max_threads = omp_get_max_threads();
    // (two parts per thread: the segments of ContactApplyLists)
    if (cs.apply_part.size() < 2 * static_cast<size_t>(max_threads))
        cs.apply_part.resize(2 * static_cast<size_t>(max_threads));
    ContactApplyPart* parts = cs.apply_part.data();
    int nparts = 1;
    const bool par_apply = max_threads > 1 && n_next >= kMinParallelApply;
    // (a distributed run: the bookkeeping of its own pairs here; their forces with one thread
    // here too where no other process's record reaches, the rest with the other processes'
    // records in apply_merged(). own_k: the narrow phase's index of each own pair in pair order)
    const bool local = share != nullptr;
    // the narrow phase's chunk of candidate pr < npairs, and where pr is or would be in its
    // ascending list of pairs in contact (in_contact)
    const auto locate = [&](int32_t pr, int32_t& ch) {
        ch = static_cast<int32_t>(static_cast<int64_t>(pr) * kPairChunks / npairs);
        while (ch + 1 < kPairChunks && chunk_begin(ch + 1) <= pr)
            ++ch;
        while (ch > 0 && chunk_begin(ch) > pr)
            --ch;
        const int32_t* b = in_contact + chunk_begin(ch);
        return std::lower_bound(b, b + chunk_count[ch], pr);
    };
    // the index k (in_contact[k] == pr, out[k] its result) of candidate pr, -1 if not in contact
    const auto in_contact_at = [&](int32_t pr) {
        int32_t ch;
        const int32_t* it = locate(pr, ch);
        if (it == in_contact + chunk_begin(ch) + chunk_count[ch] || *it != pr) return -1;
        return static_cast<int32_t>(it - in_contact);
    };
    int32_t* own_k = nullptr;
    DirectAdds direct{};
    if (local) {
        resize_grow(share->own_k, static_cast<size_t>(n_next));
        own_k = share->own_k.data();
        for_places(0, n_next, [own_k](int32_t p, int32_t k) { own_k[p] = k; });
        share->own_records = n_next;
    }
    if (!par_apply) {
        parts[0] = ContactApplyPart{};
        if (local) {
            // (the other processes' records first: the own pairs' forces at the nodes none
            // of them reaches go in here, the rest in apply_merged())
            resize_grow(share->deferred, static_cast<size_t>(n_next));
            exchange_records(m, ct, *plan, *comm, s, in_contact_at, in_contact, out);
            mark_exposed(m, ct, *share, 1);
            direct.need = share->need.data();
            direct.exposed = share->exposed.data();
            direct.exposed_body = share->exposed_body.data();
            direct.body_all = share->body_all.data();
            direct.deferred = share->deferred.data();
            bookkeeping(0, n_next, 0, n_act, parts[0], DirectForces{}, 0, 0, nullptr, &direct);
        } else {
            bookkeeping(0, n_next, 0, n_act, parts[0], AllForces{}, 0, 0, nullptr, nullptr);
        }
    } else if (local) {
        // (a distributed run: the bookkeeping by places; the forces in apply_merged())
#pragma omp parallel
        {
            const int nt = omp_get_num_threads(), t = omp_get_thread_num();
            ContactApplyPart& part = parts[t];
            part = ContactApplyPart{};
            if (t == 0) nparts = nt;
            const auto slice = [&](int r) {
                return static_cast<int32_t>(static_cast<int64_t>(n_next) * r / nt);
            };
            const int32_t p0 = slice(t), p1 = slice(t + 1);
            bookkeeping(p0, p1, t == 0 ? 0 : old_from(p0), old_from(p1), part, NoForces{}, 0, 0,
                        nullptr, nullptr);
        }
    } else {
        // thread t: the pairs of its two segments (ContactApplyLists), their bookkeeping and
        // forces in one loop each, the forces of the foreign pairs on its nodes before, between
        // and after them in pair order, all to its own node range: no barrier. Segment s
        // books into parts[s], so the parts combine in pair order
        ContactApplyLists& L = cs.apply_lists;
        const int built = L.threads;  // (read before the region: the same test on every thread)
        // the place of the first pair in contact at or after candidate pr
        const auto place_of = [&](int32_t pr) {
            if (pr >= npairs) return n_next;
            int32_t ch;
            const int32_t* it = locate(pr, ch);
            return span_pos[ch] + static_cast<int32_t>(it - (in_contact + chunk_begin(ch)));
        };
#pragma omp parallel
        {
            const int nt = omp_get_num_threads(), t = omp_get_thread_num();
            if (built != nt) {
#pragma omp single
                build_apply_lists(m, ct, cs.cand, nt, L);
            }
            if (t == 0) nparts = 2 * nt;
            const NodeId lo = L.range_lo[static_cast<size_t>(t)];
            const NodeId hi = L.range_lo[static_cast<size_t>(t) + 1];
            const int32_t* fl = L.foreign.data();
            int32_t q = L.foreign_begin[static_cast<size_t>(t)];
            const int32_t qe = L.foreign_begin[static_cast<size_t>(t) + 1];
            // the foreign pairs below candidate end that are in contact, on this range's nodes
            // (the candidates of a chunk of the narrow phase in contact ascend in in_contact)
            const auto foreign_below = [&](int32_t end) {
                for (; q < qe && fl[q] < end; ++q) {
                    const int32_t pr = fl[q];
                    int32_t ch;
                    const int32_t* it = locate(pr, ch);
                    if (it == in_contact + chunk_begin(ch) + chunk_count[ch] || *it != pr)
                        continue;  // (not in contact)
                    add_pair_forces(ct, f, fc, key_node[pr], out[it - in_contact], lo, hi);
                }
            };
            for (const int sg : {t, nt + t}) {
                const int32_t c0 = L.first[static_cast<size_t>(sg)];
                const int32_t c1 = L.first[static_cast<size_t>(sg) + 1];
                foreign_below(c0);
                ContactApplyPart& part = parts[sg];
                part = ContactApplyPart{};
                const int32_t p0 = place_of(c0), p1 = place_of(c1);
                bookkeeping(p0, p1, sg == 0 ? 0 : old_from(p0), old_from(p1), part, SliceForces{},
                            lo, hi, L.inside.data(), nullptr);
            }
            foreign_below(npairs);
        }
    }
    if (!local) {
        note_contact_force_nodes(cs, static_cast<size_t>(n_next), [&](auto&& visit) {
            for_places(0, n_next, [&](int32_t, int32_t k) {
                visit_pair_forces(ct, key_node[in_contact[k]], out[k], visit);
            });
        });
    } else if (!par_apply) {
        apply_merged(m, ct, *plan, s, direct.deferred, direct.n_deferred, own_k, n_next, true,
                     in_contact, out);
        mark_exposed(m, ct, *share, 0);
    } else {
        exchange_records(m, ct, *plan, *comm, s, in_contact_at, in_contact, out);
        apply_merged(m, ct, *plan, s, own_k, n_next, own_k, n_next, false, in_contact, out);
    }
    // the threads' shares in thread order (the exact sums in any order); a distributed run:
    // this process's share, then the sums, counts and maxima over the processes
    ExactSum stored;
    ExactSum step_dissipated;  // (a distributed run: this step's, summed over the processes)
    ExactSum& dissipated = local ? step_dissipated : s.energy_sums.dissipated_contact;
    Real max_ratio = cs.max_depth_ratio;
    int64_t deep = cs.deep_penetrations;
    for (int r = 0; r < nparts; ++r) {
        const ContactApplyPart& part = parts[r];
        stored.add(part.stored);
        dissipated.add(part.dissipated);
        max_ratio = std::max(max_ratio, part.max_depth_ratio);
        deep += part.deep;
        cs.lost_inside += static_cast<decltype(cs.lost_inside)>(part.lost);
        if (part.lost_node != kNone &&
            (cs.lost_node < 0 || part.lost_depth_ratio > cs.lost_depth_ratio)) {
            cs.lost_node = part.lost_node;
            cs.lost_body = part.lost_body;
            cs.lost_depth_ratio = part.lost_depth_ratio;
        }
    }
    cs.max_depth_ratio = max_ratio;
    cs.deep_penetrations = static_cast<decltype(cs.deep_penetrations)>(deep);
    std::swap(cs.active, cs.active_next);
    if (cs.rebase_pending) {  // consumed (eq. 9.26); keeps its capacity
        cs.rebase.clear();
        cs.rebase_pending = false;
    }
    if (local) {
        // this process's share: step() sums it over the processes with the step's other sums
        // (finish_contact_sums() sets the totals); the largest depth ratios stay this
        // process's own until a lost pair or a checkpoint needs them (gather_active())
        ExactSum* sums = share->sums;
        sums[0] = stored;
        sums[1] = dissipated;
        sums[2] = ExactSum{};
        sums[2].add(static_cast<double>(n_next));
        sums[3] = ExactSum{};
        sums[3].add(static_cast<double>(deep));
        sums[4] = ExactSum{};
        sums[4].add(static_cast<double>(cs.lost_inside));
        share->sums_pending = true;
        cs.max_depth_ratio_ever = std::max(cs.max_depth_ratio_ever, cs.max_depth_ratio);
        return;
    }

    if (energy) s.energy.contact = stored.value();  // (else stale, State::need_energy)
    s.energy.dissipated_contact = dissipated.value();
    cs.active_contacts = static_cast<int32_t>(n_next);
    cs.total_deep_penetrations += cs.deep_penetrations;
    cs.total_lost_inside += cs.lost_inside;
    cs.max_depth_ratio_ever = std::max(cs.max_depth_ratio_ever, cs.max_depth_ratio);
}

}  // namespace

bool clear_listed_contact_forces(State& s, NodeId num_nodes) {
    ContactState& cs = s.contact;
    if (cs.fc_sparse) {
        Vec2* const fc = s.f_contact.data();
        for (const NodeId i : cs.fc_nodes)
            fc[i] = {};
        cs.fc_nodes.clear();
        return true;
    }
    // the caller zeroes every node it reads: the empty list is exact from there on
    const size_t cap = static_cast<size_t>(num_nodes / kSparseContactForceRatio);
    if (cs.fc_nodes.capacity() < cap) cs.fc_nodes.reserve(cap);  // (the first step)
    if (cs.fc_mark.size() != static_cast<size_t>(num_nodes))
        cs.fc_mark.assign(static_cast<size_t>(num_nodes), 0);
    cs.fc_nodes.clear();
    cs.fc_sparse = true;
    return false;
}

Real max_speed2(const Vec2* v, std::span<const std::pair<NodeId, NodeId>> runs) {
#ifdef __SSE2__
    // four running maxima in two SSE2 registers (max is exact and order-free): x^2 + y^2 of
    // two nodes at once, as norm2() computes it (no FMA: -ffp-contract=off). maxpd(a, m)
    // returns m when a is NaN, as std::max(m, a) does, so NaN is skipped the same way (and the
    // zero start makes -0 irrelevant: |v|^2 >= +0)
    __m128d m0 = _mm_setzero_pd(), m1 = _mm_setzero_pd();
    Real tail = 0;
    const double* d = reinterpret_cast<const double*>(v);  // (Vec2: x, y contiguous)
    for (const auto& [b, e] : runs) {
        NodeId i = b;
        for (; i + 4 <= e; i += 4) {
            const double* p = d + 2 * static_cast<size_t>(i);
            const __m128d a0 = _mm_loadu_pd(p), a1 = _mm_loadu_pd(p + 2);  // (x, y) of i, i+1
            const __m128d a2 = _mm_loadu_pd(p + 4), a3 = _mm_loadu_pd(p + 6);
            const __m128d x01 = _mm_unpacklo_pd(a0, a1), y01 = _mm_unpackhi_pd(a0, a1);
            const __m128d x23 = _mm_unpacklo_pd(a2, a3), y23 = _mm_unpackhi_pd(a2, a3);
            const __m128d n01 = _mm_add_pd(_mm_mul_pd(x01, x01), _mm_mul_pd(y01, y01));
            const __m128d n23 = _mm_add_pd(_mm_mul_pd(x23, x23), _mm_mul_pd(y23, y23));
            m0 = _mm_max_pd(n01, m0);
            m1 = _mm_max_pd(n23, m1);
        }
        for (; i < e; ++i)
            tail = std::max(tail, norm2(v[i]));
    }
    alignas(16) double l[4];
    _mm_store_pd(l, m0);
    _mm_store_pd(l + 2, m1);
    return std::max(std::max(std::max(l[0], l[1]), std::max(l[2], l[3])), tail);
#else
    // (without SSE2: four running maxima, four independent dependency chains)
    Real v2s[4] = {0, 0, 0, 0};
    for (const auto& [b, e] : runs) {
        NodeId i = b;
        for (; i + 4 <= e; i += 4) {
            for (int k = 0; k < 4; ++k)
                v2s[k] = std::max(v2s[k], norm2(v[i + k]));
        }
        for (; i < e; ++i)
            v2s[0] = std::max(v2s[0], norm2(v[i]));
    }
    return std::max(std::max(v2s[0], v2s[1]), std::max(v2s[2], v2s[3]));
#endif
}

void contact_exchange_counts(const Model& m, const State& s, const StepPlan& plan,
                             std::vector<int64_t>& to, std::vector<uint8_t>& may_send) {
    may_send_marks(m, s, plan, may_send);
    to.assign(static_cast<size_t>(plan.procs), 0);
    const ContactTopology& ct = s.topology;
    const int32_t me = plan.rank;
    const ContactShare& sh = plan.contact;
    for (const ActiveContact& a : s.contact.active) {
        if (plan.node_owner[static_cast<size_t>(target_node(ct, a.node))] != me) continue;
        const int64_t tick = ++sh.tick;
        pair_ranks(ct, plan, a.node, a.body, [&](int32_t r) {
            if (r == me || sh.stamp[static_cast<size_t>(r)] == tick) return;
            sh.stamp[static_cast<size_t>(r)] = tick;
            ++to[static_cast<size_t>(r)];
        });
    }
}

void finish_contact_sums(State& s, const StepPlan& plan, const Comm& comm, const ExactSum* totals) {
    const ContactShare& sh = plan.contact;
    sh.sums_pending = false;
    ContactState& cs = s.contact;
    if (s.need_energy) s.energy.contact = totals[0].value();  // (else stale: zero terms)
    s.energy_sums.dissipated_contact.add(totals[1]);
    s.energy.dissipated_contact = s.energy_sums.dissipated_contact.value();
    cs.active_contacts = static_cast<int32_t>(totals[2].value());
    cs.deep_penetrations = static_cast<decltype(cs.deep_penetrations)>(totals[3].value());
    const int64_t lost = static_cast<int64_t>(totals[4].value());
    if (lost > 0) {
        // the failure message (run_checks.cpp): the largest depth ratio, and the deepest lost
        // pair, of equals the smallest (node, body) (the first in pair order, as the serial
        // loop keeps it)
        constexpr double kNoValue = std::numeric_limits<double>::infinity();
        const bool here = cs.lost_node != kNone;
        double mins[2] = {-cs.max_depth_ratio, here ? -cs.lost_depth_ratio : kNoValue};
        comm.min(mins, 2);
        const bool deepest = here && -cs.lost_depth_ratio == mins[1];
        const double node = comm.min(deepest ? static_cast<double>(cs.lost_node) : kNoValue);
        const bool first = deepest && static_cast<double>(cs.lost_node) == node;
        const double body = comm.min(first ? static_cast<double>(cs.lost_body) : kNoValue);
        cs.max_depth_ratio = -mins[0];
        cs.lost_node = static_cast<NodeId>(node);
        cs.lost_body = static_cast<BodyId>(body);
        cs.lost_depth_ratio = -mins[1];
    }
    cs.lost_inside = static_cast<decltype(cs.lost_inside)>(lost);
    cs.total_deep_penetrations += cs.deep_penetrations;
    cs.total_lost_inside += cs.lost_inside;
}

void gather_active(State& s, const StepPlan& plan, const Comm& comm) {
    const ContactShare& sh = plan.contact;
    // the largest depth ratios of the last step and of the run (each process keeps its own)
    ContactState& cs = s.contact;
    double mins[2] = {-cs.max_depth_ratio, -cs.max_depth_ratio_ever};
    comm.min(mins, 2);
    cs.max_depth_ratio = -mins[0];
    cs.max_depth_ratio_ever = -mins[1];
    if (sh.active_full) return;  // (already the serial list on every process)
    static_assert(std::is_trivially_copyable_v<ActiveContact>);
    // the list and the one of the step before (active_next after the swap: scratch, but saved
    // in checkpoints, which must be the serial file)
    for (std::vector<ActiveContact>* list : {&s.contact.active, &s.contact.active_next}) {
        std::vector<ActiveContact>& a = *list;
        std::vector<char> mine(a.size() * sizeof(ActiveContact)), all;
        if (!a.empty()) std::memcpy(mine.data(), a.data(), mine.size());
        comm.allgather_bytes(mine, all);
        a.resize(all.size() / sizeof(ActiveContact));
        if (!a.empty()) std::memcpy(a.data(), all.data(), all.size());
        // the processes' targets are disjoint: in (node, body) order this is the serial list
        std::sort(a.begin(), a.end(), [](const ActiveContact& x, const ActiveContact& y) {
            return pair_key_less(x, y);
        });
    }
    sh.active_full = true;
}

void set_force_readers(StepPlan& plan, std::span<const std::vector<NodeId>> contact_nodes,
                       std::span<const std::vector<NodeId>> force_nodes,
                       std::span<const int32_t> set_rank) {
    ContactShare& sh = plan.contact;
    // (node, process) for the nodes of each set its process does not own, ascending, unique
    const auto readers = [&](std::span<const std::vector<NodeId>> nodes,
                             std::vector<std::pair<NodeId, int32_t>>& out) {
        for (size_t k = 0; k < nodes.size(); ++k) {
            const int32_t r = set_rank[k];
            for (const NodeId i : nodes[k]) {
                if (plan.node_owner[static_cast<size_t>(i)] != r) out.emplace_back(i, r);
            }
        }
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
    };
    sh.f_readers.clear();
    readers(force_nodes, sh.f_readers);
    sh.force_readers = sh.f_readers;  // f_contact or f: the union
    readers(contact_nodes, sh.force_readers);
    sh.body_rank_begin.clear();  // (recomputed with the readers at the next step)
    sh.dest_valid = false;
    plan.clear_valid = false;  // the forces it clears include the read nodes
}

void gather_candidates(State& s, const StepPlan& plan, const Comm& comm) {
    Candidates& cand = s.contact.cand;
    s.contact.box_list_valid = false;
    s.contact.apply_lists.threads = 0;
    const ContactTopology& ct = s.topology;
    // the pairs of my targets only (after a first gather a process holds every pair), as
    // [pairs][tris][node...][body...][count per pair...][tri...] (int32 words)
    std::vector<size_t> mine_pairs;
    size_t nt = 0;
    for (size_t p = 0; p < cand.node.size(); ++p) {
        if (plan.node_owner[static_cast<size_t>(target_node(ct, cand.node[p]))] != plan.rank)
            continue;
        mine_pairs.push_back(p);
        nt += static_cast<size_t>(cand.begin[p + 1] - cand.begin[p]);
    }
    const size_t np = mine_pairs.size();
    std::vector<int32_t> words;
    words.reserve(2 + 3 * np + nt);
    words.push_back(static_cast<int32_t>(np));
    words.push_back(static_cast<int32_t>(nt));
    for (const size_t p : mine_pairs)
        words.push_back(cand.node[p]);
    for (const size_t p : mine_pairs)
        words.push_back(cand.body[p]);
    for (const size_t p : mine_pairs)
        words.push_back(cand.begin[p + 1] - cand.begin[p]);
    for (const size_t p : mine_pairs)
        words.insert(words.end(), cand.tri.begin() + cand.begin[p],
                     cand.tri.begin() + cand.begin[p + 1]);
    std::vector<char> mine(words.size() * sizeof(int32_t)), all;
    std::memcpy(mine.data(), words.data(), mine.size());
    comm.allgather_bytes(mine, all);
    std::vector<int32_t> w(all.size() / sizeof(int32_t));
    std::memcpy(w.data(), all.data(), w.size() * sizeof(int32_t));
    // every pair as (node, body, first tri in w, count), then in (node, body) order: the
    // processes' targets are disjoint, so this is the serial list
    struct Ref {
        NodeId node;
        BodyId body;
        size_t tri;
        int32_t count;
    };
    std::vector<Ref> refs;
    for (size_t at = 0; at < w.size();) {
        const size_t p_n = static_cast<size_t>(w[at]), t_n = static_cast<size_t>(w[at + 1]);
        const size_t nodes = at + 2, bodies = nodes + p_n, counts = bodies + p_n,
                     tris = counts + p_n;
        size_t t = tris;
        for (size_t p = 0; p < p_n; ++p) {
            refs.push_back(Ref{w[nodes + p], w[bodies + p], t, w[counts + p]});
            t += static_cast<size_t>(w[counts + p]);
        }
        at = tris + t_n;
    }
    std::sort(refs.begin(), refs.end(), [](const Ref& a, const Ref& b) {
        return a.node != b.node ? a.node < b.node : a.body < b.body;
    });
    cand.node.clear();
    cand.body.clear();
    cand.begin.assign(1, 0);
    cand.tri.clear();
    for (const Ref& r : refs) {
        cand.node.push_back(r.node);
        cand.body.push_back(r.body);
        cand.tri.insert(cand.tri.end(), w.begin() + static_cast<std::ptrdiff_t>(r.tri),
                        w.begin() + static_cast<std::ptrdiff_t>(r.tri) + r.count);
        cand.begin.push_back(static_cast<int32_t>(cand.tri.size()));
    }
    plan.contact.total_candidates = static_cast<int64_t>(cand.node.size());
    plan.contact.dest_valid = false;  // (ContactShare::send_cand indexes the candidates)
}

const std::vector<BodyId>& contactor_bodies(const Model& m, const State& s, const StepPlan& plan) {
    const ContactShare& share = plan.contact;
    if (share.boxes_valid) return share.box_bodies;
    list_contactors(m, s.topology, s.contact.cand, plan.node_owner.data(), plan.rank,
                    share.body_mark, share.box_bodies);
    share.boxes_valid = true;
    return share.box_bodies;
}

void add_contact_forces(const Model& m, State& s) {
    contact_forces_impl(m, s, nullptr, nullptr);
}

void add_contact_forces(const Model& m, State& s, const StepPlan& plan, const Comm& comm) {
    contact_forces_impl(m, s, &plan, &comm);
}

namespace {

// Baseline A (docs/theory.md eq. 7.11): a node of a boundary edge of length L sunk by delta
// into a triangle of altitude H >= h_min feels phi = 3 delta / H; the consistent edge stiffness
// (p L / H)[[1, 1/2], [1/2, 1]] has largest eigenvalue 3 p L / (2H) per edge, so a node with
// boundary edges e gets k_i <= (3 p / h_min) sum_e L_e / 2 (= 3 p L / H for two equal edges).
// The reaction on a partner of similar mass adds a factor 2 to k / m. Friction: one spring
// p_t per edge and partner triangle, at most 3 partners per edge for similar element sizes.
Real legacy_triangle_stable_dt(const Model& m, const ContactTopology& ct) {
    const ContactModel& cm = m.contact;
    Real p_max = 0, pt_max = 0;
    for (const ContactParams& p : cm.resolved) {
        p_max = std::max(p_max, p.penalty);
        if (p.friction > 0) pt_max = std::max(pt_max, p.tangential_penalty);
    }
    std::vector<Real> half_len(static_cast<size_t>(m.num_nodes()), 0.0);
    std::vector<int32_t> edges(static_cast<size_t>(m.num_nodes()), 0);
    for (const auto& e : ct.boundary_edges) {
        const Real l = norm(m.node_x0[e[1]] - m.node_x0[e[0]]);
        for (NodeId i : e) {
            half_len[i] += 0.5 * l;
            ++edges[i];
        }
    }
    Real dt = std::numeric_limits<Real>::infinity();
    for (NodeId i : ct.boundary_nodes) {
        if (ct.body_fixed[m.node_body[i]] || !(m.node_mass[i] > 0)) continue;
        const Real k = 3.0 * p_max / cm.h_min * half_len[i];
        dt = std::min(dt, 2.0 / std::sqrt(2.0 * k / m.node_mass[i]));
        if (pt_max > 0) {
            const Real kt = 3.0 * edges[i] * pt_max;
            dt = std::min(dt, 2.0 / std::sqrt(2.0 * kt / m.node_mass[i]));
        }
    }
    return dt;
}

}  // namespace

Real contact_stable_dt(const Model& m, const ContactTopology& ct) {
    const ContactModel& cm = m.contact;
    Real dt = std::numeric_limits<Real>::infinity();
    if (cm.algorithm == ContactAlgorithm::None || ct.num_sub_tris() == 0 || !(cm.m_bar > 0)) {
        return dt;
    }
    if (cm.algorithm == ContactAlgorithm::LegacyTriangle) return legacy_triangle_stable_dt(m, ct);

    // baseline B: |grad d_B| = H_ref / H_o <= H_ref / h_min instead of ~1, and the stiffness
    // g' k_n |grad d|^2 grows with its square (docs/theory.md §7.4)
    Real grad2 = 1;
    for (const LegacyBoundaryTri& t : ct.sub_legacy_b) {
        const Real r = t.h_ref / cm.h_min;
        grad2 = std::max(grad2, r * r);
    }

    // mass ratio of the pair spring (theory eq. 6.15): the target force (m_j/mbar) k g' d also
    // acts, spread by N_i <= 1, on a contactor node of mass m_i, so the two-mass system has omega^2
    // = (k g' / mbar)(1 + m_j / m_i) (the 1/m_j term vanishes for a fixed target, the m_j/m_i term
    // does not). Bound it by the heaviest target over the lightest movable contactor node: with
    // heavy base nodes pushing light block nodes the old factor 2 was unstable.
    // Edge targets (theory §6.12): a midpoint of scale w acts like a node of mass w m_dt, and
    // the target-side term 1 becomes the row-sum bound target_dt_factor
    Real m_target_max = 0, m_contactor_min = std::numeric_limits<Real>::infinity();
    for (NodeId j : ct.boundary_nodes)
        m_target_max = std::max(m_target_max, m.node_mass[j]);
    for (const Real w : ct.edge_scale)
        m_target_max = std::max(m_target_max, w * ct.m_dt);
    for (int32_t t = 0; t < ct.num_sub_tris(); ++t) {
        for (NodeId i : ct.sub_tri[t]) {
            if (i >= ct.num_real_nodes || m.node_inv_mass[i] == 0) continue;
            m_contactor_min = std::min(m_contactor_min, m.node_mass[i]);
        }
    }
    const Real mass_factor = std::isfinite(m_contactor_min) && m_contactor_min > 0
                                 ? ct.target_dt_factor + m_target_max / m_contactor_min
                                 : 1.0 + ct.target_dt_factor;

    // stiffness factor g' at the deepest penetration expected, d_ref = 0.1 h_min (spec §4.6);
    // the unloading branch is up to beta times stiffer than the loading one (theory eq. 6.13)
    const Real d_ref = 0.1 * cm.h_min;
    for (const ContactParams& p : cm.resolved) {
        Real gp = contact_dg(d_ref, p.alpha, p.length_scale);
        if (p.unloading == UnloadingLaw::Continuous) {
            gp = std::max(gp, p.beta * contact_g(d_ref, p.alpha, p.length_scale) / d_ref);
        } else {
            gp = std::max(gp, contact_dg(d_ref, p.beta, p.length_scale));
        }
        // omega_c = sqrt(g' k_n (1 + m_j/m_i) / mbar) (theory eq. 6.15; spec §3.4 has the factor
        // 2 of equal masses); damping lowers the bound
        const Real k = gp * p.penalty * grad2;
        const Real omega = std::sqrt(mass_factor * k / ct.m_dt);
        const Real zeta = p.damping / (2.0 * std::sqrt(k * ct.m_dt));
        dt = std::min(dt, 2.0 / omega * (std::sqrt(1.0 + zeta * zeta) - zeta));
        if (p.friction > 0 && p.tangential_penalty > 0) {
            dt = std::min(dt, 2.0 / std::sqrt(mass_factor * p.tangential_penalty / ct.m_dt));
        }
    }
    return dt;
}

}  // namespace fdem
