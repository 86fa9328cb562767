// Spec §8 T18 (analytic check of spec §6.1): Hertz line contact. An elastic disk (R = 1 m,
// E = 1 GPa, nu = 0, rho = 1000) pressed onto a fixed plane by a body force whose resultant is
// P = 7.85 MN/m, brought to rest by heavy mass damping. Plane strain, rigid plane (spec §6.1,
// Johnson's line contact):
//   1/E* = (1 - nu^2)/E (rigid plane adds 0) = 1/E,  a = sqrt(4 P R / (pi E*)),
//   p0 = 2 P / (pi a),  p(x) = p0 sqrt(1 - x^2 / a^2).
// With P = pi E a^2 / (4 R) for a = 0.1 m: P = 7.854e6 N/m, a = 0.100 m, p0 = 50.0 MPa.
// The mesh is a gmsh .geo written by make_hertz() with a box refinement h_c <= a/10 around the
// contact (spec T18), elsewhere h_far.
#pragma once

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "fdem/build.hpp"
#include "fdem/mesh.hpp"
#include "support/scenes.hpp"
#include "validation/cases/common.hpp"

namespace fdem::validation {

struct HertzOptions {
    double h_contact = 0.01;   ///< element size near the contact [m] (spec T18: <= a/10)
    double h_far = 0.1;        ///< element size elsewhere [m]
    double a_target = 0.1;     ///< half-width the load is chosen for [m] (spec §6.1)
    double dt_fraction = 0.5;  ///< of the stable limit: quasi-static, heavily damped
    /// mass damping c [1/s]: ~ critical for the slowest mode, the disk on its contact
    /// (omega ~ 480 rad/s measured from the overdamped decay at c = 1500)
    double damping = 1000;
    double t_end = 0.05;  ///< [s] of damped settling (residual ~2e-6 P measured)
    ContactScaling scaling = ContactScaling::Length;
    /// false: one-way, the fixed plane is the contactor and the disk's boundary nodes are the
    /// targets (a rigid plane, spec §6.1; the nodal forces on the disk are then the pressure
    /// resultants). Two-way on this graded mesh would also bound dt by the heaviest coarse node
    /// over the lightest fine one (docs/theory.md eq. 6.15): 17x smaller steps.
    bool two_way = false;
    static HertzOptions quick() { return HertzOptions{}; }
    static HertzOptions full() {
        HertzOptions o;
        o.h_contact = 0.005;
        o.h_far = 0.08;
        return o;
    }
};

struct HertzResult {
    Table profile{{"x", "pressure", "pressure_analytic", "force"}};
    Table series{{"time", "contact_force", "kinetic"}};
    double load = 0;             ///< P = body force resultant [N/m]
    double a_an = 0, p0_an = 0;  ///< analytic half-width [m] and peak pressure [Pa]
    double a_moment = NAN;       ///< 2 sqrt(sum x^2 F / sum F) (= a for a semi-ellipse) [m]
    double a_extent = NAN;       ///< largest |x| of a loaded node [m]
    double p0 = NAN;             ///< largest nodal pressure [Pa]
    double l2_error = NAN;       ///< || p - p_an ||_2 / || p_an ||_2 over the contact zone
    double force_sum = NAN;      ///< sum of the vertical contact forces on the disk [N/m]
    double kinetic_end = NAN;    ///< [J/m] at the end (equilibrium indicator)
    double max_depth = 0;        ///< largest contact depth at the end [m]
    int loaded_nodes = 0;        ///< disk boundary nodes with a contact force
    int32_t tris = 0;
    double dt = 0;
};

/// The .geo of the T18 set-up: disk centre (0, R), touching the plane y = 0 at the origin;
/// plane [-0.6, 0.6] x [-0.2, 0]; box field h_contact on |x| <= 0.25, |y| <= 0.25.
inline std::string hertz_geo(const HertzOptions& o) {
    char b[2048];
    std::snprintf(b, sizeof b,
                  "// T18 Hertz line contact (tests/validation/cases/hertz.hpp), written at run "
                  "time\n"
                  "hc = %.17g; hf = %.17g;\n"
                  "Point(1) = {0, 1, 0, hf}; Point(2) = {0, 0, 0, hc}; Point(3) = {1, 1, 0, hf};\n"
                  "Point(4) = {0, 2, 0, hf}; Point(5) = {-1, 1, 0, hf};\n"
                  "Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5};\n"
                  "Circle(4) = {5, 1, 2};\n"
                  "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\n"
                  "Point(11) = {-0.6, -0.2, 0, hf}; Point(12) = {0.6, -0.2, 0, hf};\n"
                  "Point(13) = {0.6, 0, 0, hf}; Point(14) = {-0.6, 0, 0, hf};\n"
                  "Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14};\n"
                  "Line(14) = {14, 11};\n"
                  "Curve Loop(2) = {11, 12, 13, 14}; Plane Surface(2) = {2};\n"
                  "Field[1] = Box; Field[1].VIn = hc; Field[1].VOut = hf;\n"
                  "Field[1].XMin = -0.25; Field[1].XMax = 0.25;\n"
                  "Field[1].YMin = -0.25; Field[1].YMax = 0.25; Field[1].Thickness = 0.3;\n"
                  "Background Field = 1;\n"
                  "Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0;\n"
                  "Mesh.MeshSizeFromCurvature = 0;\n"
                  "Physical Surface(\"disk\") = {1}; Physical Surface(\"plane\") = {2};\n",
                  o.h_contact, o.h_far);
    return b;
}

inline Model make_hertz(const HertzOptions& o, double* load) {
    const std::filesystem::path geo =
        std::filesystem::temp_directory_path() /
        ("fdem_hertz_" + std::to_string(static_cast<long long>(o.h_contact * 1e6)) + "_" +
         std::to_string(static_cast<long long>(o.h_far * 1e6)) + ".geo");
    {
        std::ofstream f(geo);
        f << hertz_geo(o);
    }
    const MeshData mesh = read_mesh(geo.string(), 0);
    std::filesystem::remove(geo);
    Model m;
    m.materials.push_back(scenes::paper_material("paper"));
    for (const char* name : {"disk", "plane"}) {
        const auto& pg = mesh.physical.at(name);
        std::vector<int32_t> tris;
        for (const PhysicalGroup& g : mesh.groups)
            if (g.dim == 2 && g.tag == pg.second) tris = g.elements;
        BodyOptions opt;
        opt.name = name;
        opt.material = 0;
        opt.fixed = std::string(name) == "plane";
        add_bodies(m, mesh, tris, opt);
    }
    m.contact.algorithm = ContactAlgorithm::Smooth;
    m.contact.params.penalty = 5e9;  // spec §5: k_n = 5 E
    m.contact.scaling = o.scaling;
    m.contact.two_way = o.two_way;
    finalize_model(m);  // lumped masses now known
    // body force: P = pi E* a^2 / (4 R) (spec §6.1 solved for P), applied as gravity on the
    // meshed disk's mass (the polygonal disk is slightly lighter than pi R^2 rho)
    const double E = 1e9, R = 1.0;
    const double P = std::acos(-1.0) * E * o.a_target * o.a_target / (4 * R);
    double mass = 0;
    for (NodeId i = m.bodies[0].node_begin; i < m.bodies[0].node_end; ++i)
        mass += m.node_mass[i];
    m.gravity = {0, -P / mass};
    m.mass_damping = {o.damping, 1e30};
    if (load) *load = P;
    return m;
}

inline HertzResult run_hertz(const HertzOptions& o) {
    HertzResult r;
    const Model m = make_hertz(o, &r.load);
    r.tris = m.num_tris();
    const double pi = std::acos(-1.0), E = 1e9, R = 1.0;
    r.a_an = std::sqrt(4 * r.load * R / (pi * E));  // spec §6.1
    r.p0_an = 2 * r.load / (pi * r.a_an);           // spec §6.1
    // Time step: the engine's bound (docs/theory.md eq. 6.15) multiplies the contact frequency by
    // 1 + (heaviest boundary node / lightest movable contactor node) over the whole model, 300
    // on this graded mesh. Here the only contactor is the fixed plane, so the contactor term of
    // eq. 6.15 vanishes and the target's single-DOF frequency omega^2 = g' k_n / m_dt remains
    // (g' = 2 for alpha = 1, phi = d^2): dt <= 2 / omega, and the element bound (theory §5).
    Model no_contact = m;
    no_contact.contact.algorithm = ContactAlgorithm::None;
    const double dt_contact =
        2.0 / std::sqrt(2.0 * m.contact.params.penalty / build_topology(m).m_dt);
    const double dt = o.dt_fraction * std::min(stable_time_step(no_contact),
                                               o.two_way ? stable_time_step(m) : dt_contact);
    r.dt = dt;
    State s = make_state(m, dt);
    const int64_t n = static_cast<int64_t>(std::ceil(o.t_end / dt));
    const int64_t every = std::max<int64_t>(1, n / 400);
    for (int64_t k = 0; k < n; ++k) {
        step(m, s);
        if (k % every == 0 || k == n - 1)
            r.series.row({s.energy.time, body_sums(m, s, 0).contact_force.y, s.energy.kinetic});
    }
    r.kinetic_end = s.energy.kinetic;
    r.force_sum = body_sums(m, s, 0).contact_force.y;
    r.max_depth = max_active_depth(s);
    // tributary length of each disk boundary node: half of its two boundary edges, projected
    // on x (the pressure acts on the plane y = 0)
    std::map<NodeId, double> trib;
    const ContactTopology& cm = s.topology;
    for (int32_t e = cm.body_bedge_begin[0]; e < cm.body_bedge_begin[1]; ++e) {
        const auto [i, j] = cm.boundary_edges[static_cast<size_t>(e)];
        const double lx = std::abs(s.x[j].x - s.x[i].x);
        trib[i] += 0.5 * lx;
        trib[j] += 0.5 * lx;
    }
    double sf = 0, sx = 0;
    for (const auto& [i, t] : trib) {
        const double f = s.f_contact[i].y;
        if (f <= 0) continue;
        sf += f;
        sx += f * s.x[i].x;
    }
    const double xc = sx / sf;
    double sxx = 0, num = 0, den = 0;
    r.p0 = 0;
    r.a_extent = 0;
    for (const auto& [i, t] : trib) {
        const double x = s.x[i].x, f = std::max(0.0, s.f_contact[i].y);
        if (s.x[i].y > 0.2) continue;  // bottom of the disk only
        sxx += f * (x - xc) * (x - xc);
        const double p = f / t;
        const double p_an =
            std::abs(x) < r.a_an ? r.p0_an * std::sqrt(1 - x * x / (r.a_an * r.a_an)) : 0.0;
        if (std::abs(x) < 1.5 * r.a_an) {
            num += t * (p - p_an) * (p - p_an);
            den += t * p_an * p_an;
            r.profile.row({x, p, p_an, f});
        }
        if (f > 0) {
            ++r.loaded_nodes;
            r.p0 = std::max(r.p0, p);
            r.a_extent = std::max(r.a_extent, std::abs(x));
        }
    }
    r.a_moment = 2 * std::sqrt(sxx / sf);  // semi-ellipse: int x^2 p / int p = a^2 / 4
    r.l2_error = std::sqrt(num / den);
    // sort the profile by x for plotting
    std::vector<size_t> idx(r.profile.size());
    for (size_t i = 0; i < idx.size(); ++i)
        idx[i] = i;
    std::sort(idx.begin(), idx.end(),
              [&](size_t a, size_t b) { return r.profile.cols[0][a] < r.profile.cols[0][b]; });
    Table sorted{r.profile.names};
    for (size_t i : idx)
        sorted.row({r.profile.cols[0][i], r.profile.cols[1][i], r.profile.cols[2][i],
                    r.profile.cols[3][i]});
    r.profile = std::move(sorted);
    return r;
}

inline std::vector<Check> hertz_checks(const HertzResult& r, const std::string& tag) {
    std::vector<Check> c;
    c.push_back(check("T18", "contact half-width a (2 sqrt of the load's 2nd moment)" + tag,
                      r.a_moment, Rel::RelTol, r.a_an, 0.10, "m",
                      "a = sqrt(4PR/(pi E*)) (spec §6.1); spec T18: 10 %. A semi-ellipse has "
                      "int x^2 p / int p = a^2/4, so this uses every nodal force"));
    c.push_back(check("T18", "outermost loaded node |x|" + tag, r.a_extent, Rel::Report, r.a_an, 0,
                      "m", "a within one element size h_c"));
    c.push_back(check("T18", "peak pressure p0 (largest nodal force / tributary length)" + tag,
                      r.p0 / 1e6, Rel::RelTol, r.p0_an / 1e6, 0.10, "MPa",
                      "p0 = 2P/(pi a) (spec §6.1); spec T18: 10 %"));
    c.push_back(check("T18", "L2 error of p(x) vs the semi-ellipse / ||p_an||" + tag, r.l2_error,
                      Rel::AtMost, 0.10, 0, "",
                      "p0 sqrt(1 - x^2/a^2) (spec §6.1), nodes |x| < 1.5 a; spec T18: 10 %"));
    c.push_back(check("T18", "sum of vertical contact forces on the disk / P" + tag,
                      r.force_sum / r.load, Rel::Abs, 1.0, 1e-4, "",
                      "equilibrium with the body force P (spec T18: 1e-4)"));
    c.push_back(check("T18", "loaded disk nodes" + tag, r.loaded_nodes, Rel::Report, 0, 0, "",
                      "2a / h_c + 1 expected"));
    c.push_back(check("T18", "largest contact depth / a" + tag, r.max_depth / r.a_an, Rel::Report,
                      0, 0, "", "penalty compliance, small against the Hertz approach a^2/(2R)"));
    return c;
}

/// T18 with length scaling (docs/theory.md §6.11: uniform pressure, uniform depth on the
/// unstructured mesh); with_mass_scaling adds the paper's eq. 19 scaling, same checks.
inline std::vector<Check> hertz_suite(const HertzOptions& o, const std::string& out_dir,
                                      bool with_mass_scaling = false) {
    std::vector<Check> c;
    for (ContactScaling sc : {ContactScaling::Length, ContactScaling::Mass}) {
        if (sc == ContactScaling::Mass && !with_mass_scaling) continue;
        HertzOptions v = o;
        v.scaling = sc;
        const HertzResult r = run_hertz(v);
        const char* name = sc == ContactScaling::Length ? "length" : "mass";
        char tag[96];
        std::snprintf(tag, sizeof tag, " (h_c = %g m, %d triangles, %s scaling)", o.h_contact,
                      r.tris, name);
        if (!out_dir.empty()) {
            r.profile.write(out_dir + "/hertz_profile_" + name + ".csv");
            r.series.write(out_dir + "/hertz_series_" + name + ".csv");
        }
        for (const Check& k : hertz_checks(r, tag))
            c.push_back(k);
    }
    return c;
}

}  // namespace fdem::validation
