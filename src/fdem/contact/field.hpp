// Geometry kernel of the smooth contact: barycentric coordinates (paper eq. 4), distance field
// d = sum N_i d_i (eq. 3) and its gradient (eqs. 8-10). docs/theory.md §6.3.
// Everything is inline: it sits in the innermost loop of the narrow phase.
#pragma once

#include "fdem/contact_topology.hpp"
#include "fdem/math.hpp"

namespace fdem {

/// 1 / (2A) of triangle (p0, p1, p2), signed: what barycentric() and shape_gradients() divide by.
inline Real inverse_double_area(Vec2 p0, Vec2 p1, Vec2 p2) {
    return 1.0 / cross(p1 - p0, p2 - p0);
}

/// Barycentric coordinates N_i = A_i / A of x in triangle (p0, p1, p2) (eq. 4), either
/// orientation, and inv = inverse_double_area() (bitwise). Returns false for a degenerate
/// triangle (N and inv left untouched).
inline bool barycentric(Vec2 p0, Vec2 p1, Vec2 p2, Vec2 x, Real N[3], Real& inv_a2) {
    const Real a2 = cross(p1 - p0, p2 - p0);  // 2A, signed
    if (a2 == 0) return false;
    const Real inv = 1.0 / a2;
    N[0] = cross(p1 - x, p2 - x) * inv;
    N[1] = cross(p2 - x, p0 - x) * inv;
    N[2] = cross(p0 - x, p1 - x) * inv;
    inv_a2 = inv;
    return true;
}

inline bool barycentric(Vec2 p0, Vec2 p1, Vec2 p2, Vec2 x, Real N[3]) {
    Real inv;
    return barycentric(p0, p1, p2, x, N, inv);
}

/// Gradients of the shape functions: grad N_i = -n_i / (2A) with n_i the scaled outward normal
/// of the edge opposite node i (eqs. 8-10); valid for both orientations because A is signed.
/// inv = inverse_double_area(p0, p1, p2), passed where the locate test already has it (the
/// narrow phase: one division less per pair in contact, the same bits).
inline void shape_gradients(Vec2 p0, Vec2 p1, Vec2 p2, Real inv, Vec2 g[3]) {
    g[0] = Vec2{p1.y - p2.y, p2.x - p1.x} * inv;
    g[1] = Vec2{p2.y - p0.y, p0.x - p2.x} * inv;
    g[2] = Vec2{p0.y - p1.y, p1.x - p0.x} * inv;
}

inline void shape_gradients(Vec2 p0, Vec2 p1, Vec2 p2, Vec2 g[3]) {
    shape_gradients(p0, p1, p2, inverse_double_area(p0, p1, p2), g);
}

/// One evaluation of a contactor's potential field at a point.
struct FieldSample {
    Real N[3] = {0, 0, 0};  ///< weights that distribute the reaction to the triangle (eq. 20)
    Real d = 0;             ///< distance field [m] (eq. 3)
    Vec2 grad;              ///< grad d [-], points into the contactor (eq. 8)
    Real layer = 0;         ///< largest nodal distance of the triangle [m] (depth diagnostics)
};

/// Smooth field of Lei et al. 2020 in one contactor sub-triangle with nodal distances dist[].
/// N must already hold the barycentric coordinates of the point; inv = inverse_double_area(p).
inline void smooth_field(const Vec2 p[3], const Real dist[3], Real inv, FieldSample& fs) {
    Vec2 g[3];
    shape_gradients(p[0], p[1], p[2], inv, g);
    fs.d = fs.N[0] * dist[0] + fs.N[1] * dist[1] + fs.N[2] * dist[2];
    fs.grad = dist[0] * g[0] + dist[1] * g[1] + dist[2] * g[2];
    fs.layer = dist[0] > dist[1] ? dist[0] : dist[1];
    if (dist[2] > fs.layer) fs.layer = dist[2];
}

inline void smooth_field(const Vec2 p[3], const Real dist[3], FieldSample& fs) {
    smooth_field(p, dist, inverse_double_area(p[0], p[1], p[2]), fs);
}

/// Field of baseline B (spec §1.3, docs/theory.md eq. 7.9) in one contactor sub-triangle with
/// vertices p (current positions) and terms c, mirroring smooth_field(): fs.N must already hold
/// the barycentric coordinates of the point; fills fs.d = H_ref phi_B, fs.grad = H_ref grad
/// phi_B (the gradient of the active term: normal to its boundary edge, into the body),
/// fs.layer = H_ref. In a vertex-only wedge (terms = 0) d = 0: no force there (intended).
inline void legacy_boundary_field(const Vec2 p[3], const LegacyBoundaryTri& c, Real inv,
                                  FieldSample& fs) {
    fs.layer = c.h_ref;
    if (c.terms == 0) {
        fs.d = 0;
        fs.grad = Vec2{};
        return;
    }

    // active term = smallest value (first one on ties, deterministic)
    int k = 0;
    Real best = 0;
    for (int t = 0; t < c.terms; ++t) {
        const Real v = c.coef[t][0] * fs.N[0] + c.coef[t][1] * fs.N[1] + c.coef[t][2] * fs.N[2];
        if (t == 0 || v < best) {
            best = v;
            k = t;
        }
    }
    Vec2 g[3];
    shape_gradients(p[0], p[1], p[2], inv, g);
    fs.d = c.h_ref * best;
    fs.grad = c.h_ref * (c.coef[k][0] * g[0] + c.coef[k][1] * g[1] + c.coef[k][2] * g[2]);
}

inline void legacy_boundary_field(const Vec2 p[3], const LegacyBoundaryTri& c, FieldSample& fs) {
    legacy_boundary_field(p, c, inverse_double_area(p[0], p[1], p[2]), fs);
}

/// The field of the selected algorithm in contactor sub-triangle `sub` (vertices p, nodal
/// distances dist): the single plug-in point of the triangle-to-node law (law.hpp), which is
/// shared by the smooth field and baseline B. Baseline A (LegacyTriangle) does not come here:
/// it integrates triangle-to-triangle (legacy_triangle.hpp). inv = inverse_double_area(p).
inline void evaluate_field(ContactAlgorithm algorithm, const ContactTopology& ct, int32_t sub,
                           const Vec2 p[3], const Real dist[3], Real inv, FieldSample& fs) {
    switch (algorithm) {
        case ContactAlgorithm::LegacyBoundary:
            legacy_boundary_field(p, ct.sub_legacy_b[static_cast<size_t>(sub)], inv, fs);
            break;
        case ContactAlgorithm::Smooth:
        default:
            smooth_field(p, dist, inv, fs);
            break;
    }
}

}  // namespace fdem
