// Loading a scenario (issue #16 item 4): load_scenario() of the brick-bond pack of
// tests/loading/make_pack_scenario.py with N two-triangle blocks, one [[body]] entry per block
// (Arg 1 = 0) or one entry with pieces = "separate" (Arg 1 = 1). Parse, mesh read through Gmsh,
// bodies, finalize_model(), load-time contact checks and the dt choice; no process start-up.
// items/s = [[body]] entries (or pieces) per second; linear loading keeps it flat in N.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include <fmt/format.h>

#include "fdem/scenario.hpp"

namespace fdem {
namespace {

/// The scenario file of the pack of n blocks in the temp folder, written if missing (the
/// generator is deterministic, so a file left by an earlier run is the same).
std::string pack_scenario(int64_t n, bool separate) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      fmt::format("fdem_bench_load_{}_{}", n, separate ? "s" : "g");
    const std::filesystem::path toml = dir / "scenario.toml";
    if (!std::filesystem::exists(toml)) {
        const std::string cmd =
            fmt::format("/usr/bin/python3 {}/tests/loading/make_pack_scenario.py {} {}{}",
                        FDEM_SOURCE_DIR, dir.string(), n, separate ? " --mode separate" : "");
        if (std::system(cmd.c_str()) != 0) return {};
    }
    return toml.string();
}

void BM_LoadPack(benchmark::State& st) {
    const int64_t n = st.range(0);
    const std::string path = pack_scenario(n, st.range(1) != 0);
    if (path.empty()) {
        st.SkipWithError("make_pack_scenario.py failed");
        return;
    }
    int64_t bodies = 0;
    for (auto _ : st) {
        const Scenario sc = load_scenario(path);
        bodies = sc.model.num_bodies();
        benchmark::DoNotOptimize(bodies);
    }
    if (bodies != n) st.SkipWithError("wrong number of bodies");
    st.SetItemsProcessed(st.iterations() * n);
    st.counters["bodies"] = static_cast<double>(bodies);
}

BENCHMARK(BM_LoadPack)->ArgsProduct({{1000, 3000, 10000}, {0, 1}})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace fdem
