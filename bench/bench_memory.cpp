// Memory per triangle of the block scene (model + state), target <= 200 B (docs/performance.md).
// peak_B_per_tri: getrusage() peak resident set over the process (includes the mesh and the
// temporaries of model building, and the ~10 MB of the program itself) divided by triangles.
// Run one size per process, e.g. --benchmark_filter=BM_Memory/4194304, or the peak of an earlier
// larger case is what you see. Args: {triangles, jointed}: jointed = 1 makes every internal edge
// an intact cohesive joint (scenes::BlockOptions::jointed: every triangle its own three nodes,
// 1.5 joints per triangle; issue #14, against the estimate of spec fracture.md §1.4 "Costs").
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>

#include "fdem/simulate.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

double peak_rss_bytes() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_maxrss) * 1024.0;  // ru_maxrss is in KiB on Linux
}

double current_rss_bytes() {
    long pages = 0, resident = 0;
    if (FILE* f = std::fopen("/proc/self/statm", "r")) {
        if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
        std::fclose(f);
    }
    return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE));
}

template <class T>
double bytes(const std::vector<T>& v) {
    return static_cast<double>(v.capacity() * sizeof(T));
}

// bytes of the joint arrays (Model::joints and State::joints), by capacity; dn_max ... as_min are
// sized only for mixed_mode = "proportional" (the default since 2026-12-02: 96 B per joint)
double joint_bytes(const Model& m, const State& s) {
    const Joints& J = m.joints;
    const JointState& js = s.joints;
    return bytes(J.nodes) + bytes(J.length0) + bytes(J.law) + bytes(J.laws) + bytes(J.gather_node) +
           bytes(J.gather_begin) + bytes(J.gather_entry) + bytes(js.d_max) + bytes(js.z_max) +
           bytes(js.dn_max) + bytes(js.ds_max) + bytes(js.an_min) + bytes(js.as_min) +
           bytes(js.status) + bytes(js.mode_bits) + bytes(js.mode) + bytes(js.break_step) +
           bytes(js.work) + bytes(js.f_prev) + bytes(js.d_prev) + bytes(js.jf) +
           bytes(js.chunk_sums);
}

void BM_Memory(benchmark::State& st) {
    const double base = current_rss_bytes();
    for (auto _ : st) {
        scenes::BlockOptions o;
        o.num_tris = st.range(0);
        o.gravity = o.clamp = true;
        o.jointed = st.range(1) != 0;
        const Model m = scenes::make_block(o);
        State s = make_state(m, 0.9 * stable_time_step(m));
        for (int k = 0; k < 3; ++k)
            step(m, s);
        const double nt = m.num_tris();
        st.counters["peak_B_per_tri"] = peak_rss_bytes() / nt;
        st.counters["live_B_per_tri"] = (current_rss_bytes() - base) / nt;
        st.counters["tris"] = nt;
        st.counters["nodes_per_tri"] = m.num_nodes() / nt;
        st.counters["joints_per_tri"] = m.joints.num_joints() / nt;
        st.counters["joint_arrays_B_per_tri"] = joint_bytes(m, s) / nt;
    }
}

BENCHMARK(BM_Memory)
    ->ArgsProduct({{1 << 20, 1 << 22}, {0, 1}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace fdem
