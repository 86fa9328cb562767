// The performance scenes of tests/support/scenes.hpp (contact-heavy pack, particle box) are
// what the benchmarks and example 04 claim them to be: sizes, seeded determinism, contact
// actually happening and the energy balance holding.
#include <gtest/gtest.h>

#include "fdem/simulate.hpp"
#include "support/hash.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

TEST(Scenes, ContactPackHasTwoTrianglesPerBlockAndOneBodyEach) {
    scenes::PackOptions o;
    o.blocks_x = 20;
    o.blocks_y = 10;
    const Model m = scenes::make_contact_pack(o);
    EXPECT_EQ(m.num_bodies(), 200);
    EXPECT_EQ(m.num_tris(), 400);
    EXPECT_EQ(m.num_nodes(), 800);
    // the halves converge: left bodies move right at ~speed (jitter 5 %), right bodies left
    Real vmin = 1e9, vmax = -1e9;
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        vmin = std::min(vmin, m.node_v0[i].x);
        vmax = std::max(vmax, m.node_v0[i].x);
    }
    EXPECT_NEAR(vmax, 20.0, 1.0);  // 1.0 m/s: the jitter bound, 5 % of 20 m/s
    EXPECT_NEAR(vmin, -20.0, 1.0);
}

TEST(Scenes, ParticleBoxIsSeededAndCollides) {
    scenes::ParticleOptions o;
    o.nx = o.ny = 10;
    const Model a = scenes::make_particle_box(o), b = scenes::make_particle_box(o);
    EXPECT_EQ(a.num_bodies(), 100 + 4);  // particles + four walls
    ASSERT_EQ(a.node_x0.size(), b.node_x0.size());
    for (size_t i = 0; i < a.node_x0.size(); ++i) {
        ASSERT_EQ(a.node_x0[i].x, b.node_x0[i].x);
        ASSERT_EQ(a.node_v0[i].y, b.node_v0[i].y);
    }
    // 5..8 triangles per particle
    for (BodyId k = 0; k < 100; ++k) {
        const TriId n = a.bodies[k].tri_end - a.bodies[k].tri_begin;
        EXPECT_GE(n, 5);
        EXPECT_LE(n, 8);
    }
    State s = make_state(a, 0.5 * stable_time_step(a));
    step(a, s);
    const Real e0 = s.energy.total();
    int32_t max_active = 0;
    Real scale = 0, drift = 0;
    for (int k = 0; k < 2000; ++k) {
        step(a, s);
        max_active = std::max(max_active, s.contact.active_contacts);
        scale = std::max(scale, s.energy.kinetic + s.energy.strain + s.energy.contact);
        drift = std::max(drift, std::abs(s.energy.total() - e0));
    }
    EXPECT_GT(max_active, 0) << "particles never touched: the scene proves nothing";
    // 2 %: the explicit scheme with contact impacts at dt = 0.5 x stable keeps the balance to
    // O(dt) per impact; the CLI's default check stops at 10 %
    EXPECT_LT(drift, 0.02 * scale);
    check_state(a, s);
}

}  // namespace
}  // namespace fdem
