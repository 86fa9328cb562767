// Explicit dynamics of composite bodies (issue #7, docs/theory.md §3.5 and §5):
//  * stable time step: the largest eigenfrequency of M^-1 K (power iteration with the kernel's
//    own forces) against the printed per-sub-triangle bound h_min / c_p (theory eq. 5.3), for
//    the composite and for CSTs on the same nodes; runs at 0.95 and 1.05 of 2 / omega_max and of
//    the printed limit;
//  * energy conservation of a free vibrating composite block at dt and dt/2 (second order).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "element/cst.hpp"
#include "fdem/build.hpp"
#include "fdem/simulate.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

// Free 1 m x 1 m block, 4 x 4 cells of two 6-node triangles, interior nodes perturbed by up to
// 8 % of the cell so the spectrum is not degenerate.
Model free_block(ElementKind kind, Real nu) {
    Model m;
    m.materials.push_back(scenes::paper_material("p", 1e9, nu, 1000.0));
    scenes::add_rectangle_order2(m, 0, 0, 1, 1, 4, 4, 0, kind);
    std::mt19937 rng(3);
    std::uniform_real_distribution<Real> u(-0.02, 0.02);
    for (auto& p : m.node_x0) {
        const bool boundary = p.x < 1e-12 || p.y < 1e-12 || p.x > 1 - 1e-12 || p.y > 1 - 1e-12;
        if (!boundary) p = p + Vec2{u(rng), u(rng)};
    }
    finalize_model(m);
    return m;
}

/// Largest eigenvalue omega_max^2 of M^-1 K at the reference configuration: power iteration
/// with K p = -(f(X + e p) - f(X - e p)) / (2 e) through the element kernel, Rayleigh quotient
/// p.Kp / p.Mp (a lower bound that converges from below).
Real omega_max(const Model& m) {
    const size_t n = static_cast<size_t>(m.num_nodes());
    std::vector<Vec2> p(n), kp(n), xp(n), fp(n), fm(n), v(n);
    std::mt19937 rng(1);
    std::uniform_real_distribution<Real> u(-1, 1);
    for (auto& q : p)
        q = {u(rng), u(rng)};
    Real rq = 0;
    for (int it = 0; it < 4000; ++it) {
        Real pmax = 0;
        for (const Vec2& q : p)
            pmax = std::max(pmax, norm(q));
        for (auto& q : p)
            q = (1.0 / pmax) * q;
        const Real e = 1e-7;  // [m]: strains ~1e-6, linear regime
        for (int sgn : {1, -1}) {
            std::vector<Vec2>& f = sgn > 0 ? fp : fm;
            for (size_t i = 0; i < n; ++i) {
                xp[i] = m.node_x0[i] + (sgn * e) * p[i];
                f[i] = {0, 0};
            }
            add_internal_forces(m, xp.data(), v.data(), f.data(), 0, m.num_tris());
        }
        Real pkp = 0, pmp = 0;
        for (size_t i = 0; i < n; ++i) {
            kp[i] = (-1.0 / (2 * e)) * (fp[i] - fm[i]);
            pkp += dot(p[i], kp[i]);
            pmp += m.node_mass[i] * dot(p[i], p[i]);
        }
        rq = pkp / pmp;
        for (size_t i = 0; i < n; ++i)
            p[i] = m.node_inv_mass[i] * kp[i];
    }
    return std::sqrt(rq);
}

/// Run 3000 steps of a free body from small random velocities at time step dt; true if the
/// motion stays bounded (max speed below 100 x the initial one).
bool stays_bounded(const Model& m0, Real dt) {
    Model m = m0;
    std::mt19937 rng(9);
    std::uniform_real_distribution<Real> u(-1e-3, 1e-3);
    for (auto& v : m.node_v0)
        v = {u(rng), u(rng)};
    State s = make_state(m, dt);
    s.need_energy = false;
    for (int k = 0; k < 3000; ++k) {
        step(m, s);
        Real vmax = 0;
        for (const Vec2& v : s.v)
            vmax = std::max(vmax, norm(v));
        if (!(vmax < 0.1 * std::sqrt(3.0))) return false;
    }
    return true;
}

TEST(CompositeDynamics, PrintedStableStepIsBelowTheTrueLimit) {
    for (Real nu : {0.3, 0.499}) {
        for (ElementKind kind : {ElementKind::Composite6, ElementKind::Cst}) {
            const Model m = free_block(kind, nu);
            const Real printed = stable_time_step(m);
            const Real w = omega_max(m);
            const Real dt_true = 2.0 / w;  // central differences: dt <= 2 / omega_max
            const char* name = kind == ElementKind::Composite6 ? "composite" : "cst";
            std::printf("nu %.3f %-9s printed dt %.4e s, 2/omega_max %.4e s, ratio %.3f\n", nu,
                        name, printed, dt_true, printed / dt_true);
            // the printed bound is safe (theory §3.5: the per-sub-triangle bound also holds for
            // the composite)
            EXPECT_LT(printed, dt_true) << name << " nu " << nu;
            // the eigenvalue estimate is right: 5 % below 2 / omega_max the run is stable, 5 %
            // above it the top mode grows (by ~1.9 per step) and the run blows up
            EXPECT_TRUE(stays_bounded(m, 0.95 * dt_true)) << name << " nu " << nu;
            EXPECT_FALSE(stays_bounded(m, 1.05 * dt_true)) << name << " nu " << nu;
            // and the brief's check: 0.95 and 1.05 of the printed limit are both stable, the
            // latter because the printed bound keeps a margin (ratio above)
            EXPECT_TRUE(stays_bounded(m, 0.95 * printed)) << name << " nu " << nu;
            EXPECT_TRUE(stays_bounded(m, 1.05 * printed)) << name << " nu " << nu;
        }
    }
}

/// max |E_tot(t) - E_0| / E_0 over 10 ms (about three periods of the block's lowest modes) of a
/// free, undamped composite block started with a shear velocity field.
Real energy_error(Real dt) {
    Model m = free_block(ElementKind::Composite6, 0.45);
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        const Vec2 X = m.node_x0[i];
        m.node_v0[i] = {0.5 * std::sin(M_PI * X.y), 0.3 * std::cos(M_PI * X.x)};
    }
    State s = make_state(m, dt);
    step(m, s);
    const Real e0 = s.energy.total();
    Real err = 0;
    while (s.time < 1e-2) {
        step(m, s);
        err = std::max(err, std::abs(s.energy.total() - e0));
    }
    return err / e0;
}

TEST(CompositeDynamics, FreeVibrationConservesEnergyToSecondOrder) {
    const Model m = free_block(ElementKind::Composite6, 0.45);
    const Real dt = 0.2 * stable_time_step(m);
    const Real e1 = energy_error(dt), e2 = energy_error(0.5 * dt);
    const Real order = std::log2(e1 / e2);
    std::printf(
        "composite free vibration: energy error %.3e (dt = %.3e s), %.3e (dt/2), "
        "order %.2f\n",
        e1, dt, e2, order);
    // the central-difference energy error is bounded and O(dt^2) (spec T13): small, and
    // halving dt divides it by ~4 (order >= 1.8 leaves room for the oscillating error's
    // sampling; a first-order error source would give ~1)
    EXPECT_LT(e1, 1e-3);
    EXPECT_GT(order, 1.8);
}

}  // namespace
}  // namespace fdem
