// Validation V2 of spec fracture.md §11: pure shear (mode II) of one jointed line, the two blocks
// of examples/07_pull_apart (W x H = 0.02 m x 0.01 m each, 5 joints of h = 0.004 m on their
// common edge, nu = 0, undamped; mesh tests/validation/data/shear_blocks.geo = 07's blocks.geo
// with the blocks as surface groups "lower" and "upper").
//
// (a) sigma_n = 0, o held at 0: y held on every node of both blocks, bottom edge held in x, top
//     edge driven in x at v = 1 mm/s. With nu = 0 the blocks are in uniform simple shear (u_x
//     linear in y, u_y = 0 is the exact solution, the side faces' shear traction taken by the y
//     supports), so every joint point has o = 0 and the same tau = grip force / W. Expected:
//       peak tau = c                                        (theory eqs. 9.7, 9.8)
//       Gamma_II = work to break / W = G_II + (4/3) h c^2/p_s  (eq. 9.13 in mode II, 'exact')
//     measured at the grip (W_ext - KE - strain - E_joint at the end, no use of the joints'
//     bookkeeping) and by the audit of eq. 9.20 (sum of W_J of the mode-II breaks / sum of h_0).
//     The blocks' shear stiffness mu/(2H) = 1.25e12 Pa/m is below the steepest softening slope
//     in shear (about 2.04 c^2 I_z/G_II = 2.8e12 Pa/m), so the line snaps back once softening
//     starts: the peak is reached quasi-statically, the break is dynamic (the energy it releases
//     rings in the blocks and is subtracted at the grip as KE + strain).
// (b) sigma_n = -5, -10 MPa: a dead traction (0, sigma_n) on the top edge, ramped over 2 ms (the
//     block's slowest y mode has a period ~ 1e-5 s, so the ramp leaves < 0.3 % of sigma_n
//     ringing), then the whole upper block is driven in x at v (every node: no moment about
//     the joint, sigma uniform along the line), the lower block held. The grip force is then
//     the joints' shear force. Expected: peak tau = c + |sigma_n| tan(phi) (eq. 9.7 with
//     sigma_c = sigma_n). The run ends before the break (a broken joint drops its compressive
//     force too and there is no contact in this model).
// Tolerances of spec §11: 1 % on each.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "fdem/measure.hpp"
#include "fdem/scenario.hpp"
#include "fdem/simulate.hpp"
#include "validation/cases/common.hpp"

namespace fdem::validation {

struct ShearResult {
    Table series{{"time", "u", "tau", "kinetic", "strain", "joint", "fracture", "work_external"}};
    double sigma_n = 0;         ///< applied normal stress [Pa] (negative: compression)
    double c = 0, phi = 0;      ///< cohesion [Pa], friction angle [rad]
    double GII = 0, ps = 0;     ///< G_II [J/m^2], shear penalty [Pa]
    double width = 0;           ///< joint line length W [m]
    double h = 0;               ///< mean reference joint length [m]
    double peak_expected = 0;   ///< c + |sigma_n| tan(phi) (eq. 9.7) [Pa]
    double gamma_expected = 0;  ///< G_II + (4/3) h c^2/p_s (eq. 9.13, mode II) [J/m^2]
    double peak_tau = 0;        ///< largest |grip force x| / W over every step [Pa]
    double u_peak = 0;          ///< grip displacement there [m]
    double gamma_grip = NAN;    ///< (W_ext - KE - strain - E_joint)_end / W [J/m^2]
    double gamma_audit = NAN;   ///< sum W_J (mode-II breaks) / sum h_0 (eq. 9.20) [J/m^2]
    double w_ext = 0;           ///< work of the supports at the end [J/m]
    double drift = NAN;         ///< max |E_tot - E_tot(step 1)| / W_ext(end)
    int32_t joints = 0, broken = 0, broken_mode_ii = 0;
    int64_t steps = 0;
};

inline std::string shear_dir() {
    return std::string(FDEM_SOURCE_DIR) + "/tests/validation/data";
}

/// The scenario text of V2 (a) (sigma_n = 0) or (b) (sigma_n < 0) at grip speed v [m/s].
inline std::string shear_text(double sigma_n, double v, double end_time, double ramp) {
    char b[4096];
    const std::string common_text = "\n" + jointed_rock_toml("\"auto\"") + R"(
[[body]]
name = "blocks"
mesh = "shear_blocks.geo"
mesh_size = 0.004
material = "rock"
fracture_group = "joint"
)";
    const char* common = common_text.c_str();
    if (sigma_n == 0) {
        std::snprintf(b, sizeof b, R"([simulation]
end_time = %.17g
dt = "auto"
%s
[[boundary]]
body = "blocks"
group = "upper"
fix = ["y"]

[[boundary]]
body = "blocks"
group = "lower"
fix = ["y"]

[[boundary]]
body = "blocks"
group = "bottom"
fix = ["x"]

[[boundary]]
body = "blocks"
group = "top"
velocity = [%.17g, 0.0]
components = ["x"]
)",
                      end_time, common, v);
    } else {
        std::snprintf(b, sizeof b, R"([simulation]
end_time = %.17g
dt = "auto"
%s
[[boundary]]
body = "blocks"
group = "lower"
fix = ["x", "y"]

[[boundary]]
body = "blocks"
group = "upper"
fix = ["x"]
end = %.17g

[[boundary]]
body = "blocks"
group = "upper"
velocity = [%.17g, 0.0]
components = ["x"]
start = %.17g

[[load]]
body = "blocks"
group = "top"
traction = [0.0, %.17g]
time_function = "ramp"
ramp_time = %.17g
)",
                      end_time, common, ramp, v, ramp, sigma_n, ramp);
    }
    return b;
}

