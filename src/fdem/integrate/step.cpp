// The explicit time step (docs/architecture.md, docs/theory.md §5):
//   0. load forces at t^n on x^n (integrate/loads.cpp), their work over [x^{n-1}, x^n]
//   1. kicks due at t^n overwrite velocities
//   2. clear forces
//   3. internal forces of the triangles (elastic + viscous)          element/cst.cpp
//   3b. cohesive joint forces, damage, breaking (theory §9)          fracture/joints.cpp
//   3c. on steps where joints broke: sectors, fragments, contact topology of the dirty bodies,
//       broad phase again                                             integrate/fracture_update.cpp
//   4. contact forces (broad phase when the skin is exceeded, law)    contact/
//      + the load forces of step 0
//   5. gravity and mass-proportional damping
//   6. central difference: v^{n+1/2} = v^{n-1/2} + dt f/m; prescribed components overwrite v
//      (the controls State::bc_velocity / bc_enabled, theory §4.3)
//   7. energy accounting at t^n; x^{n+1} = x^n + dt v^{n+1/2}
//   8. failure checks (inverted element from step 3, NaN)
//
// Parallel loops (OpenMP) are bitwise deterministic: per-node work is independent, and every
// reduction is summed per fixed block of nodes (kNodeBlock, independent of the thread count) and
// then over the blocks in block order (docs/performance.md).
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "contact/contact.hpp"
#include "core/huge_pages.hpp"
#include "element/cst.hpp"
#include "fdem/error.hpp"
#include "fdem/simulate.hpp"
#include "fracture/joints.hpp"
#include "integrate/fracture_update.hpp"
#include "integrate/loads.hpp"
#include "integrate/node_update.hpp"
#include "parallel/decompose.hpp"
#include "parallel/distributed.hpp"

namespace fdem {

namespace {

/// Nodes per reduction block of the node update. Fixed, so the partial sums do not depend on
/// the number of threads.
constexpr NodeId kNodeBlock = 2048;

/// Node loops run on one thread below this many nodes (fork/join costs more than the work).
constexpr NodeId kMinParallelNodes = 4 * kNodeBlock;
// "no bad joint" in the reduction of a distributed step's joint pass (above every joint id)
constexpr double kNoJoint = 1e300;

// kNodeGroup (parallel/distributed.hpp): the node update's energy terms are summed naively over
// each group of kNodeGroup consecutive node ids, then the groups exactly (theory §4.4). A
// distributed run owns whole groups, so its sums are the serial ones (issue #15).
static_assert(kNodeBlock % kNodeGroup == 0);

/// Partial sums per node group in State::scratch_sums: kinetic2, gravity work, damping power.
constexpr size_t kNodeSlots = 3;

// A support active at t = 0 imposes its velocity from the start: it is the initial velocity of
// its nodes, so E_0 contains their kinetic energy (theory §4; otherwise the jump from v0 to the
// prescribed value in the first half step would be unaccounted work). Called by make_state() and
// again by the first step, so controls changed in between set v^0 too (theory §4.3).
void apply_initial_supports(const Model& m, State& s) {
    const Real tm = 0.5 * s.dt;
    for (size_t k = 0; k < m.bcs.size(); ++k) {
        const BoundaryCondition& bc = m.bcs[k];
        if (!s.bc_enabled[k] || !(bc.start <= tm && tm < bc.end)) continue;
        const Vec2 vel = s.bc_velocity[k];
        for (NodeId i : bc.nodes) {
            if (m.node_inv_mass[i] == 0) continue;
            if (bc.has_x) s.v[i].x = vel.x;
            if (bc.has_y) s.v[i].y = vel.y;
        }
    }
}

// the per-node arrays of the state, the topology's and the joints' on huge pages
// (core/huge_pages.hpp: advice, no result changes; arrays under 1 MiB are left alone)
void state_on_huge_pages(const State& s) {
    for (const auto* a : {&s.x, &s.v, &s.f, &s.f_contact})
        prefer_huge_pages(*a);
    prefer_huge_pages(s.scratch_sums);
    const ContactTopology& t = s.topology;
    for (const auto* a : {&t.node_scale, &t.node_dist})
        prefer_huge_pages(*a);
    prefer_huge_pages(t.node_dist_edge);
    prefer_huge_pages(t.sub_tri);
    prefer_huge_pages(t.sub_parent);
    prefer_huge_pages(t.body_cnode);
    const JointState& j = s.joints;
    for (const auto* a : {&j.d_max, &j.z_max})
        prefer_huge_pages(*a);
    for (const auto* a : {&j.f_prev, &j.d_prev})
        prefer_huge_pages(*a);
    prefer_huge_pages(j.status);
    prefer_huge_pages(j.work);
}

}  // namespace

State make_state(const Model& m, Real dt) {
    State s;
    s.dt = dt;
    s.x = m.node_x0;
    s.v = m.node_v0;
    // fixed bodies never move, whatever velocity their entry was given
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        if (m.bodies[m.node_body[i]].fixed) s.v[i] = {};
    }
    // controls (State::bc_velocity, bc_enabled): the Model's values until a caller changes them
    s.bc_velocity.resize(m.bcs.size());
    for (size_t k = 0; k < m.bcs.size(); ++k)
        s.bc_velocity[k] = m.bcs[k].velocity;
    s.bc_enabled.assign(m.bcs.size(), 1);
    apply_initial_supports(m, s);
    s.f.assign(m.node_x0.size(), Vec2{});
    s.f_contact.assign(m.node_x0.size(), Vec2{});
    size_t n_bc = 0;
    for (const BoundaryCondition& bc : m.bcs)
        n_bc += bc.nodes.size();
    s.scratch_bc_v.assign(2 * n_bc, Vec2{});  // v^{n-1/2}, then x^n of each supported node
    size_t n_load_slots = 0;
    for (const Load& ld : m.loads)
        n_load_slots += static_cast<size_t>(ld.num_slots());
    s.scratch_load.assign(n_load_slots, Vec2{});
    s.bc_reaction.assign(n_bc, Vec2{});
    // partial sums: 4 per element chunk (element/cst.cpp), 3 per node group (below)
    const size_t n_groups = (m.node_x0.size() + kNodeGroup - 1) / kNodeGroup;
    s.scratch_sums.assign(
        std::max(4 * static_cast<size_t>(m.element_schedule.num_chunks()), kNodeSlots * n_groups),
        0.0);
    init_fracture_state(m, s);  // joint history, pre-broken joints, sectors, fragments
    init_contact_state(m, s);
    if (!m.prebroken_joints.empty()) rebuild_fracture_views(m, s);  // topology with the cracks
    state_on_huge_pages(s);
    return s;
}

