// Spec §8 T20 (parameter studies) for the block impact (T13, spec §5.1) and the sliding block
// (T16, spec §5.3, free vertical motion, v_i = 2 m/s): penalty k_n x {0.1, 1, 10}, time step
// x {0.5, 1}, mesh size h x {1, 1/2}. Expected (spec T20): the largest penetration scales as
// 1/k_n and stays <= 5 % of h at the default k_n = 5 E; the results converge with dt (KE after
// impact within 0.5 % KE0); on the finer mesh the outputs stay within the T13 / T16 tolerances.
// The study is centred on the reduced (CTest) resolution in both modes: base h = 0.1 m, refined
// h = 0.05 m = the spec's resolution (docs/validation/NOTES.md: the full-resolution centre would
// need h = 0.025 m runs, 8x the cost of the whole full suite's block and sliding parts).
#pragma once

#include <string>
#include <vector>

#include "validation/cases/block_impact.hpp"
#include "validation/cases/sliding_block.hpp"

namespace fdem::validation {

struct SensitivityOptions {
    int cells = 10;                   ///< base resolution (block cells per side): h = 0.1 m
    double slide_speed = 2;           ///< v_i of the sliding runs [m/s]
    bool sliding_penalty_x10 = true;  ///< the k_n x 10 sliding run (dt / sqrt(10): the costliest)
    bool refine = true;               ///< the h x 1/2 runs (8x the cost of a base run)
    bool sliding = true;              ///< the sliding-block part
};

/// Append " (tag)" to every check name and set the id.
inline std::vector<Check> tagged(std::vector<Check> c, const std::string& id,
                                 const std::string& tag) {
    for (Check& k : c) {
        k.id = id;
        k.name += " (" + tag + ")";
    }
    return c;
}

struct SensitivitySeries {
    std::vector<std::pair<std::string, BlockImpactResult>> block;
    std::vector<std::pair<std::string, SlidingResult>> slide;
};

inline std::vector<Check> sensitivity_suite(const SensitivityOptions& o, const std::string& out_dir,
                                            SensitivitySeries* keep = nullptr) {
    std::vector<Check> c;
    SensitivitySeries ser;
    auto finish = [&]() {
        if (!out_dir.empty()) {
            auto fname = [](const std::string& tag) {
                std::string f;
                for (char ch : tag)
                    if (ch != ',') f += (ch == ' ' || ch == '.') ? '_' : ch;
                return f;
            };
            for (const auto& [tag, r] : ser.block)
                r.series.write(out_dir + "/sens_" + fname(tag) + ".csv");
            for (const auto& [tag, r] : ser.slide)
                r.series.write(out_dir + "/sens_" + fname(tag) + ".csv");
        }
        if (keep) *keep = std::move(ser);
        return c;
    };
    // ---- block impact -------------------------------------------------------------------
    BlockImpactOptions base;
    base.cells = o.cells;
    const double kn = base.penalty;
    std::vector<BlockImpactResult> pen;
    for (double f : {0.1, 1.0, 10.0}) {
        BlockImpactOptions b = base;
        b.penalty = f * kn;
        pen.push_back(run_block_impact(b));
        char tag[64];
        std::snprintf(tag, sizeof tag, "block, k_n x %g", f);
        ser.block.emplace_back(tag, pen.back());
        if (f != 1.0) {
            // spec T20 asks only for the penetration here: the T13 rows are reported, except
            // the <= 5 % h bound and no lost node, which every penalty must keep (T13 at the
            // default k_n is the block case's own rows; k_n x 10 leaves more vibration behind:
            // rebound 9.48 m/s, NOTES.md)
            for (Check k : tagged(block_impact_checks(pen.back()), "T20", tag)) {
                if (k.name.find("penetration") == std::string::npos &&
                    k.name.find("lost") == std::string::npos &&
                    k.name.find("boundary layer") == std::string::npos) {
                    k.why =
                        "reported (spec T20 checks T13 outputs only at the default k_n); "
                        "would be: " +
                        k.why;
                    k.rel = Rel::Report;
                }
                c.push_back(k);
            }
        }
    }
    // Spec T20 expects penetration ~ 1/k_n: true at a given force (checked on the resting
    // sliding block below). In the impact the contact spring of a bottom node (mass ~mbar,
    // stiffness 2 k_n: omega = sqrt(2 k_n / mbar) = 4.5e4 1/s at the default, h = 0.1 m) is
    // faster than the element (2c/h = 2e4 1/s): each node row impacts on its own spring and
    // rattles, its peak depth ~ v sqrt(mbar / (2 k_n)) ~ 1/sqrt(k_n) (ratio 3.16 per decade);
    // the softest penalty is between the two regimes. Reported, with the 5 % h bound checked.
    c.push_back(check("T20", "block: peak depth k_n x 0.1 / k_n x 1",
                      pen[0].max_depth / pen[1].max_depth, Rel::Report, 0, 0, "",
                      "reported: node-row impact, between 1/sqrt(k_n) (3.16) and 1/k_n (10) "
                      "(sensitivity.hpp, NOTES.md)"));
    c.push_back(check("T20", "block: peak depth k_n x 1 / k_n x 10",
                      pen[1].max_depth / pen[2].max_depth, Rel::Report, 0, 0, "",
                      "reported: node-row impact ~ 1/sqrt(k_n), sqrt(10) = 3.16"));
    c.push_back(check("T20", "block: plateau depth (scaled mean) k_n x 0.1 / k_n x 1",
                      pen[0].plateau_depth / pen[1].plateau_depth, Rel::Report, 0, 0, "",
                      "reported: mean over the pairs in contact of the rattling nodes"));
    c.push_back(check("T20", "block: plateau depth (scaled mean) k_n x 1 / k_n x 10",
                      pen[1].plateau_depth / pen[2].plateau_depth, Rel::Report, 0, 0, "",
                      "reported: as above"));
    c.push_back(check("T20", "block: max penetration / h at the default k_n = 5 E",
                      pen[1].max_depth / pen[1].h, Rel::AtMost, 0.05, 0, "",
                      "spec T20 / T13: <= 5 % of h"));
    {
        BlockImpactOptions b = base;
        b.dt_fraction *= 0.5;
        const BlockImpactResult r = run_block_impact(b);
        ser.block.emplace_back("block, dt x 0.5", r);
        c.push_back(check("T20", "block: KE after (dt x 0.5) - KE after (dt x 1), / KE0",
                          (r.ke_after - pen[1].ke_after) / r.ke0, Rel::Abs, 0, 0.005, "",
                          "spec T20: results converge with dt, KE after impact within 0.5 %"));
        for (const Check& k : tagged(block_impact_checks(r), "T20", "block, dt x 0.5"))
            c.push_back(k);
    }
    if (o.refine) {
        BlockImpactOptions b = base;
        b.cells = 2 * o.cells;
        const BlockImpactResult r = run_block_impact(b);
        ser.block.emplace_back("block, h x 0.5", r);
        for (const Check& k : tagged(block_impact_checks(r), "T20", "block, h x 0.5"))
            c.push_back(k);
        c.push_back(check("T20", "block: KE after (h x 0.5) - KE after (h x 1), / KE0",
                          (r.ke_after - pen[1].ke_after) / r.ke0, Rel::Report, 0, 0, "",
                          "vibration left in the block depends on the mesh (reported)"));
    }
    // ---- sliding block (T16, free vertical motion) ----------------------------------------
    if (!o.sliding) return finish();
    SlidingOptions so = SlidingOptions::quick();
    so.cells = o.cells;
    const SlidingVariant var = sliding_variants()[0];  // "free", xi = 1 (NOTES.md)
    auto slide = [&](const SlidingOptions& opt, double penalty_factor, const std::string& tag) {
        SlidingOptions v = opt;
        v.penalty = penalty_factor * opt.penalty;
        SlidingResult r = run_sliding_block(v, o.slide_speed, false);
        r.tag = tag;
        ser.slide.emplace_back(tag, r);
        return r;
    };
    std::vector<SlidingResult> sp;
    for (double f : {0.1, 1.0, 10.0}) {
        if (f == 10.0 && !o.sliding_penalty_x10) continue;
        char tag[64];
        std::snprintf(tag, sizeof tag, "sliding, k_n x %g", f);
        sp.push_back(slide(so, f, tag));
        if (f != 1.0) {
            for (Check k : tagged(sliding_checks(sp.back(), var), "T20", tag)) {
                if (k.rel != Rel::Report) {
                    k.why =
                        "reported (spec T20 checks T16 outputs only at the default k_n); "
                        "would be: " +
                        k.why;
                    k.rel = Rel::Report;
                }
                c.push_back(k);
            }
        }
    }
    const double h = 1.0 / o.cells;
    c.push_back(check("T20", "sliding: static depth (scaled mean) k_n x 0.1 / k_n x 1",
                      sp[0].depth_relaxed_mean / sp[1].depth_relaxed_mean, Rel::RelTol, 10, 0.05,
                      "",
                      "spec T20: at rest sum s_j 2 k_n d_j = m g (paper eqs. 6, 19), so the "
                      "scaled mean depth is exactly 1/k_n while the same nodes touch; 5 %"));
    if (sp.size() > 2)
        c.push_back(check("T20", "sliding: static depth (scaled mean) k_n x 1 / k_n x 10",
                          sp[1].depth_relaxed_mean / sp[2].depth_relaxed_mean, Rel::RelTol, 10,
                          0.05, "", "as above"));
    c.push_back(check("T20", "sliding: largest static depth k_n x 0.1 / k_n x 1",
                      sp[0].depth_relaxed / sp[1].depth_relaxed, Rel::Report, 0, 0, "",
                      "the largest depth also follows the block's own compliance, which "
                      "redistributes the load differently for each k_n (reported)"));
    c.push_back(check("T20", "sliding: static depth / h at the default k_n",
                      sp[1].depth_relaxed / h, Rel::AtMost, 0.05, 0, "", "spec T20: <= 5 % of h"));
    {
        SlidingOptions v = so;
        v.dt_fraction *= 0.5;
        const SlidingResult r = slide(v, 1.0, "sliding, dt x 0.5");
        c.push_back(check("T20", "sliding: d_max (dt x 0.5) / d_max (dt x 1) - 1",
                          r.d_max / sp[1].d_max - 1, Rel::Abs, 0, 0.005, "",
                          "spec T20: converged with dt; 0.5 % as for the KE of the impact"));
        c.push_back(check("T20", "sliding: mean friction (dt x 0.5) / (dt x 1) - 1",
                          r.friction_mean / sp[1].friction_mean - 1, Rel::Abs, 0, 0.005, "",
                          "spec T20: converged with dt; 0.5 %"));
        for (const Check& k : tagged(sliding_checks(r, var), "T20", "sliding, dt x 0.5"))
            c.push_back(k);
    }
    if (o.refine) {
        SlidingOptions v = so;
        v.cells = 2 * o.cells;
        const SlidingResult r = slide(v, 1.0, "sliding, h x 0.5");
        for (const Check& k : tagged(sliding_checks(r, var), "T20", "sliding, h x 0.5"))
            c.push_back(k);
    }
    return finish();
}

}  // namespace fdem::validation