/// Run one V2 scenario to its end; the grip is "blocks/top" in (a), "blocks/upper" in (b).
inline ShearResult run_shear(double sigma_n, double v, double end_time, double ramp = 2e-3) {
    ShearResult r;
    r.sigma_n = sigma_n;
    const Scenario sc = load_scenario_from_string(shear_text(sigma_n, v, end_time, ramp),
                                                  "shear.toml", shear_dir());
    const Model& m = sc.model;
    const JointMaterial& jm = m.materials[0].fracture;
    r.c = jm.cohesion;
    r.phi = jm.friction_angle;
    r.GII = jm.fracture_energy_II;
    r.ps = jm.shear_penalty;
    r.joints = m.joints.num_joints();
    double h_sum = 0;
    for (int32_t j = 0; j < r.joints; ++j)
        h_sum += m.joints.length0[static_cast<size_t>(j)];
    r.h = h_sum / r.joints;
    r.width = h_sum;  // the line: 5 joints end to end across the block width
    r.peak_expected = r.c + std::abs(sigma_n) * std::tan(r.phi);
    r.gamma_expected = r.GII + 4.0 / 3.0 * r.h * r.c * r.c / r.ps;
    State s = make_state(m, sc.run.dt);
    const Resultants res(m, s.topology);
    const std::string grip_name = sigma_n == 0 ? "blocks/top" : "blocks/upper";
    int32_t grip = -1;
    for (int32_t k = 0; k < res.num_sets(); ++k) {
        if (res.name(k) == grip_name) grip = k;
    }
    NodeId probe = kNone;  // a node of the grip, for its displacement
    for (const BoundaryCondition& bc : m.bcs) {
        if (bc.name == grip_name && !bc.nodes.empty()) probe = bc.nodes[0];
    }
    const double x_probe = m.node_x0[static_cast<size_t>(probe)].x;
    const int64_t n = static_cast<int64_t>(std::ceil(sc.run.end_time / sc.run.dt - 1e-9));
    r.steps = n;
    const int64_t every = std::max<int64_t>(1, n / 2000);
    double e0 = NAN;
    for (int64_t k = 0; k < n; ++k) {
        step(m, s);
        Vec2 contact, reaction;
        res.forces(m, s, grip, contact, reaction);
        const double u = s.x[static_cast<size_t>(probe)].x - x_probe;
        const double tau = reaction.x / r.width;  // the grip's force on the blocks, at t^n
        if (std::abs(tau) > r.peak_tau) {
            r.peak_tau = std::abs(tau);
            r.u_peak = u;
        }
        const Energy& e = s.energy;
        if (k == 0) e0 = e.total();
        r.drift = std::isnan(r.drift) ? 0.0 : std::max(r.drift, std::abs(e.total() - e0));
        if (k % every == 0 || k == n - 1)
            r.series.row(
                {e.time, u, tau, e.kinetic, e.strain, e.joint, e.fracture, e.work_external});
    }
    const Energy& e = s.energy;
    r.w_ext = e.work_external;
    r.drift /= r.w_ext;
    r.gamma_grip = (e.work_external - e.kinetic - e.strain - e.joint) / r.width;
    double w_ii = 0, h_ii = 0;
    for (int32_t j = 0; j < r.joints; ++j) {
        const size_t i = static_cast<size_t>(j);
        if (s.joints.status[i] != JointStatus::Broken) continue;
        ++r.broken;
        if (s.joints.mode[i] != JointMode::II) continue;
        ++r.broken_mode_ii;
        w_ii += s.joints.work[i];
        h_ii += m.joints.length0[i];
    }
    if (h_ii > 0) r.gamma_audit = w_ii / h_ii;
    return r;
}

