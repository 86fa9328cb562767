// FDEM_ASSERT failure handler (include/fdem/assert.hpp).
#include "fdem/assert.hpp"

#include <cstdio>
#include <cstdlib>

namespace fdem::detail {

void assert_fail(const char* condition, const char* message, const char* file, int line) noexcept {
    std::fprintf(stderr, "%s:%d: internal error: FDEM_ASSERT(%s) failed: %s\n", file, line,
                 condition, message);
    std::fflush(stderr);
    std::abort();
}

}  // namespace fdem::detail
