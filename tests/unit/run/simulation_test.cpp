// The run loop as a library object (include/fdem/simulation.hpp): same bits as the CLI, the
// callback cadence, stopping, checkpoints through the API, typed failures, no allocation.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "fdem/error.hpp"
#include "fdem/simulation.hpp"
#include "support/alloc_count.hpp"

namespace fdem {
namespace {

namespace fs = std::filesystem;

const std::string kDemo = FDEM_SOURCE_DIR "/examples/03_contact_slide/scenario.toml";
const std::string kCrush = FDEM_SOURCE_DIR "/tests/cli/crush.toml";
constexpr Real kShort = 0.002;  // s: about 360 steps of the demo

std::string temp_dir(const std::string& name) {
    const fs::path p = fs::temp_directory_path() / fmt::format("fdem_simulation_test_{}", name);
    fs::remove_all(p);
    return p.string();
}

// `fdem run --quiet --print-hash` of the CLI built with this library ("hash <hex>")
std::string cli_hash(const std::string& scenario, Real end_time, const std::string& out) {
    const std::string cmd = fmt::format(
        "\"{}\" run \"{}\" --quiet --print-hash --end-time {} "
        "--out \"{}\"",
        FDEM_CLI_PATH, scenario, end_time, out);
    std::FILE* p = popen(cmd.c_str(), "r");
    EXPECT_NE(p, nullptr);
    std::string text;
    char buf[256];
    while (p != nullptr && std::fgets(buf, sizeof buf, p) != nullptr)
        text += buf;
    if (p != nullptr) {
        EXPECT_EQ(pclose(p), 0) << cmd;
    }
    return text;
}

std::string hex(uint64_t h) {
    return fmt::format("hash {:016x}\n", h);
}

TEST(Simulation, RunToTimeEqualsTheCliHash) {
    const std::string expected = cli_hash(kDemo, kShort, temp_dir("cli"));
    ASSERT_FALSE(expected.empty());
    {
        Simulation sim = Simulation::from_file(kDemo);
        sim.settings().end_time = kShort;
        const RunResult r = sim.run(kShort);
        EXPECT_EQ(r.status, RunStatus::Reached);
        EXPECT_EQ(r.steps, sim.state().step);
        EXPECT_EQ(hex(sim.state_hash()), expected);
    }
    {
        // with output, and split into two calls: the same bits
        Simulation sim = Simulation::from_file(kDemo);
        sim.settings().end_time = kShort;
        sim.open_output(temp_dir("api_out"));
        sim.run(0.4 * kShort);
        sim.run_to_end();
        EXPECT_EQ(hex(sim.state_hash()), expected);
        EXPECT_TRUE(fs::exists(fs::path(sim.output_dir()) / "history.csv"));
        EXPECT_TRUE(fs::exists(sim.last_frame().path));
        EXPECT_EQ(sim.last_frame().step, sim.state().step);  // the final frame at end_time
    }
}

TEST(Simulation, CallbackCadenceAndStop) {
    Simulation sim = Simulation::from_file(kDemo);
    std::vector<int64_t> seen;
    RunResult r = sim.run(
        kShort,
        [&seen](Simulation& s) {
            seen.push_back(s.state().step);
            return s.state().step < 35;  // false after step 35: stop there
        },
        7);
    EXPECT_EQ(r.status, RunStatus::CallbackStopped);
    EXPECT_EQ(sim.state().step, 35);
    EXPECT_EQ(r.steps, 35);
    EXPECT_EQ(seen, (std::vector<int64_t>{7, 14, 21, 28, 35}));

    // request_stop() from inside the run stops it after the next step; the flag is then cleared
    r = sim.run(kShort, [](Simulation& s) {
        if (s.state().step == 40) s.request_stop();
        return true;
    });
    EXPECT_EQ(r.status, RunStatus::Stopped);
    EXPECT_EQ(sim.state().step, 41);
    r = sim.run(sim.state().time + 3 * sim.state().dt);
    EXPECT_EQ(r.status, RunStatus::Reached);
    EXPECT_EQ(r.steps, 3);
}

TEST(Simulation, CheckpointRestoreContinuesBitwise) {
    const std::string dir = temp_dir("checkpoint");
    fs::create_directories(dir);
    const std::string file = (fs::path(dir) / "mid.fdck").string();
    Simulation a = Simulation::from_file(kDemo);
    a.run(0.5 * kShort);
    a.save_checkpoint(file);
    a.run(kShort);

    Simulation b = Simulation::from_file(kDemo);
    const Vec2* x = b.state().x.data();
    b.run(0.2 * kShort);  // a different state first: restore replaces it
    b.restore_checkpoint(file);
    EXPECT_EQ(b.state().x.data(), x);  // views of the arrays stay valid across a restore
    b.run(kShort);
    EXPECT_EQ(b.state().step, a.state().step);
    EXPECT_EQ(b.state_hash(), a.state_hash());
    EXPECT_EQ(b.energy_monitor().max_error, a.energy_monitor().max_error);

    // a checkpoint of another model is refused and leaves the state as it was
    Simulation c = Simulation::from_file(kCrush);
    const uint64_t before = c.state_hash();
    EXPECT_THROW(c.restore_checkpoint(file), InputError);
    EXPECT_EQ(c.state_hash(), before);
}

TEST(Simulation, FailureIsTypedAndWritesFailureVtu) {
    Simulation sim = Simulation::from_file(kCrush);
    sim.open_output(temp_dir("crush"));
    try {
        sim.run_to_end();
        FAIL() << "the crush scenario must fail";
    } catch (const SimulationError& e) {
        EXPECT_EQ(e.step(), sim.state().step);
        EXPECT_EQ(e.time(), sim.state().time);
        EXPECT_NE(e.entity().find("triangle"), std::string::npos) << e.entity();
        EXPECT_NE(std::string(e.what()).find("element inverted"), std::string::npos);
    }
    EXPECT_TRUE(fs::exists(sim.failure_file().path)) << sim.failure_write_error();
    EXPECT_EQ(sim.failure_file().step, sim.state().step);
}

// set_rebalance() (spec D10): bad settings are refused; on a one-process run it changes nothing
TEST(Simulation, RebalanceSettingsAreCheckedAndIdleOnOneProcess) {
    Simulation sim = Simulation::from_file(kDemo);
    Simulation::Rebalance bad;
    bad.every = -1;
    EXPECT_THROW(sim.set_rebalance(bad), std::invalid_argument);
    bad.every = 1;  // no partition function
    EXPECT_THROW(sim.set_rebalance(bad), std::invalid_argument);
    bad.partition = [](std::span<const Vec2>, std::span<const double> w, int64_t) {
        return std::vector<int32_t>(w.size(), 0);
    };
    bad.imbalance = 0.9;
    EXPECT_THROW(sim.set_rebalance(bad), std::invalid_argument);
    bad.imbalance = std::numeric_limits<double>::infinity();
    EXPECT_THROW(sim.set_rebalance(bad), std::invalid_argument);
    Simulation::Rebalance ok;
    ok.every = 1;
    ok.imbalance = 1;
    int calls = 0;
    ok.partition = [&calls](std::span<const Vec2>, std::span<const double> w, int64_t) {
        ++calls;
        return std::vector<int32_t>(w.size(), 0);
    };
    sim.set_rebalance(ok);
    sim.run(kShort);
    EXPECT_GT(sim.contact_counts().broad_phase_runs, 1);
    EXPECT_EQ(calls, 0);
    EXPECT_EQ(sim.rebalance_stats().checks, 0);
}

TEST(Simulation, RunAllocatesNothingAfterWarmUp) {
    Simulation sim = Simulation::from_file(kDemo);
    int64_t calls = 0;
    const Simulation::StepCallback cb = [&calls](Simulation&) {
        ++calls;
        return true;
    };
    sim.run(0.5 * kShort, cb);  // warm-up: contact buffers, thread team
    alloc_count::g_allocations = 0;
    alloc_count::g_counting = true;
    const RunResult r = sim.run(kShort, cb);
    alloc_count::g_counting = false;
    EXPECT_GT(r.steps, 100);
    EXPECT_EQ(alloc_count::g_allocations.load(), 0);
}

}  // namespace
}  // namespace fdem
