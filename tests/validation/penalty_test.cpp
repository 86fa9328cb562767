// Validation V3 and V3b of spec fracture.md §11 (tests/validation/cases/penalty.hpp), structured
// mesh only (the unstructured fits run in scripts/validate): E_eff/E of a fully jointed square
// against theory eqs. 9.24 and 9.6 within 2 % for p/E = 1..100; power-iteration omega_max within
// the eq. 9.21 bound; 0.95 x the measured limit bounded, 1.05 x diverges.
#include <gtest/gtest.h>

#include "validation/cases/penalty.hpp"

namespace fdem::validation {
namespace {

TEST(Penalty, V3StructuredAndV3bTimeStep) {
    for (const Check& c : penalty_suite(PenaltyOptions::quick(), "")) {
        std::printf("[ info ] %s %s: %.6g (expected %.6g, %s)\n", c.id.c_str(), c.name.c_str(),
                    c.measured, c.expected, c.tolerance_text().c_str());
        EXPECT_TRUE(c.pass()) << c.id << " " << c.name << ": measured " << c.measured
                              << ", expected " << c.expected << " " << c.tolerance_text() << " ("
                              << c.why << ")";
    }
}

}  // namespace
}  // namespace fdem::validation