namespace {

/// Kernel of the node update (set_node_kernel).
NodeKernel g_node_kernel = NodeKernel::Auto;

// Steps 5-7 for every node: gravity and mass damping, v^{n+1/2} = v^{n-1/2} + dt f/m, the
// energies at t^n, and x^{n+1} = x^n + dt v^{n+1/2} (supported nodes are redone by the caller
// once their velocity is prescribed). Partial sums per fixed block of kNodeBlock nodes go to
// part[kNodeSlots * block]. kGravity / kDamped compile out the gravity work (and its read of
// X) and the damping term when they are zero, which leaves the sums bitwise unchanged. Without
// kEnergy (State::need_energy false) the kinetic energy and the gravity work are not summed
// (slots 0, 1 stay 0; step() then leaves them stale, like the strain energy): their ordered sums
// are serial chains of one addition per node, ~4 cycles each, the largest cost of the update on
// the 3 nodes per triangle of a jointed mesh (docs/performance.md). The damping power is
// integrated every step and always summed.
// The AVX-512 kernel (integrate/node_update_simd.cpp) does the same per block, bitwise.
template <bool kGravity, bool kDamped, bool kEnergy>
void update_nodes(const Model& m, const NodeUpdate& u, Vec2* __restrict x, Vec2* __restrict v,
                  const Vec2* __restrict f, Real* __restrict part, NodeId first_node,
                  NodeId end_node) {
    // nodes [first_node, end_node), whole groups (all nodes, or a process's share)
    const NodeId nn = end_node;
    const NodeId n_blocks = (end_node - first_node + kNodeBlock - 1) / kNodeBlock;
    const Real* __restrict mass = m.node_mass.data();
    const Real* __restrict inv_mass = m.node_inv_mass.data();
    const Vec2* __restrict x0 = m.node_x0.data();
    const bool simd = node_update_uses_avx512();
    const bool avx2 = node_update_uses_avx2();  // never with simd (Auto prefers AVX-512)
    const NodeArrays arrays{x, v, f, mass, inv_mass, x0};
#pragma omp parallel for schedule(static) if (end_node - first_node >= kMinParallelNodes)
    for (NodeId blk = 0; blk < n_blocks; ++blk) {
        const NodeId block_begin = first_node + blk * kNodeBlock;
        const NodeId block_end = std::min(nn, block_begin + kNodeBlock);
        if (simd) {  // the whole block in one call, partials per group
            detail::node_block_avx512(
                arrays, u, kGravity, kDamped, kEnergy, block_begin, block_end,
                part + kNodeSlots * static_cast<size_t>(block_begin / kNodeGroup));
            continue;
        }
        if (avx2) {  // the same with 4 nodes per instruction
            detail::node_block_avx2(
                arrays, u, kGravity, kDamped, kEnergy, block_begin, block_end,
                part + kNodeSlots * static_cast<size_t>(block_begin / kNodeGroup));
            continue;
        }
        for (NodeId g0 = block_begin; g0 < block_end; g0 += kNodeGroup) {
            Real kin = 0, grav = 0, damp = 0;
            const NodeId end = std::min(nn, g0 + kNodeGroup);
            Real* slot = part + kNodeSlots * static_cast<size_t>(g0 / kNodeGroup);
            for (NodeId i = g0; i < end; ++i) {
                const Real inv = inv_mass[i];
                if (inv == 0) continue;  // nodes of fixed bodies
                const Real mi = mass[i];
                const Vec2 v_old = v[i];
                Vec2 fi = f[i] + mi * u.g;
                if constexpr (kDamped) fi -= (u.c * mi) * v_old;
                const Vec2 v_new = v_old + (u.dt_v * inv) * fi;
                const Vec2 vn = u.first ? v_old : 0.5 * (v_old + v_new);  // v^n (theory eq. 5.2)
                if constexpr (kEnergy) kin += mi * norm2(vn);
                // work of gravity up to x^n: the exact potential change (theory eq. 4.2)
                if constexpr (kGravity && kEnergy) grav += mi * dot(u.g, x[i] - x0[i]);
                if constexpr (kDamped) damp += u.c * mi * dot(v_old, vn);
                v[i] = v_new;
                x[i] += u.dt * v_new;
            }
            slot[0] = kin;
            slot[1] = grav;
            slot[2] = damp;
        }
    }
}

// Is the next velocity kick due at this step (judged at mid-step, theory §5.2)?
bool kick_due(const Model& m, const State& s) {
    return s.next_kick < static_cast<int32_t>(m.kicks.size()) &&
           m.kicks[static_cast<size_t>(s.next_kick)].time <= s.time + 0.5 * s.dt;
}

// Apply the velocity kicks whose time has come (theory §5.2). Their energy input is counted as
// external work, so the balance still closes.
void apply_kicks(const Model& m, State& s) {
    while (kick_due(m, s)) {
        const VelocityKick& k = m.kicks[static_cast<size_t>(s.next_kick)];
        for (const Body& b : m.bodies) {
            if (b.group != k.group || b.fixed) continue;
            for (NodeId i = b.node_begin; i < b.node_end; ++i) {
                const Vec2 old = s.v[i];
                if (k.has_x) s.v[i].x = k.velocity.x;
                if (k.has_y) s.v[i].y = k.velocity.y;
                s.energy_sums.work_external.add(0.5 * m.node_mass[i] *
                                                (norm2(s.v[i]) - norm2(old)));
            }
        }
        ++s.next_kick;
    }
}

}  // namespace

void set_node_kernel(NodeKernel k) {
    g_node_kernel = k;
}

