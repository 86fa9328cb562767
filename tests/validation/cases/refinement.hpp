// Validation V7 on V1 of spec fracture.md §11: mesh refinement of the mode-I pull-apart with an
// inclined jointed line. The blocks of examples/07_pull_apart (W x H = 0.02 m x 0.01 m each, the
// material of 07, nu = 0, undamped) turned by 30 degrees (tests/validation/data/
// refinement_<alg>.geo), unstructured by Gmsh algorithms 1, 5, 6 (the three "seeds") at
// mesh_size h = 4, 2, 1 mm; joints on the common line only; bottom edge held, top edge pulled
// along the line's normal n = (-sin 30, cos 30) at 1 mm/s. Expected per run, every joint
// breaking in mode I with the exact softening length (theory eq. 9.13 per joint, W_J = h_J
// (G_I + (4/3) h_J f_t^2/p)):
//   Gamma = W_frac / L_broken = G_I + (4/3) (sum h_J^2 / sum h_J) f_t^2/p   (eq. 9.20)
// within 2 % (spec V7) at every h; reported: L_broken / L_projected (= 1 here: the joints lie on
// the straight line, so the broken path cannot wander), the change of W_frac from h/2 to h/4,
// the peak grip stress / f_t.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "fdem/measure.hpp"
#include "fdem/scenario.hpp"
#include "fdem/simulate.hpp"
#include "validation/cases/common.hpp"

namespace fdem::validation {

struct RefinementRun {
    int alg = 0;
    double h = 0;               ///< mesh_size [m]
    double gamma_audit = NAN;   ///< W_frac / L_broken [J/m^2]
    double gamma_grip = NAN;    ///< (W_ext - KE - strain - E_joint) / L_line [J/m^2]
    double gamma_expected = 0;  ///< eq. 9.13 per joint, summed [J/m^2]
    double w_frac = 0;          ///< W_frac at the end [J/m]
    double l_broken = 0, l_line = 0;
    double peak_ratio = 0;  ///< largest grip force . n / L_line / f_t
    int32_t joints = 0, broken = 0, mode_i = 0;
    int32_t triangles = 0;
    int64_t steps = 0;
};

inline RefinementRun run_refinement(int alg, double h) {
    RefinementRun r;
    r.alg = alg;
    r.h = h;
    const double th = M_PI / 6, v = 1e-3;
    const Vec2 nrm{-std::sin(th), std::cos(th)};
    char b[4096];
    std::snprintf(b, sizeof b, R"([simulation]
end_time = 0.016
dt = "auto"

%s
[[body]]
name = "blocks"
mesh = "refinement_%d.geo"
mesh_size = %.17g
material = "rock"
fracture_group = "joint"

[[boundary]]
body = "blocks"
group = "bottom"
fix = ["x", "y"]

[[boundary]]
body = "blocks"
group = "top"
velocity = [%.17g, %.17g]
)",
                  jointed_rock_toml("\"auto\"").c_str(), alg, h, v * nrm.x, v * nrm.y);
    const Scenario sc = load_scenario_from_string(
        b, "refinement.toml", std::string(FDEM_SOURCE_DIR) + "/tests/validation/data");
    const Model& m = sc.model;
    const JointMaterial& jm = m.materials[0].fracture;
    r.joints = m.joints.num_joints();
    r.triangles = m.num_tris();
    double sh = 0, sh2 = 0;
    for (int32_t j = 0; j < r.joints; ++j) {
        const double hj = m.joints.length0[static_cast<size_t>(j)];
        sh += hj;
        sh2 += hj * hj;
    }
    r.l_line = sh;
    const double ft = jm.tensile_strength;
    r.gamma_expected = jm.fracture_energy_I + 4.0 / 3.0 * (sh2 / sh) * ft * ft / jm.penalty;
    State s = make_state(m, sc.run.dt);
    const Resultants res(m, s.topology);
    int32_t grip = -1;
    for (int32_t k = 0; k < res.num_sets(); ++k) {
        if (res.name(k) == "blocks/top") grip = k;
    }
    const int64_t n = static_cast<int64_t>(std::ceil(sc.run.end_time / sc.run.dt - 1e-9));
    r.steps = n;
    for (int64_t k = 0; k < n; ++k) {
        step(m, s);
        Vec2 contact, reaction;
        res.forces(m, s, grip, contact, reaction);
        r.peak_ratio = std::max(r.peak_ratio, dot(reaction, nrm) / r.l_line / ft);
    }
    const Energy& e = s.energy;
    r.w_frac = e.fracture;
    for (int32_t j = 0; j < r.joints; ++j) {
        const size_t i = static_cast<size_t>(j);
        if (s.joints.status[i] != JointStatus::Broken) continue;
        ++r.broken;
        r.mode_i += s.joints.mode[i] == JointMode::I ? 1 : 0;
        r.l_broken += m.joints.length0[i];
    }
    r.gamma_audit = r.l_broken > 0 ? e.fracture / r.l_broken : NAN;
    r.gamma_grip = (e.work_external - e.kinetic - e.strain - e.joint) / r.l_line;
    return r;
}

