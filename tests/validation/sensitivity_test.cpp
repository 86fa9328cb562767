// T20 (spec §8) in the default suite: penalty x {0.1, 1, 10} and dt x {0.5, 1} around the
// reduced-resolution block impact and sliding block (h = 0.1 m), same checks and tolerances as
// scripts/validate. The h x 1/2 runs (h = 0.05 m, the spec's resolution) and the sliding
// k_n x 10 run are left to scripts/validate (label `full`) for time.
#include <gtest/gtest.h>

#include "validation/cases/sensitivity.hpp"

namespace fdem::validation {
namespace {

TEST(Sensitivity, T20PenaltyAndTimeStep) {
    SensitivityOptions o;
    o.refine = false;
    o.sliding_penalty_x10 = false;
    for (const Check& c : sensitivity_suite(o, "")) {
        std::printf("[ info ] %s %s: %.6g (expected %.6g, %s)\n", c.id.c_str(), c.name.c_str(),
                    c.measured, c.expected, c.tolerance_text().c_str());
        EXPECT_TRUE(c.pass()) << c.id << " " << c.name << ": measured " << c.measured
                              << ", expected " << c.expected << " " << c.tolerance_text() << " ("
                              << c.why << ")";
    }
}

}  // namespace
}  // namespace fdem::validation