bool node_update_avx2_available() {
    static const bool supported = __builtin_cpu_supports("avx2");
    return supported;
}

bool node_update_uses_avx2() {
    return (g_node_kernel == NodeKernel::Auto && !node_update_uses_avx512() &&
            node_update_avx2_available()) ||
           (g_node_kernel == NodeKernel::Avx2 && node_update_avx2_available());
}

bool node_update_uses_avx512() {
    static const bool supported = __builtin_cpu_supports("avx512f");
    return g_node_kernel == NodeKernel::Auto && supported;
}

const char* node_update_kernel_name() {
    return node_update_uses_avx512() ? "avx512" : node_update_uses_avx2() ? "avx2" : "portable";
}

namespace {

// mark[i] != 0 as runs
void make_runs(std::span<const uint8_t> mark, NodeRuns& out) {
    const NodeId nn = static_cast<NodeId>(mark.size());
    out.runs.clear();
    out.first.clear();
    out.count = 0;
    for (NodeId i = 0; i < nn;) {
        if (!mark[static_cast<size_t>(i)]) {
            ++i;
            continue;
        }
        NodeId e = i + 1;
        while (e < nn && mark[static_cast<size_t>(e)])
            ++e;
        out.runs.emplace_back(i, e);
        out.first.push_back(out.count);
        out.count += e - i;
        i = e;
    }
    out.first.push_back(out.count);
}

// StepPlan::clear_f: the owned nodes, GhostExchange::static_need (the other nodes of its element
// runs and chunks, the load nodes) and the nodes of the bodies.csv sets it sums whose f it reads
// (ContactShare::f_readers): every node its element pass, loads and contact apply write f at;
// StepPlan::clear_fc: those and the nodes whose f_contact only its sets read
// (ContactShare::force_readers), where the contact apply writes f_contact only. clear_f leaves
// out the nodes of the triangles of its element runs in ElementSchedule::chunk_first chunks: the
// element pass stores their forces every step (first_internal_forces(); a chunk it runs whole on
// energy steps holds those runs too)
void make_clear_runs(const Model& m, const StepPlan& p) {
    std::vector<uint8_t> mark(static_cast<size_t>(m.num_nodes()), 0);
    for (const auto& [b, e] : p.own_runs)
        std::fill(mark.begin() + b, mark.begin() + e, uint8_t{1});
    for (const NodeId i : p.ghosts.static_need)
        mark[static_cast<size_t>(i)] = 1;
    for (const auto& [i, r] : p.contact.f_readers) {
        if (r == p.rank) mark[static_cast<size_t>(i)] = 1;
    }
    std::vector<uint8_t> mark_fc = mark;
    for (const auto& [i, r] : p.contact.force_readers) {
        if (r == p.rank) mark_fc[static_cast<size_t>(i)] = 1;
    }
    make_runs(mark_fc, p.clear_fc);
    const ElementSubset& es = p.elements;
    for (size_t k = 0; k < es.chunks.size(); ++k) {
        if (!m.element_schedule.chunk_first[static_cast<size_t>(es.chunks[k])]) continue;
        for (int32_t r = es.run_begin[k]; r < es.run_begin[k + 1]; ++r) {
            const auto [b, e] = es.runs[static_cast<size_t>(r)];
            for (TriId t = b; t < e; ++t) {
                for (NodeId n : m.tri_nodes[t])
                    mark[static_cast<size_t>(n)] = 0;
            }
        }
    }
    make_runs(mark, p.clear_f);
    p.clear_valid = true;
}

// zero a[i] for the nodes of runs; threads split them evenly
void clear_runs(Vec2* a, const NodeRuns& nr) {
    const NodeId total = nr.count;
    const auto* runs = nr.runs.data();
    const NodeId* first = nr.first.data();
    const int32_t nruns = static_cast<int32_t>(nr.runs.size());
#pragma omp parallel if (total >= kMinParallelNodes)
    {
        const int nthr = omp_get_num_threads(), t = omp_get_thread_num();
        const NodeId k0 = static_cast<NodeId>(static_cast<int64_t>(total) * t / nthr);
        const NodeId k1 = static_cast<NodeId>(static_cast<int64_t>(total) * (t + 1) / nthr);
        // the run holding the k0-th node: the last with first[r] <= k0
        int32_t r = static_cast<int32_t>(std::upper_bound(first, first + nruns, k0) - first) - 1;
        for (NodeId k = k0; k < k1 && r < nruns; ++r) {
            const NodeId b = runs[r].first + (k - first[r]);
            const NodeId e = std::min(runs[r].second, b + (k1 - k));
            std::fill(a + b, a + e, Vec2{});
            k += e - b;
        }
    }
}

// Step 2 of a distributed step: f zero on StepPlan::clear_f, and f_contact on clear_fc or at the
// nodes of ContactState::fc_nodes (clear_listed_contact_forces())
void clear_forces(const Model& m, State& s, const StepPlan& p) {
    if (!p.clear_valid) {
        make_clear_runs(m, p);
        // nodes new to the runs may hold f_contact that nobody cleared while they were not read
        s.contact.fc_sparse = false;
    }
    clear_runs(s.f.data(), p.clear_f);
    // f_contact at the nodes the last applies reached when they are few (ContactState::fc_nodes)
    if (m.contact.algorithm != ContactAlgorithm::None &&
        !clear_listed_contact_forces(s, m.num_nodes()))
        clear_runs(s.f_contact.data(), p.clear_fc);
}

// The step; with a plan, as one process of a distributed run (parallel/distributed.hpp): the
// element pass over the plan's chunks, the node update and the supports over its nodes, then the
// owned parts exchanged so that every process holds the whole State again.
void step_impl(const Model& m, State& s, const StepPlan* plan, const Comm* comm) {
    const NodeId nn = m.num_nodes();
    const Real dt = s.dt;
    Vec2* x = s.x.data();
    Vec2* v = s.v.data();
    Vec2* f = s.f.data();
    const bool first = s.step == 0;
    StepTiming& timing = s.timing;  // (wall time per phase; no result reads it)
    timing.begin();
    if (first) apply_initial_supports(m, s);  // controls changed since make_state()
    // ghost lists after distribute() or a restore (every node is current then)
    if (plan != nullptr && plan->ghosts.active && plan->ghosts.dirty) {
        rebuild_ghosts(m, s, *plan, *comm);
        timing.mark(StepPhase::Communication);
    }

    // 0. load forces F^n on x^n, and the half of their trapezoidal work over [x^{n-1}, x^n]
    // that F^n does: 1/2 F^n . dt v^{n-1/2} (theory eq. 4.7), with v^{n-1/2} before any kick
    // (it is what moved the nodes); the F^{n-1} half was booked as pending by the last step
    const bool loaded = !m.loads.empty();
    Vec2* load_f = s.scratch_load.data();
    Real load_work_now = 0;
    if (loaded) {
        evaluate_loads(m, s.time, x, load_f);
        if (!first) load_work_now = 0.5 * dt * load_power(m, load_f, v);
    }

    // 1. kicks (a distributed run with ghosts: they read and write every node of their
    // bodies, so x and v are all-gathered first on the steps that have one)
    if (plan != nullptr && plan->ghosts.active && kick_due(m, s)) {
        timing.mark(StepPhase::Elements);
        gather_nodes(x, *plan, *comm);
        gather_nodes(v, *plan, *comm);
        timing.mark(StepPhase::Communication);
    }
    apply_kicks(m, s);

    // 2. clear forces (without contact, f_contact is never written and stays zero)
    Vec2* fc = s.f_contact.data();
    // the serial step's element pass stores the forces of nodes no other triangle has (jointed
    // bodies, first_internal_forces()): f is zeroed on the other nodes only
    const bool first_writer = plan == nullptr;
    if (plan != nullptr && plan->ghosts.active &&
        (m.contact.algorithm == ContactAlgorithm::None ||
         m.contact.algorithm == ContactAlgorithm::Smooth)) {
        // a distributed run: only the nodes this process adds forces to (StepPlan::clear_f,
        // clear_fc)
        clear_forces(m, s, *plan);
    } else {
        // f_contact: at the nodes the last applies reached when they are few
        // (ContactState::fc_nodes), else at every node
        if (m.contact.algorithm != ContactAlgorithm::None && !clear_listed_contact_forces(s, nn)) {
#pragma omp parallel for schedule(static) if (nn >= kMinParallelNodes)
            for (NodeId i = 0; i < nn; ++i)
                fc[i] = {};
        }
        if (first_writer) {
            for (const auto& [b, e] : m.element_schedule.clear_runs) {
#pragma omp parallel for schedule(static) if (e - b >= kMinParallelNodes)
                for (NodeId i = b; i < e; ++i)
                    f[i] = {};
            }
        } else {
#pragma omp parallel for schedule(static) if (nn >= kMinParallelNodes)
            for (NodeId i = 0; i < nn; ++i)
                f[i] = {};
        }
    }

    // 3. internal forces (parallel over the element schedule, deterministic)
    ElementPass pass;
    ExactSum element_sums[2];  // (distributed: this process's strain energy and viscous power)
    if (plan == nullptr) {
        pass = first_internal_forces(m, s);  // (first_writer: the clear above left their nodes)
    } else {
        // owner computes (spec D7.1); energies as exact sums over the processes (theory §4.4)
        // (first = true: the chunk_first chunks store, make_clear_runs() left their nodes)
        const ElementSubsetPass sp =
            add_internal_forces(m, s, plan->elements, plan->viscous, /*first=*/true);
        // strain energy and viscous power: summed over the processes with the node update's
        // sums at the end of the step (one reduction)
        element_sums[0] = sp.strain_energy;
        element_sums[1] = sp.viscous_power;
        timing.mark(StepPhase::Elements);
        // the smallest det F over the processes, ties to the smallest chunk: the serial one;
        // with the skin trigger's max |v|^2 of contact (v is final for this step's contact
        // after the kicks) in one reduction (spec D8.3)
        // (without contact no skin: no pass over v)
        const bool skin = m.contact.algorithm != ContactAlgorithm::None;
        double mins[2] = {sp.min_jacobian, skin ? -max_speed2(v, plan->own_runs) : 0.0};
        comm->min(mins, 2);
        timing.mark(StepPhase::Communication);
        pass.min_jacobian = mins[0];
        plan->max_speed2 = -mins[1];
        if (!(pass.min_jacobian > 0)) {  // the same branch on every process
            const bool mine = sp.min_jacobian == pass.min_jacobian;
            const Real chunk = comm->min(mine ? sp.min_jacobian_chunk : 1e300);
            pass.min_jacobian_tri = static_cast<TriId>(
                comm->min(mine && sp.min_jacobian_chunk == chunk ? sp.min_jacobian_tri : 1e300));
            // the failure below: failure.vtu shows the forces of the serial run at this point
            gather_forces(s, *plan, *comm);
        }
    }
    timing.mark(StepPhase::Elements);  // (a distributed step: the branch above, if taken)
    if (pass.min_jacobian_tri != kNone && !(pass.min_jacobian > 0)) {
        const TriId t = pass.min_jacobian_tri;
        throw SimulationError(
            s.step, s.time, fmt::format("triangle {} (body {})", t, m.tri_body[t]),
            fmt::format("element inverted (det F = {:.3g}); reduce dt (now {:.3g} s) or increase "
                        "the contact penalty",
                        pass.min_jacobian, dt));
    }

    // 3b. cohesive joints (theory eqs. 9.3-9.19): forces added to f, damage, work; E_joint and
    // W_frac are evaluated only with need_energy, else they keep their last values (stale, like
    // the strain energy)
    ExactSum joint_elastic;  // (distributed: this process's E_joint, with need_energy)
    bool broke = false;      // (distributed: a joint of any process broke in this step)
    if (!m.joints.nodes.empty() && plan != nullptr) {
        // each process its JointSubset (owner computes, docs/parallel.md "Joints"); the work
        // is summed over the processes on energy steps, the failure and the breaks every step
        const JointSubsetPass jp =
            joint_forces(m.joints, s.joints, s.x, s.f, s.need_energy, plan->joints.subset, s.step);
        plan->joints.work.add(jp.work);
        joint_elastic = jp.elastic;
        timing.mark(StepPhase::Joints);
        // the smallest bad joint (the serial one: the first in joint order) and whether any
        // joint broke, in one reduction
        double r[2] = {jp.bad >= 0 ? static_cast<double>(jp.bad) : kNoJoint,
                       -static_cast<double>(jp.newly_broken)};
        comm->min(r, 2);
        timing.mark(StepPhase::Communication);
        if (r[0] < kNoJoint) {
            gather_forces(s, *plan, *comm);  // failure.vtu: the serial forces at this point
            throw_joint_failure(static_cast<int32_t>(r[0]), s.step, s.time);
        }
        if (r[1] < 0) {
            broke = true;
            // 3c. the breaks of every process, then the serial break processing everywhere
            // (it reads no positions: sectors, fragments and topology come from the mesh and
            // the joints' status; the contact's broad phase below all-gathers x and v first)
            share_breaks(m, s, *plan, *comm);
            timing.mark(StepPhase::Communication);
            process_breaks(m, s);
            timing.mark(StepPhase::Joints);
        }
    } else if (!m.joints.nodes.empty()) {
        const JointPass jp =
            joint_forces(m.joints, s.joints, s.x, s.f, s.need_energy, s.step, s.time);
        if (s.need_energy) {
            s.energy.joint = jp.elastic_energy;  // eq. 9.18
            s.energy.fracture = jp.fracture;     // eq. 9.19
        }
        // 3c. break processing (spec fracture.md §7): serial, only on steps with breaks
        if (jp.newly_broken > 0) process_breaks(m, s);
        timing.mark(StepPhase::Joints);
    }

    // 4. contact forces (writes s.f, s.f_contact, s.energy.contact, dissipated_contact; marks
    // its own phases)
    if (plan == nullptr) {
        add_contact_forces(m, s);
    } else {
        add_contact_forces(m, s, *plan, *comm);  // the pairs of the owned targets
    }
    timing.mark(StepPhase::ContactApply);
    if (loaded) add_load_forces(m, load_f, f);

    // remember v^{n-1/2} and x^n of supported nodes (preallocated scratch): their reaction needs
    // the old velocity, and their position is redone from x^n once the support has set v
    const size_t n_bc = s.scratch_bc_v.size() / 2;
    {
        size_t k = 0;
        for (const BoundaryCondition& bc : m.bcs) {
            for (NodeId i : bc.nodes) {
                s.scratch_bc_v[k] = v[i];
                s.scratch_bc_v[n_bc + k] = x[i];
                ++k;
            }
        }
    }

    // 5. gravity and mass damping; 6. velocity update; 7. energies at t^n
    // judged at mid-step like kicks and supports, so damping that ends when a kick fires does not
    // also damp the kicked velocity
    const bool mass_damped =
        s.time + 0.5 * dt < m.mass_damping.until && m.mass_damping.coefficient > 0;
    const Real c = m.mass_damping.coefficient;
    const Vec2 g = m.gravity;
    // the first step starts from v^0 and advances half a step to v^{1/2} (theory eq. 5.1), so a
    // constant acceleration is integrated exactly: x^n = x^0 + v^0 t + a t^2 / 2
    const Real dt_v = first ? 0.5 * dt : dt;
    const NodeId n_groups = (nn + kNodeGroup - 1) / kNodeGroup;
    if (s.scratch_sums.size() < kNodeSlots * static_cast<size_t>(n_groups)) {
        s.scratch_sums.resize(kNodeSlots * static_cast<size_t>(n_groups));  // first call only
    }
    // the nodes this process updates: all, or its runs of whole groups
    const std::pair<NodeId, NodeId> all_nodes{0, nn};
    const std::span<const std::pair<NodeId, NodeId>> runs =
        plan != nullptr ? std::span<const std::pair<NodeId, NodeId>>(plan->own_runs)
                        : std::span<const std::pair<NodeId, NodeId>>(&all_nodes, 1);
    Real* part = s.scratch_sums.data();
    const Real* inv_mass = m.node_inv_mass.data();
    const bool gravity = g.x != 0 || g.y != 0;
    const NodeUpdate u{dt, dt_v, c, g, first};
    const auto update = [&]<bool kEnergy>() {
        for (const auto& [b, e] : runs) {
            if (gravity && mass_damped) {
                update_nodes<true, true, kEnergy>(m, u, x, v, f, part, b, e);
            } else if (gravity) {
                update_nodes<true, false, kEnergy>(m, u, x, v, f, part, b, e);
            } else if (mass_damped) {
                update_nodes<false, true, kEnergy>(m, u, x, v, f, part, b, e);
            } else {
                update_nodes<false, false, kEnergy>(m, u, x, v, f, part, b, e);
            }
        }
    };
    if (s.need_energy) {
        update.template operator()<true>();
    } else {
        update.template operator()<false>();
    }
    // the group partials combined exactly (theory §4.4): the same sums whatever the thread count
    // or the grouping of the groups (over processes too)
    // (only the sums this step evaluates: the others are zeros)
    ExactSum kinetic2, gravity_work, damping_power;
    if (s.need_energy || mass_damped) {
        for (const auto& [b, e] : runs) {
            for (NodeId grp = b / kNodeGroup; grp < (e + kNodeGroup - 1) / kNodeGroup; ++grp) {
                const Real* slot = part + kNodeSlots * static_cast<size_t>(grp);
                kinetic2.add(slot[0]);
                gravity_work.add(slot[1]);
                damping_power.add(slot[2]);
            }
        }
    }

    // prescribed velocity components overwrite v^{n+1/2}; the support reaction
    // R = m (v_new - v_free)/dt does the work R . v^n dt (theory eq. 4.3)
    // their work and kinetic-energy corrections are summed naively over runs of consecutive
    // support slots whose nodes lie in one node group, then the runs exactly (theory §4.4): the
    // run boundaries depend only on the Model, and a run has one owner in a distributed step
    ExactSum support_work_sum;
    {
        size_t k = 0;
        const Real tm = s.time + 0.5 * dt;
        NodeId run_group = -1;
        Real run_work = 0, run_kinetic = 0;
        const auto flush = [&] {
            support_work_sum.add(run_work);
            kinetic2.add(run_kinetic);
            run_work = run_kinetic = 0;
        };
        for (size_t b = 0; b < m.bcs.size(); ++b) {
            const BoundaryCondition& bc = m.bcs[b];
            // the controls (State::bc_enabled, bc_velocity) as of this step: a change books its
            // work like a window boundary of the support (theory §4.3)
            const bool active = s.bc_enabled[b] && tm >= bc.start && tm < bc.end;
            const Vec2 vel = s.bc_velocity[b];
            for (NodeId i : bc.nodes) {
                const size_t slot = k++;
                if (i / kNodeGroup != run_group) {  // before any skip: the same runs everywhere
                    flush();
                    run_group = i / kNodeGroup;
                }
                const Vec2 v_old = s.scratch_bc_v[slot];
                s.bc_reaction[slot] = {};
                if (!active || m.node_inv_mass[i] == 0) continue;
                if (plan != nullptr && plan->node_owner[i] != plan->rank) continue;  // its owner's
                const Real mi = m.node_mass[i];
                const Vec2 v_free = v[i];
                Vec2 v_new = v_free;
                if (bc.has_x) v_new.x = vel.x;
                if (bc.has_y) v_new.y = vel.y;
                const Vec2 reaction = (mi / dt_v) * (v_new - v_free);
                const Vec2 vn_free = first ? v_old : 0.5 * (v_old + v_free);
                const Vec2 vn = first ? v_old : 0.5 * (v_old + v_new);
                s.bc_reaction[slot] = reaction;  // theory eq. 8.1 (bodies.csv)
                run_work += dot(reaction, vn) * dt_v;
                run_kinetic += mi * (norm2(vn) - norm2(vn_free));
                v[i] = v_new;
            }
        }
        flush();
    }

    // x^{n+1} = x^n + dt v^{n+1/2} of the supported nodes, now that their v is final (the others
    // were moved by update_nodes; redoing it from the saved x^n gives the same bits as one pass)
    {
        size_t k = 0;
        for (const BoundaryCondition& bc : m.bcs) {
            for (NodeId i : bc.nodes) {
                const Vec2 x_old = s.scratch_bc_v[n_bc + k++];
                if (inv_mass[i] == 0) continue;
                if (plan != nullptr && plan->node_owner[i] != plan->rank) continue;
                x[i] = x_old + dt * v[i];
            }
        }
    }

    timing.mark(StepPhase::NodeUpdate);
    if (plan != nullptr) {
        // the energy sums over the processes in one reduction (else all are zero everywhere),
        // with the contact sums of the step (energies, pairs in contact, lost pairs: the ghost
        // exchange below needs the total of those)
        const bool pair_sums = plan->contact.sums_pending;
        // the joints' work since the last energy step and E_joint (theory eqs. 9.17-9.19)
        const bool joint_sums = s.need_energy && !m.joints.nodes.empty();
        if (s.need_energy || mass_damped || plan->viscous || !m.bcs.empty() || pair_sums) {
            ExactSum sums[8 + kContactSums] = {kinetic2,         gravity_work,    damping_power,
                                               support_work_sum, element_sums[0], element_sums[1]};
            int n = 6;
            if (joint_sums) {
                sums[n++] = plan->joints.work;
                sums[n++] = joint_elastic;
            }
            if (pair_sums) std::copy_n(plan->contact.sums, kContactSums, sums + n);
            comm->sum(sums, pair_sums ? n + kContactSums : n);
            kinetic2 = sums[0];
            gravity_work = sums[1];
            damping_power = sums[2];
            support_work_sum = sums[3];
            pass.strain_energy = sums[4].value();
            pass.viscous_power = sums[5].value();
            if (joint_sums) {
                JointState& js = s.joints;
                plan->joints.work.clear();
                js.total_work_sum.add(sums[6]);
                js.total_work = js.total_work_sum.value();
                s.energy.joint = sums[7].value();                    // eq. 9.18
                s.energy.fracture = js.total_work - s.energy.joint;  // eq. 9.19
            }
            if (pair_sums) finish_contact_sums(s, *plan, *comm, sums + n);
        }
        // x and v of the nodes each process reads, from their owners (with ghosts; every node
        // without, after a step that lost a contact: its message names the node's position,
        // and after a step with breaks: cracks.csv gives the broken joints' positions); the
        // supports' reactions; f, f_contact (each process has them for the nodes it needs) and
        // the other nodes' x and v are gathered where they are written (Simulation, output
        // steps)
        if (plan->ghosts.active && s.contact.lost_inside == 0 && !broke) {
            exchange_ghosts(s, *plan, *comm);
        } else {
            gather_nodes(s.x.data(), *plan, *comm);
            gather_nodes(s.v.data(), *plan, *comm);
        }
        if (!plan->bc_order.empty()) {
            double* buf = plan->bc_buffer.data();
            const size_t b = static_cast<size_t>(plan->bc_displs[plan->rank]) / 2;
            const size_t e = b + static_cast<size_t>(plan->bc_counts[plan->rank]) / 2;
            for (size_t j = b; j < e; ++j) {
                const Vec2 r = s.bc_reaction[static_cast<size_t>(plan->bc_order[j])];
                buf[2 * j] = r.x;
                buf[2 * j + 1] = r.y;
            }
            comm->allgatherv(buf, plan->bc_counts, plan->bc_displs);
            for (size_t j = 0; j < plan->bc_order.size(); ++j)
                s.bc_reaction[static_cast<size_t>(plan->bc_order[j])] = {buf[2 * j],
                                                                         buf[2 * j + 1]};
        }
        timing.mark(StepPhase::Communication);
    }
    const Real support_work = support_work_sum.value();
    s.energy.time = s.time;
    if (s.need_energy) {  // else stale (State::need_energy)
        s.energy.kinetic = 0.5 * kinetic2.value();
        s.energy.strain = pass.strain_energy;
        s.energy.work_gravity = gravity_work.value();
    }
    // the reaction R^n acts over [t^{n-1/2}, t^{n+1/2}]: half of its work belongs before t^n, the
    // other half is booked with the next step (theory eq. 4.3); the integrated terms go into
    // their exact running sums (theory §4.4), rounded once below
    ExactSum& work_external = s.energy_sums.work_external;
    if (loaded) {
        // loads: 1/2 F^n . (x^{n+1} - x^n) belongs after t^n, booked next step (theory eq. 4.7)
        const Real load_work_pending = 0.5 * dt * load_power(m, load_f, v);
        work_external.add(s.energy.work_external_pending);
        work_external.add(0.5 * support_work);
        work_external.add(load_work_now);
        s.energy.work_external_pending = 0.5 * support_work + load_work_pending;
    } else {
        work_external.add(s.energy.work_external_pending);
        work_external.add(0.5 * support_work);
        s.energy.work_external_pending = 0.5 * support_work;
    }
    s.energy_sums.dissipated_viscous.add((pass.viscous_power + damping_power.value()) * dt_v);
    s.energy.work_external = work_external.value();
    s.energy.dissipated_viscous = s.energy_sums.dissipated_viscous.value();

    s.time += dt;
    ++s.step;
    timing.end_step(StepPhase::NodeUpdate);
}

}  // namespace

