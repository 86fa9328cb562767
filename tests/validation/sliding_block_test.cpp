// T16/T17 (spec §8) at reduced resolution (h = 0.1 m, v_i = 2 and 4 m/s; same checks and
// tolerances). Full resolution and all speeds: scripts/validate (label `full`).
#include <gtest/gtest.h>

#include "validation/cases/sliding_block.hpp"

namespace fdem::validation {
namespace {

TEST(SlidingBlock, T16T17ReducedResolution) {
    for (const Check& c : sliding_block_suite(SlidingOptions::quick(), "")) {
        std::printf("[ info ] %s %s: %.6g (expected %.6g, %s)\n", c.id.c_str(), c.name.c_str(),
                    c.measured, c.expected, c.tolerance_text().c_str());
        EXPECT_TRUE(c.pass()) << c.id << " " << c.name << ": measured " << c.measured
                              << ", expected " << c.expected << " " << c.tolerance_text() << " ("
                              << c.why << ")";
    }
}

}  // namespace
}  // namespace fdem::validation
