// STREAM-like triad a = b + s c (McCalpin's STREAM): the memory bandwidth that bounds the
// element loop once its arrays leave the cache (roofline in docs/performance.md).
// bytes/s counts 24 B per element (read b, c; write a), as STREAM does (write-allocate traffic
// not counted). Args: {doubles per array, OpenMP threads}.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cstddef>
#include <vector>

namespace {

void BM_Triad(benchmark::State& st) {
    const auto n = static_cast<std::ptrdiff_t>(st.range(0));
    omp_set_num_threads(static_cast<int>(st.range(1)));
    std::vector<double> a(static_cast<size_t>(n)), b(static_cast<size_t>(n), 1.0),
        c(static_cast<size_t>(n), 2.0);
    double* pa = a.data();
    const double* pb = b.data();
    const double* pc = c.data();
    const double s = 3.0;
    // first touch by the threads that will use the pages
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < n; ++i)
        pa[i] = 0.0;
    for (auto _ : st) {
#pragma omp parallel for schedule(static)
        for (std::ptrdiff_t i = 0; i < n; ++i)
            pa[i] = pb[i] + s * pc[i];
        benchmark::ClobberMemory();
    }
    st.SetBytesProcessed(st.iterations() * n * 24);
    st.counters["omp_threads"] = static_cast<double>(st.range(1));
}

BENCHMARK(BM_Triad)
    ->Args({1 << 13, 1})  // 192 KB: L2
    ->Args({1 << 13, 2})
    ->Args({1 << 24, 1})  // 384 MB: main memory
    ->Args({1 << 24, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