void step(const Model& m, State& s) {
    step_impl(m, s, nullptr, nullptr);
}

void step_distributed(const Model& m, State& s, const StepPlan& plan, const Comm& comm) {
    step_impl(m, s, &plan, &comm);
}

void gather_nodes(Vec2* a, const StepPlan& plan, const Comm& comm) {
    double* buf = plan.gather_buffer.data();
    const NodeId* order = plan.gather_order.data();
    const size_t b = static_cast<size_t>(plan.node_displs[static_cast<size_t>(plan.rank)]) / 2;
    const size_t e = b + static_cast<size_t>(plan.node_counts[static_cast<size_t>(plan.rank)]) / 2;
    for (size_t k = b; k < e; ++k) {
        buf[2 * k] = a[order[k]].x;
        buf[2 * k + 1] = a[order[k]].y;
    }
    comm.allgatherv(buf, plan.node_counts, plan.node_displs);
    // the other processes' parts (its own values are already there)
    for (size_t k = 0; k < b; ++k)
        a[order[k]] = {buf[2 * k], buf[2 * k + 1]};
    for (size_t k = e; k < plan.gather_order.size(); ++k)
        a[order[k]] = {buf[2 * k], buf[2 * k + 1]};
}

void gather_forces(State& s, const StepPlan& plan, const Comm& comm) {
    gather_nodes(s.f.data(), plan, comm);
}

