// Internal consistency checks (style guide §4.6: programming errors never reach users as an
// InputError or SimulationError). FDEM_ASSERT(cond, message) aborts with file:line, the condition
// and the message when FDEM_ENABLE_ASSERTS is defined: in Debug builds, in sanitizer builds
// (FDEM_SANITIZE, the asan preset) and with -DFDEM_ASSERTS=ON (CMakeLists.txt). Otherwise it
// compiles to nothing and does not evaluate its arguments, so a check may be as expensive as it
// needs to be (validate_topology() after every topology build).
//
// Use it in .cpp files of the library and in tests only, not in inline code of the public headers:
// a consumer built with a different setting would otherwise see two definitions of one function.
#pragma once

namespace fdem {

#if defined(FDEM_ENABLE_ASSERTS)
inline constexpr bool kAssertsEnabled = true;
#else
inline constexpr bool kAssertsEnabled = false;
#endif

namespace detail {
/// Prints "file:line: internal error: FDEM_ASSERT(condition) failed: message" to stderr and
/// aborts (never returns; not an exception, so no caller can swallow it).
[[noreturn]] void assert_fail(const char* condition, const char* message, const char* file,
                              int line) noexcept;
}  // namespace detail

}  // namespace fdem

#if defined(FDEM_ENABLE_ASSERTS)
#define FDEM_ASSERT(cond, message) \
    ((cond) ? static_cast<void>(0) \
            : ::fdem::detail::assert_fail(#cond, message, __FILE__, __LINE__))
#else
#define FDEM_ASSERT(cond, message) static_cast<void>(0)
#endif
