// Validation V2 of spec fracture.md §11 (tests/validation/cases/shear.hpp): mode II of one jointed
// line, peak shear stress = c and c + |sigma_n| tan(phi) at sigma_n = -5, -10 MPa, Gamma_II =
// G_II + (4/3) h c^2/p_s at sigma_n = 0 at the grip and by the joint audit, each within 1 %.
#include <gtest/gtest.h>

#include "validation/cases/shear.hpp"

namespace fdem::validation {
namespace {

TEST(Shear, V2ModeII) {
    for (const Check& c : shear_suite("")) {
        std::printf("[ info ] %s %s: %.6g (expected %.6g, %s)\n", c.id.c_str(), c.name.c_str(),
                    c.measured, c.expected, c.tolerance_text().c_str());
        EXPECT_TRUE(c.pass()) << c.id << " " << c.name << ": measured " << c.measured
                              << ", expected " << c.expected << " " << c.tolerance_text() << " ("
                              << c.why << ")";
    }
}

}  // namespace
}  // namespace fdem::validation
