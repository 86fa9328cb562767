// Validation V1 of spec fracture.md §11: mode-I pull-apart of one jointed line, the scenario of
// examples/07_pull_apart (two blocks W x H = 0.02 m x 0.01 m, 5 joints of h = 0.004 m on their
// common edge, bottom held, top pulled at v = 1 mm/s, undamped, nu = 0). Expected:
//   peak grip stress F/W = f_t                         (docs/theory.md eq. 9.5)
//   Gamma_I = work to break / W = G_I + (4/3) h f_t^2/p (eq. 9.13; exact softening length)
// Gamma_I is measured twice: at the grip (the work the supports did, minus the kinetic, strain
// and joint energy left at the end: no use of the joints' own bookkeeping) and by the joints'
// audit W_frac / W (eq. 9.19). Tolerances of spec §11: 1 % on both; energy drift <= 0.5 % of the
// external work. Run again with softening_length = "y-geo" (o_r - o_p = 3 G_I/f_t): the softening
// branch then dissipates 3 I_z G_I = 1.159 G_I.
#pragma once

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fdem/measure.hpp"
#include "fdem/scenario.hpp"
#include "fdem/simulate.hpp"
#include "validation/cases/common.hpp"

namespace fdem::validation {

struct PullApartResult {
    Table series{
        {"time", "u", "stress", "kinetic", "strain", "joint", "fracture", "work_external"}};
    double ft = 0, GI = 0, p = 0;  ///< f_t [Pa], G_I [J/m^2], penalty [Pa]
    double width = 0;              ///< joint line length W [m]
    double h = 0;                  ///< mean reference joint length [m]
    double gamma_expected = 0;     ///< eq. 9.13 [J/m^2]
    double peak_stress = 0;        ///< largest grip reaction / W over every step [Pa]
    double u_peak = 0;             ///< grip displacement there [m]
    double gamma_grip = NAN;       ///< (W_ext - KE - strain - E_joint)_end / W [J/m^2]
    double gamma_audit = NAN;      ///< W_frac / W at the end (eq. 9.19) [J/m^2]
    double w_ext = 0;              ///< work of the supports at the end [J/m]
    double drift = NAN;            ///< max |E_tot - E_tot(step 1)| / W_ext(end)
    double ke_ratio = 0;           ///< max KE / strain energy from half the peak time to the peak
    int32_t joints = 0, broken = 0;
    int64_t steps = 0;
};

/// The text of examples/07_pull_apart/scenario.toml, and its folder (for the mesh).
inline std::string pull_apart_dir() {
    return std::string(FDEM_SOURCE_DIR) + "/examples/07_pull_apart";
}
inline std::string pull_apart_text() {
    std::ifstream f(pull_apart_dir() + "/scenario.toml");
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

/// Run the scenario text (examples/07_pull_apart/scenario.toml, possibly edited) to its end time.
inline PullApartResult run_pull_apart(const std::string& text) {
    PullApartResult r;
    const Scenario sc = load_scenario_from_string(text, "pull_apart.toml", pull_apart_dir());
    const Model& m = sc.model;
    const Material& mat = m.materials[0];
    r.ft = mat.fracture.tensile_strength;
    r.GI = mat.fracture.fracture_energy_I;
    r.p = mat.fracture.penalty;
    r.joints = m.joints.num_joints();
    for (int32_t j = 0; j < r.joints; ++j)
        r.h += m.joints.length0[static_cast<size_t>(j)] / r.joints;
    // eq. 9.13: the pre-peak branch dissipates (4/3) h f_t^2/p, the softening branch G_I with
    // the exact rule, 3 I_z G_I with "y-geo" (o_r - o_p = 3 G_I/f_t, eq. 9.12)
    const double softening = mat.fracture.softening_length == SofteningLength::YGeo
                                 ? 3.0 * softening_integral(mat.fracture.softening) * r.GI
                                 : r.GI;
    r.gamma_expected = softening + 4.0 / 3.0 * r.h * r.ft * r.ft / r.p;
    State s = make_state(m, sc.run.dt);
    const Resultants res(m, s.topology);
    int32_t grip = -1;
    for (int32_t k = 0; k < res.num_sets(); ++k) {
        if (res.name(k) == "blocks/top") grip = k;
    }
    // W: extent of the grip's nodes (the top edge spans the block width)
    double x0 = INFINITY, x1 = -INFINITY, y_top = 0;
    std::vector<NodeId> top;
    for (const BoundaryCondition& bc : m.bcs) {
        if (bc.name != "blocks/top") continue;
        for (const NodeId n : bc.nodes) {
            x0 = std::min(x0, m.node_x0[static_cast<size_t>(n)].x);
            x1 = std::max(x1, m.node_x0[static_cast<size_t>(n)].x);
            y_top = m.node_x0[static_cast<size_t>(n)].y;
            top.push_back(n);
        }
    }
    r.width = x1 - x0;
    const int64_t n = static_cast<int64_t>(std::ceil(sc.run.end_time / sc.run.dt - 1e-9));
    r.steps = n;
    const int64_t every = std::max<int64_t>(1, n / 2000);
    double e0 = NAN;
    std::vector<double> t_hist, ke_hist, strain_hist;
    for (int64_t k = 0; k < n; ++k) {
        step(m, s);
        Vec2 contact, reaction;
        res.forces(m, s, grip, contact, reaction);
        const double u = s.x[static_cast<size_t>(top[0])].y - y_top;
        const double stress = reaction.y / r.width;  // at t^n = energy.time
        if (stress > r.peak_stress) {
            r.peak_stress = stress;
            r.u_peak = u;
        }
        const Energy& e = s.energy;
        if (k == 0) e0 = e.total();
        r.drift = std::isnan(r.drift) ? 0.0 : std::max(r.drift, std::abs(e.total() - e0));
        t_hist.push_back(e.time);
        ke_hist.push_back(e.kinetic);
        strain_hist.push_back(e.strain);
        if (k % every == 0 || k == n - 1)
            r.series.row(
                {e.time, u, stress, e.kinetic, e.strain, e.joint, e.fracture, e.work_external});
    }
    const Energy& e = s.energy;
    r.w_ext = e.work_external;
    r.drift /= r.w_ext;
    r.gamma_grip = (e.work_external - e.kinetic - e.strain - e.joint) / r.width;
    r.gamma_audit = e.fracture / r.width;
    for (const JointStatus st : s.joints.status)
        r.broken += st == JointStatus::Broken ? 1 : 0;
    // quasi-static before the peak: KE / strain energy from half the time to the peak on (the
    // start-up, when the strain energy is still ~0, is left out)
    size_t i_peak = 0;
    for (size_t i = 0; i < r.series.size(); ++i) {
        if (r.series.cols[2][i] >= r.series.cols[2][i_peak]) i_peak = i;
    }
    const double t_peak = r.series.cols[0][i_peak];
    for (size_t i = 0; i < t_hist.size() && t_hist[i] <= t_peak; ++i) {
        if (t_hist[i] >= 0.5 * t_peak && strain_hist[i] > 0)
            r.ke_ratio = std::max(r.ke_ratio, ke_hist[i] / strain_hist[i]);
    }
    return r;
}

inline std::vector<Check> pull_apart_suite(const std::string& out,
                                           PullApartResult* result = nullptr) {
    const PullApartResult r = run_pull_apart(pull_apart_text());
    if (!out.empty()) r.series.write(out + "/pull_apart.csv");
    if (result) *result = r;
    // the same with the Y-Geo softening length 3 G_I/f_t (spec V1: 1.159 G_I +- 1 %)
    std::string text = pull_apart_text();
    const std::string key = "penalty = \"auto\"";
    text.replace(text.find(key), key.size(), key + "\nsoftening_length = \"y-geo\"");
    const PullApartResult y = run_pull_apart(text);
    if (!out.empty()) y.series.write(out + "/pull_apart_ygeo.csv");
    const std::string eq13 = "theory eq. 9.13: G_I + (4/3) h f_t^2/p (exact rule); spec V1 ±1 %";
    return {
        check("V1", "pull-apart: peak grip stress F/W", r.peak_stress, Rel::RelTol, r.ft, 0.01,
              "Pa", "f_t (theory eq. 9.5); spec fracture.md §11 V1 ±1 %"),
        check("V1", "pull-apart: Gamma_I at the grip (W_ext - stored energy) / W", r.gamma_grip,
              Rel::RelTol, r.gamma_expected, 0.01, "J/m^2", eq13),
        check("V1", "pull-apart: Gamma_I by the joint audit W_frac / W", r.gamma_audit, Rel::RelTol,
              r.gamma_expected, 0.01, "J/m^2", eq13 + " (theory eq. 9.19)"),
        check("V1", "pull-apart: joints broken at the end", r.broken, Rel::Abs, r.joints, 0, "",
              "every joint of the line breaks"),
        check("V1", "pull-apart: max |E_tot drift| / W_ext", r.drift, Rel::AtMost, 0.005, 0, "",
              "spec V1: drift <= 0.5 % of the external work"),
        check("V1", "pull-apart: max KE / strain energy, half the peak time to the peak",
              r.ke_ratio, Rel::Report, 0, 0, "", "spec §11: quasi-static if <= 1 % (reported)"),
        check("V1", "pull-apart, softening_length = y-geo: peak grip stress F/W", y.peak_stress,
              Rel::RelTol, y.ft, 0.01, "Pa", "f_t (theory eq. 9.5); spec V1 ±1 %"),
        check("V1", "pull-apart, softening_length = y-geo: Gamma_I at the grip", y.gamma_grip,
              Rel::RelTol, y.gamma_expected, 0.01, "J/m^2",
              "3 I_z G_I + (4/3) h f_t^2/p = 1.159 G_I + ... (theory eqs. 9.12, 9.13); spec V1 "
              "±1 %"),
        check("V1", "pull-apart, softening_length = y-geo: joints broken", y.broken, Rel::Abs,
              y.joints, 0, "", "every joint of the line breaks"),
    };
}

}  // namespace fdem::validation
