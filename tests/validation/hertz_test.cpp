// T18 (spec §8, analytic values of spec §6.1): Hertz line contact of a disk on a rigid plane at
// the spec's resolution h_c = a/10 near the contact (length scaling). The finer mesh (h_c = a/20)
// and the paper's mass scaling: scripts/validate (label `full`).
#include <gtest/gtest.h>

#include "validation/cases/hertz.hpp"

namespace fdem::validation {
namespace {

TEST(Hertz, T18LineContact) {
    for (const Check& c : hertz_suite(HertzOptions::quick(), "")) {
        std::printf("[ info ] %s %s: %.6g (expected %.6g, %s)\n", c.id.c_str(), c.name.c_str(),
                    c.measured, c.expected, c.tolerance_text().c_str());
        EXPECT_TRUE(c.pass()) << c.id << " " << c.name << ": measured " << c.measured
                              << ", expected " << c.expected << " " << c.tolerance_text() << " ("
                              << c.why << ")";
    }
}

}  // namespace
}  // namespace fdem::validation
