// Validation V7 on V1 of spec fracture.md §11 (tests/validation/cases/refinement.hpp), at the
// coarsest size h = 4 mm only (h/2, h/4 run in scripts/validate): the inclined jointed line on
// three unstructured meshes, Gamma = W_frac / L_broken and at the grip within 2 % of
// G_I + (4/3) (sum h_J^2/sum h_J) f_t^2/p, every joint broken.
#include <gtest/gtest.h>

#include "validation/cases/refinement.hpp"

namespace fdem::validation {
namespace {

TEST(Refinement, V7InclinedLineCoarse) {
    for (const Check& c : refinement_suite(RefinementOptions::quick(), "")) {
        std::printf("[ info ] %s %s: %.6g (expected %.6g, %s)\n", c.id.c_str(), c.name.c_str(),
                    c.measured, c.expected, c.tolerance_text().c_str());
        EXPECT_TRUE(c.pass()) << c.id << " " << c.name << ": measured " << c.measured
                              << ", expected " << c.expected << " " << c.tolerance_text() << " ("
                              << c.why << ")";
    }
}

}  // namespace
}  // namespace fdem::validation
