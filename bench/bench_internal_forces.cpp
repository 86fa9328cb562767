// Deformation part of the step (docs/performance.md): internal forces of every triangle, and
// internal forces + node update (a step() of a free block with no gravity, contact or support).
// items/s = element-steps/s. Args: {triangles, OpenMP threads}. The NoEnergy variants skip the
// strain energy (State::need_energy = false), as the CLI does between output steps.
#include "bench_common.hpp"
#include "element/cst.hpp"
#include "fdem/simulate.hpp"

namespace fdem {
namespace {

// element pass only: F, stress, energy (when `energy`) and nodal forces of every triangle
void internal_forces(benchmark::State& st, bool energy) {
    omp_set_num_threads(static_cast<int>(st.range(1)));
    const Model& m = bench::cached_block(st.range(0), false, false);
    State s = make_state(m, 0.5 * stable_time_step(m));
    for (int k = 0; k < 5; ++k)
        step(m, s);  // warm up to a deformed state
    s.need_energy = energy;
    for (auto _ : st) {
        const ElementPass p = add_internal_forces(m, s);
        benchmark::DoNotOptimize(p.strain_energy);
    }
    st.SetItemsProcessed(st.iterations() * m.num_tris());
    st.counters["omp_threads"] = static_cast<double>(st.range(1));
}

void BM_InternalForces(benchmark::State& st) {
    internal_forces(st, true);
}
// without the strain energy (State::need_energy = false, as the CLI between output steps)
void BM_InternalForcesNoEnergy(benchmark::State& st) {
    internal_forces(st, false);
}

// internal forces + node update: a whole step() of the deformation-only block
void deformation_step(benchmark::State& st, bool shuffled, bool energy = true) {
    omp_set_num_threads(static_cast<int>(st.range(1)));
    const Model& m = bench::cached_block(st.range(0), false, shuffled);
    State s = make_state(m, 0.5 * stable_time_step(m));
    for (int k = 0; k < 5; ++k)
        step(m, s);
    s.need_energy = energy;
    for (auto _ : st)
        step(m, s);
    st.SetItemsProcessed(st.iterations() * m.num_tris());
    st.counters["omp_threads"] = static_cast<double>(st.range(1));
}

void BM_DeformationStep(benchmark::State& st) {
    deformation_step(st, false);
}
void BM_DeformationStepShuffled(benchmark::State& st) {
    deformation_step(st, true);
}
void BM_DeformationStepNoEnergy(benchmark::State& st) {
    deformation_step(st, false, false);
}

BENCHMARK(BM_InternalForces)
    ->Apply([](auto* b) {
        bench::tri_sizes(b, 1);
        bench::tri_sizes(b, 2);
    }) -> Unit(benchmark::kMicrosecond);
BENCHMARK(BM_InternalForcesNoEnergy)
    ->Apply([](auto* b) {
        bench::tri_sizes(b, 1);
        bench::tri_sizes(b, 2);
    }) -> Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DeformationStep)
    ->Apply([](auto* b) {
        bench::tri_sizes(b, 1);
        bench::tri_sizes(b, 2);
    }) -> Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DeformationStepNoEnergy)
    ->Apply([](auto* b) {
        bench::tri_sizes(b, 1);
        bench::tri_sizes(b, 2);
    }) -> Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DeformationStepShuffled)
    ->Args({1 << 20, 1})
    ->Args({1 << 20, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace fdem
