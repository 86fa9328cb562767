// Distance-field pictures of the composite element (paper Figs. 15-18) at a coarse sampling:
// option (b) must be exact, option (a) is reported. The pictures themselves: scripts/validate.
#include <gtest/gtest.h>

#include "validation/cases/composite_field_maps.hpp"

namespace fdem::validation {
namespace {

TEST(CompositeFieldMaps, FanExactSplitReported) {
    const std::vector<Check> checks = composite_field_maps_suite("", 60);
    EXPECT_EQ(checks.size(), 6u);  // 3 shapes x 2 options
    for (const Check& c : checks) {
        std::printf("[ info ] %s %s: %.6g\n", c.id.c_str(), c.name.c_str(), c.measured);
        EXPECT_TRUE(c.pass()) << c.name << ": " << c.measured << " (" << c.why << ")";
    }
}

}  // namespace
}  // namespace fdem::validation
