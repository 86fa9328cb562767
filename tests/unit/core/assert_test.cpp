// FDEM_ASSERT (include/fdem/assert.hpp): evaluated and fatal in checked builds (Debug, sanitizer,
// -DFDEM_ASSERTS=ON), compiled out otherwise.
#include "fdem/assert.hpp"

#include <gtest/gtest.h>

namespace fdem {
namespace {

TEST(FdemAssert, OnlyInCheckedBuilds) {
    int evaluated = 0;
    FDEM_ASSERT(++evaluated > 0, "the condition holds");
    EXPECT_EQ(evaluated, kAssertsEnabled ? 1 : 0);  // off: the condition is not even evaluated
    if (kAssertsEnabled) {
        EXPECT_DEATH(FDEM_ASSERT(evaluated < 0, "the message"),
                     "internal error: FDEM_ASSERT\\(evaluated < 0\\) failed: the message");
    }
}

}  // namespace
}  // namespace fdem
