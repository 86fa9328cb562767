// Stable time step with contact (issue #12 item 3, docs/theory.md §6.9): the largest
// eigenfrequency of M^-1 (K_e + K_c) of a block resting on a fixed slab, by power iteration on the
// assembled element + contact forces, against the printed bounds; and the energy balance of the
// undamped resting block at the default step (0.2 of the contact limit) and at the old one
// (0.5 x stable).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "contact/contact.hpp"
#include "element/cst.hpp"
#include "fdem/build.hpp"
#include "fdem/scenario.hpp"
#include "fdem/simulate.hpp"

namespace fdem {
namespace {

// A 0.2 m x 0.1 m block lying at zero depth on a fixed 2 m x 0.1 m slab (Gmsh, mesh size
// 0.04 m), rock E = 0.1 GPa, gravity, no friction, no damping; dt = "auto" with dt_fraction
// given or (empty) the default; contact_extra adds [contact] keys (e.g. edge_targets = false).
Scenario resting_block(const std::string& dt_fraction, const std::string& contact_extra = "") {
    const std::string text = R"(
[simulation]
end_time = 0.4
dt = "auto"
)" + dt_fraction + R"(
gravity = [0.0, -9.81]
[[material]]
name = "rock"
density = 2500.0
youngs_modulus = 1.0e8
poisson_ratio = 0.25
[[body]]
name = "slab"
mesh = "block_on_slab.geo"
mesh_size = 0.04
group = "slab"
material = "rock"
fixed = true
[[body]]
name = "block"
mesh = "block_on_slab.geo"
mesh_size = 0.04
group = "block"
material = "rock"
[contact]
algorithm = "smooth"
)" + contact_extra + "\n";
    return load_scenario_from_string(text, "resting_block.toml", FDEM_TEST_DATA_DIR);
}

// element + contact forces at positions x (zero velocities: no damping, no friction increment),
// on a copy of the state so the pair history is not advanced
void forces(const Model& m, const State& s0, const std::vector<Vec2>& x, std::vector<Vec2>& f) {
    State c = s0;
    c.x = x;
    for (Vec2& v : c.v)
        v = {};
    for (Vec2& q : c.f)
        q = {};
    c.contact.need_rebuild = true;
    add_internal_forces(m, c.x.data(), c.v.data(), c.f.data(), 0, m.num_tris());
    add_contact_forces(m, c);
    f = c.f;
}

/// omega_max of M^-1 (K_e + K_c) at the state s: power iteration, K p by central differences of
/// the forces (eps p, eps well below the contact depths), Rayleigh quotient p.Kp / p.Mp.
Real omega_max(const Model& m, const State& s) {
    const size_t n = static_cast<size_t>(m.num_nodes());
    std::vector<Vec2> p(n), kp(n), xp(n), fp, fm;
    std::mt19937 rng(1);
    std::uniform_real_distribution<Real> u(-1, 1);
    for (size_t i = 0; i < n; ++i)
        p[i] = m.node_inv_mass[i] > 0 ? Vec2{u(rng), u(rng)} : Vec2{};
    Real rq = 0;
    for (int it = 0; it < 600; ++it) {
        Real pmax = 0;
        for (const Vec2& q : p)
            pmax = std::max(pmax, norm(q));
        for (Vec2& q : p)
            q = (1.0 / pmax) * q;
        const Real eps = 1e-10;  // [m]; static depths ~1e-7 m
        for (size_t i = 0; i < n; ++i)
            xp[i] = s.x[i] + eps * p[i];
        forces(m, s, xp, fp);
        for (size_t i = 0; i < n; ++i)
            xp[i] = s.x[i] - eps * p[i];
        forces(m, s, xp, fm);
        Real pkp = 0, pmp = 0;
        for (size_t i = 0; i < n; ++i) {
            kp[i] = m.node_inv_mass[i] > 0 ? (-1.0 / (2 * eps)) * (fp[i] - fm[i]) : Vec2{};
            pkp += dot(p[i], kp[i]);
            pmp += m.node_mass[i] * dot(p[i], p[i]);
        }
        rq = pkp / pmp;
        for (size_t i = 0; i < n; ++i)
            p[i] = m.node_inv_mass[i] * kp[i];
    }
    return std::sqrt(rq);
}

/// max |E_tot - E_0| over 0.4 s at step dt, relative to the largest energy term seen.
Real balance_error(const Model& m, Real dt) {
    State s = make_state(m, dt);
    step(m, s);
    const Real e0 = s.energy.total();
    Real err = 0, scale = 0;
    while (s.time < 0.4) {
        step(m, s);
        err = std::max(err, std::abs(s.energy.total() - e0));
        scale = std::max({scale, s.energy.kinetic + s.energy.strain + s.energy.contact,
                          std::abs(s.energy.work_gravity)});
    }
    return err / scale;
}

/// 2 / omega_max of the block settled into contact at a small step, and the bounds.
struct Limits {
    Real dt_e, dt_c, stable, dt_true;
};
Limits measure_limits(const Model& m, const char* what) {
    Limits l{element_stable_time_step(m), contact_stable_dt(m, build_topology(m)),
             stable_time_step(m), 0};
    State s = make_state(m, 0.1 * l.dt_c);
    for (int k = 0; k < 1000; ++k)
        step(m, s);
    EXPECT_GT(s.contact.active_contacts, 5);
    l.dt_true = 2.0 / omega_max(m, s);
    std::printf(
        "%s: element bound %.4e s, contact bound %.4e s (%.3f of the true limit), combined "
        "%.4e s (%.3f), 2/omega_max %.4e s\n",
        what, l.dt_e, l.dt_c, l.dt_c / l.dt_true, l.stable, l.stable / l.dt_true, l.dt_true);
    return l;
}

// The paper's node-only targets: eq. 6.15 alone is close to the true limit (0.90 measured), and
// the combined bound (eq. 6.17) is below it.
TEST(ContactStability, NodeTargetsBoundIsCloseToTheTrueLimit) {
    const Scenario sc = resting_block("", "edge_targets = false");
    const Limits l = measure_limits(sc.model, "node targets");
    EXPECT_LT(l.stable, l.dt_true);
    EXPECT_GT(l.dt_c / l.dt_true, 0.8);
    EXPECT_LT(l.dt_c / l.dt_true, 1.1);
}

// Edge targets (the default, theory §6.12): the bound of eq. 6.15 with target_dt_factor is safe
// but more conservative (0.77 of the true limit on this block: the factor covers the worst
// node/midpoint share, docs/theory.md §6.12); the combined bound is safe.
TEST(ContactStability, PrintedBoundIsBelowTheTrueLimitAndTheDefaultStepConserves) {
    const Scenario sc = resting_block("");
    const Model& m = sc.model;
    const Real dt_e = element_stable_time_step(m), dt_c = contact_stable_dt(m, build_topology(m));
    EXPECT_EQ(sc.run.stable_dt, stable_time_step(m));
    const Limits l = measure_limits(m, "edge targets");
    // both bounds are safe. No closeness check here: target_dt_factor (4/3 for a node next to
    // midpoints) is a worst case, and on this block the true limit with edge targets is larger
    // than with nodes only while the bound is smaller (measured 0.770 of the true limit against
    // 0.913 with node targets; the step is ~16 % shorter than it needs to be: issue #16)
    EXPECT_LT(l.stable, l.dt_true);
    EXPECT_LT(l.dt_c, l.dt_true);

    // energy: the default step min(0.5 dt_e, 0.2 dt_c) (theory §6.9) against the old default
    // 0.5 x stable, where the undamped contact vibration gains energy
    EXPECT_DOUBLE_EQ(sc.run.dt, std::min(0.5 * dt_e, 0.2 * dt_c));
    const Scenario old = resting_block("dt_fraction = 0.5");
    const Real err_default = balance_error(m, sc.run.dt);
    const Real err_old = balance_error(old.model, old.run.dt);
    std::printf("resting block: balance error %.3e at the default dt %.4e s, %.3e at %.4e s\n",
                err_default, sc.run.dt, err_old, old.run.dt);
    EXPECT_LT(err_default, 0.005);
    EXPECT_GT(err_old, 0.02);
}

}  // namespace
}  // namespace fdem
