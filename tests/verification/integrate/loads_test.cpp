// External loads against analytic answers (docs/theory.md §4.1, eqs. 4.5-4.8): a bar under a
// ramped end traction (static elongation; undamped energy balance at two time steps), a
// thick-walled ring under external follower pressure (Lame), a point force (impulse).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "fdem/scenario.hpp"
#include "fdem/simulate.hpp"

namespace fdem {
namespace {

// Bar [0, 1] x [0, 0.1] m (tests/data/loaded_bar.geo), nu = 0, plane stress, E = 1 GPa:
// x held on the left end, y at its lower corner, `load` on the right end.
std::string bar_scenario(const std::string& load, const std::string& extra = "",
                         Real dt_fraction = 0.5) {
    return fmt::format(R"(
[simulation]
end_time = 1.0
dt = "auto"
dt_fraction = {}
[[material]]
name = "m"
density = 1000.0
youngs_modulus = 1e9
poisson_ratio = 0.0
plane = "stress"
[[body]]
name = "bar"
mesh = "loaded_bar.geo"
mesh_size = 0.05
material = "m"
[[boundary]]
body = "bar"
group = "left"
fix = ["x"]
[[boundary]]
body = "bar"
group = "corner"
fix = ["y"]
[[load]]
body = "bar"
group = "right"
{}
{}
)",
                       dt_fraction, load, extra);
}

Scenario load(const std::string& text) {
    return load_scenario_from_string(text, "loads.toml", FDEM_TEST_DATA_DIR);
}

std::vector<NodeId> nodes_where(const Model& m, bool (*pred)(Vec2)) {
    std::vector<NodeId> out;
    for (NodeId i = 0; i < m.num_nodes(); ++i)
        if (pred(m.node_x0[i])) out.push_back(i);
    return out;
}

// Quasi-static: a traction ramped to 1e5 Pa over 2 ms on the right end, mass damping to rest
// (fundamental period 4 L / c = 4 ms). The uniaxial stress state is exact for CSTs with
// nu = 0, so the end moves by t L / E = 1e-4 m up to the finite-strain correction O(t/E).
TEST(Loads, BarUnderRampedTractionReachesTheStaticElongation) {
    const Scenario sc =
        load(bar_scenario("traction = [1e5, 0.0]\ntime_function = \"ramp\"\nramp_time = 0.002",
                          "[damping]\nmass_proportional = 1500.0\nuntil = 1.0"));
    const Model& m = sc.model;
    State s = make_state(m, sc.run.dt);
    while (s.time < 0.02)
        step(m, s);
    const auto right = nodes_where(m, [](Vec2 p) { return p.x > 1 - 1e-9; });
    ASSERT_GE(right.size(), 3u);
    const Real expect = 1e5 * 1.0 / 1e9;
    for (NodeId i : right) {
        EXPECT_NEAR(s.x[i].x - m.node_x0[i].x, expect, 1e-3 * expect) << "node " << i;
    }
    // strain energy 1/2 sigma eps V = 1/2 1e5 1e-4 0.1 = 0.5 J/m
    EXPECT_NEAR(s.energy.strain, 0.5, 1e-3);
    EXPECT_LT(s.energy.kinetic, 1e-9);
}

// Undamped, the same ramp: the balance of eq. 4.1 with the load work of eq. 4.7 closes at
// second order (max |E_tot - E_0| over the run, relative to the work done, ~4x smaller at dt/2).
Real undamped_bar_energy_error(Real dt_fraction, const std::string& load_keys) {
    const Scenario sc = load(bar_scenario(load_keys, "", dt_fraction));
    const Model& m = sc.model;
    State s = make_state(m, sc.run.dt);
    step(m, s);
    const Real e0 = s.energy.total();
    Real worst = 0, work = 0;
    while (s.time < 0.006) {
        step(m, s);
        worst = std::max(worst, std::abs(s.energy.total() - e0));
        work = std::max(work, std::abs(s.energy.work_external));
    }
    EXPECT_GT(work, 0.5);
    return worst / work;
}

TEST(Loads, UndampedBarBalanceClosesAtSecondOrder) {
    int k = 0;
    for (const char* keys : {"traction = [1e5, 2e4]\ntime_function = \"ramp\"\nramp_time = 0.002",
                             "pressure = -1e5\ntime_function = \"table\"\n"
                             "table = [[0, 0], [0.001, 1], [0.003, 0.5]]"}) {
        const Real e1 = undamped_bar_energy_error(0.4, keys);
        const Real e2 = undamped_bar_energy_error(0.2, keys);
        RecordProperty(fmt::format("error_dt_{}", k), fmt::format("{:.3g}", e1));
        RecordProperty(fmt::format("error_dt_half_{}", k++), fmt::format("{:.3g}", e2));
        EXPECT_LT(e1, 2e-3) << keys;
        EXPECT_GT(e1 / e2, 3.0) << keys << ": " << e1 << " -> " << e2;
        EXPECT_LT(e1 / e2, 5.5) << keys << ": " << e1 << " -> " << e2;
    }
}

// A point force on the "tip" point of a free bar: the momentum is the impulse of the force,
// exactly in the central-difference scheme (theory eq. 5.1 start): P^{n+1/2} = dt (F^0/2 + F^1
// + ... + F^n) with F^k = F k dt / t_r on the ramp.
TEST(Loads, PointForceImpulseIsTheMomentum) {
    const Scenario sc = load_scenario_from_string(R"(
[simulation]
end_time = 1.0
dt = 1e-5
[[material]]
name = "m"
density = 1000.0
youngs_modulus = 1e9
poisson_ratio = 0.25
[[body]]
name = "bar"
mesh = "loaded_bar.geo"
mesh_size = 0.05
material = "m"
[[load]]
body = "bar"
group = "tip"
force = [30.0, -40.0]
time_function = "ramp"
ramp_time = 1e-3
)",
                                                  "force.toml", FDEM_TEST_DATA_DIR);
    const Model& m = sc.model;
    ASSERT_EQ(m.loads.size(), 1u);
    ASSERT_EQ(m.loads[0].nodes.size(), 1u);
    EXPECT_NEAR(m.node_x0[m.loads[0].nodes[0]].x, 1.0, 1e-12);
    EXPECT_NEAR(m.node_x0[m.loads[0].nodes[0]].y, 0.05, 1e-12);
    State s = make_state(m, 1e-5);
    const int n = 200;  // t = 2 ms: past the ramp
    Real impulse = 0;   // dt (F^0 / 2 + F^1 + ... + F^{n-1}) / |F|
    for (int k = 0; k < n; ++k) {
        impulse += (k == 0 ? 0.5 : 1.0) * 1e-5 * std::min(k * 1e-5 / 1e-3, 1.0);
        step(m, s);
    }
    Vec2 p{0, 0};
    for (NodeId i = 0; i < m.num_nodes(); ++i)
        p += m.node_mass[i] * s.v[i];
    EXPECT_NEAR(p.x, 30.0 * impulse, 1e-12 * 30.0);
    EXPECT_NEAR(p.y, -40.0 * impulse, 1e-12 * 40.0);
    // analytic: F (t - t_r / 2) at t = 1.995 ms (the mid-step of v^{n-1/2})
    EXPECT_NEAR(impulse, 1.995e-3 - 0.5e-3, 1e-9);
}

