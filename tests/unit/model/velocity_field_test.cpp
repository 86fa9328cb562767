// Initial velocity field of a [[body]] entry (docs/scenario.md, docs/theory.md eq. 5.5):
// v(x) = velocity + omega e_z x (x - o) + G (x - o), per piece, from one entry.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fdem/scenario.hpp"
#include "fdem/simulate.hpp"

namespace fdem {
namespace {

Scenario load(const std::string& body_keys, const std::string& mesh,
              const std::string& more = "") {
    return load_scenario_from_string(R"([simulation]
end_time = 0.01
dt = 1e-7
[[material]]
name = "m"
density = 2000.0
youngs_modulus = 1e9
poisson_ratio = 0.25
[[body]]
name = "b"
material = "m"
mesh = ")" + mesh + "\"\n" + more + body_keys + "\n",
                                     "field.toml", FDEM_TEST_DATA_DIR);
}

struct Moments {
    Real mass = 0;
    Vec2 centre, momentum;
    Real inertia = 0;  // sum m |x - c|^2 about the mass centre
    Real spin = 0;     // sum m (x - c) x v
};

Moments moments(const Model& m, BodyId b, const std::vector<Vec2>& v) {
    Moments r;
    const Body& body = m.bodies[b];
    for (NodeId i = body.node_begin; i < body.node_end; ++i) {
        r.mass += m.node_mass[i];
        r.centre += m.node_mass[i] * m.node_x0[i];
        r.momentum += m.node_mass[i] * v[i];
    }
    r.centre = r.centre / r.mass;
    for (NodeId i = body.node_begin; i < body.node_end; ++i) {
        const Vec2 d = m.node_x0[i] - r.centre;
        r.inertia += m.node_mass[i] * norm2(d);
        r.spin += m.node_mass[i] * cross(d, v[i]);
    }
    return r;
}

// A disk (R = 0.1 m, centre (1, 2)) spinning at 50 rad/s about its own mass centre while
// translating at (1, -2) m/s, from one entry: momentum M v0, angular momentum I omega, and the
// kinetic energy of the first step 1/2 M |v0|^2 + 1/2 I omega^2, I = sum m r^2 -> 1/2 M R^2.
TEST(VelocityField, SpinningDiskFromOneEntry) {
    const Real w = 50.0;
    const Scenario sc =
        load("velocity = [1.0, -2.0]\nangular_velocity = 50.0", "disk.geo", "mesh_size = 0.02\n");
    const Model& m = sc.model;
    ASSERT_EQ(m.num_bodies(), 1);
    const Moments r = moments(m, 0, m.node_v0);
    EXPECT_NEAR(r.momentum.x, r.mass * 1.0, 1e-12 * r.mass);
    EXPECT_NEAR(r.momentum.y, r.mass * -2.0, 1e-12 * r.mass);
    EXPECT_NEAR(r.spin, r.inertia * w, 1e-12 * r.inertia * w);
    const Real M = 2000.0 * M_PI * 0.01, I = 0.5 * M * 0.01;  // continuum disk
    EXPECT_NEAR(r.mass, M, 0.02 * M);    // inscribed polygon
    EXPECT_NEAR(r.inertia, I, 0.04 * I);  // lumped masses on a polygon
    State s = make_state(m, 1e-7);
    step(m, s);
    EXPECT_NEAR(s.energy.kinetic, 0.5 * r.mass * 5.0 + 0.5 * r.inertia * w * w,
                1e-12 * s.energy.kinetic);
}

// A ring expanding at a strain rate of 3/s about its centre: v = 3 (x - c) at every node.
TEST(VelocityField, ExpandingRing) {
    const Scenario sc = load("velocity_gradient = [[3.0, 0.0], [0.0, 3.0]]", "ring.geo",
                             "mesh_size = 0.2\n");
    const Model& m = sc.model;
    const Moments r = moments(m, 0, m.node_v0);
    EXPECT_LT(norm(r.centre), 1e-12);
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        const Vec2 expect = 3.0 * (m.node_x0[i] - r.centre);
        EXPECT_NEAR(m.node_v0[i].x, expect.x, 1e-12);
        EXPECT_NEAR(m.node_v0[i].y, expect.y, 1e-12);
    }
}

// Two unit squares (mass centres (0.5, 0.5) and (2.5, 0.5)) converging on (1.5, 0.5) at a
// strain rate of -10/s, pieces = "separate", one entry. Rigid: every node of a piece moves at
// the field's value at its mass centre, -10 (c - o) = (+-10, 0). Affine: v = -10 (x - o).
TEST(VelocityField, ConvergingPackGivesEachPieceItsRigidVelocity) {
    const std::string keys =
        "pieces = \"separate\"\nvelocity_gradient = [[-10.0, 0.0], [0.0, -10.0]]\n"
        "origin = [1.5, 0.5]\n";
    const Scenario rigid =
        load(keys + "piece_motion = \"rigid\"", "two_pieces.geo", "mesh_size = 0.25\n");
    const Model& m = rigid.model;
    ASSERT_EQ(m.num_bodies(), 2);
    for (BodyId b = 0; b < 2; ++b) {
        const Moments r = moments(m, b, m.node_v0);
        const Real vx = r.centre.x < 1.5 ? 10.0 : -10.0;
        EXPECT_NEAR(r.centre.y, 0.5, 1e-12);
        for (NodeId i = m.bodies[b].node_begin; i < m.bodies[b].node_end; ++i) {
            EXPECT_NEAR(m.node_v0[i].x, vx, 1e-12);
            EXPECT_NEAR(m.node_v0[i].y, 0.0, 1e-12);
        }
    }
    const Scenario affine = load(keys, "two_pieces.geo", "mesh_size = 0.25\n");
    for (NodeId i = 0; i < affine.model.num_nodes(); ++i) {
        const Vec2 expect = -10.0 * (affine.model.node_x0[i] - Vec2{1.5, 0.5});
        EXPECT_NEAR(affine.model.node_v0[i].x, expect.x, 1e-12);
        EXPECT_NEAR(affine.model.node_v0[i].y, expect.y, 1e-12);
    }
}

// origin = "centroid" (the default) with pieces = "separate": every piece spins about itself,
// so each has no momentum and angular momentum I omega about its own centre.
TEST(VelocityField, EveryPieceSpinsAboutItsOwnCentre) {
    const Scenario sc = load("pieces = \"separate\"\nangular_velocity = -4.0", "two_pieces.geo",
                             "mesh_size = 0.25\n");
    const Model& m = sc.model;
    ASSERT_EQ(m.num_bodies(), 2);
    for (BodyId b = 0; b < 2; ++b) {
        const Moments r = moments(m, b, m.node_v0);
        EXPECT_LT(norm(r.momentum), 1e-12 * r.mass);
        EXPECT_NEAR(r.spin, -4.0 * r.inertia, 1e-12 * 4.0 * r.inertia);
    }
}

// A rigid piece with a velocity gradient spins with its vorticity (G_yx - G_xy) / 2 and does
// not deform: a shear field [[0, 2], [0, 0]] gives spin -1 rad/s about each centre.
TEST(VelocityField, RigidPieceTakesTheVorticityOfTheGradient) {
    const Scenario sc = load(
        "pieces = \"separate\"\nvelocity_gradient = [[0.0, 2.0], [0.0, 0.0]]\norigin = [0, 0]\n"
        "piece_motion = \"rigid\"",
        "two_pieces.geo", "mesh_size = 0.25\n");
    const Model& m = sc.model;
    for (BodyId b = 0; b < 2; ++b) {
        const Moments r = moments(m, b, m.node_v0);
        EXPECT_NEAR(r.momentum.x / r.mass, 2.0 * r.centre.y, 1e-12);
        EXPECT_NEAR(r.spin, -1.0 * r.inertia, 1e-12 * r.inertia);
    }
}

}  // namespace
}  // namespace fdem