namespace {
// the centre of every node group (kNodeGroup consecutive ids) at the positions x, and a weight
// of 1 per group. The centres are in units of the groups' mean extent along each axis (the mean
// width and height of their bounding boxes; unscaled where a mean is 0 or not finite): RCB cuts
// across the longest extent of its points, so in these units it cuts where it crosses the
// fewest groups. A group sticks out of a cut by about its own extent, so that is the cut that
// leaves the thinnest band of interleaved groups (the 6 400-block pack's groups are 16 blocks
// of a row, 3.2 m x 0.1 m: a cut across x interleaved the two parts over a 3.2 m band, ~8 000
// ghost nodes per process; docs/parallel.md "Node groups' extent"). Any partition gives the
// same bits (spec D10).
void group_centres(NodeId nn, const Vec2* x, std::vector<Vec2>& centre,
                   std::vector<double>& weight) {
    const NodeId groups = (nn + kNodeGroup - 1) / kNodeGroup;
    centre.assign(static_cast<size_t>(groups), Vec2{});
    weight.assign(static_cast<size_t>(groups), 1.0);
    Real wx = 0, wy = 0;  // sums of the groups' extents
    for (NodeId g = 0; g < groups; ++g) {
        const NodeId b = g * kNodeGroup, e = std::min(nn, b + kNodeGroup);
        Vec2 c, lo = x[b], hi = x[b];
        for (NodeId i = b; i < e; ++i) {
            c += x[i];
            lo = {std::min(lo.x, x[i].x), std::min(lo.y, x[i].y)};
            hi = {std::max(hi.x, x[i].x), std::max(hi.y, x[i].y)};
        }
        centre[static_cast<size_t>(g)] = (1.0 / static_cast<Real>(e - b)) * c;
        wx += hi.x - lo.x;
        wy += hi.y - lo.y;
    }
    if (!(wx > 0) || !(wy > 0) || !std::isfinite(wx) || !std::isfinite(wy)) return;
    const Real sx = static_cast<Real>(groups) / wx, sy = static_cast<Real>(groups) / wy;
    for (Vec2& c : centre)
        c = {c.x * sx, c.y * sy};
}
}  // namespace