struct RefinementOptions {
    std::vector<double> sizes{0.004, 0.002, 0.001};  ///< h, h/2, h/4
    std::vector<int> algs{1, 5, 6};
    static RefinementOptions quick() {
        RefinementOptions o;
        o.sizes = {0.004};
        return o;
    }
};

inline std::vector<Check> refinement_suite(const RefinementOptions& opt, const std::string& out) {
    std::vector<Check> c;
    Table t({"h", "alg", "gamma_audit", "gamma_grip", "gamma_expected", "w_frac", "l_broken",
             "l_line", "peak_ratio", "joints", "broken", "mode_i", "triangles"});
    std::vector<std::vector<double>> wfrac(opt.sizes.size());
    for (size_t ih = 0; ih < opt.sizes.size(); ++ih) {
        for (const int alg : opt.algs) {
            const RefinementRun r = run_refinement(alg, opt.sizes[ih]);
            wfrac[ih].push_back(r.w_frac);
            t.row({r.h, static_cast<double>(alg), r.gamma_audit, r.gamma_grip, r.gamma_expected,
                   r.w_frac, r.l_broken, r.l_line, r.peak_ratio, static_cast<double>(r.joints),
                   static_cast<double>(r.broken), static_cast<double>(r.mode_i),
                   static_cast<double>(r.triangles)});
            char tag[96];
            std::snprintf(tag, sizeof tag, "refinement, h = %g mm, Gmsh algorithm %d", r.h * 1e3,
                          alg);
            c.push_back(check("V7", std::string(tag) + ": Gamma = W_frac / L_broken", r.gamma_audit,
                              Rel::RelTol, r.gamma_expected, 0.02, "J/m^2",
                              "G_I + (4/3) (sum h_J^2/sum h_J) f_t^2/p (theory eqs. 9.13, 9.20); "
                              "spec V7 ±2 %"));
            c.push_back(check("V7", std::string(tag) + ": Gamma at the grip (W_ext - stored) / L",
                              r.gamma_grip, Rel::RelTol, r.gamma_expected, 0.02, "J/m^2",
                              "the same, without the joints' bookkeeping; spec V7 ±2 %"));
            c.push_back(check("V7", std::string(tag) + ": joints broken", r.broken, Rel::Abs,
                              r.joints, 0, "", "every joint of the line breaks"));
            c.push_back(check("V7", std::string(tag) + ": L_broken / L_projected",
                              r.l_broken / r.l_line, Rel::Report, 0, 0, "",
                              "tortuosity (1: joints on the straight line only; reported)"));
            c.push_back(check("V7", std::string(tag) + ": peak grip stress / f_t", r.peak_ratio,
                              Rel::Report, 0, 0, "", "reported"));
            c.push_back(check("V7", std::string(tag) + ": joints broken in mode I / all",
                              r.broken ? double(r.mode_i) / r.broken : NAN, Rel::Report, 0, 0, "",
                              "reported"));
        }
    }
    if (opt.sizes.size() >= 3) {
        const double a = mean(wfrac[1]), b = mean(wfrac[2]);
        c.push_back(check("V7", "refinement: |W_frac(h/4) / W_frac(h/2) - 1| (seed means)",
                          std::abs(b / a - 1.0), Rel::AtMost, 0.05, 0, "",
                          "spec V7: total W_frac changes <= 5 % from h/2 to h/4"));
    }
    if (!out.empty()) t.write(out + "/refinement.csv");
    return c;
}

}  // namespace fdem::validation
