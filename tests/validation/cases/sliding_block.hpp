// Spec §5.3, T16/T17 (paper §5, Figs. 27-37, eqs. 21-24): a 1 m x 1 m elastic block (1000 kg/m)
// relaxes under gravity on a fixed 10 m platform (mass damping, then off), gets a horizontal
// velocity v_i and slides to rest with Coulomb friction mu = 0.5. Analytic (eqs. 21-24):
// f = mu m g = 4900 N/m, v(t) = v_i - g mu t, d(t) = v_i t - g mu t^2 / 2, d_max = v_i^2/(2 g mu).
// Variant "fixed": the block's vertical velocity is held at 0 from the kick on (T17), so the
// penetration is frozen and the friction exposes any non-smoothness of the contact field.
#pragma once

#include <string>
#include <vector>

#include "fdem/build.hpp"
#include "support/scenes.hpp"
#include "validation/cases/common.hpp"

namespace fdem::validation {

struct SlidingOptions {
    int cells = 20;  ///< block cells per side (spec §5: h = 0.05 m)
    std::vector<double> speeds{2, 4, 6, 8};
    double dt_fraction = 0.25;   ///< of the stable limit
    double relax = 0.05;         ///< gravity relaxation before the kick [s] (spec §5.3)
    double mass_damping = 1000;  ///< c [1/s] during the relaxation
    bool fixed_variant = true;   ///< also run T17
    static SlidingOptions quick() {
        SlidingOptions o;
        o.cells = 10;
        o.speeds = {2, 4};
        return o;
    }
};

constexpr double kSlideG = 9.8, kSlideMu = 0.5, kSlideMass = 1000.0;

struct SlidingResult {
    Table series{{"t", "d", "v", "friction", "normal", "d_analytic", "v_analytic"}};
    double v_i = 0;
    bool fixed = false;
    double t_kick = 0;
    double d_max = NAN;           ///< CoM displacement at the end [m]
    double max_v_error = 0;       ///< max |v - v_an| after the 20 ms transient [m/s]
    double max_d_error = 0;       ///< max |d - d_an| after the transient [m]
    double friction_mean = NAN;   ///< mean of -(horizontal contact force) while sliding [N/m]
    double friction_std = NAN;    ///< std without spikes [N/m]
    int spikes = 0;               ///< samples further than 10 % from the median (logged, excluded)
    double spike_max = 0;         ///< largest |f - median| of a spike [N/m]
    double normal_relaxed = NAN;  ///< contact normal force at the kick [N/m]
};

inline Model make_sliding_block(const SlidingOptions& o, double v_i, bool fixed) {
    Model m;
    m.materials.push_back(scenes::paper_material("paper"));
    const double h = 1.0 / o.cells;
    scenes::add_rectangle(m, 1.0, 0.25, 1.0, 1.0, o.cells, o.cells, 0, false, {}, false, "block");
    scenes::add_rectangle(m, 0.0, 0.0, 10.0, 0.25, static_cast<int>(std::lround(10.0 / h)),
                          std::max(1, static_cast<int>(std::lround(0.25 / h))), 0, true, {}, false,
                          "platform");
    m.gravity = {0, -kSlideG};
    m.mass_damping = {o.mass_damping, o.relax};
    VelocityKick k;
    k.group = 0;
    k.time = o.relax;
    k.has_x = k.has_y = true;
    k.velocity = {v_i, 0};
    m.kicks.push_back(k);
    if (fixed) {
        BoundaryCondition bc;
        bc.name = "block_vertical";
        for (NodeId i = m.bodies[0].node_begin; i < m.bodies[0].node_end; ++i)
            bc.nodes.push_back(i);
        bc.has_y = true;
        bc.start = o.relax;
        m.bcs.push_back(bc);
    }
    m.contact.algorithm = ContactAlgorithm::Smooth;
    m.contact.params.penalty = 5e9;  // spec §5
    m.contact.params.friction = kSlideMu;
    finalize_model(m);
    return m;
}

inline SlidingResult run_sliding_block(const SlidingOptions& o, double v_i, bool fixed) {
    const Model m = make_sliding_block(o, v_i, fixed);
    SlidingResult r;
    r.v_i = v_i;
    r.fixed = fixed;
    r.t_kick = o.relax;
    const double a = kSlideG * kSlideMu;  // deceleration [m/s^2]
    const double t_stop = v_i / a, dmax_an = v_i * v_i / (2 * a);
    const double dt = o.dt_fraction * stable_time_step(m);
    State s = make_state(m, dt);
    const double t_end = o.relax + t_stop + 0.05;
    const int64_t n = static_cast<int64_t>(std::ceil(t_end / dt));
    const int64_t every =
        std::max<int64_t>(1, static_cast<int64_t>(std::ceil((t_end - o.relax) / dt / 1500)));
    double x0 = NAN;
    std::vector<double> fr;
    for (int64_t k = 0; k < n; ++k) {
        step(m, s);
        const double t = s.energy.time;  // forces and x^n belong to t^n
        if (t + 0.5 * dt < o.relax) continue;
        const BodySums b = body_sums(m, s, 0);
        if (std::isnan(x0)) {
            x0 = b.com.x;
            r.normal_relaxed = b.contact_force.y;
        }
        const double tt = t - o.relax;
        const double v_an = std::max(0.0, v_i - a * tt);
        const double d_an = tt < t_stop ? v_i * tt - 0.5 * a * tt * tt : dmax_an;
        // CoM velocity at t^n: mean of v^{n-1/2} and v^{n+1/2} is not stored; v^{n+1/2} is
        // half a step ahead, so compare it with v_an(t + dt/2)
        const double v = b.momentum.x / b.mass;
        const double v_an_half = std::max(0.0, v_i - a * (tt + 0.5 * dt));
        const double d = b.com.x - x0;
        if (tt > 0.02) {
            r.max_v_error = std::max(r.max_v_error, std::abs(v - v_an_half));
            r.max_d_error = std::max(r.max_d_error, std::abs(d - d_an));
        }
        if (tt > 0.02 && tt < t_stop - 0.02) fr.push_back(-b.contact_force.x);
        if (k % every == 0 || k == n - 1)
            r.series.row({tt, d, v, -b.contact_force.x, b.contact_force.y, d_an, v_an});
    }
    r.d_max = body_sums(m, s, 0).com.x - x0;
    r.friction_mean = mean(fr);
    const double med = median(fr);
    std::vector<double> calm;
    for (double f : fr) {
        if (std::abs(f - med) > 0.1 * std::abs(med)) {
            ++r.spikes;
            r.spike_max = std::max(r.spike_max, std::abs(f - med));
        } else {
            calm.push_back(f);
        }
    }
    r.friction_std = stddev(calm);
    return r;
}

inline std::vector<Check> sliding_checks(const SlidingResult& r) {
    std::vector<Check> c;
    const double a = kSlideG * kSlideMu;
    const double dmax_an = r.v_i * r.v_i / (2 * a);
    const std::string id = r.fixed ? "T17" : "T16";
    char tag[48];
    std::snprintf(tag, sizeof tag, " (v_i = %g m/s, %s)", r.v_i,
                  r.fixed ? "vertical fixed" : "free");
    c.push_back(check(id, "max |v - v_an| / v_i" + std::string(tag), r.max_v_error / r.v_i,
                      Rel::AtMost, 0.01, 0, "", "paper eq. 22; spec T16: 1 % of v_i after 20 ms"));
    c.push_back(check(id, "max |d - d_an| / d_max" + std::string(tag), r.max_d_error / dmax_an,
                      Rel::AtMost, 0.01, 0, "", "paper eq. 23; spec T16: 1 % of d_max"));
    c.push_back(check(id, "d_max" + std::string(tag), r.d_max, Rel::RelTol, dmax_an, 0.01, "m",
                      "v_i^2/(2 g mu) (paper eq. 24); spec T16: 1 %"));
    const double f_exp = r.fixed ? kSlideMu * r.normal_relaxed : kSlideMu * kSlideMass * kSlideG;
    c.push_back(check(id, "mean friction" + std::string(tag), r.friction_mean, Rel::RelTol, f_exp,
                      0.01, "N/m",
                      r.fixed ? "mu x relaxed normal force; spec T17: 1 %"
                              : "mu m g = 4900 N/m (paper eq. 21); spec T16: 1 %"));
    c.push_back(check(id, "friction std/mean without spikes" + std::string(tag),
                      r.friction_std / r.friction_mean, Rel::AtMost, r.fixed ? 0.005 : 0.02, 0, "",
                      r.fixed ? "spec T17: <= 0.5 % (two-way)" : "spec T16: <= 2 %"));
    c.push_back(check(id, "friction spikes (> 10 % off the median), count" + std::string(tag),
                      r.spikes, Rel::Report, 0, 0, "", "spec §5.3: corner transitions, logged"));
    return c;
}

inline std::vector<Check> sliding_block_suite(const SlidingOptions& o, const std::string& out_dir) {
    std::vector<Check> c;
    for (int fixed = 0; fixed < (o.fixed_variant ? 2 : 1); ++fixed) {
        for (double v : o.speeds) {
            const SlidingResult r = run_sliding_block(o, v, fixed != 0);
            if (!out_dir.empty())
                r.series.write(out_dir + "/sliding_" + (fixed ? "fixed" : "free") + "_v" +
                               std::to_string(static_cast<int>(v)) + ".csv");
            for (const Check& k : sliding_checks(r))
                c.push_back(k);
        }
    }
    return c;
}

}  // namespace fdem::validation
