// The block impact (spec §5.1, T13) and the sliding block (spec §5.3, T16) with the block made of
// 6-node composite elements (Lei et al. 2016; spec §3.3, ElementKind::Composite6, issue #7):
// a composite mesh of n/2 x n/2 cells (6-node right triangles of size 2h) has the same nodes as
// the CST mesh of n x n cells (size h), so the contact sees the same boundary node spacing h and
// the checks and tolerances of T13 / T16 apply unchanged (spec §5: "block 20x20 squares = 800
// CST or 10x10 composite"). The base / platform stays CST (fixed, so its formulation is moot).
#pragma once

#include <string>
#include <vector>

#include "support/scenes.hpp"
#include "validation/cases/block_impact.hpp"
#include "validation/cases/sliding_block.hpp"

namespace fdem::validation {

/// Block builder: nx/2 x ny/2 composite 6-node elements (nx, ny even) = the nodes of nx x ny CSTs.
inline BlockBuilder composite_block_builder() {
    return [](Model& m, double x0, double y0, double w, double hgt, int nx, int ny, Vec2 v,
              const std::string& name) {
        scenes::add_rectangle_order2(m, x0, y0, w, hgt, nx / 2, ny / 2, 0, ElementKind::Composite6,
                                     false, v, false, name);
    };
}

/// Both modes use the spec's composite resolution, 10 x 10 composites (spec §5: "block 20 x 20
/// squares = 800 CST or 10 x 10 composite"); the reduced one only drops speeds. At 5 x 5
/// composites (the nodes of the quick CST block) the rebound is 9.27 m/s, -7.3 %, outside T13's
/// 5 % (NOTES.md): five elements across are too coarse for the composite's wave propagation.
struct CompositeDynamicsOptions {
    int cells = 20;  ///< node spacing h = 1 / cells (composite elements of size 2h)
    std::vector<double> speeds{2, 4};
    bool energy_order = false;  ///< the T13 dt-halving fit (3 runs costing 14x the base run)
    static CompositeDynamicsOptions quick() { return {}; }
    static CompositeDynamicsOptions full() { return {20, {2, 4, 6, 8}, true}; }
};

inline std::vector<Check> composite_dynamics_suite(const CompositeDynamicsOptions& o,
                                                   const std::string& out_dir) {
    std::vector<Check> c;
    const BlockBuilder comp = composite_block_builder();
    char tag[96];
    std::snprintf(tag, sizeof tag, "composite 6-node, %d x %d elements of 2h, h = %g m",
                  o.cells / 2, o.cells / 2, 1.0 / o.cells);
    // T13: block impact, no damping; the energy-error order over three dt halvings as in T13
    BlockImpactOptions bo;
    bo.cells = o.cells;
    // the paper's node-only targets: with the edge targets of docs/theory.md §6.12 the rebound
    // is 9.48 m/s (-5.2 %, just outside T13's 5 %; 9.52 m/s with the block a quarter cell off
    // the base's target grid), KE after 0.933, energy error 0.057 % (NOTES.md, composite)
    bo.edge_targets = false;
    const BlockImpactResult r = run_block_impact(bo, make_block_impact(bo, comp));
    for (Check k : block_impact_checks(r)) {
        k.name += std::string(" (") + tag + ")";
        c.push_back(k);
    }
    if (o.energy_order) {
        double sx = 0, sy = 0, sxx = 0, sxy = 0;
        const double fr[4] = {0.2, 0.1, 0.05, 0.025};
        for (int k = 0; k < 4; ++k) {
            BlockImpactOptions b = bo;
            b.dt_fraction = fr[k];
            const double y =
                k == 0
                    ? std::log2(r.max_energy_error)
                    : std::log2(run_block_impact(b, make_block_impact(b, comp)).max_energy_error);
            sx += k;
            sy += y;
            sxx += k * k;
            sxy += k * y;
        }
        c.push_back(check(
            "T13",
            std::string("order of the energy error (fit over 3 halvings of dt) (") + tag + ")",
            -(4 * sxy - sx * sy) / (4 * sxx - sx * sx), Rel::AtLeast, 1.5, 0, "",
            "as for the CST block: central differences are 2nd order (spec T13)"));
    }
    if (!out_dir.empty()) r.series.write(out_dir + "/composite_block_impact.csv");
    // T16: sliding block, free vertical motion, block damping xi = 1 as the CST runs (NOTES.md)
    SlidingOptions so = SlidingOptions::quick();
    so.cells = o.cells;
    so.speeds = o.speeds;
    const SlidingVariant var = sliding_variants()[0];  // "free"
    for (double v : o.speeds) {
        SlidingResult sr = run_sliding_block(so, v, false, make_sliding_block(so, v, false, comp));
        sr.tag = var.tag;
        if (!out_dir.empty())
            sr.series.write(out_dir + "/composite_sliding_v" + std::to_string(static_cast<int>(v)) +
                            ".csv");
        for (Check k : sliding_checks(sr, var)) {
            k.name += std::string(" (") + tag + ")";
            c.push_back(k);
        }
    }
    return c;
}

}  // namespace fdem::validation
