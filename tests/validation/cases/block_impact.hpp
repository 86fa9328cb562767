// Spec §5.1, T13/T14 (paper §5, Figs. 23-24): an elastic 1 m x 1 m block (E = 1 GPa, nu = 0,
// rho = 1000) hits a fixed 1.25 m x 0.2 m base at 10 m/s. With nu = 0 and a flat face this is a
// 1-D bar hitting a rigid wall: contact lasts 2L/c = 2 ms, the contact stress is rho c v = 10 MPa
// (1e7 N/m over the 1 m face) and the block leaves with 10 m/s (spec §5.1, derived there).
#pragma once

#include "fdem/build.hpp"
#include "support/scenes.hpp"
#include "validation/cases/common.hpp"

namespace fdem::validation {

struct BlockImpactOptions {
    int cells = 20;            ///< block cells per side (h = 1/cells); spec §5: h = 0.05 m
    double damping = 0;        ///< contact damping gamma [N s/m^2] (paper eq. 13)
    double dt_fraction = 0.2;  ///< of the stable limit (spec §3.4: 0.1-0.2)
    double penalty = 5e9;      ///< k_n [Pa] (spec §5: 5 E)
    double gap = 0.005;        ///< initial gap [m] (spec §5.1)
    int samples = 600;         ///< rows of the KE(t) series
};

struct BlockImpactResult {
    Table series{{"time", "kinetic", "energy_error", "contact_force", "com_vy"}};
    double dt = 0, h = 0, ke0 = 0;
    double t_first = NAN, t_last = NAN;  ///< first/last step with a contact force on the block
    double duration = NAN;               ///< [s]
    double plateau_force = NAN;          ///< mean contact force over the middle half [N/m]
    double vy_after = NAN;               ///< CoM velocity at the end [m/s]
    double ke_after = NAN;               ///< kinetic energy at the end [J/m]
    double max_energy_error = 0;         ///< max |E_tot(t) - E_tot(0)| [J/m]
    double max_depth = 0;                ///< largest contact depth [m]
    double max_depth_ratio = 0;          ///< largest d / layer [-]
    int64_t lost_inside = 0;
    int64_t steps = 0;
};

inline Model make_block_impact(const BlockImpactOptions& o) {
    Model m;
    m.materials.push_back(scenes::paper_material("paper"));
    const double h = 1.0 / o.cells;
    // block first (body 0), base second (body 1); both on the same h
    scenes::add_rectangle(m, 0.125, 0.2 + o.gap, 1.0, 1.0, o.cells, o.cells, 0, false, {0, -10},
                          false, "block");
    scenes::add_rectangle(m, 0.0, 0.0, 1.25, 0.2, static_cast<int>(std::lround(1.25 / h)),
                          std::max(1, static_cast<int>(std::lround(0.2 / h))), 0, true, {}, false,
                          "base");
    m.contact.algorithm = ContactAlgorithm::Smooth;
    m.contact.params.penalty = o.penalty;
    m.contact.params.damping = o.damping;
    finalize_model(m);
    return m;
}

inline BlockImpactResult run_block_impact(const BlockImpactOptions& o) {
    const Model m = make_block_impact(o);
    BlockImpactResult r;
    r.h = 1.0 / o.cells;
    r.dt = o.dt_fraction * stable_time_step(m);
    State s = make_state(m, r.dt);
    const double c = 1000.0;  // sqrt(E / rho), nu = 0
    const double t_end = o.gap / 10.0 + 2.0 / c + 1.5e-3;
    const int64_t n = static_cast<int64_t>(std::ceil(t_end / r.dt));
    const int64_t every = std::max<int64_t>(1, n / o.samples);
    r.ke0 = 0.5 * 1000.0 * 1.0 * 100.0;  // 1/2 rho A v^2 = 50 kJ/m
    double e0 = 0;
    std::vector<double> tf, ff;  // time and contact force of every step
    for (int64_t k = 0; k < n; ++k) {
        step(m, s);
        if (k == 0) e0 = s.energy.total();
        const BodySums b = body_sums(m, s, 0);
        const double err = s.energy.total() - e0;
        r.max_energy_error = std::max(r.max_energy_error, std::abs(err));
        r.max_depth = std::max(r.max_depth, max_active_depth(s));
        tf.push_back(s.energy.time);
        ff.push_back(b.contact_force.y);
        if (b.contact_force.y != 0) {
            if (std::isnan(r.t_first)) r.t_first = s.energy.time;
            r.t_last = s.energy.time;
        }
        if (k % every == 0 || k == n - 1)
            r.series.row(
                {s.energy.time, s.energy.kinetic, err, b.contact_force.y, b.momentum.y / b.mass});
    }
    r.steps = n;
    r.duration = r.t_last - r.t_first + r.dt;
    // the boundary nodes rattle against the base (force 0 on some steps), so average over every
    // step of the window, not only over the steps with a force
    std::vector<double> mid;
    for (size_t i = 0; i < tf.size(); ++i)
        if (tf[i] > r.t_first + 0.25 * r.duration && tf[i] < r.t_last - 0.25 * r.duration)
            mid.push_back(ff[i]);
    r.plateau_force = mean(mid);
    const BodySums b = body_sums(m, s, 0);
    r.vy_after = b.momentum.y / b.mass;
    r.ke_after = s.energy.kinetic;
    r.max_depth_ratio = s.contact.max_depth_ratio_ever;
    r.lost_inside = s.contact.total_lost_inside;
    return r;
}

/// T13 checks for one undamped run (spec §8 T13).
inline std::vector<Check> block_impact_checks(const BlockImpactResult& r) {
    std::vector<Check> c;
    c.push_back(check("T13", "contact duration", r.duration * 1e3, Rel::RelTol, 2.0, 0.10, "ms",
                      "2L/c of a 1-D bar on a rigid wall (spec §5.1); ±10 % spec T13"));
    c.push_back(check("T13", "mean contact force over the plateau", r.plateau_force, Rel::RelTol,
                      1.0e7, 0.10, "N/m", "rho c v L (spec §5.1); ±10 % spec T13"));
    c.push_back(check("T13", "CoM rebound velocity", r.vy_after, Rel::RelTol, 10.0, 0.05, "m/s",
                      "elastic bar: leaves with the impact speed; ±5 % spec T13"));
    c.push_back(check("T13", "KE after release / KE0", r.ke_after / r.ke0, Rel::AtLeast, 0.90, 0,
                      "", "spec T13: >= 90 % (the rest stays as vibration)"));
    c.push_back(check("T13", "energy balance error / KE0", r.max_energy_error / r.ke0, Rel::AtMost,
                      0.005, 0, "", "spec T13: drift <= 0.5 % of KE0"));
    c.push_back(check("T13", "max penetration / h", r.max_depth / r.h, Rel::AtMost, 0.05, 0, "",
                      "spec T13: <= 5 % of the element size"));
    c.push_back(check("T13", "nodes lost inside the contactor", static_cast<double>(r.lost_inside),
                      Rel::AtMost, 0, 0, "", "spec T13: no node deeper than the boundary layer"));
    c.push_back(check("T13", "largest depth / boundary layer", r.max_depth_ratio, Rel::AtMost, 1.0,
                      0, "", "spec T13 / §4.6: the node must stay inside the layer"));
    return c;
}

}  // namespace fdem::validation

