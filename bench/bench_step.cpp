// The whole step on the continuum block scene with gravity and a clamped base
// (docs/performance.md). items/s = triangle-steps/s. Counters: dt [s], the relative energy drift
// |E(t) - E(0)| / max(kinetic + strain) over the timed steps, and the low 32 bits of the state
// hash (a speed-up that changes it must say so, style guide §4.9). Args: {triangles, threads}.
#include <algorithm>
#include <cmath>

#include "bench_common.hpp"
#include "fdem/simulate.hpp"
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

}  // namespace
}  // namespace fdem
