// T13 and T16 (spec §8) with the block made of 6-node composite elements (issue #7) at the
// spec's composite resolution (10 x 10 composites = the nodes of 20 x 20 CST cells, h = 0.05 m),
// v_i = 2 and 4 m/s, same checks and tolerances. All four speeds and the dt-halving order fit of
// the energy error: scripts/validate (label `full`).
#include <gtest/gtest.h>

#include "validation/cases/composite_dynamics.hpp"

namespace fdem::validation {
namespace {

TEST(CompositeDynamics, T13T16ReducedResolution) {
    for (const Check& c : composite_dynamics_suite(CompositeDynamicsOptions::quick(), "")) {
        std::printf("[ info ] %s %s: %.6g (expected %.6g, %s)\n", c.id.c_str(), c.name.c_str(),
                    c.measured, c.expected, c.tolerance_text().c_str());
        EXPECT_TRUE(c.pass()) << c.id << " " << c.name << ": measured " << c.measured
                              << ", expected " << c.expected << " " << c.tolerance_text() << " ("
                              << c.why << ")";
    }
}

}  // namespace
}  // namespace fdem::validation
