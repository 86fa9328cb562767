// Two bodies of one 6-node composite element each (paper case 2, Figs. 9-10) collide through the
// real time step, with both contact options of paper §2.4 (docs/theory.md §6.1.1): no NaN, no
// lost contact, energy drift <= 1 % (spec T19), momentum conserved to round-off.
#include <gtest/gtest.h>

#include <cmath>

#include "fdem/build.hpp"
#include "fdem/simulate.hpp"
#include "support/composite.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

scenes::CompositeMesh rotated(const std::vector<Vec2>& corners, Real a, Vec2 c, Vec2 t) {
    std::vector<Vec2> p = corners;
    for (Vec2& x : p) {
        const Vec2 r = x - c;
        x = c + Vec2{std::cos(a) * r.x - std::sin(a) * r.y, std::sin(a) * r.x + std::cos(a) * r.y} +
            t;
    }
    return scenes::composite_mesh(p, {{0, 1, 2}});
}

TEST(CompositeCollision, SingleCompositesCollide) {
    const std::vector<Vec2> tri{{0, 0}, {0.1, 0}, {0.03, 0.08}};
    for (CompositeSpecialCase o : {CompositeSpecialCase::Fan, CompositeSpecialCase::Split}) {
        for (int k = 0; k < 3; ++k) {
            Model m;
            m.materials.push_back(scenes::paper_material());
            m.contact.algorithm = ContactAlgorithm::Smooth;
            m.contact.composite_special_case = o;
            const scenes::CompositeMesh a = rotated(tri, 0.7 * k, {0.04, 0.03}, {0, 0});
            scenes::CompositeMesh b = rotated(tri, 2.1 + 1.3 * k, {0.04, 0.03}, {0, 0});
            Real hi_a = -1e9, lo_b = 1e9;
            for (const Vec2& p : a.nodes)
                hi_a = std::max(hi_a, p.x);
            for (const Vec2& p : b.nodes)
                lo_b = std::min(lo_b, p.x);
            // 5 mm gap in x, second body 5 mm x k higher
            for (Vec2& p : b.nodes)
                p += Vec2{hi_a + 0.005 - lo_b, 0.005 * k};
            scenes::add_composite_body(m, a, 0, false, {2.5, 0}, "a");
            scenes::add_composite_body(m, b, 0, false, {-2.5, 0}, "b");
            finalize_model(m);

            const Real dt = 0.1 * stable_time_step(m);  // spec §3.4: 0.1-0.2 x the limit
            State s = make_state(m, dt);
            Real ke0 = 0, p_scale = 0;
            Vec2 p0;
            for (NodeId i = 0; i < m.num_nodes(); ++i) {
                ke0 += 0.5 * m.node_mass[i] * norm2(s.v[i]);
                p0 += m.node_mass[i] * s.v[i];
                p_scale += m.node_mass[i] * norm(s.v[i]);
            }
            Real drift = 0, dp = 0;
            int max_active = 0;
            const int steps = static_cast<int>(0.008 / dt);
            for (int n = 0; n < steps; ++n) {
                step(m, s);
                check_state(m, s);  // throws SimulationError on NaN / inverted elements
                if (n > 0) drift = std::max(drift, std::abs(s.energy.total() - ke0) / ke0);
                max_active = std::max(max_active, s.contact.active_contacts);
                Vec2 p;
                for (NodeId i = 0; i < m.num_nodes(); ++i)
                    p += m.node_mass[i] * s.v[i];
                dp = std::max(dp, norm(p - p0) / p_scale);
            }
            auto body_velocity = [&](BodyId bb) {  // centre-of-mass velocity
                Vec2 pv;
                Real mass = 0;
                for (NodeId i = m.bodies[bb].node_begin; i < m.bodies[bb].node_end; ++i) {
                    pv += m.node_mass[i] * s.v[i];
                    mass += m.node_mass[i];
                }
                return pv / mass;
            };
            const Vec2 va = body_velocity(0), vb = body_velocity(1);
            std::printf(
                "[ info ] composites %s #%d: drift %.2e, momentum %.1e, max active %d, "
                "v_a.x %.3f, v_b.x %.3f\n",
                o == CompositeSpecialCase::Fan ? "fan" : "split", k, drift, dp, max_active, va.x,
                vb.x);
            EXPECT_GT(max_active, 0);     // they did meet
            EXPECT_LT(va.x, 2.5 - 1e-3);  // and exchanged momentum (glancing in some runs)
            EXPECT_LE(drift, 0.01);       // spec T19
            EXPECT_LE(dp, 1e-12);         // pair forces cancel exactly (round-off)
            EXPECT_EQ(s.contact.total_lost_inside, 0);
        }
    }
}

}  // namespace
}  // namespace fdem