void node_group_points(const Model& m, std::vector<Vec2>& centre, std::vector<double>& weight) {
    group_centres(m.num_nodes(), m.node_x0.data(), centre, weight);
    for (const auto& t : m.tri_nodes)
        weight[static_cast<size_t>(t[0] / kNodeGroup)] += 1.0;
}

void node_group_work(const Model& m, const State& s, std::vector<Vec2>& centre,
                     std::vector<double>& weight) {
    group_centres(m.num_nodes(), s.x.data(), centre, weight);
    for (const Body& b : m.bodies) {
        if (b.fixed) continue;  // (no element forces: outside the element chunks)
        for (TriId t = b.tri_begin; t < b.tri_end; ++t)
            weight[static_cast<size_t>(m.tri_nodes[t][0] / kNodeGroup)] += kWorkPerTriangle;
    }
    const ContactAlgorithm a = m.contact.algorithm;
    if (a == ContactAlgorithm::None || a == ContactAlgorithm::LegacyTriangle) return;
    const ContactTopology& ct = s.topology;
    for (const NodeId j : s.contact.cand.node)
        weight[static_cast<size_t>(target_node(ct, j) / kNodeGroup)] += kWorkPerCandidate;
    for (const ActiveContact& c : s.contact.active)
        weight[static_cast<size_t>(target_node(ct, c.node) / kNodeGroup)] += kWorkPerContact;
}

