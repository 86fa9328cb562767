// Broad phase (detect/broad_phase.cpp, uniform grid + counting sort) on the contact-heavy pack:
// one find_candidates() from the current positions, after the virtual-node update. Reported as
// seconds per mesh triangle per detection (counter s_per_tri, printed as e.g. 40n = 40 ns) for N =
// 1e4 ... 4e6 triangles: a flat column means linear time. items/s = triangles/s. Serial code: one
// thread. Args: {triangles}.
#include "bench_common.hpp"
#include "contact/contact.hpp"
#include "detect/broad_phase.hpp"
#include "fdem/simulate.hpp"

namespace fdem {
namespace {

void run_broad_phase(benchmark::State& st, BroadKernel kernel) {
    omp_set_num_threads(1);
    const Model& m = bench::cached_pack(st.range(0), false);
    State s = make_state(m, 0.5 * stable_time_step(m));
    update_virtual_nodes(m, s);
    find_candidates(m, s.topology, s.x.data(), s.contact.xv.data(), s.contact.cand, s.contact.broad,
                    kernel);  // warm-up: sizes
    for (auto _ : st) {
        update_virtual_nodes(m, s);
        find_candidates(m, s.topology, s.x.data(), s.contact.xv.data(), s.contact.cand,
                        s.contact.broad, kernel);
    }
    st.SetItemsProcessed(st.iterations() * m.num_tris());
    st.counters["omp_threads"] = 1;
    st.counters["s_per_tri"] =
        benchmark::Counter(static_cast<double>(st.iterations()) * m.num_tris(),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    st.counters["sub_tris"] = s.topology.num_sub_tris();
    st.counters["pairs"] = static_cast<double>(s.contact.cand.node.size());
}

// the default path (AVX-512 node loop where the CPU has it)
void BM_BroadPhase(benchmark::State& st) {
    run_broad_phase(st, BroadKernel::Auto);
}
// the portable node loop (what CPUs without AVX-512 run)
void BM_BroadPhaseScalar(benchmark::State& st) {
    run_broad_phase(st, BroadKernel::Scalar);
}

BENCHMARK(BM_BroadPhaseScalar)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BroadPhase)
    ->Arg(10000)
    ->Arg(30000)
    ->Arg(100000)
    ->Arg(300000)
    ->Arg(1000000)
    ->Arg(4000000)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace fdem
