// T6 (spec §8): the pair forces of add_contact_forces sum to zero with zero moment (including
// the redistribution of virtual-node shares to parents), and the force on a target node is
// minus the finite-difference gradient of the stored potential (m_j/mbar) k_n phi(d), edge
// targets (whose potential moves with both end nodes) included.
#include <gtest/gtest.h>

#include <random>

#include "contact/contact.hpp"
#include "fdem/simulate.hpp"
#include "unit/contact/contact_fixture.hpp"

namespace fdem {
namespace {

//   single-triangle target bodies, apex pushed into a one-element-thick strip (all of the strip
//   is boundary layer; its interior edges are chords with virtual mid-nodes)
//
//        /\    /\    /\ .
//   +---/--\--/--\--/--\---+   y = 1
//   |  / .  \/ .  \/ .  \  |   (apex inside)
//   +----------------------+   y = 0
Model make_scene(bool fixed_strip, bool two_way, unsigned seed) {
    testing::ModelBuilder b;
    b.m.contact.two_way = two_way;
    b.add_body(make_rectangle_mesh(0, 0, 4, 1, 4, 1), fixed_strip);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> jx(-0.05, 0.05), uy(0.05, 0.95);
    for (int k = 0; k < 6; ++k) {
        const Vec2 p{0.45 + 0.6 * k + jx(rng), uy(rng)};
        b.add_body(testing::mesh_of({p, p + Vec2{0.2, 1.2}, p + Vec2{-0.2, 1.2}}, {{0, 1, 2}}));
    }
    return b.finalize();
}

TEST(ContactPairForce, ForcesAndMomentsBalance) {
    for (int mode = 0; mode < 2; ++mode) {
        const Model m = make_scene(mode == 0, mode == 1, 21);
        State s = make_state(m, 1e-6);
        add_contact_forces(m, s);
        EXPECT_GE(s.contact.active_contacts, 6);
        Vec2 sum;
        Real moment = 0, fscale = 0, mscale = 0;
        for (NodeId i = 0; i < m.num_nodes(); ++i) {
            const Vec2 f = s.f_contact[i];
            sum += f;
            moment += cross(s.x[i], f);
            fscale += norm(f);
            mscale += norm(s.x[i]) * norm(f);
        }
        // 1e-12 relative: sums of O(1e9) terms, round-off only
        EXPECT_LE(norm(sum), 1e-12 * fscale);
        EXPECT_LE(std::abs(moment), 1e-12 * mscale);
    }
}

TEST(ContactPairForce, TargetForceIsMinusGradientOfPotential) {
    const Model m = make_scene(true, false, 5);
    const State s0 = make_state(m, 1e-6);
    int checked = 0;
    for (BodyId b = 1; b < m.num_bodies(); ++b) {
        const NodeId j = m.bodies[b].node_begin;  // the apex
        State s = s0;
        add_contact_forces(m, s);
        const Vec2 f = s.f_contact[j];
        auto energy = [&](Vec2 dx) {
            State t = s0;
            t.x[j] += dx;
            add_contact_forces(m, t);
            return t.energy.contact;
        };
        const Real h = 1e-6;
        const Vec2 g{(energy({h, 0}) - energy({-h, 0})) / (2 * h),
                     (energy({0, h}) - energy({0, -h})) / (2 * h)};
        // phi = d^2 is quadratic in x_j inside a triangle: the central difference is exact up
        // to round-off eps E / h ~ 1e-10 relative
        EXPECT_NEAR(f.x, -g.x, 1e-7 * norm(f)) << "body " << b;
        EXPECT_NEAR(f.y, -g.y, 1e-7 * norm(f)) << "body " << b;
        EXPECT_GT(norm(f), 0);
        ++checked;
    }
    EXPECT_EQ(checked, 6);
}

// Edge targets (docs/theory.md §6.12): a triangle whose bottom edge lies 0.2 deep in the strip
// (one-way, strip fixed): the edge's midpoint is a target besides its two nodes, its force
// reaches each end node with weight 1/2 and its potential moves with both (chain rule), so the
// contact force on every node is minus the gradient of the booked energy.
TEST(ContactPairForce, EdgeTargetForceIsMinusGradientOfPotential) {
    testing::ModelBuilder b;
    b.m.contact.two_way = false;
    b.add_body(make_rectangle_mesh(0, 0, 4, 1, 4, 1), true);
    b.add_body(testing::mesh_of({{1.23, 0.8}, {1.81, 0.79}, {1.5, 1.6}}, {{0, 1, 2}}));
    const Model& m = b.finalize();
    const ContactTopology& topo = b.topo;
    const State s0 = make_state(m, 1e-6);
    State s = s0;
    add_contact_forces(m, s);
    int edge_pairs = 0;
    for (const ActiveContact& a : s.contact.active)
        edge_pairs += a.node >= topo.edge_target_base ? 1 : 0;
    EXPECT_EQ(edge_pairs, 1);  // the bottom edge's midpoint
    for (NodeId j = m.bodies[1].node_begin; j < m.bodies[1].node_begin + 2; ++j) {
        const Vec2 f = s.f_contact[j];
        auto energy = [&](Vec2 dx) {
            State t = s0;
            t.x[j] += dx;
            add_contact_forces(m, t);
            return t.energy.contact;
        };
        const Real h = 1e-6;
        const Vec2 g{(energy({h, 0}) - energy({-h, 0})) / (2 * h),
                     (energy({0, h}) - energy({0, -h})) / (2 * h)};
        EXPECT_NEAR(f.x, -g.x, 1e-7 * norm(f)) << "node " << j;
        EXPECT_NEAR(f.y, -g.y, 1e-7 * norm(f)) << "node " << j;
        EXPECT_GT(norm(f), 0);
    }
}

}  // namespace
}  // namespace fdem