StepPlan make_part_plan(const Model& m, int32_t rank, int32_t procs,
                        std::vector<int32_t> node_owner) {
    StepPlan p;
    p.rank = rank;
    p.procs = procs;
    const NodeId nn = m.num_nodes();
    if (node_owner.size() != static_cast<size_t>(nn))
        throw std::invalid_argument("make_part_plan: node_owner must have one entry per node");
    p.node_owner = std::move(node_owner);
    for (NodeId b = 0; b < nn; b += kNodeGroup) {
        if (p.node_owner[static_cast<size_t>(b)] != rank) continue;
        const NodeId e = std::min(nn, b + kNodeGroup);
        if (!p.own_runs.empty() && p.own_runs.back().second == b) {
            p.own_runs.back().second = e;
        } else {
            p.own_runs.emplace_back(b, e);
        }
    }
    p.elements = element_subset(m, p.node_owner, rank);
    if (!m.joints.nodes.empty()) p.joints.subset = joint_subset(m.joints, p.node_owner, rank);
    init_ghosts(m, p);
    for (const Material& mt : m.materials)
        p.viscous = p.viscous || mt.viscosity > 0 || mt.damping_ratio > 0;
    // support slots (the order of Model::bcs and their nodes) grouped by the owner of the node
    std::vector<std::vector<int32_t>> by_owner(static_cast<size_t>(procs));
    int32_t slot = 0;
    for (const BoundaryCondition& bc : m.bcs) {
        for (NodeId i : bc.nodes)
            by_owner[static_cast<size_t>(p.node_owner[static_cast<size_t>(i)])].push_back(slot++);
    }
    p.bc_counts.assign(static_cast<size_t>(procs), 0);
    p.bc_displs.assign(static_cast<size_t>(procs), 0);
    for (int32_t r = 0; r < procs; ++r) {
        p.bc_displs[static_cast<size_t>(r)] = 2 * static_cast<int>(p.bc_order.size());
        p.bc_counts[static_cast<size_t>(r)] =
            2 * static_cast<int>(by_owner[static_cast<size_t>(r)].size());
        p.bc_order.insert(p.bc_order.end(), by_owner[static_cast<size_t>(r)].begin(),
                          by_owner[static_cast<size_t>(r)].end());
    }
    p.bc_buffer.assign(2 * p.bc_order.size(), 0.0);
    return p;
}

