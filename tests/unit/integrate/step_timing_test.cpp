// State::timing (include/fdem/step_timing.hpp): off, the step reads no clock and records
// nothing; on, it records every step's wall time in the phases that ran, and no bit of the run
// changes either way.
#include <gtest/gtest.h>

#include <chrono>

#include "fdem/simulate.hpp"
#include "support/hash.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

// a converging pack of 20 x 20 blocks, in contact from the first steps
Model pack() {
    scenes::PackOptions o;
    o.blocks_x = 20;
    o.blocks_y = 20;
    o.gap = 0.0;
    o.converge = true;
    return scenes::make_contact_pack(o);
}

struct Timed {
    uint64_t hash = 0;
    StepTiming timing;
    double wall = 0;  ///< seconds of the whole loop, by the same clock
};

Timed run(const Model& m, int steps, bool on) {
    State s = make_state(m, 0.5 * stable_time_step(m));
    s.timing.on = on;
    const auto t0 = StepTiming::Clock::now();
    for (int k = 0; k < steps; ++k)
        step(m, s);
    Timed r;
    r.wall = std::chrono::duration<double>(StepTiming::Clock::now() - t0).count();
    r.hash = scenes::state_hash(s);
    r.timing = s.timing;
    return r;
}

double at(const StepTiming& t, StepPhase p) {
    return t.seconds[static_cast<int>(p)];
}

TEST(StepTiming, OffRecordsNothing) {
    const Timed r = run(pack(), 20, false);
    EXPECT_EQ(r.timing.steps, 0);
    for (double s : r.timing.seconds)
        EXPECT_EQ(s, 0.0);
}

TEST(StepTiming, OnChangesNoBitAndChargesThePhasesThatRan) {
    const Model m = pack();
    const int steps = 40;
    const Timed off = run(m, steps, false);
    const Timed on = run(m, steps, true);
    EXPECT_EQ(on.hash, off.hash);
    EXPECT_EQ(on.timing.steps, steps);
    double sum = 0;
    for (double s : on.timing.seconds) {
        EXPECT_GE(s, 0.0);
        sum += s;
    }
    // the phases tile each step from its first clock read to its last: within the loop's time
    EXPECT_LE(sum, on.wall);
    EXPECT_GT(sum, 0.5 * on.wall);
    EXPECT_GT(at(on.timing, StepPhase::Elements), 0.0);
    EXPECT_GT(at(on.timing, StepPhase::BroadPhase), 0.0);
    EXPECT_GT(at(on.timing, StepPhase::NarrowPhase), 0.0);
    EXPECT_GT(at(on.timing, StepPhase::ContactApply), 0.0);
    EXPECT_GT(at(on.timing, StepPhase::NodeUpdate), 0.0);
    // a one-process run of a model without joints
    EXPECT_EQ(at(on.timing, StepPhase::Joints), 0.0);
    EXPECT_EQ(at(on.timing, StepPhase::Communication), 0.0);
}

TEST(StepTiming, ResetClearsTheRecord) {
    Timed r = run(pack(), 5, true);
    ASSERT_EQ(r.timing.steps, 5);
    r.timing.reset();
    EXPECT_EQ(r.timing.steps, 0);
    for (double s : r.timing.seconds)
        EXPECT_EQ(s, 0.0);
}

}  // namespace
}  // namespace fdem
