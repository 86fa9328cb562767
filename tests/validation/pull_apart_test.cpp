// Validation V1 of spec fracture.md §11 (examples/07_pull_apart): peak grip stress = f_t and
// Gamma_I = G_I + (4/3) h f_t^2/p, each within 1 %, measured at the grip and by the joint audit.
#include <gtest/gtest.h>

#include "validation/cases/pull_apart.hpp"

namespace fdem::validation {
namespace {

TEST(PullApart, V1ModeI) {
    for (const Check& c : pull_apart_suite("")) {
        std::printf("[ info ] %s %s: %.6g (expected %.6g, %s)\n", c.id.c_str(), c.name.c_str(),
                    c.measured, c.expected, c.tolerance_text().c_str());
        EXPECT_TRUE(c.pass()) << c.id << " " << c.name << ": measured " << c.measured
                              << ", expected " << c.expected << " " << c.tolerance_text() << " ("
                              << c.why << ")";
    }
}

}  // namespace
}  // namespace fdem::validation
