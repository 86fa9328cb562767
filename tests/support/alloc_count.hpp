// Allocation counter of the unit-test executable: the global operator new of
// tests/unit/integrate/determinism_test.cpp counts every allocation while g_counting is set.
// Only for tests linked into fdem_unit_tests.
#pragma once

#include <atomic>

namespace alloc_count {
extern std::atomic<bool> g_counting;
extern std::atomic<long> g_allocations;
}  // namespace alloc_count