// Thick-walled ring (a = 0.5 m, b = 1 m), plane strain, external follower pressure p ramped and
// damped to rest. Lame: u_r(r) = (1 + nu) / E ((1 - 2 nu) A r + C / r) with
// A = -p b^2 / (b^2 - a^2), C = -p a^2 b^2 / (b^2 - a^2).
TEST(Loads, RingUnderExternalPressureMatchesLame) {
    const Real p = 1e5, E = 1e9, nu = 0.25, a = 0.5, b = 1.0;
    const Scenario sc = load_scenario_from_string(R"(
[simulation]
end_time = 1.0
dt = "auto"
[[material]]
name = "m"
density = 1000.0
youngs_modulus = 1e9
poisson_ratio = 0.25
[[body]]
name = "ring"
mesh = "ring.geo"
mesh_size = 0.1
material = "m"
[[load]]
body = "ring"
group = "outer"
pressure = 1e5
time_function = "ramp"
ramp_time = 0.004
[damping]
mass_proportional = 2000.0
until = 1.0
)",
                                                  "ring.toml", FDEM_TEST_DATA_DIR);
    const Model& m = sc.model;
    State s = make_state(m, sc.run.dt);
    while (s.time < 0.03)
        step(m, s);
    const Real A = -p * b * b / (b * b - a * a), C = -p * a * a * b * b / (b * b - a * a);
    const auto u_r = [&](Real r) { return (1 + nu) / E * ((1 - 2 * nu) * A * r + C / r); };
    Real worst_outer = 0, worst_inner = 0;
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        const Real r = norm(m.node_x0[i]);
        const Vec2 er = m.node_x0[i] / r;
        const Real ur = dot(s.x[i] - m.node_x0[i], er);
        if (std::abs(r - b) < 1e-6) worst_outer = std::max(worst_outer, std::abs(ur / u_r(b) - 1));
        if (std::abs(r - a) < 1e-6) worst_inner = std::max(worst_inner, std::abs(ur / u_r(a) - 1));
    }
    RecordProperty("worst_outer", std::to_string(worst_outer));
    RecordProperty("worst_inner", std::to_string(worst_inner));
    // coarse CST mesh (5 elements through the wall): a few percent
    EXPECT_LT(worst_outer, 0.03);
    EXPECT_LT(worst_inner, 0.03);
    EXPECT_LT(s.energy.kinetic, 1e-6 * s.energy.strain);
}

}  // namespace
}  // namespace fdem
