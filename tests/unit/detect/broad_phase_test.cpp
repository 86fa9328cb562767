// T11 (spec §8): the grid broad phase returns exactly the brute-force set of bounding-circle
// overlaps |x_j - c_tau| < r_tau + b on 100 random layouts of 50-2000 small bodies, with both
// inner loops (portable, and AVX-512 where the CPU has it: same bits, docs/performance.md).
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <random>

#include "contact/contact.hpp"
#include "detect/broad_phase.hpp"
#include "fdem/simulate.hpp"
#include "unit/contact/contact_fixture.hpp"

namespace fdem {
namespace {

Model random_layout(std::mt19937& rng, int n_bodies, Real box, bool two_way) {
    testing::ModelBuilder b;
    b.m.contact.two_way = two_way;
    std::uniform_real_distribution<Real> u(0, box), us(0.3, 1.5), ua(0, 2 * M_PI), u01(0, 1);
    for (int k = 0; k < n_bodies; ++k) {
        const Vec2 c{u(rng), u(rng)};
        const Real s = us(rng), a = ua(rng);
        const Vec2 e1{s * std::cos(a), s * std::sin(a)}, e2 = perp(e1);
        const bool fixed = u01(rng) < 0.1;
        if (u01(rng) < 0.5) {
            b.add_body(testing::mesh_of({c, c + e1, c + 0.8 * e2 + 0.3 * e1}, {{0, 1, 2}}), fixed);
        } else {
            b.add_body(testing::mesh_of({c, c + e1, c + e1 + e2, c + e2}, {{0, 1, 2}, {0, 2, 3}}),
                       fixed);
        }
    }
    b.m.contact.buffer = 0.05 + 0.3 * u01(rng);
    return b.finalize();
}

TEST(BroadPhase, EqualsBruteForceOnRandomLayouts) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<Real> ulog(std::log(50.0), std::log(2000.0)), ud(0.5, 3);
    size_t total = 0;
    for (int layout = 0; layout < 100; ++layout) {
        const int n = static_cast<int>(std::exp(ulog(rng)));
        const Real box = std::sqrt(n * ud(rng));  // from dense (overlapping) to sparse
        const Model m = random_layout(rng, n, box, layout % 3 != 0);
        State s = make_state(m, 1e-6);
        update_virtual_nodes(m, s);
        ContactState grid = s.contact, scalar = s.contact, brute = s.contact;
        find_candidates(m, s.topology, s.x.data(), s.contact.xv.data(), grid.cand, grid.broad);
        find_candidates(m, s.topology, s.x.data(), s.contact.xv.data(), scalar.cand, scalar.broad,
                        BroadKernel::Scalar);
        find_candidates_brute_force(m, s.topology, s.x.data(), s.contact.xv.data(), brute.cand,
                                    brute.broad);
        for (const ContactState* c : {&grid, &scalar}) {
            const char* path = c == &grid ? "default" : "portable";
            ASSERT_EQ(c->cand.node, brute.cand.node) << "layout " << layout << ", " << path;
            ASSERT_EQ(c->cand.body, brute.cand.body) << "layout " << layout << ", " << path;
            ASSERT_EQ(c->cand.begin, brute.cand.begin) << "layout " << layout << ", " << path;
            ASSERT_EQ(c->cand.tri, brute.cand.tri) << "layout " << layout << ", " << path;
        }
        total += grid.cand.tri.size();
    }
    std::printf("[ info ] %zu candidate couples over 100 layouts\n", total);
    EXPECT_GT(total, 1000u);
}

// A distributed run's local broad phase (spec D5.3): with the targets of one process only
// (TargetOwner), the list is exactly the full list's pairs of those targets, in the same order,
// with the same sub-triangles, on both inner loops; the processes' lists together are the full
// list. Random owners per node (edge targets go with their first end node) on even layouts,
// and on odd ones owners by stripes of x (as a spatial partition).
TEST(BroadPhase, OwnTargetsGiveTheFullListsPairsOfThoseTargets) {
    std::mt19937 rng(99);
    size_t edge_pairs = 0;
    for (int layout = 0; layout < 20; ++layout) {
        const Model m = random_layout(rng, 300, 15.0, layout % 2 == 0);
        State s = make_state(m, 1e-6);
        update_virtual_nodes(m, s);
        const ContactTopology& ct = s.topology;
        ContactState full = s.contact;
        find_candidates(m, ct, s.x.data(), s.contact.xv.data(), full.cand, full.broad);
        constexpr int kProcs = 3;
        std::uniform_int_distribution<int32_t> up(0, kProcs - 1);
        std::vector<int32_t> owner(static_cast<size_t>(m.num_nodes()));
        for (int32_t& o : owner)
            o = up(rng);
        const bool stripes = layout % 2 == 1;
        if (stripes) {
            Real lo = s.x[0].x, hi = lo;
            for (const Vec2& p : s.x) {
                lo = std::min(lo, p.x);
                hi = std::max(hi, p.x);
            }
            for (size_t i = 0; i < owner.size(); ++i) {
                const auto o = static_cast<int32_t>((s.x[i].x - lo) / (hi - lo) * kProcs);
                owner[i] = std::min(o, kProcs - 1);
            }
        }
        size_t pairs = 0;
        for (int32_t rank = 0; rank < kProcs; ++rank) {
            for (const BroadKernel kernel : {BroadKernel::Auto, BroadKernel::Scalar}) {
                ContactState mine = s.contact;
                find_candidates(m, ct, s.x.data(), s.x.data(), s.contact.xv.data(), mine.cand,
                                mine.broad, TargetOwner{owner.data(), rank}, kernel);
                Candidates want;
                want.begin.push_back(0);
                for (size_t p = 0; p < full.cand.node.size(); ++p) {
                    const NodeId j = full.cand.node[p];
                    if (owner[static_cast<size_t>(target_node(ct, j))] != rank) continue;
                    want.node.push_back(j);
                    want.body.push_back(full.cand.body[p]);
                    for (int32_t k = full.cand.begin[p]; k < full.cand.begin[p + 1]; ++k)
                        want.tri.push_back(full.cand.tri[static_cast<size_t>(k)]);
                    want.begin.push_back(static_cast<int32_t>(want.tri.size()));
                    edge_pairs += j >= ct.edge_target_base && kernel == BroadKernel::Auto;
                }
                ASSERT_EQ(mine.cand.node, want.node) << "layout " << layout << " rank " << rank;
                ASSERT_EQ(mine.cand.body, want.body) << "layout " << layout << " rank " << rank;
                ASSERT_EQ(mine.cand.begin, want.begin) << "layout " << layout << " rank " << rank;
                ASSERT_EQ(mine.cand.tri, want.tri) << "layout " << layout << " rank " << rank;
                if (kernel == BroadKernel::Auto) pairs += mine.cand.node.size();
            }
        }
        EXPECT_EQ(pairs, full.cand.node.size()) << "layout " << layout;
    }
    EXPECT_GT(edge_pairs, 100u);  // edge targets were among the filtered ones
}

// From 4 096 targets the queries run on all threads, each a contiguous range of targets into its
// own list, the lists concatenated in order: the same list for 1, 2, 3 and 5 threads, on both
// inner loops and for one process's targets (a distributed run), and the brute-force set.
TEST(BroadPhase, SameListForAnyThreadCount) {
    std::mt19937 rng(5);
    const Model m = random_layout(rng, 2500, 50.0, true);
    State s = make_state(m, 1e-6);
    update_virtual_nodes(m, s);
    const ContactTopology& ct = s.topology;
    ASSERT_GT(ct.boundary_nodes.size(), 4096u);  // above the threshold of the parallel queries
    std::vector<int32_t> owner(static_cast<size_t>(m.num_nodes()));
    for (size_t i = 0; i < owner.size(); ++i)
        owner[i] = static_cast<int32_t>((i * 7919) % 3);
    ContactState brute = s.contact;
    find_candidates_brute_force(m, ct, s.x.data(), s.contact.xv.data(), brute.cand, brute.broad);
    const int before = omp_get_max_threads();
    for (const BroadKernel kernel : {BroadKernel::Auto, BroadKernel::Scalar}) {
        for (const bool distributed : {false, true}) {
            const TargetOwner own = distributed ? TargetOwner{owner.data(), 1} : TargetOwner{};
            omp_set_num_threads(1);
            ContactState one = s.contact;
            find_candidates(m, ct, s.x.data(), s.x.data(), s.contact.xv.data(), one.cand, one.broad,
                            own, kernel);
            if (!distributed) {
                ASSERT_EQ(one.cand.node, brute.cand.node);
                ASSERT_EQ(one.cand.tri, brute.cand.tri);
            }
            for (const int threads : {2, 3, 5}) {
                SCOPED_TRACE(threads);
                omp_set_num_threads(threads);
                ContactState c = s.contact;
                // twice: the second detection reuses the per-thread lists
                for (int rep = 0; rep < 2; ++rep) {
                    find_candidates(m, ct, s.x.data(), s.x.data(), s.contact.xv.data(), c.cand,
                                    c.broad, own, kernel);
                    ASSERT_EQ(c.cand.node, one.cand.node);
                    ASSERT_EQ(c.cand.body, one.cand.body);
                    ASSERT_EQ(c.cand.begin, one.cand.begin);
                    ASSERT_EQ(c.cand.tri, one.cand.tri);
                }
            }
        }
    }
    omp_set_num_threads(before);
}

// A second detection on the same state (scratch and output buffers already sized, cell-ordered
// copies present behind the id-ordered data) gives the same candidates as the first, and a
// state whose bodies moved gives the brute-force set again (no stale scratch is read).
TEST(BroadPhase, RepeatedDetectionsUseNoStaleScratch) {
    std::mt19937 rng(7);
    const Model m = random_layout(rng, 400, 20.0, true);
    State s = make_state(m, 1e-6);
    update_virtual_nodes(m, s);
    find_candidates(m, s.topology, s.x.data(), s.contact.xv.data(), s.contact.cand,
                    s.contact.broad);
    const std::vector<int32_t> first = s.contact.cand.tri;
    find_candidates(m, s.topology, s.x.data(), s.contact.xv.data(), s.contact.cand,
                    s.contact.broad);
    EXPECT_EQ(s.contact.cand.tri, first);
    for (Vec2& p : s.x)
        p = Vec2{p.x * 0.7 + 1.0, p.y * 0.7 - 2.0};  // denser: more candidates than before
    update_virtual_nodes(m, s);
    ContactState brute = s.contact;
    find_candidates(m, s.topology, s.x.data(), s.contact.xv.data(), s.contact.cand,
                    s.contact.broad);
    find_candidates_brute_force(m, s.topology, s.x.data(), s.contact.xv.data(), brute.cand,
                                brute.broad);
    EXPECT_GT(s.contact.cand.tri.size(), first.size());
    EXPECT_EQ(s.contact.cand.node, brute.cand.node);
    EXPECT_EQ(s.contact.cand.body, brute.cand.body);
    EXPECT_EQ(s.contact.cand.begin, brute.cand.begin);
    EXPECT_EQ(s.contact.cand.tri, brute.cand.tri);
}

TEST(BroadPhase, RoughlyLinearRuntime) {
    // informative timing (not asserted: shared machine), spec T11 asks for <= 12x per 10x
    std::mt19937 rng(1);
    for (int n : {1000, 10000}) {
        const Model m = random_layout(rng, n, std::sqrt(2.0 * n), true);
        State s = make_state(m, 1e-6);
        update_virtual_nodes(m, s);
        const auto t0 = std::chrono::steady_clock::now();
        find_candidates(m, s.topology, s.x.data(), s.contact.xv.data(), s.contact.cand,
                        s.contact.broad);
        const auto t1 = std::chrono::steady_clock::now();
        std::printf("[ info ] %d bodies: %.2f ms, %zu couples\n", n,
                    std::chrono::duration<double, std::milli>(t1 - t0).count(),
                    s.contact.cand.tri.size());
    }
}

}  // namespace
}  // namespace fdem
