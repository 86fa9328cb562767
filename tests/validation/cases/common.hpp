// Shared pieces of the paper-reproduction cases (spec §5, §8 T13-T20): checks with their
// tolerances, time series written as CSV, body sums over nodes. Header-only so that the same code
// runs in the CTest suite (tests/validation/*_test.cpp, reduced resolution) and in the validation
// driver (tools/validate, full resolution, writes docs/validation/).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "fdem/build.hpp"
#include "fdem/model.hpp"
#include "fdem/simulate.hpp"
#include "fdem/state.hpp"

namespace fdem::validation {

/// How a measured value is compared with the expected one.
enum class Rel {
    Abs,      ///< |measured - expected| <= tol
    RelTol,   ///< |measured / expected - 1| <= tol
    AtMost,   ///< measured <= expected
    AtLeast,  ///< measured >= expected
    Report,   ///< no pass/fail: a number the spec asks to report
};

/// One validation check: a row of docs/validation/README.md and one CTest assertion.
struct Check {
    std::string id;    ///< spec test id, e.g. "T13"
    std::string name;  ///< what is checked
    double measured = 0;
    double expected = 0;
    Rel rel = Rel::Report;
    double tol = 0;    ///< for Abs / RelTol
    std::string unit;  ///< unit of measured/expected ("" = dimensionless)
    std::string why;   ///< where the expected value and the tolerance come from
    bool pass() const {
        if (!std::isfinite(measured)) return rel == Rel::Report;
        switch (rel) {
            case Rel::Abs:
                return std::abs(measured - expected) <= tol;
            case Rel::RelTol:
                return std::abs(measured / expected - 1.0) <= tol;
            case Rel::AtMost:
                return measured <= expected;
            case Rel::AtLeast:
                return measured >= expected;
            case Rel::Report:
                return true;
        }
        return false;
    }
    std::string tolerance_text() const {
        char b[64];
        switch (rel) {
            case Rel::Abs:
                std::snprintf(b, sizeof b, "± %.3g %s", tol, unit.c_str());
                break;
            case Rel::RelTol:
                std::snprintf(b, sizeof b, "± %.3g %%", 100 * tol);
                break;
            case Rel::AtMost:
                std::snprintf(b, sizeof b, "≤ expected");
                break;
            case Rel::AtLeast:
                std::snprintf(b, sizeof b, "≥ expected");
                break;
            case Rel::Report:
                std::snprintf(b, sizeof b, "reported");
                break;
        }
        return b;
    }
};

inline Check check(std::string id, std::string name, double measured, Rel rel, double expected,
                   double tol, std::string unit, std::string why) {
    return Check{std::move(id), std::move(name), measured,      expected, rel,
                 tol,           std::move(unit), std::move(why)};
}

/// Adds a square-celled rectangle body [x0, x0 + w] x [y0, y0 + hgt] with node spacing w / nx
/// (nx x ny cells of CSTs by default; validation/cases/composite_dynamics.hpp passes a builder of
/// 6-node composite elements with the same nodes). Used for the block of the dynamic cases.
using BlockBuilder = std::function<void(Model& m, double x0, double y0, double w, double hgt,
                                        int nx, int ny, Vec2 velocity, const std::string& name)>;

/// Columns of equal length written as one CSV file (header = column names).
struct Table {
    std::vector<std::string> names;
    std::vector<std::vector<double>> cols;
    explicit Table(std::vector<std::string> n) : names(std::move(n)), cols(names.size()) {}
    void row(std::initializer_list<double> v) {
        size_t k = 0;
        for (double x : v)
            cols[k++].push_back(x);
    }
    size_t size() const { return cols.empty() ? 0 : cols[0].size(); }
    bool write(const std::string& path) const {
        std::ofstream f(path);
        if (!f) return false;
        for (size_t k = 0; k < names.size(); ++k)
            f << (k ? "," : "") << names[k];
        f << "\n";
        char b[32];
        for (size_t i = 0; i < size(); ++i) {
            for (size_t k = 0; k < cols.size(); ++k) {
                std::snprintf(b, sizeof b, "%.10g", cols[k][i]);
                f << (k ? "," : "") << b;
            }
            f << "\n";
        }
        return static_cast<bool>(f);
    }
};

/// Distance from p to the segment [a, b] [m] (the exact distance of the field maps).
/// x as TOML text with all its digits (%.17g)
inline std::string number(double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%.17g", x);
    return b;
}

/// The jointed rock of the fracture cases V1-V3, V7 (examples 07's, docs/scenario.md): the
/// [[material]] "rock" and its [material.fracture] table with the joint penalty `penalty` and,
/// when not empty, `shear_penalty` (TOML values as text: "\"auto\"" or a number).
inline std::string jointed_rock_toml(const std::string& penalty,
                                     const std::string& shear_penalty = "") {
    std::string t = R"([[material]]
name = "rock"
density = 2700.0
youngs_modulus = 5.0e10
poisson_ratio = 0.0

[material.fracture]
tensile_strength = 1.0e7
cohesion = 3.0e7
friction_angle = 30.0
fracture_energy_I = 50.0
fracture_energy_II = 250.0
penalty = )" + penalty +
                    "\n";
    if (!shear_penalty.empty()) t += "shear_penalty = " + shear_penalty + "\n";
    return t;
}

