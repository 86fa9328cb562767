// Distance-field pictures (paper Figs. 2, 15-22) at a coarse sampling: the exact cases of spec
// §4.4 / §6.5 must hold. The pictures themselves: scripts/validate.
#include <gtest/gtest.h>

#include "validation/cases/field_maps.hpp"

namespace fdem::validation {
namespace {

TEST(FieldMaps, ExactCasesAndReportedErrors) {
    for (const Check& c : field_maps_suite("", 60)) {
        std::printf("[ info ] %s %s: %.6g\n", c.id.c_str(), c.name.c_str(), c.measured);
        EXPECT_TRUE(c.pass()) << c.name << ": " << c.measured << " (" << c.why << ")";
    }
}

}  // namespace
}  // namespace fdem::validation
