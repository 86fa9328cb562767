// Spec parallel-and-python.md T9 (label mpi): after warm-up, a step of a distributed run that
// makes no broad-phase search allocates nothing on any process: the ghost exchange, the
// gathered pairs in contact, the reductions and the node update reuse their buffers. Searches
// (and the rebalances that follow them) may grow buffers; they are counted apart. The counter
// sees every C++ allocation of fdem and the standard library (Open MPI's own C allocations are
// not operator new and are not counted).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <string>

#include "fdem/simulation.hpp"
#include "parallel/mpi/mpi_comm.hpp"
#include "support/scenes.hpp"

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t n) {
    if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1);
    if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
    return operator new(n);
}
// (GCC 12's -Wmismatched-new-delete false positive for a malloc/free replacement pair, as in
// tests/unit/integrate/determinism_test.cpp)
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

TEST(DistributedStep, AllocatesNothingBetweenSearchesAfterWarmUp) {
    const MpiComm comm;
    scenes::ParticleOptions o;
    o.nx = 24;
    o.ny = 20;
    RunSettings run;
    run.end_time = 1.0;
    Simulation sim(scenes::make_particle_box(o), run, "particle box");
    sim.distribute(comm);  // contiguous node-id ranges; the ghost exchange is active
    const Real dt = sim.state().dt;
    sim.run(300 * dt);  // the first searches, ghost lists, pairs in contact
    // warm-up: the counted interval once, so that every buffer has grown to what it needs (the
    // pairs in contact keep rising in this box: their buffers grow twofold, ~5 times here),
    // then back to its start by a checkpoint and the same interval again, counted
    const std::string path =
        (std::filesystem::temp_directory_path() / "fdem_mpi_alloc_test.fdck").string();
    sim.save_checkpoint(path);
    sim.run(1200 * dt);
    sim.restore_checkpoint(path);
    sim.run(320 * dt);  // (the restored candidate list until the first search after it)
    int64_t searches = sim.contact_counts().broad_phase_runs;
    long before = 0, plain_allocs = 0, search_allocs = 0;
    int64_t plain_steps = 0, search_steps = 0;
    const Simulation::StepCallback cb = [&](Simulation& s) {
        const long now = g_allocations.load();
        const int64_t n = s.contact_counts().broad_phase_runs;
        if (n != searches) {
            search_allocs += now - before;
            ++search_steps;
        } else {
            plain_allocs += now - before;
            ++plain_steps;
        }
        searches = n;
        before = g_allocations.load();  // (the callback itself allocates nothing)
        return true;
    };
    g_allocations = 0;
    g_counting = true;
    sim.run(1200 * dt, cb);
    g_counting = false;
    EXPECT_EQ(comm.sum(plain_steps), plain_steps * comm.size());  // the same steps everywhere
    EXPECT_GT(plain_steps, 700);
    EXPECT_GT(search_steps, 10);                    // searches happened in between
    EXPECT_GT(sim.contact_counts().in_contact, 5);  // (16 on the last step)
    EXPECT_EQ(comm.sum(static_cast<int64_t>(plain_allocs)), 0)
        << "this process: " << plain_allocs << " allocations in " << plain_steps
        << " steps without a search (" << search_allocs << " in " << search_steps
        << " steps with one)";
    if (comm.rank() == 0) std::filesystem::remove(path);
}

}  // namespace
}  // namespace fdem