inline double segment_distance(Vec2 p, Vec2 a, Vec2 b) {
    const Vec2 ab = b - a;
    double t = dot(p - a, ab) / norm2(ab);
    t = std::clamp(t, 0.0, 1.0);
    return norm(p - (a + t * ab));
}

/// Reference position of contact node i: a model node, or a virtual node placed by its frozen
/// parent weights (fdem/contact_model.hpp).
inline Vec2 contact_node_x0(const Model& m, const ContactTopology& cm, NodeId i) {
    if (i < cm.num_real_nodes) return m.node_x0[i];
    const int32_t v = i - cm.num_real_nodes;
    Vec2 p;
    for (int k = 0; k < 3; ++k)
        p += cm.virt_weight[v][k] * m.node_x0[cm.virt_parent[v][k]];
    return p;
}

/// One row (x0, y0, x1, y1, x2, y2) per mesh triangle into mesh and per contact sub-triangle into
/// sub: the outlines drawn under the field maps.
inline void outline_rows(const Model& m, Table& mesh, Table& sub) {
    const ContactTopology topo = build_topology(m);
    for (TriId t = 0; t < m.num_tris(); ++t) {
        const auto& tn = m.tri_nodes[t];
        mesh.row({m.node_x0[tn[0]].x, m.node_x0[tn[0]].y, m.node_x0[tn[1]].x, m.node_x0[tn[1]].y,
                  m.node_x0[tn[2]].x, m.node_x0[tn[2]].y});
    }
    for (const auto& q : topo.sub_tri) {
        const Vec2 a = contact_node_x0(m, topo, q[0]), b = contact_node_x0(m, topo, q[1]),
                   c = contact_node_x0(m, topo, q[2]);
        sub.row({a.x, a.y, b.x, b.y, c.x, c.y});
    }
}

/// Sums over the nodes of a body: mass, centre of mass, momentum, contact force.
struct BodySums {
    double mass = 0;
    Vec2 com, momentum, contact_force;
};

inline BodySums body_sums(const Model& m, const State& s, BodyId b) {
    BodySums r;
    for (NodeId i = m.bodies[b].node_begin; i < m.bodies[b].node_end; ++i) {
        const double mi = m.node_mass[i];
        r.mass += mi;
        r.com += mi * s.x[i];
        r.momentum += mi * s.v[i];
        r.contact_force += s.f_contact[i];
    }
    r.com = r.com / r.mass;
    return r;
}

/// Largest contact depth d [m] over the active pairs of the last step.
inline double max_active_depth(const State& s) {
    double d = 0;
    for (const auto& a : s.contact.active)
        d = std::max(d, a.h.d_prev);
    return d;
}

/// Mean contact depth weighted by the target force scale (m_j / mbar or l_j / lbar, paper eq. 19,
/// shared with the edge targets by eq. 6.19):
/// sum s_j d_j / sum s_j over the active pairs of the last step. On a flat face the normal force
/// is sum s_j 2 k_n d_j (g = 2d, |grad d| = 1), so for a given load this mean scales exactly as
/// 1/k_n as long as the same nodes touch.
inline double scaled_mean_depth(const Model& /*m*/, const State& s) {
    double sd = 0, ss = 0;
    for (const auto& a : s.contact.active) {
        if (a.h.d_prev <= 0) continue;
        const double sc = target_scale(s.topology, a.node);  // node or edge target (§6.12)
        sd += sc * a.h.d_prev;
        ss += sc;
    }
    return ss > 0 ? sd / ss : 0.0;
}

inline double mean(const std::vector<double>& v) {
    double s = 0;
    for (double x : v)
        s += x;
    return v.empty() ? NAN : s / static_cast<double>(v.size());
}

inline double stddev(const std::vector<double>& v) {
    const double mu = mean(v);
    double s = 0;
    for (double x : v)
        s += (x - mu) * (x - mu);
    return v.size() < 2 ? NAN : std::sqrt(s / static_cast<double>(v.size() - 1));
}

inline double median(std::vector<double> v) {
    if (v.empty()) return NAN;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

}  // namespace fdem::validation
