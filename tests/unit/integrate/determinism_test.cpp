// Determinism and allocation-freedom of the step (issue "performance"; docs/performance.md):
// the same scene run with 1, 2 and 3 OpenMP threads must give bitwise identical x and v, and
// step() must not allocate once warmed up.
#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "element/cst.hpp"
#include "fdem/scenario.hpp"
#include "fdem/simulate.hpp"
#include "support/alloc_count.hpp"
#include "support/hash.hpp"
#include "support/scenes.hpp"

// Counting global allocator for this test executable: while g_counting is set, every operator
// new is counted. Replacing the global operator new is the only way to see allocations made
// inside the library and the standard containers it uses. Other tests of this executable use
// the counters through support/alloc_count.hpp.
namespace alloc_count {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};
}  // namespace alloc_count
using alloc_count::g_allocations;
using alloc_count::g_counting;

void* operator new(std::size_t n) {
    if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1);
    if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
    return operator new(n);
}
// GCC 12 warns -Wmismatched-new-delete at the free() below when it inlines this operator delete
// into a caller whose pointer came from operator new: a false positive for a replacement pair
// that allocates with malloc and frees with free (both operators here)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete[](void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
    std::free(p);
}
#pragma GCC diagnostic pop

namespace fdem {
namespace {

// A deforming block (about 20k triangles, so it is renumbered and cut into many chunks of
// several colors) with gravity, a clamped base and material viscosity: every parallel loop and
// every reduction of the step is exercised.
const Model& block() {
    static const Model m = [] {
        scenes::BlockOptions o;
        o.num_tris = 20000;
        o.gravity = o.clamp = true;
        o.viscosity = 2e3;  // Pa s: small next to the stable-dt limit, exercises the viscous path
        return scenes::make_block(o);
    }();
    return m;
}

struct RunResult {
    uint64_t hash = 0;
    Energy energy;
};

RunResult run(int threads, int steps) {
    omp_set_num_threads(threads);
    const Model& m = block();
    State s = make_state(m, 0.9 * stable_time_step(m));
    for (int k = 0; k < steps; ++k)
        step(m, s);
    return {scenes::state_hash(s), s.energy};
}

TEST(Determinism, SameBitsForOneTwoAndThreeThreads) {
    const RunResult r1 = run(1, 60), r2 = run(2, 60), r3 = run(3, 60);
    // exact equality: the parallel loops must not change any floating-point operation order
    EXPECT_EQ(r1.hash, r2.hash);
    EXPECT_EQ(r1.hash, r3.hash);
    EXPECT_EQ(r1.energy.strain, r2.energy.strain);
    EXPECT_EQ(r1.energy.strain, r3.energy.strain);
    EXPECT_EQ(r1.energy.kinetic, r3.energy.kinetic);
    EXPECT_EQ(r1.energy.dissipated_viscous, r3.energy.dissipated_viscous);
    EXPECT_EQ(r1.energy.work_external, r3.energy.work_external);
    EXPECT_EQ(r1.energy.work_gravity, r3.energy.work_gravity);
    // and the run really deformed the block (a hash of a resting block proves nothing)
    EXPECT_GT(r1.energy.strain, 1e-3);
}

// The parallel element pass equals the serial reference loop up to the summation order of the
// nodal forces: at most a few ulps of the largest force.
TEST(Determinism, ParallelElementPassMatchesTheSerialLoop) {
    omp_set_num_threads(2);
    const Model& m = block();
    State s = make_state(m, 0.9 * stable_time_step(m));
    for (int k = 0; k < 10; ++k)
        step(m, s);
    std::vector<Vec2> f_ref(s.x.size());
    const ElementPass ref =
        add_internal_forces(m, s.x.data(), s.v.data(), f_ref.data(), 0, m.num_tris());
    std::fill(s.f.begin(), s.f.end(), Vec2{});
    const ElementPass par = add_internal_forces(m, s);
    Real fmax = 0;
    for (const Vec2& fi : f_ref)
        fmax = std::max(fmax, norm(fi));
    for (size_t i = 0; i < f_ref.size(); ++i) {
        // 1e-12 relative to the largest force: round-off of a different summation order (a node
        // sums at most ~8 terms of size <= fmax)
        ASSERT_NEAR(s.f[i].x, f_ref[i].x, 1e-12 * fmax) << "node " << i;
        ASSERT_NEAR(s.f[i].y, f_ref[i].y, 1e-12 * fmax) << "node " << i;
    }
    EXPECT_NEAR(par.strain_energy, ref.strain_energy, 1e-12 * ref.strain_energy);
    EXPECT_NEAR(par.viscous_power, ref.viscous_power, 1e-12 * ref.viscous_power);
    EXPECT_EQ(par.min_jacobian, ref.min_jacobian);
}

TEST(Determinism, StepAllocatesNothingAfterWarmUp) {
    for (int threads : {1, 2}) {
        omp_set_num_threads(threads);
        const Model& m = block();
        State s = make_state(m, 0.9 * stable_time_step(m));
        step(m, s);  // warm-up: first-use buffers and the OpenMP thread team
        step(m, s);
        g_allocations = 0;
        g_counting = true;
        for (int k = 0; k < 20; ++k)
            step(m, s);
        g_counting = false;
        EXPECT_EQ(g_allocations.load(), 0) << threads << " threads";
    }
}

// Loads (theory §4.1): a ring of about 6000 triangles (renumbered, many element chunks) under a
// follower pressure with a table on its rim and a dead traction on its bore: the same bits for
// 1 and 2 threads, and no allocation in the step.
TEST(Determinism, LoadedRingIsReproducibleAndAllocationFree) {
    const Scenario sc = load_scenario_from_string(R"([simulation]
end_time = 1.0
dt = "auto"
[[material]]
name = "m"
density = 1000.0
youngs_modulus = 1e9
poisson_ratio = 0.25
[[body]]
name = "ring"
mesh = "ring.geo"
mesh_size = 0.03
material = "m"
[[load]]
body = "ring"
group = "outer"
pressure = 1e7
time_function = "table"
table = [[0, 0], [1e-4, 1]]
[[load]]
body = "ring"
group = "inner"
traction = [1e6, 0]
)",
                                                  "ring.toml", FDEM_TEST_DATA_DIR);
    const Model& m = sc.model;
    uint64_t hash[2] = {};
    Real work[2] = {};
    for (int threads : {1, 2}) {
        omp_set_num_threads(threads);
        State s = make_state(m, sc.run.dt);
        step(m, s);
        step(m, s);
        g_allocations = 0;
        g_counting = true;
        for (int k = 0; k < 40; ++k)
            step(m, s);
        g_counting = false;
        EXPECT_EQ(g_allocations.load(), 0) << threads << " threads";
        hash[threads - 1] = scenes::state_hash(s);
        work[threads - 1] = s.energy.work_external;
    }
    EXPECT_EQ(hash[0], hash[1]);
    EXPECT_EQ(work[0], work[1]);
    EXPECT_GT(work[0], 0.0);
}

// A block dropped on a fixed slab with smooth contact (paper's contact, spec §4): contact forces
// too must be bitwise reproducible, and the contact code must not allocate once warmed up.
//
//           +-----+  free block 0.3 x 0.3 m, v0 = -1 m/s, 0.1 mm above the slab
//           |     |
//   +-------+-----+--------+  fixed slab 1 x 0.2 m
TEST(Determinism, ContactSceneIsReproducibleAndAllocationFree) {
    Model m;
    m.materials.push_back(scenes::paper_material());
    m.gravity = {0, -9.81};
    scenes::add_rectangle(m, 0, 0, 1, 0.2, 40, 8, 0, true);
    // 0.1 mm gap: closed within the 1500 steps even at the smaller contact dt of theory eq. 6.15
    scenes::add_rectangle(m, 0.3, 0.2001, 0.3, 0.3, 12, 12, 0, false, {0, -1});
    m.contact.algorithm = ContactAlgorithm::Smooth;
    finalize_model(m);
    uint64_t hash1 = 0;
    for (int threads : {1, 2, 3}) {
        omp_set_num_threads(threads);
        State s = make_state(m, 0.5 * stable_time_step(m));
        for (int k = 0; k < 3; ++k)
            step(m, s);
        int32_t max_active = 0;
        g_allocations = 0;
        g_counting = true;
        for (int k = 0; k < 1500; ++k) {
            step(m, s);
            max_active = std::max(max_active, s.contact.active_contacts);
        }
        g_counting = false;
        EXPECT_EQ(g_allocations.load(), 0) << threads << " threads";
        EXPECT_GT(max_active, 0) << "the block never touched the slab: the test proves nothing";
        if (threads == 1) hash1 = scenes::state_hash(s);
        EXPECT_EQ(scenes::state_hash(s), hash1) << threads << " threads";
    }
}

// Renumbering keeps the supports on the nodes the scene selected by position.
TEST(Determinism, RenumberingKeepsSupportsOnTheirNodes) {
    const Model& m = block();
    ASSERT_EQ(m.bcs.size(), 1u);
    const int n = static_cast<int>(std::lround(std::sqrt(20000 / 2.0)));
    EXPECT_EQ(m.bcs[0].nodes.size(), static_cast<size_t>(n + 1));
    for (NodeId i : m.bcs[0].nodes)
        EXPECT_EQ(m.node_x0[i].y, 0.0) << "node " << i;
    EXPECT_TRUE(std::is_sorted(m.bcs[0].nodes.begin(), m.bcs[0].nodes.end()));
}

}  // namespace
}  // namespace fdem
