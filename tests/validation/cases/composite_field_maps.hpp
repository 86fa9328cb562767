// Distance-field pictures of the 6-node composite element (paper Figs. 15-19, issue #7): one
// composite element, a diamond of two and a rectangle of four, each with both contact options of
// paper §2.4 (docs/theory.md §6.1.1): "fan" = option (b), "split" = option (a). The smooth field d
// (eqs. 1-4) is sampled on a grid next to the exact distance to the boundary and written as CSV
// for scripts/validate_report.py. Checks: option (b) is exact for all three (spec §4.4 "When is
// the interpolated field exact?"); the option (a) errors are reported.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "contact/field.hpp"
#include "fdem/build.hpp"
#include "support/composite.hpp"
#include "support/scenes.hpp"
#include "validation/cases/common.hpp"

namespace fdem::validation {

struct CompositeFieldCase {
    std::string shape;  ///< "triangle" (one element, Figs. 15-16) or "diamond" (Figs. 17-18)
    std::vector<Vec2> corners;
    std::vector<std::array<int32_t, 3>> tris;  ///< corner triangles of the composite elements
    CompositeSpecialCase option = CompositeSpecialCase::Fan;
    std::string name() const {
        return shape + (option == CompositeSpecialCase::Fan ? "_fan" : "_split");
    }
    bool exact() const { return option == CompositeSpecialCase::Fan; }
};

/// Same outlines as the CST pictures of field_maps.hpp (triangle, diamond), as composites.
inline std::vector<CompositeFieldCase> composite_field_cases() {
    std::vector<CompositeFieldCase> c;
    for (CompositeSpecialCase o : {CompositeSpecialCase::Fan, CompositeSpecialCase::Split}) {
        c.push_back({"triangle", {{0, 0}, {1, 0}, {0.3, 0.8}}, {{0, 1, 2}}, o});
        // cut along the short diagonal: two elements, each with two boundary edges (case 1)
        c.push_back({"diamond", {{1, 0}, {0, 0.6}, {-1, 0}, {0, -0.6}}, {{0, 1, 3}, {1, 2, 3}}, o});
        // paper Fig. 19: a 2 x 1 rectangle of four structured composites; (0,4,3) and (1,2,5)
        // have two boundary edges (case 1). With the fans around the diagonals' midpoints
        // (0.5, 0.5) and (1.5, 0.5), which are on the medial axis, every contact sub-triangle lies
        // in one nearest-side region, so option (b) is exact here too
        c.push_back({"rectangle",
                     {{0, 0}, {1, 0}, {2, 0}, {0, 1}, {1, 1}, {2, 1}},
                     {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}},
                     o});
    }
    return c;
}

struct CompositeFieldResult {
    Table grid{{"x", "y", "smooth", "exact"}};
    Table mesh{{"x0", "y0", "x1", "y1", "x2", "y2"}};  ///< mesh sub-triangles
    Table sub{{"x0", "y0", "x1", "y1", "x2", "y2"}};   ///< contact sub-triangles
    double max_error = 0;  ///< max |d - exact distance| over inside samples [m]
    double size = 0;       ///< bounding-box diagonal [m]
    int num_sub = 0, num_virtual = 0;
};

inline CompositeFieldResult sample_composite_field(const CompositeFieldCase& fc, int n = 240) {
    Model m;
    m.materials.push_back(scenes::paper_material("paper"));
    m.contact.algorithm = ContactAlgorithm::Smooth;
    m.contact.composite_special_case = fc.option;
    scenes::add_composite_body(m, scenes::composite_mesh(fc.corners, fc.tris), 0, false, {},
                               fc.shape);
    finalize_model(m);
    const ContactTopology cm = build_topology(m);
    auto cpos = [&](NodeId i) { return contact_node_x0(m, cm, i); };
    CompositeFieldResult r;
    r.num_sub = cm.num_sub_tris();
    r.num_virtual = cm.num_virtual();
    Vec2 lo{1e30, 1e30}, hi{-1e30, -1e30};
    for (const Vec2& p : m.node_x0) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    r.size = norm(hi - lo);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (int iy = 0; iy <= n; ++iy) {
        for (int ix = 0; ix <= n; ++ix) {
            const Vec2 x{lo.x + (hi.x - lo.x) * ix / n, lo.y + (hi.y - lo.y) * iy / n};
            double ds = nan, ex = nan;
            for (int32_t k = 0; k < cm.num_sub_tris(); ++k) {
                const auto& q = cm.sub_tri[k];
                const Vec2 p[3] = {cpos(q[0]), cpos(q[1]), cpos(q[2])};
                FieldSample fs;
                if (!barycentric(p[0], p[1], p[2], x, fs.N)) continue;
                if (std::min({fs.N[0], fs.N[1], fs.N[2]}) < -1e-12) continue;
                const Real dist[3] = {cm.node_dist[q[0]], cm.node_dist[q[1]], cm.node_dist[q[2]]};
                smooth_field(p, dist, fs);
                ds = fs.d;
                break;
            }
            if (!std::isnan(ds)) {
                ex = 1e300;
                for (const auto& e : cm.boundary_edges)
                    ex = std::min(ex, segment_distance(x, m.node_x0[e[0]], m.node_x0[e[1]]));
                r.max_error = std::max(r.max_error, std::abs(ds - ex));
            }
            r.grid.row({x.x, x.y, ds, ex});
        }
    }
    outline_rows(m, r.mesh, r.sub);
    return r;
}

/// Files field_composite_<shape>_<option>{,_mesh,_sub}.csv and one check per case.
inline std::vector<Check> composite_field_maps_suite(const std::string& out_dir, int n = 240) {
    std::vector<Check> c;
    for (const CompositeFieldCase& fc : composite_field_cases()) {
        const CompositeFieldResult r = sample_composite_field(fc, n);
        const std::string base = out_dir + "/field_composite_" + fc.name();
        if (!out_dir.empty()) {
            r.grid.write(base + ".csv");
            r.mesh.write(base + "_mesh.csv");
            r.sub.write(base + "_sub.csv");
        }
        const std::string count = fc.shape == "triangle"  ? " (one element"
                                  : fc.shape == "diamond" ? " (two elements"
                                                          : " (four elements";
        const std::string what =
            fc.shape + count +
            (fc.option == CompositeSpecialCase::Fan ? ", option (b) fan)" : ", option (a) split)");
        c.push_back(check("T4", "composite element: max |d - exact distance| / size, " + what,
                          r.max_error / r.size, fc.exact() ? Rel::AtMost : Rel::Report,
                          fc.exact() ? 1e-12 : 0, 0, "",
                          fc.exact() ? "theory §6.1.1: every fan triangle is a nearest-side "
                                       "region, exact; 1e-12 round-off"
                                     : "paper Figs. 15/17 option (a): not exact (reported)"));
    }
    return c;
}

}  // namespace fdem::validation