inline std::vector<Check> shear_suite(const std::string& out) {
    // (a) v = 1 mm/s: the peak at u ~ 2H c/mu + s_p = 24.5 um (t = 24.5 ms >> 50 L/c_s = 0.33 ms)
    const ShearResult a = run_shear(0.0, 1e-3, 0.03);
    if (!out.empty()) a.series.write(out + "/shear.csv");
    std::vector<Check> c = {
        check("V2", "shear, sigma_n = 0: peak grip stress F/W", a.peak_tau, Rel::RelTol,
              a.peak_expected, 0.01, "Pa",
              "c (theory eqs. 9.7, 9.8); spec fracture.md §11 V2 ±1 %"),
        check("V2", "shear, sigma_n = 0: Gamma_II at the grip (W_ext - stored energy) / W",
              a.gamma_grip, Rel::RelTol, a.gamma_expected, 0.01, "J/m^2",
              "theory eq. 9.13 in mode II: G_II + (4/3) h c^2/p_s; spec V2 ±1 %"),
        check("V2", "shear, sigma_n = 0: Gamma_II by the audit (mode-II W_J / h_0)", a.gamma_audit,
              Rel::RelTol, a.gamma_expected, 0.01, "J/m^2",
              "theory eqs. 9.13, 9.20: G_II + (4/3) h c^2/p_s; spec V2 ±1 %"),
        check("V2", "shear, sigma_n = 0: joints broken in mode II", a.broken_mode_ii, Rel::Abs,
              a.joints, 0, "", "every joint of the line breaks, in mode II (theory §9.4)"),
        check("V2", "shear, sigma_n = 0: max |E_tot drift| / W_ext", a.drift, Rel::Report, 0, 0, "",
              "energy balance eq. 9.22 (reported; the break is dynamic, eq. 9.23)"),
    };
    // (b) the normal stress ramped over 2 ms, then shear at 1 mm/s: the peak at s_p =
    // 2 h f_s/p_s = 0.53 (0.57) um, 0.5 ms after the ramp; stop 2 ms after the ramp
    for (const double sn : {-5e6, -10e6}) {
        const ShearResult b = run_shear(sn, 1e-3, 4e-3);
        char tag[64];
        std::snprintf(tag, sizeof tag, "sigma_n = %g MPa", sn / 1e6);
        if (!out.empty()) {
            char f[64];
            std::snprintf(f, sizeof f, "/shear_sn%g.csv", -sn / 1e6);
            b.series.write(out + f);
        }
        c.push_back(check("V2", std::string("shear, ") + tag + ": peak joint shear stress F/W",
                          b.peak_tau, Rel::RelTol, b.peak_expected, 0.01, "Pa",
                          "c + |sigma_n| tan(phi) (theory eqs. 9.7, 9.8); spec V2 ±1 %"));
    }
    return c;
}

}  // namespace fdem::validation
