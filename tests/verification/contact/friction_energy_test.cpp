// Energy balance of Coulomb friction through the time step (issue #12 item 1, docs/theory.md
// eq. 6.11): a block sliding to rest on a fixed slab, no damping of any kind. The friction
// dissipation is the work of the friction force minus the change of the stored tangential
// energy, so the balance of eq. 4.1 closes at second order in dt: the error shrinks ~4x per
// halving: 3.2e-3, 7.9e-4, 1.8e-4 of the initial kinetic energy at the three steps below.
// (Booking only the capped force times the slip left the spring energy released by a falling
// cap mu |f_n| unbooked, a first-order error: 6.3e-2, 3.1e-2, 1.6e-2, ratio ~2 per halving, at
// 0.2 of the stable limit before eq. 6.17 lowered it by 3 %.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fdem/build.hpp"
#include "fdem/simulate.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

// A 0.2 m x 0.1 m block (4 x 2 cells) lying on a fixed 1 m x 0.1 m slab (10 x 2 cells), nodes
// not aligned with the slab's, gravity, initial sliding velocity 0.5 m/s, mu = 0.5, k_t the
// default 0.1 k_n. It stops after ~0.1 s, then rocks on the contact springs.
Model sliding_block(Real damping = 0) {
    Model m;
    m.materials.push_back(scenes::paper_material("rock", 1e7, 0.25, 1000.0));
    scenes::add_rectangle(m, 0, 0, 1, 0.1, 10, 2, 0, true, {}, false, "slab");
    scenes::add_rectangle(m, 0.1234, 0.1, 0.2, 0.1, 4, 2, 0, false, {0.5, 0}, false, "block");
    m.gravity = {0, -9.81};
    m.contact.algorithm = ContactAlgorithm::Smooth;
    m.contact.params.friction = 0.5;
    m.contact.params.damping = damping;
    // node-only targets (the numbers above): with the edge targets of docs/theory.md §6.12 the
    // undamped balance errors are 2.7e-3, 5.2e-4, 1.6e-4 (ratios 5.1, 3.4), but the block's
    // rocking on its undamped contact springs leaves 4.8 % / 2.9 % of KE_0 at t = 0.15 s at the
    // first two steps, above the 1 % "at rest" check
    m.contact.edge_targets = false;
    finalize_model(m);
    return m;
}

/// max |E_tot - E_0| over 0.15 s divided by the initial kinetic energy.
Real balance_error(const Model& m, Real dt, Real* slid) {
    State s = make_state(m, dt);
    step(m, s);
    const Real e0 = s.energy.total();
    Real ke0 = 0;
    for (NodeId i = 0; i < m.num_nodes(); ++i)
        ke0 += 0.5 * m.node_mass[i] * norm2(m.node_v0[i]);
    Real err = 0;
    while (s.time < 0.15) {
        step(m, s);
        err = std::max(err, std::abs(s.energy.total() - e0));
    }
    const NodeId corner = m.bodies[1].node_begin;
    *slid = s.x[corner].x - m.node_x0[corner].x;
    // the block has stopped sliding: its mean horizontal velocity is below 5 % of v0 = 0.5 m/s
    // (what is left is the undamped rocking on the contact springs, ~0.01-0.02 m/s)
    Real px = 0, mass = 0;
    for (NodeId i = m.bodies[1].node_begin; i < m.bodies[1].node_end; ++i) {
        px += m.node_mass[i] * s.v[i].x;
        mass += m.node_mass[i];
    }
    EXPECT_LT(std::abs(px / mass), 0.025) << "the block must have come to rest";
    return err / ke0;
}

TEST(FrictionEnergy, SlidingToRestClosesTheBalanceAtSecondOrder) {
    const Model m = sliding_block();
    const Real dt0 = 0.2 * stable_time_step(m);
    Real err[3], slid[3];
    for (int k = 0; k < 3; ++k) {
        const Real dt = dt0 / (1 << k);
        err[k] = balance_error(m, dt, &slid[k]);
        std::printf("dt %.4e s: balance error %.3e of KE_0, slid %.5f m\n", dt, err[k], slid[k]);
    }
    // at least v0^2 / (2 mu g) = 25.5 mm: the block starts at zero depth and rocks on its
    // undamped contact springs, so the cap mu |f_n| oscillates and the tangential spring, which
    // must be stretched again after each drop, stays on average below the cap (~13 % here)
    const Real coulomb = 0.5 * 0.5 / (2 * 0.5 * 9.81);
    EXPECT_GT(slid[2], coulomb);
    EXPECT_LT(slid[2], 1.2 * coulomb);
    for (int k = 0; k < 2; ++k) {
        const Real ratio = err[k] / err[k + 1];
        std::printf("ratio %.2f\n", ratio);
        EXPECT_GT(ratio, 3.0) << "halving dt must divide the balance error by ~4 (second order)";
    }
    EXPECT_LT(err[0], 0.02);
}

// The same with contact damping gamma = 3000 N s/m^2 (normal and tangential): its dissipation is
// the trapezoidal work of the damping force (theory eq. 6.10), second order as well (booking
// gamma |v_r|^2 dt with v^{n-1/2} gave 1.8e-2, 9.0e-3, 4.5e-3, ratio 2; now 6.7e-4, 1.8e-4,
// 5.3e-5).
TEST(FrictionEnergy, SlidingToRestWithContactDampingClosesAtSecondOrder) {
    const Model m = sliding_block(3000.0);
    const Real dt0 = 0.2 * stable_time_step(m);
    Real err[3], slid[3];
    for (int k = 0; k < 3; ++k) {
        const Real dt = dt0 / (1 << k);
        err[k] = balance_error(m, dt, &slid[k]);
        std::printf("damped, dt %.4e s: balance error %.3e of KE_0\n", dt, err[k]);
    }
    for (int k = 0; k < 2; ++k)
        EXPECT_GT(err[k] / err[k + 1], 3.0) << "second order with damping as well";
    EXPECT_LT(err[0], 0.02);
}

}  // namespace
}  // namespace fdem
