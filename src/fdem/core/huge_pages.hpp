// Transparent huge pages for the large flat arrays the step streams (docs/performance.md
// "Huge pages"). With 4 KiB pages a pass over a model of 10^5+ triangles misses the TLB on
// nearly every page it touches (the second-level TLB covers ~12 MB); Linux's transparent huge
// pages (2 MiB on x86-64) cover the same arrays with 512x fewer entries. Debian's kernels ship
// THP in "madvise" mode: only memory a program asks for gets them, so the arrays ask.
//
// Advice only: page size changes no result bit, and where the kernel cannot or will not (no
// THP, no MADV_COLLAPSE before Linux 6.1, fragmented memory) the arrays stay as they were.
#pragma once

#include <cstddef>
#include <vector>

namespace fdem {

/// The huge page size of the kernel (`/sys/kernel/mm/transparent_hugepage/hpage_pmd_size`), or
/// 0 without transparent huge pages (no such file, or `enabled` is `never`).
size_t huge_page_size();

/// Asks the kernel to back every huge page that [p, p + bytes) overlaps with a transparent huge
/// page now: madvise(MADV_COLLAPSE) page by page (Linux >= 6.1; synchronous, it copies the
/// pages once; it works whatever the `enabled` mode short of `never`). Arrays under half a huge
/// page are left alone. Returns the bytes collapsed (0: too small, disabled or refused). The
/// memory must be this process's anonymous memory (a std::vector's).
size_t prefer_huge_pages(const void* p, size_t bytes);

template <class T>
size_t prefer_huge_pages(const std::vector<T>& v) {
    return prefer_huge_pages(v.data(), v.size() * sizeof(T));
}

/// Off: prefer_huge_pages() does nothing (`fdem run --no-huge-pages`, for A/B runs of one
/// binary; set it before the model is built). On by default.
void set_huge_pages(bool on);
bool huge_pages_enabled();

/// Bytes of this process's memory backed by transparent huge pages now (AnonHugePages of
/// /proc/self/smaps_rollup; 0 where the file does not exist).
size_t huge_page_bytes_in_use();

}  // namespace fdem
