// Resultants (include/fdem/measure.hpp, bodies.csv) against analytic numbers: equilibrium of a
// block resting on a fixed slab, a bar stretched by a prescribed end, Newton's third law in a
// collision, and free flight under gravity (docs/theory.md §8).
#include <gtest/gtest.h>

#include <cmath>

#include "fdem/build.hpp"
#include "fdem/measure.hpp"
#include "fdem/simulate.hpp"
#include "unit/contact/contact_fixture.hpp"

namespace fdem {
namespace {

using testing::ModelBuilder;

Real stable_dt(const Model& m) {
    return stable_time_step(m);
}

// Run n steps, accumulating impulses over the last `window` steps; returns the values after.
std::vector<SetValues> run(const Model& m, State& s, const Resultants& r, int n, int window,
                           IntervalImpulses* acc_out = nullptr) {
    IntervalImpulses acc = r.make_impulses();
    for (int k = 0; k < n; ++k) {
        step(m, s);
        if (k == n - window) acc.clear();
        r.accumulate(m, s, acc);
    }
    std::vector<SetValues> out(static_cast<size_t>(r.num_sets()));
    r.evaluate(m, s, acc, out.data());
    if (acc_out) *acc_out = acc;
    return out;
}

// A 0.2 x 0.2 m block (rho = 1000 kg/m^3: M = 40 kg/m) rests on a fixed 1 x 0.1 m slab
// (M = 100 kg/m) under g = 9.81 m/s^2, settled by mass damping. The block's contact resultant
// is its weight upwards, the slab's the same downwards, and the ground holds both bodies:
// R_slab = (40 + 100) x 9.81 N/m upwards (theory eq. 8.2).
TEST(Resultants, BlockRestingOnFixedSlab) {
    ModelBuilder b;
    b.m.gravity = {0, -9.81};
    b.m.mass_damping = {3000.0, 1.0};
    b.add_body(make_rectangle_mesh(0, -0.1, 1, 0.1, 10, 2), true);     // entry 0: slab
    b.add_body(make_rectangle_mesh(0.33, 0, 0.2, 0.2, 2, 2), false);  // entry 1: block
    const Model& m = b.finalize();
    State s = make_state(m, 0.5 * stable_dt(m));
    const Resultants r(m);
    ASSERT_EQ(r.num_sets(), 2);
    ASSERT_EQ(r.num_entries(), 2);
    const int n = static_cast<int>(0.02 / s.dt);
    const auto v = run(m, s, r, n, 200);
    const Real W = 40 * 9.81, Ws = 100 * 9.81;
    std::printf("[ info ] %d steps: block contact (%.9g, %.9g), slab contact (%.9g, %.9g), "
                "slab reaction (%.9g, %.9g) N/m; weights %.9g, %.9g\n",
                n, v[1].contact.x, v[1].contact.y, v[0].contact.x, v[0].contact.y,
                v[0].reaction.x, v[0].reaction.y, W, Ws);
    const Real tol = 1e-6 * W;
    EXPECT_NEAR(v[1].contact.y, W, tol);
    EXPECT_NEAR(v[1].contact.x, 0, tol);
    EXPECT_NEAR(v[0].contact.y, -W, tol);
    EXPECT_NEAR(v[0].reaction.y, W + Ws, tol);
    EXPECT_NEAR(v[0].reaction.x, 0, tol);
    EXPECT_NEAR(v[1].contact_avg.y, W, tol);
    EXPECT_NEAR(v[0].reaction_avg.y, W + Ws, tol);
    EXPECT_EQ(v[1].reaction.x, 0.0);  // the block has no support
    EXPECT_EQ(v[1].reaction.y, 0.0);
    EXPECT_EQ(v[0].u.x, 0.0);  // a fixed body does not move
    EXPECT_EQ(v[0].u.y, 0.0);
    EXPECT_LT(v[1].u.y, 0.0);  // the block sank a little into the contact layer
    EXPECT_GT(v[1].u.y, -0.01);
}

// A bar L x H = 1 x 0.1 m (E = 1 GPa, nu = 0, plane strain: lambda = 0, mu = E/2) with x fixed
// at its left end and x velocity V prescribed at its right end, started on the uniform-stretch
// motion v0 = V X / L, which is an exact discrete solution with no acceleration: the bar stays
// in quasi-static uniaxial stretch lambda = 1 + V t / L. Cauchy stress (theory eq. 2.2) with
// lambda_2 = 1: sigma_xx = (E/2)(lambda^2 - 1)/lambda, force F = sigma_xx H (per unit thickness),
// ~ E A eps for small eps. The right support pulls with +F, the left one holds with -F.
TEST(Resultants, BarPulledByPrescribedEnd) {
    const Real E = 1e9, L = 1, H = 0.1, V = 0.05;
    ModelBuilder b(E);
    b.m.contact.algorithm = ContactAlgorithm::None;
    b.add_body(make_rectangle_mesh(0, 0, L, H, 20, 2));
    BoundaryCondition left, right;
    left.name = "b0/left";
    left.has_x = true;
    right.name = "b0/right";
    right.has_x = true;
    right.velocity = {V, 0};
    for (NodeId i = 0; i < b.m.num_nodes(); ++i) {
        if (b.m.node_x0[i].x < 1e-9) left.nodes.push_back(i);
        if (b.m.node_x0[i].x > L - 1e-9) right.nodes.push_back(i);
    }
    b.m.bcs = {left, right};
    Model& m = b.finalize();
    for (NodeId i = 0; i < m.num_nodes(); ++i)
        m.node_v0[i] = {V * m.node_x0[i].x / L, 0};
    State s = make_state(m, 0.5 * stable_dt(m));
    const Resultants r(m);
    ASSERT_EQ(r.num_sets(), 3);  // the bar, then its two boundary groups
    EXPECT_EQ(r.name(1), "b0/left");
    EXPECT_EQ(r.name(2), "b0/right");
    const int n = static_cast<int>(0.01 / s.dt), window = 100;
    const auto v = run(m, s, r, n, window);
    auto force = [&](Real t) {
        const Real lam = 1 + V * t / L;
        return 0.5 * E * (lam * lam - 1) / lam * H;
    };
    // forces of the last step are at x^n, t^n = time - dt; the window's average is the mean of
    // the analytic F at the window's steps t^{n-window} .. t^{n-1} (equal weights dt)
    const Real F = force(s.time - s.dt);
    Real Fmid = 0;
    for (int k = n - window; k < n; ++k)
        Fmid += force(k * s.dt);
    Fmid /= window;
    std::printf("[ info ] %d steps, strain %.4g: F = %.9g N/m (E A eps = %.9g), left %.9g, "
                "right %.9g, body %.3g\n",
                n, V * (s.time - s.dt) / L, F, E * H * V * (s.time - s.dt) / L, v[1].reaction.x,
                v[2].reaction.x, v[0].reaction.x);
    EXPECT_NEAR(v[2].reaction.x, F, 1e-9 * F);
    EXPECT_NEAR(v[1].reaction.x, -F, 1e-9 * F);
    EXPECT_NEAR(v[0].reaction.x, 0, 1e-9 * F);  // the bar: both supports, in equilibrium
    EXPECT_NEAR(v[2].reaction_avg.x, Fmid, 1e-7 * F);
    EXPECT_NEAR(v[1].reaction_avg.x, -Fmid, 1e-7 * F);
    EXPECT_NEAR(v[2].u.x, V * s.time, 1e-12);  // the prescribed end moved V t
    EXPECT_NEAR(v[2].v.x, V, 1e-12);
    EXPECT_NEAR(v[1].u.x, 0, 1e-15);
}

// Two free blocks collide obliquely with friction (no gravity, no supports): the contact
// resultants of the two bodies cancel at every step, for every contact algorithm, and equal
// the sum of the nodal contact forces over every node of the body.
TEST(Resultants, CollisionObeysNewtonsThirdLaw) {
    for (ContactAlgorithm alg : {ContactAlgorithm::Smooth, ContactAlgorithm::LegacyTriangle,
                                 ContactAlgorithm::LegacyBoundary}) {
        ModelBuilder b;
        b.m.contact.algorithm = alg;
        b.m.contact.params.friction = 0.3;
        b.add_body(make_rectangle_mesh(0, 0, 0.2, 0.2, 4, 4), false, {1, 0.2});
        b.add_body(make_rectangle_mesh(0.2005, 0.05, 0.2, 0.2, 4, 4, true), false, {-1, 0});
        const Model& m = b.finalize();
        State s = make_state(m, 0.3 * stable_dt(m));
        const Resultants r(m);
        IntervalImpulses acc = r.make_impulses();
        Real worst = 0, fmax = 0;
        int in_contact = 0;
        for (int k = 0; k < 3000; ++k) {
            step(m, s);
            r.accumulate(m, s, acc);
            Vec2 c[2], re[2];
            for (int e = 0; e < 2; ++e) {
                r.forces(m, s, e, c[e], re[e]);
                Vec2 all{};  // every node of the body, in id order
                for (NodeId i = m.bodies[e].node_begin; i < m.bodies[e].node_end; ++i)
                    all += s.f_contact[i];
                ASSERT_EQ(c[e].x, all.x) << "step " << k;
                ASSERT_EQ(c[e].y, all.y) << "step " << k;
                EXPECT_EQ(re[e].x, 0.0);
            }
            const Real f = norm(c[0]);
            if (f > 0) ++in_contact;
            fmax = std::max(fmax, f);
            worst = std::max(worst, norm(c[0] + c[1]));
        }
        std::printf("[ info ] algorithm %d: %d steps in contact, max |F| %.4g N/m, max |F_0 + "
                    "F_1| %.3g N/m; impulses (%.4g, %.4g) + (%.4g, %.4g)\n",
                    static_cast<int>(alg), in_contact, fmax, worst, acc.contact[0].x,
                    acc.contact[0].y, acc.contact[1].x, acc.contact[1].y);
        EXPECT_GT(in_contact, 50);
        EXPECT_LE(worst, 1e-12 * fmax);
        EXPECT_LE(norm(acc.contact[0] + acc.contact[1]), 1e-12 * norm(acc.contact[0]));
        EXPECT_GT(norm(acc.contact[0]), 0.0);
    }
}

// A body in free flight under gravity: the mean displacement is v0 t + g t^2 / 2 exactly
// (theory eq. 5.1) and the mean velocity v0 + g (t - dt/2) (v^{n+1/2}, half a step behind).
TEST(Resultants, FreeFlightMeanMotion) {
    ModelBuilder b;
    b.m.gravity = {0, -9.81};
    b.add_body(make_rectangle_mesh(0, 0, 0.3, 0.1, 6, 2), false, {2.0, 3.0});
    const Model& m = b.finalize();
    State s = make_state(m, 0.5 * stable_dt(m));
    const Resultants r(m);
    const auto v = run(m, s, r, 2000, 10);
    const Real t = s.time;
    std::printf("[ info ] t = %.6g s: u = (%.15g, %.15g), v = (%.15g, %.15g)\n", t, v[0].u.x,
                v[0].u.y, v[0].v.x, v[0].v.y);
    EXPECT_NEAR(v[0].u.x, 2.0 * t, 1e-12);
    EXPECT_NEAR(v[0].u.y, 3.0 * t - 0.5 * 9.81 * t * t, 1e-12);
    EXPECT_NEAR(v[0].v.x, 2.0, 1e-12);
    EXPECT_NEAR(v[0].v.y, 3.0 - 9.81 * (t - 0.5 * s.dt), 1e-12);
    EXPECT_EQ(v[0].contact.y, 0.0);
    EXPECT_EQ(v[0].reaction.y, 0.0);
}

}  // namespace
}  // namespace fdem
