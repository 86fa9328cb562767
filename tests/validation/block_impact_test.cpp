// T13/T14 (spec §8) at reduced resolution (h = 0.1 m instead of 0.05 m; same checks and
// tolerances). Full resolution: scripts/validate (label `full`).
#include <gtest/gtest.h>

#include "validation/cases/block_impact.hpp"

namespace fdem::validation {
namespace {

TEST(BlockImpact, T13T14ReducedResolution) {
    for (const Check& c : block_impact_suite(10, nullptr)) {
        std::printf("[ info ] %s %s: %.6g (expected %.6g, %s)\n", c.id.c_str(), c.name.c_str(),
                    c.measured, c.expected, c.tolerance_text().c_str());
        EXPECT_TRUE(c.pass()) << c.id << " " << c.name << ": measured " << c.measured
                              << ", expected " << c.expected << " " << c.tolerance_text() << " ("
                              << c.why << ")";
    }
}

}  // namespace
}  // namespace fdem::validation
