// Zoltan RCB (parallel/mpi/rcb.hpp) under mpirun with 1-4 processes.
#include "parallel/mpi/rcb.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace fdem {
namespace {

struct Box {
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
};

// 20 000 jittered points (no ties at a cut), dealt round-robin, split into `parts` parts: every
// point gets one part, the parts are balanced, and their bounding boxes do not overlap (RCB
// cuts space into boxes); the same call again gives the same parts (DETERMINISTIC).
void check_rcb(int parts) {
    const MpiComm comm;
    const int n = 20000;
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Vec2> x;
    std::vector<double> w;
    std::vector<uint64_t> gid;
    for (int i = 0; i < n; ++i) {
        const Vec2 p{2.0 * u(rng), u(rng)};
        if (i % comm.size() != comm.rank()) continue;
        x.push_back(p);
        w.push_back(1.0);
        gid.push_back(static_cast<uint64_t>(i));
    }
    const std::vector<int> part = rcb_parts(comm, x, w, gid, parts);
    ASSERT_EQ(part.size(), x.size());
    EXPECT_EQ(rcb_parts(comm, x, w, gid, parts), part);

    std::vector<int64_t> count(static_cast<size_t>(parts), 0);
    std::vector<Box> box(static_cast<size_t>(parts));
    for (size_t i = 0; i < x.size(); ++i) {
        ASSERT_GE(part[i], 0);
        ASSERT_LT(part[i], parts);
        const size_t p = static_cast<size_t>(part[i]);
        ++count[p];
        box[p].x0 = std::min(box[p].x0, x[i].x);
        box[p].y0 = std::min(box[p].y0, x[i].y);
        box[p].x1 = std::max(box[p].x1, x[i].x);
        box[p].y1 = std::max(box[p].y1, x[i].y);
    }
    int64_t total = 0;
    for (size_t p = 0; p < count.size(); ++p) {
        count[p] = comm.sum(count[p]);
        box[p].x0 = comm.min(box[p].x0);
        box[p].y0 = comm.min(box[p].y0);
        box[p].x1 = comm.max(box[p].x1);
        box[p].y1 = comm.max(box[p].y1);
        total += count[p];
    }
    EXPECT_EQ(total, n);
    const double mean = static_cast<double>(n) / parts;
    for (int64_t c : count)
        EXPECT_LE(static_cast<double>(c), 1.1 * mean) << "parts " << parts;  // Zoltan's default
    for (size_t a = 0; a < box.size(); ++a) {
        for (size_t b = a + 1; b < box.size(); ++b) {
            const double ox = std::min(box[a].x1, box[b].x1) - std::max(box[a].x0, box[b].x0);
            const double oy = std::min(box[a].y1, box[b].y1) - std::max(box[a].y0, box[b].y0);
            EXPECT_FALSE(ox > 0 && oy > 0) << "parts " << a << " and " << b << " overlap";
        }
    }
}

TEST(Rcb, PartsAreBalancedDisjointBoxes) {
    for (int parts : {1, 2, 3, 4, 7})
        check_rcb(parts);
}

}  // namespace
}  // namespace fdem
