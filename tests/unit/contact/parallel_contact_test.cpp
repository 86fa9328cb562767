// The contact phase with 1 to 4 OpenMP threads (contact/contact.cpp): the pairs are evaluated in
// parallel and applied in pair order (each thread adds them to its range of nodes, the pairs
// whose forces cross into it from the other threads' segments around its own; the
// energies are exact sums over its share of the bookkeeping), so x, v, the forces and the contact
// energies must be bitwise those of one thread for any thread count. The pack is large enough for
// the parallel narrow phase (more candidate pairs than its serial threshold), is in saturated
// contact and has edge midpoint targets; the shuffled pack numbers its bodies far apart in space.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "fdem/simulate.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

struct Run {
    std::vector<Vec2> x, v, f, f_contact;
    Real contact = 0, dissipated = 0;
    int32_t active = 0;
    size_t candidates = 0;
    // the apply's lists (ContactApplyLists): foreign candidates before / after a range's own
    // segment of real targets, and candidates whose forces leave their thread's range
    size_t foreign_below = 0, foreign_above = 0, leaving = 0;
    // candidates with a real target in each thread's node range (ContactApplyLists::range_lo)
    std::vector<size_t> per_range;
};

Run run(const Model& m, int threads, int steps) {
    omp_set_num_threads(threads);
    State s = make_state(m, 0.5 * stable_time_step(m));
    for (int k = 0; k < steps; ++k)
        step(m, s);
    Run r{s.x,
          s.v,
          s.f,
          s.f_contact,
          s.energy.contact,
          s.energy.dissipated_contact,
          s.contact.active_contacts,
          s.contact.cand.node.size(),
          0,
          0,
          0,
          {}};
    const ContactApplyLists& L = s.contact.apply_lists;
    if (L.threads == threads) {
        for (int u = 0; u < threads; ++u) {
            for (int32_t q = L.foreign_begin[u]; q < L.foreign_begin[u + 1]; ++q) {
                r.foreign_below += L.foreign[q] < L.first[u] ? 1 : 0;
                r.foreign_above += L.foreign[q] >= L.first[u + 1] ? 1 : 0;
            }
        }
        for (const uint8_t in : L.inside)
            r.leaving += in ? 0 : 1;
        r.per_range.assign(static_cast<size_t>(threads), 0);
        for (const NodeId j : s.contact.cand.node) {
            if (j >= s.topology.num_real_nodes) continue;
            const auto it = std::upper_bound(L.range_lo.begin() + 1, L.range_lo.end() - 1, j);
            ++r.per_range[static_cast<size_t>(it - (L.range_lo.begin() + 1))];
        }
    }
    return r;
}

bool same_bits(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec2)) == 0;
}

void expect_thread_independent(const Model& m) {
    const Run one = run(m, 1, 80);
    // the scene must exercise what this test is about: more candidate pairs than the serial
    // threshold of the narrow phase (2048), and more pairs in contact than that of the apply
    // (4096), whose bookkeeping and force scatter are then split over the threads
    ASSERT_GT(one.candidates, 4096u);
    ASSERT_GT(one.active, 4096);
    ASSERT_GT(one.contact, 0.0);
    for (int threads : {2, 3, 4}) {
        SCOPED_TRACE(threads);
        const Run r = run(m, threads, 80);
        // the forces of some pairs cross the threads' node ranges both ways: the foreign
        // lists are walked before and after the threads' own segments
        EXPECT_GT(r.leaving, 0u);
        EXPECT_GT(r.foreign_below, 0u);
        EXPECT_GT(r.foreign_above, 0u);
        EXPECT_TRUE(same_bits(one.x, r.x));
        EXPECT_TRUE(same_bits(one.v, r.v));
        EXPECT_TRUE(same_bits(one.f, r.f));
        EXPECT_TRUE(same_bits(one.f_contact, r.f_contact));
        EXPECT_EQ(one.contact, r.contact);
        EXPECT_EQ(one.dissipated, r.dissipated);
        EXPECT_EQ(one.active, r.active);
    }
}

scenes::PackOptions saturated_pack(bool shuffled) {
    scenes::PackOptions o;
    o.blocks_x = o.blocks_y = 30;  // 1800 triangles
    o.gap = 0;                     // touching from the start
    o.speed = 0.5;
    o.converge = true;
    o.brick_bond = true;
    o.shuffled = shuffled;
    return o;
}

TEST(ParallelContact, SameBitsForOneToFourThreads) {
    expect_thread_independent(scenes::make_contact_pack(saturated_pack(false)));
}

TEST(ParallelContact, SameBitsForOneToFourThreadsWithShuffledBodies) {
    expect_thread_independent(scenes::make_contact_pack(saturated_pack(true)));
}

// The pairs in contact in the later 40 % of the node ids (1 350 resting blocks far away come
// first): the threads' node ranges still split the candidates about evenly (they are quantiles
// of the candidates' nodes; equal shares of the ids gave thread 0 of 2 none of them), and the
// bits are those of one thread.
TEST(ParallelContact, NodeRangesShareTheCandidatesWhereTheContactsLie) {
    scenes::PackOptions o = saturated_pack(false);
    o.idle_blocks = 1350;
    const Model m = scenes::make_contact_pack(o);
    expect_thread_independent(m);
    for (int threads : {2, 3, 4}) {
        SCOPED_TRACE(threads);
        const fdem::Run r = run(m, threads, 5);
        ASSERT_EQ(r.per_range.size(), static_cast<size_t>(threads));
        size_t total = 0;
        for (const size_t c : r.per_range)
            total += c;
        for (const size_t c : r.per_range) {
            EXPECT_GT(c, total / threads * 3 / 4);
            EXPECT_LT(c, total / threads * 5 / 4);
        }
    }
}

}  // namespace
}  // namespace fdem