namespace fdem::validation {

/// Paper Fig. 24 damping values (spec §5.1): zeta ~ 0.05, 0.1, 0.2 for k_n = 5 GPa, mbar = 1.25.
inline const std::vector<double>& block_impact_dampings() {
    static const std::vector<double> g{0.0, 1.1e4, 2.2e4, 4.5e4};
    return g;
}

/// T13 (with the dt-halving order check) and T14 on a block of `cells` cells per side.
/// results receives the four damping runs (gamma = 0 first) for plotting.
inline std::vector<Check> block_impact_suite(int cells, std::vector<BlockImpactResult>* results) {
    std::vector<Check> c;
    std::vector<BlockImpactResult> runs;
    for (double g : block_impact_dampings()) {
        BlockImpactOptions o;
        o.cells = cells;
        o.damping = g;
        runs.push_back(run_block_impact(o));
    }
    c = block_impact_checks(runs[0]);
    BlockImpactOptions half;
    half.cells = cells;
    half.dt_fraction = 0.1;
    const BlockImpactResult r2 = run_block_impact(half);
    const double order = std::log2(runs[0].max_energy_error / r2.max_energy_error);
    c.push_back(check("T13", "order of the energy error when dt is halved", order, Rel::Abs, 2.0,
                      0.5, "",
                      "central differences are 2nd order (error / 4 per halving, spec T13); "
                      "±0.5 because contact on/off events are not smooth in time"));
    for (size_t i = 1; i < runs.size(); ++i) {
        char name[96];
        std::snprintf(name, sizeof name, "KE after, gamma = %.2g minus gamma = %.2g (J/m)",
                      block_impact_dampings()[i], block_impact_dampings()[i - 1]);
        c.push_back(check("T14", name, runs[i].ke_after - runs[i - 1].ke_after, Rel::AtMost, 0, 0,
                          "J/m", "spec T14: KE after release strictly decreasing with gamma"));
        c.back().rel = Rel::AtMost;
        c.back().expected = -1e-9 * runs[0].ke0;  // strictly below
        std::snprintf(name, sizeof name, "energy + dissipation balance / KE0, gamma = %.2g",
                      block_impact_dampings()[i]);
        c.push_back(check("T14", name, runs[i].max_energy_error / runs[i].ke0, Rel::AtMost, 0.005,
                          0, "", "spec T14: E_tot + W_dissipated conserved within 0.5 %"));
    }
    for (size_t i = 0; i < runs.size(); ++i) {
        char name[64];
        std::snprintf(name, sizeof name, "KE after / KE0, gamma = %.2g",
                      block_impact_dampings()[i]);
        c.push_back(check("T14", name, runs[i].ke_after / runs[i].ke0, Rel::Report, 0, 0, "",
                          "paper Fig. 24 (reported)"));
    }
    if (results) *results = std::move(runs);
    return c;
}

}  // namespace fdem::validation