namespace fdem {
namespace {

// spec §4.6: penetration beyond the boundary layer is counted, never silently ignored
TEST(ContactDiagnostics, DeepPenetrationIsCounted) {
    testing::ModelBuilder b;
    b.m.contact.two_way = false;
    b.m.contact.edge_targets = false;  // the apex node alone (its edges would touch at 1.5)
    b.add_body(make_rectangle_mesh(0, 0, 12, 3, 12, 3), true);  // layer: 1 deep
    const Vec2 p{6.3, 2.9};
    b.add_body(testing::mesh_of({p, p + Vec2{0.2, 1.2}, p + Vec2{-0.2, 1.2}}, {{0, 1, 2}}));
    const Model& m = b.finalize();
    State s = make_state(m, 1e-6);
    const NodeId apex = m.bodies[1].node_begin;

    // depth 0.1 of a layer 1: shallow
    add_contact_forces(m, s);
    EXPECT_EQ(s.contact.active_contacts, 1);
    EXPECT_NEAR(s.contact.max_depth_ratio, 0.1, 1e-12);
    EXPECT_EQ(s.contact.deep_penetrations, 0);

    // depth 0.7: still located, but deeper than deep_ratio_limit = 0.5
    s.x[apex] = {6.3, 2.3};
    add_contact_forces(m, s);
    EXPECT_EQ(s.contact.deep_penetrations, 1);
    EXPECT_NEAR(s.contact.max_depth_ratio, 0.7, 1e-12);

    // depth 1.5: beyond the layer (no contactor sub-triangle holds it) -> lost inside
    s.x[apex] = {6.3, 1.5};
    s.contact.need_rebuild = true;
    add_contact_forces(m, s);
    EXPECT_EQ(s.contact.active_contacts, 0);
    EXPECT_EQ(s.contact.lost_inside, 1);
    EXPECT_EQ(s.contact.total_lost_inside, 1);
    EXPECT_EQ(s.contact.total_deep_penetrations, 1);
}

}  // namespace
}  // namespace fdem
