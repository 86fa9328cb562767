// The whole step on the continuum block scene with gravity and a clamped base
// (docs/performance.md). items/s = triangle-steps/s. Counters: dt [s], the relative energy drift
// |E(t) - E(0)| / max(kinetic + strain) over the timed steps, and the low 32 bits of the state
// hash (a speed-up that changes it must say so, style guide §4.9). Args: {triangles, threads}.
#include <algorithm>
#include <cmath>
#include <ctime>
#include <map>
#include <memory>
#include <numeric>
#include <random>

#include "bench_common.hpp"
#include "bench_phases.hpp"
#include "fdem/measure.hpp"
#include "fdem/simulate.hpp"
#include "integrate/fracture_update.hpp"
#include "support/hash.hpp"

namespace fdem {
namespace {

void BM_Step(benchmark::State& st) {
    omp_set_num_threads(static_cast<int>(st.range(1)));
    const Model& m = bench::cached_block(st.range(0), true, false);
    State s = make_state(m, 0.9 * stable_time_step(m));
    step(m, s);
    const Real e0 = s.energy.total();
    Real scale = 0, drift = 0;
    for (auto _ : st) {
        step(m, s);
        // a few flops per step: negligible next to the step, so not excluded from the timing
        scale = std::max(scale, s.energy.kinetic + s.energy.strain);
        drift = std::max(drift, std::abs(s.energy.total() - e0));
    }
    st.SetItemsProcessed(st.iterations() * m.num_tris());
    st.counters["omp_threads"] = static_cast<double>(st.range(1));
    st.counters["dt"] = s.dt;
    st.counters["drift"] = scale > 0 ? drift / scale : 0;
    st.counters["steps"] = static_cast<double>(s.step);
    st.counters["hash32"] = static_cast<double>(scenes::state_hash(s) & 0xffffffffu);
}

BENCHMARK(BM_Step)
    ->Apply([](auto* b) {
        bench::tri_sizes(b, 1);
        bench::tri_sizes(b, 2);
    }) -> Unit(benchmark::kMicrosecond);

// The whole step of an intact jointed continuum (issue #14 "Performance"): BM_Step's block with
// gravity and a clamped base, every internal edge an intact cohesive joint (every triangle its
// own three nodes, 1.5 joints per triangle; scenes::BlockOptions::jointed), so the step runs the
// element pass, the joint pass (theory §9) and the contact of the one fragment's boundary. dt =
// 0.9 x stable (joint bound included, theory eq. 9.21). items/s = triangle-steps/s; joints/s =
// joint-steps/s (the reference code counts triangles and joints together). Args: {triangles,
// threads, energy every step}. Skips with an error if a joint softens (the load is elastic).
const Model& cached_jointed_block(int64_t num_tris) {
    static std::map<int64_t, std::unique_ptr<Model>> cache;
    auto& slot = cache[num_tris];
    if (!slot) {
        if (num_tris >= (1 << 20)) cache.clear();
        scenes::BlockOptions o;
        o.num_tris = num_tris;
        o.gravity = o.clamp = o.jointed = true;
        auto& fresh = cache[num_tris];
        fresh = std::make_unique<Model>(scenes::make_block(o));
        return *fresh;
    }
    return *slot;
}

void BM_StepJointed(benchmark::State& st) {
    omp_set_num_threads(static_cast<int>(st.range(1)));
    const Model& m = cached_jointed_block(st.range(0));
    State s = make_state(m, 0.9 * stable_time_step(m));
    step(m, s);
    s.need_energy = st.range(2) != 0;
    for (auto _ : st)
        step(m, s);
    int64_t not_intact = 0;
    for (const JointStatus js : s.joints.status)
        not_intact += js != JointStatus::Intact;
    if (not_intact != 0) st.SkipWithError("joints left the elastic range");
    st.SetItemsProcessed(st.iterations() * m.num_tris());
    const double joints = static_cast<double>(m.joints.num_joints());
    st.counters["joints"] = joints;
    st.counters["joints_per_s"] = benchmark::Counter(static_cast<double>(st.iterations()) * joints,
                                                     benchmark::Counter::kIsRate);
    st.counters["tris_and_joints_per_s"] =
        benchmark::Counter(static_cast<double>(st.iterations()) * (joints + m.num_tris()),
                           benchmark::Counter::kIsRate);
    st.counters["omp_threads"] = static_cast<double>(st.range(1));
    st.counters["energy"] = static_cast<double>(st.range(2));
    st.counters["dt"] = s.dt;
    st.counters["steps"] = static_cast<double>(s.step);
    st.counters["hash32"] = static_cast<double>(scenes::state_hash(s) & 0xffffffffu);
}

BENCHMARK(BM_StepJointed)
    ->ArgsProduct({{1 << 14, 1 << 17, 1 << 20}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

// The cost of breaks (issue #14 "fragment splitting cost per break"; spec fracture.md §7 step 3c):
// BM_StepJointed's block; every iteration breaks the next `breaks` joints of a seeded random
// order (status Broken, break_step = this step, as the kernel marks them), then runs
// process_breaks (sectors, fragments, rebuild_contact_topology of the body, topology_changed)
// and the next step(), whose broad phase runs again. 20 iterations (<= 5 % of the joints broken,
// so the block stays one piece held by its other joints). Counters (this thread's CPU time, one
// thread): us_process_breaks per call, us_step_after (the step after, with its detection),
// us_per_break = (process_breaks + step after - a plain step) / breaks; the plain step is
// timed on the same state before the first break. Args: {triangles, breaks per step}.
void BM_StepJointedBreaks(benchmark::State& st) {
    omp_set_num_threads(1);
    const Model& m = cached_jointed_block(st.range(0));
    const int breaks = static_cast<int>(st.range(1));
    State s = make_state(m, 0.9 * stable_time_step(m));
    s.need_energy = false;
    // this thread's CPU time (the machine is shared: wall time includes other processes' slices)
    const auto now = [] {
        timespec ts{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
        return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
    };
    for (int k = 0; k < 5; ++k)
        step(m, s);
    double t0 = now();
    constexpr int kPlain = 20;
    for (int k = 0; k < kPlain; ++k)
        step(m, s);
    const double plain = (now() - t0) / kPlain;
    std::vector<int32_t> order(static_cast<size_t>(m.joints.num_joints()));
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), std::mt19937_64(7));
    size_t next = 0;
    double t_breaks = 0, t_after = 0;
    for (auto _ : st) {
        for (int k = 0; k < breaks; ++k) {
            const auto j = static_cast<size_t>(order[next++]);
            s.joints.status[j] = JointStatus::Broken;
            s.joints.mode[j] = JointMode::I;
            s.joints.break_step[j] = s.step;
        }
        t0 = now();
        process_breaks(m, s);
        const double t1 = now();
        step(m, s);
        t_breaks += t1 - t0;
        t_after += now() - t1;
    }
    const double n = static_cast<double>(st.iterations());
    st.counters["us_plain_step"] = 1e6 * plain;
    st.counters["us_process_breaks"] = 1e6 * t_breaks / n;
    st.counters["us_step_after"] = 1e6 * t_after / n;
    st.counters["us_per_break"] = 1e6 * ((t_breaks + t_after) / n - plain) / breaks;
    st.counters["joints"] = static_cast<double>(m.joints.num_joints());
    st.counters["fragments_end"] =
        static_cast<double>(std::count_if(s.tri_fragment.begin(), s.tri_fragment.end(),
                                          [&, t = TriId{0}](TriId f) mutable { return f == t++; }));
}

BENCHMARK(BM_StepJointedBreaks)
    ->ArgsProduct({{1 << 12, 1 << 14, 1 << 16}, {1, 64}})
    ->Iterations(20)
    ->Unit(benchmark::kMicrosecond);

// BM_Step with State::need_energy = false: no strain energy (one std::log per triangle), as the
// CLI runs between output steps. The hash must equal BM_Step's for the same number of steps.
void BM_StepNoEnergy(benchmark::State& st) {
    omp_set_num_threads(static_cast<int>(st.range(1)));
    const Model& m = bench::cached_block(st.range(0), true, false);
    State s = make_state(m, 0.9 * stable_time_step(m));
    step(m, s);
    s.need_energy = false;
    for (auto _ : st)
        step(m, s);
    st.SetItemsProcessed(st.iterations() * m.num_tris());
    st.counters["omp_threads"] = static_cast<double>(st.range(1));
    st.counters["dt"] = s.dt;
    st.counters["steps"] = static_cast<double>(s.step);
}

BENCHMARK(BM_StepNoEnergy)
    ->Apply([](auto* b) {
        bench::tri_sizes(b, 1);
        bench::tri_sizes(b, 2);
    }) -> Unit(benchmark::kMicrosecond);

// BM_Step on the block with a damping ratio of 0.05 (theory eq. 2.6; as most user scenes, e.g.
// examples/03_contact_slide): every triangle is viscous (tri_eta > 0), so the element pass also
// computes the rate of deformation and the viscous power. Args: {triangles, threads}.
const Model& cached_viscous_block(int64_t num_tris) {
    static std::map<int64_t, std::unique_ptr<Model>> cache;
    auto& slot = cache[num_tris];
    if (!slot) {
        if (num_tris >= (1 << 20)) cache.clear();
        auto& fresh = cache[num_tris];
        scenes::BlockOptions o;
        o.num_tris = num_tris;
        o.gravity = o.clamp = true;
        fresh = std::make_unique<Model>(scenes::make_block(o));
        Model& m = *fresh;
        Material& mat = m.materials[0];
        mat.damping_ratio = 0.05;
        // element viscosity eta + 2 h xi sqrt(E rho), h = smallest altitude (theory eq. 2.6), as
        // finalize_model computes it
        for (TriId t = 0; t < m.num_tris(); ++t) {
            const auto& n = m.tri_nodes[t];
            const Vec2 X0 = m.node_x0[n[0]], X1 = m.node_x0[n[1]], X2 = m.node_x0[n[2]];
            const Real lmax = std::max({norm(X1 - X0), norm(X2 - X1), norm(X0 - X2)});
            const Real h = 2.0 * m.tri_area0[t] / lmax;
            m.tri_eta[t] = mat.viscosity + 2.0 * h * mat.damping_ratio *
                                               std::sqrt(mat.youngs_modulus * mat.density);
        }
        return m;
    }
    return *slot;
}

void BM_StepViscous(benchmark::State& st) {
    omp_set_num_threads(static_cast<int>(st.range(1)));
    const Model& m = cached_viscous_block(st.range(0));
    State s = make_state(m, 0.9 * stable_time_step(m));
    step(m, s);
    s.need_energy = st.range(2) != 0;
    for (auto _ : st)
        step(m, s);
    st.SetItemsProcessed(st.iterations() * m.num_tris());
    st.counters["omp_threads"] = static_cast<double>(st.range(1));
    st.counters["energy"] = static_cast<double>(st.range(2));
    st.counters["dt"] = s.dt;
    st.counters["steps"] = static_cast<double>(s.step);
    st.counters["hash32"] = static_cast<double>(scenes::state_hash(s) & 0xffffffffu);
}

// {triangles, threads, energy every step}: 16k (in cache) and 1M, 1 thread
BENCHMARK(BM_StepViscous)
    ->ArgsProduct({{1 << 14, 1 << 20}, {1}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

// BM_StepNoEnergy plus Resultants::accumulate after every step, as the CLI runs it when it writes
// bodies.csv: the cost of the measurement when asked for (the clamped base is a boundary group).
// The hash must equal BM_StepNoEnergy's for the same number of steps (it only reads the state).
void BM_StepNoEnergyResultants(benchmark::State& st) {
    omp_set_num_threads(static_cast<int>(st.range(1)));
    const Model& m = bench::cached_block(st.range(0), true, false);
    State s = make_state(m, 0.9 * stable_time_step(m));
    const Resultants r(m);
    IntervalImpulses acc = r.make_impulses();
    step(m, s);
    s.need_energy = false;
    for (auto _ : st) {
        step(m, s);
        r.accumulate(m, s, acc);
    }
    st.SetItemsProcessed(st.iterations() * m.num_tris());
    st.counters["omp_threads"] = static_cast<double>(st.range(1));
    st.counters["dt"] = s.dt;
    st.counters["steps"] = static_cast<double>(s.step);
}

BENCHMARK(BM_StepNoEnergyResultants)
    ->ArgsProduct({{65536, 1048576}, {1}})
    ->Unit(benchmark::kMicrosecond);

// The whole step on a contact scene, dt = 0.5 x stable (contact bound included). Besides
// items/s = triangle-steps/s, dt and drift as in BM_Step: the per-phase breakdown in CPU seconds
// per call (bench_phases.hpp): t_element, t_broad (one detection; broad_per_step = detections
// per step), t_narrow (contact without detection); the node update, clears and supports are the
// step time minus these. Also the candidate pairs and the active contacts.
// measure: also Resultants::accumulate after every step (bodies.csv, BM_StepPackResultants).
void step_scene(benchmark::State& st, const Model& m, int warm_up, bool measure = false,
                Real warm_up_time = 0) {
    State s = make_state(m, 0.5 * stable_time_step(m));
    if (warm_up_time > 0) warm_up = static_cast<int>(std::ceil(warm_up_time / s.dt));
    for (int k = 0; k < warm_up; ++k)  // past the first steps, until the scene is in contact
        step(m, s);
    const Resultants r(m);
    IntervalImpulses acc = r.make_impulses();
    const Real e0 = s.energy.total();
    const int64_t steps0 = s.step, rebuilds0 = s.contact.rebuilds;
    Real scale = 0, drift = 0;
    for (auto _ : st) {
        step(m, s);
        if (measure) r.accumulate(m, s, acc);
        scale = std::max(scale, s.energy.kinetic + s.energy.strain + s.energy.contact);
        drift = std::max(drift, std::abs(s.energy.total() - e0));
    }
    const double steps = static_cast<double>(s.step - steps0);
    st.SetItemsProcessed(st.iterations() * m.num_tris());
    const bench::PhaseTimes p = bench::time_phases(m, s, 5);
    const double rebuild_rate = static_cast<double>(s.contact.rebuilds - rebuilds0) / steps;
    st.counters["omp_threads"] = static_cast<double>(omp_get_max_threads());
    st.counters["dt"] = s.dt;
    st.counters["drift"] = scale > 0 ? drift / scale : 0;
    st.counters["steps"] = steps;
    st.counters["t_element"] = p.element;
    st.counters["t_broad"] = p.broad;
    st.counters["broad_per_step"] = rebuild_rate;
    st.counters["t_narrow"] = p.narrow;
    st.counters["pairs"] = static_cast<double>(p.pairs);
    st.counters["cand_tris"] = static_cast<double>(p.cand_tris);  // locate tests of one pass
    st.counters["active"] = s.contact.active_contacts;
    // the in-contact pair: narrow-phase time per active contact (a (target, contactor body) pair
    // with a force), and the active contacts per body (saturation of a pack)
    st.counters["ns_per_active"] =
        s.contact.active_contacts > 0 ? 1e9 * p.narrow / s.contact.active_contacts : 0;
    st.counters["active_per_body"] =
        static_cast<double>(s.contact.active_contacts) / std::max(1, m.num_bodies());
    st.counters["hash32"] = static_cast<double>(scenes::state_hash(s) & 0xffffffffu);
}

void BM_StepPack(benchmark::State& st) {
    omp_set_num_threads(static_cast<int>(st.range(1)));
    step_scene(st, bench::cached_pack(st.range(0), false), 100);  // the middle has collided
}

BENCHMARK(BM_StepPack)->ArgsProduct({{20000, 200000}, {1, 2}})->Unit(benchmark::kMicrosecond);

// The contact-saturated pack (issue #16 item 1): brick-bond blocks, initially touching (gap 0),
// converging on the centre with neighbours closing at 0.5 m/s; measured after 0.2 ms, inside the
// compression phase, when every block presses on all its neighbours: active_per_body about 10
// (a block's 4 corners and 4 edge midpoints are targets; measured 10.6 at 0.1 ms, 9.8 at 0.5 ms,
// 0.4 at 1 ms once the pack has rebounded). With 1 mm gaps the pack saturates less (3.8 per
// block at 2 ms) and rebounds sooner. Args: {triangles, threads}.
void BM_StepPackSaturated(benchmark::State& st) {
    omp_set_num_threads(static_cast<int>(st.range(1)));
    step_scene(st, bench::cached_saturated_pack(st.range(0), 0.5, 0.0), 0, false, 2e-4);
}

BENCHMARK(BM_StepPackSaturated)
    ->ArgsProduct({{20000, 80000}, {1, 2}})
    ->Unit(benchmark::kMicrosecond);
// The same pack for exactly 300 steps: A/B runs of two binaries time the same stretch of the
// compressing pack (a variable iteration count would compare different states).
void BM_StepPackSaturatedFixed(benchmark::State& st) {
    BM_StepPackSaturated(st);
}
BENCHMARK(BM_StepPackSaturatedFixed)
    ->ArgsProduct({{20000}, {1, 2}})
    ->Iterations(300)
    ->Unit(benchmark::kMicrosecond);

// The brick-bond pack of the issue #16 comparison with the reference code ("converging brick-bond
// pack of two-triangle blocks, 20k / 80k triangles, once every gap has closed"; target >= 15 M
// triangle-steps/s): the same pack with 1 mm gaps, neighbours closing at 0.5 m/s, so every gap
// has closed at 2 ms; measured from 2.2 ms. Args: {triangles, threads}.
void BM_StepPackBrickBond(benchmark::State& st) {
    omp_set_num_threads(static_cast<int>(st.range(1)));
    step_scene(st, bench::cached_saturated_pack(st.range(0), 0.5, 1e-3), 0, false, 2.2e-3);
}

BENCHMARK(BM_StepPackBrickBond)
    ->ArgsProduct({{20000, 80000}, {1, 2}})
    ->Unit(benchmark::kMicrosecond);

// BM_StepPack plus Resultants::accumulate after every step (every node of a pack is a contact
// node: the worst case of the measurement's per-step sums)
void BM_StepPackResultants(benchmark::State& st) {
    omp_set_num_threads(static_cast<int>(st.range(1)));
    step_scene(st, bench::cached_pack(st.range(0), false), 100, true);
}

BENCHMARK(BM_StepPackResultants)->ArgsProduct({{20000}, {1}})->Unit(benchmark::kMicrosecond);

// Args: {particles per side, threads}; ~6.5 triangles per particle plus the walls
void BM_StepParticles(benchmark::State& st) {
    omp_set_num_threads(static_cast<int>(st.range(1)));
    // 1500 steps = 0.67 ms: the 1 mm gaps close at 2-5 m/s after ~0.3 ms
    step_scene(st, bench::cached_particles(static_cast<int>(st.range(0))), 1500);
}

BENCHMARK(BM_StepParticles)->ArgsProduct({{100}, {1, 2}})->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace fdem
