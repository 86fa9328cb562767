// Where the wall time of the steps goes, phase by phase (docs/parallel.md "Timing breakdown"):
// the step marks the end of each phase with one clock read; a distributed step charges its
// collective and point-to-point calls, and the waits for the other processes inside them, to
// Communication. Off by default (the library's step() reads no clock); `fdem run` turns it on
// and prints the table (min / mean / max over the processes). Not saved in checkpoints and no
// input to any result.
#pragma once

#include <chrono>
#include <cstdint>

namespace fdem {

enum class StepPhase : uint8_t {
    Elements,       ///< force clear, kicks, loads, element pass (step 0-3)
    Joints,         ///< cohesive joints, break processing (3b, 3c)
    BroadPhase,     ///< virtual nodes, broad phase, body boxes, contact positions (4)
    NarrowPhase,    ///< locate, field and law of the candidate pairs (4)
    ContactApply,   ///< bookkeeping of the pairs in contact and their forces (4)
    NodeUpdate,     ///< gravity, damping, velocities, positions, supports, energies (5-7)
    Communication,  ///< MPI calls of a distributed step, with the waits inside them
};
inline constexpr int kStepPhases = 7;

/// The phases' names as `fdem run` prints them (index: StepPhase).
inline constexpr const char* kStepPhaseNames[kStepPhases] = {
    "elements",      "joints",      "broad phase",  "narrow phase",
    "contact apply", "node update", "communication"};
/// The same as identifiers (timing.csv columns, the keys of Python's sim.timing).
inline constexpr const char* kStepPhaseKeys[kStepPhases] = {
    "elements",      "joints",      "broad_phase",  "narrow_phase",
    "contact_apply", "node_update", "communication"};

struct StepTiming {
    using Clock = std::chrono::steady_clock;
    bool on = false;                   ///< read the clock (State::timing; fdem run sets it)
    double seconds[kStepPhases] = {};  ///< wall seconds per phase since the last reset
    int64_t steps = 0;                 ///< steps timed since the last reset
    Clock::time_point last{};          ///< the end of the last phase

    // (the marks are a test of `on` where they stand; the clock reads are out of line, so that
    // the step's code, which inlines its kernels, does not grow by them)
    /// the start of a step
    void begin() {
        if (on) start();
    }
    /// the end of phase p: the time since the last mark goes to p
    void mark(StepPhase p) {
        if (on) lap(p);
    }
    /// the end of a step, whose last phase was p
    void end_step(StepPhase p) {
        if (!on) return;
        lap(p);
        ++steps;
    }
    [[gnu::noinline]] void start() { last = Clock::now(); }
    [[gnu::noinline]] void lap(StepPhase p) {
        const Clock::time_point t = Clock::now();
        seconds[static_cast<int>(p)] += std::chrono::duration<double>(t - last).count();
        last = t;
    }
    void reset() {
        for (double& s : seconds)
            s = 0;
        steps = 0;
    }
};

}  // namespace fdem