std::vector<int32_t> node_owners(const Model& m, int32_t procs,
                                 std::span<const int32_t> group_owner) {
    const NodeId nn = m.num_nodes();
    const NodeId groups = (nn + kNodeGroup - 1) / kNodeGroup;
    std::vector<int32_t> owner_of_group(static_cast<size_t>(groups), 0);
    if (!group_owner.empty()) {
        if (group_owner.size() != static_cast<size_t>(groups)) {
            throw std::invalid_argument(
                "node_owners: group_owner must have one entry per node group");
        }
        for (NodeId g = 0; g < groups; ++g) {
            const int32_t o = group_owner[static_cast<size_t>(g)];
            if (o < 0 || o >= procs) throw std::invalid_argument("node_owners: owner out of range");
            owner_of_group[static_cast<size_t>(g)] = o;
        }
    } else {
        // contiguous ranges of whole groups, about the same number of groups each
        for (int32_t r = 0; r < procs; ++r) {
            for (NodeId g = static_cast<NodeId>(int64_t{groups} * r / procs);
                 g < static_cast<NodeId>(int64_t{groups} * (r + 1) / procs); ++g)
                owner_of_group[static_cast<size_t>(g)] = r;
        }
    }
    std::vector<int32_t> node_owner(static_cast<size_t>(nn), 0);
    for (NodeId i = 0; i < nn; ++i)
        node_owner[static_cast<size_t>(i)] = owner_of_group[static_cast<size_t>(i / kNodeGroup)];
    return node_owner;
}

StepPlan make_step_plan(const Model& m, int32_t rank, int32_t procs,
                        std::span<const int32_t> group_owner) {
    const NodeId nn = m.num_nodes();
    StepPlan p = make_part_plan(m, rank, procs, node_owners(m, procs, group_owner));
    // the all-gather layout: node ids by (owner, id), one counting pass and one placing pass
    p.node_counts.assign(static_cast<size_t>(procs), 0);
    p.node_displs.assign(static_cast<size_t>(procs), 0);
    for (NodeId i = 0; i < nn; ++i)
        p.node_counts[static_cast<size_t>(p.node_owner[static_cast<size_t>(i)])] += 2;
    for (int32_t r = 1; r < procs; ++r) {
        p.node_displs[static_cast<size_t>(r)] =
            p.node_displs[static_cast<size_t>(r) - 1] + p.node_counts[static_cast<size_t>(r) - 1];
    }
    p.gather_order.resize(static_cast<size_t>(nn));
    {
        std::vector<size_t> at(static_cast<size_t>(procs));  // next place per owner, in nodes
        for (int32_t r = 0; r < procs; ++r)
            at[static_cast<size_t>(r)] =
                static_cast<size_t>(p.node_displs[static_cast<size_t>(r)]) / 2;
        for (NodeId i = 0; i < nn; ++i)
            p.gather_order[at[static_cast<size_t>(p.node_owner[static_cast<size_t>(i)])]++] = i;
    }
    p.gather_buffer.assign(2 * static_cast<size_t>(nn), 0.0);
    return p;
}

void throw_not_finite(const Model& m, const State& s, NodeId i) {
    throw SimulationError(
        s.step, s.time, fmt::format("node {} (body {})", i, m.node_body[i]),
        fmt::format("position or velocity is not finite; the run is unstable: reduce dt "
                    "(now {:.3g} s) or check penalties and damping",
                    s.dt));
}

void check_state(const Model& m, const State& s) {
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        if (!std::isfinite(s.x[i].x) || !std::isfinite(s.x[i].y) || !std::isfinite(s.v[i].x) ||
            !std::isfinite(s.v[i].y)) {
            throw_not_finite(m, s, i);
        }
    }
}

}  // namespace fdem
