// Transparent huge pages for the large arrays: see huge_pages.hpp.
#include "core/huge_pages.hpp"

#include <atomic>
#include <cstdint>
#include <fstream>
#include <string>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#ifndef MADV_COLLAPSE
#define MADV_COLLAPSE 25  // Linux 6.1 (uapi/asm-generic/mman-common.h); glibc 2.36 lacks it
#endif

namespace fdem {

namespace {

std::atomic<bool> g_on{true};

size_t read_page_size() {
    std::ifstream enabled("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string modes;
    if (!enabled || !std::getline(enabled, modes)) return 0;
    if (modes.find("[never]") != std::string::npos) return 0;
    std::ifstream size("/sys/kernel/mm/transparent_hugepage/hpage_pmd_size");
    size_t bytes = 0;
    if (!(size >> bytes)) return 0;
    return bytes;
}

}  // namespace

size_t huge_page_size() {
    static const size_t size = read_page_size();
    return size;
}

void set_huge_pages(bool on) {
    g_on.store(on, std::memory_order_relaxed);
}

bool huge_pages_enabled() {
    return g_on.load(std::memory_order_relaxed);
}

size_t prefer_huge_pages(const void* p, size_t bytes) {
#if defined(__linux__)
    const size_t page = huge_page_size();
    if (page == 0 || p == nullptr || !huge_pages_enabled()) return 0;
    if (2 * bytes < page) return 0;
    // every huge page the array overlaps, its neighbours' bytes at both ends included (a
    // std::vector's storage is not aligned to 2 MiB; where the range is one anonymous mapping,
    // which the kernel merges adjacent malloc mappings into, the whole page collapses; where it
    // is not, that page stays small). Collapsing changes no byte of anyone's memory.
    const uintptr_t first = reinterpret_cast<uintptr_t>(p) / page * page;
    const uintptr_t last = reinterpret_cast<uintptr_t>(p) + bytes;
    size_t collapsed = 0;
    for (uintptr_t a = first; a < last; a += page) {
        // EINVAL before Linux 6.1, EAGAIN / ENOMEM without a free huge page or across a mapping
        // boundary: that page stays small
        if (madvise(reinterpret_cast<void*>(a), page, MADV_COLLAPSE) == 0) collapsed += page;
    }
    return collapsed;
#else
    (void)p;
    (void)bytes;
    return 0;
#endif
}

size_t huge_page_bytes_in_use() {
    std::ifstream in("/proc/self/smaps_rollup");
    std::string key;
    size_t kb = 0;
    while (in >> key) {
        if (key == "AnonHugePages:") {
            in >> kb;
            return kb * 1024;
        }
        in.ignore(1 << 20, '\n');
    }
    return 0;
}

}  // namespace fdem
