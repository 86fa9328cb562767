// Transparent huge pages for the large arrays (core/huge_pages.hpp, docs/performance.md
// "Huge pages"): advice that changes no byte and no result.
#include "core/huge_pages.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "fdem/simulate.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

std::vector<uint64_t> pattern(size_t bytes) {
    std::vector<uint64_t> v(bytes / sizeof(uint64_t));
    for (size_t i = 0; i < v.size(); ++i)
        v[i] = i * 0x9e3779b97f4a7c15ULL;
    return v;
}

TEST(HugePages, SmallArraysAndOffAreLeftAlone) {
    if (huge_page_size() == 0) GTEST_SKIP() << "this kernel has no transparent huge pages";
    const std::vector<uint64_t> small = pattern(huge_page_size() / 4);
    EXPECT_EQ(prefer_huge_pages(small), 0u);
    const std::vector<uint64_t> large = pattern(8 * huge_page_size());
    set_huge_pages(false);
    EXPECT_EQ(prefer_huge_pages(large), 0u);
    set_huge_pages(true);
    EXPECT_TRUE(huge_pages_enabled());
}

TEST(HugePages, CollapseKeepsEveryByte) {
    const size_t page = huge_page_size();
    if (page == 0) GTEST_SKIP() << "this kernel has no transparent huge pages";
    const std::vector<uint64_t> v = pattern(8 * page);
    const std::vector<uint64_t> copy = v;
    const size_t done = prefer_huge_pages(v);
    if (done == 0) {
        GTEST_SKIP() << "the kernel collapsed nothing (MADV_COLLAPSE needs Linux 6.1; or no "
                        "free huge page)";
    }
    // at least the 7 whole pages inside the array (its ends share pages with other memory)
    EXPECT_GE(done, 7 * page);
    EXPECT_LE(done, 9 * page);
    EXPECT_GE(huge_page_bytes_in_use(), 7 * page);
    EXPECT_EQ(v, copy);
}

// The block of 2^17 triangles has per-triangle arrays of 1.5-4 MB (on huge pages when the kernel
// allows); the same bits as on 4 KiB pages.
TEST(HugePages, SameStepBitsOnEitherPageSize) {
    scenes::BlockOptions o;
    o.num_tris = 1 << 17;
    o.gravity = o.clamp = true;
    uint64_t hash[2];
    for (const bool on : {false, true}) {
        set_huge_pages(on);
        const Model m = scenes::make_block(o);
        // (on: the arrays are on huge pages already, so asking again succeeds)
        if (on && huge_page_size() > 0) {
            EXPECT_GT(prefer_huge_pages(m.tri_dm_inv), 0u);
        }
        State s = make_state(m, 0.5 * stable_time_step(m));
        for (int k = 0; k < 20; ++k)
            step(m, s);
        hash[on ? 1 : 0] = state_hash(s);
    }
    set_huge_pages(true);
    EXPECT_EQ(hash[0], hash[1]);
}

}  // namespace
}  // namespace fdem
