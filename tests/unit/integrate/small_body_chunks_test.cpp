// Element schedule of many small bodies (element/cst.cpp build_element_schedule): adjacent small
// bodies share chunks of up to 256 triangles, and the parallel pass still gives every node the
// same bits as the serial triangle-order loop (each node's triangles lie in one chunk).
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>

#include "element/cst.hpp"
#include "fdem/simulate.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

TEST(SmallBodyChunks, PackOfTwoTriangleBlocksUsesFullChunks) {
    scenes::PackOptions o;
    o.blocks_x = o.blocks_y = 100;  // 10^4 bodies, 2 * 10^4 triangles
    const Model m = scenes::make_contact_pack(o);
    // 256 triangles = 128 blocks per chunk: ceil(20000 / 256) = 79 chunks (was 10^4)
    EXPECT_EQ(m.element_schedule.num_chunks(), 79);
    // chunks of one color share no node: here every chunk has its own bodies, so one color
    EXPECT_EQ(m.element_schedule.color_units.size(), 2u);
}

TEST(SmallBodyChunks, ParallelForcesEqualTheSerialLoopBitwise) {
    omp_set_num_threads(2);
    scenes::ParticleOptions o;
    o.nx = o.ny = 40;  // 1600 particles of 5-8 triangles: many shared chunks, parallel pass
    const Model m = scenes::make_particle_box(o);
    State s = make_state(m, 0.5 * stable_time_step(m));
    // deform every particle a little (deterministic pattern), so every node has a force
    for (size_t i = 0; i < s.x.size(); ++i)
        s.x[i] += 1e-5 * Vec2{std::sin(1.7 * i), std::cos(2.3 * i)};
    std::vector<Vec2> f_ref(s.x.size());
    add_internal_forces(m, s.x.data(), s.v.data(), f_ref.data(), 0, m.num_tris());
    std::fill(s.f.begin(), s.f.end(), Vec2{});
    add_internal_forces(m, s);
    int nonzero = 0;
    for (size_t i = 0; i < f_ref.size(); ++i) {
        // exact: a node's triangles belong to one small body, summed in triangle order by both
        ASSERT_EQ(s.f[i].x, f_ref[i].x) << "node " << i;
        ASSERT_EQ(s.f[i].y, f_ref[i].y) << "node " << i;
        nonzero += f_ref[i].x != 0;
    }
    EXPECT_GT(nonzero, 1000);  // the comparison covers deformed particles
}

}  // namespace
}  // namespace fdem
