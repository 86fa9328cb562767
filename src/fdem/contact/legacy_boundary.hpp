// Baseline B of the smooth-contact paper: the boundary-aware potential attributed to Munjiza,
// Knight & Rougier 2011 as reconstructed in spec §1.3 (docs/theory.md §7.4). Per boundary
// triangle phi_B = N_o (one boundary edge, o the opposite node), the min of the two N's (two
// boundary edges), 0 (boundary vertex only). It plugs into the triangle-to-node law of law.hpp
// as the field d_B = H_ref phi_B, with H_ref the mean boundary-triangle height of the body.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "contact/field.hpp"
#include "fdem/model.hpp"

namespace fdem {

/// phi_B of one contactor sub-triangle, written in the sub-triangle's own barycentric
/// coordinates: phi_B(x) = min_{k < terms} sum_i coef[k][i] N_i(x). Each term is the shape
/// function N_o of the parent mesh triangle for one of its boundary edges; coef[k][i] is its
/// value at sub-triangle vertex i (1/0 at real nodes, 1/2 at chord midpoints, the frozen weight
/// at an incenter), so the expression is exact in the deformed configuration as well.
struct LegacyBoundaryTri {
    int32_t terms = 0;  ///< 0 (vertex-only triangle: phi_B = 0), 1, 2, or 3 (single triangle)
    Real coef[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    Real h_ref = 0;  ///< H_ref of the owning body [m] (amplitude of d_B)
};

/// Baseline B data of a model, parallel to the contact sub-triangles (ContactModel::sub_tri).
struct LegacyBoundaryField {
    std::vector<LegacyBoundaryTri> sub;  ///< one per contactor sub-triangle
    std::vector<Real> body_h_ref;        ///< H_ref per body [m] (0 for a body with no boundary)
};

/// Build the baseline B field from the contact topology of m (sub_tri, sub_parent,
/// boundary_edges, virtual nodes): H_ref(body) = mean over its boundary edges e of the height
/// 2 A_t / l_e of the triangle t owning e, in the reference configuration (theory eq. 7.8).
/// Requires build_contact_topology() to have run on m.
LegacyBoundaryField build_legacy_boundary_field(const Model& m);

/// Field of baseline B in one contactor sub-triangle with vertices p (current positions),
/// mirroring smooth_field(p, dist, fs): fs.N must already hold the barycentric coordinates of
/// the point; fills fs.d = H_ref phi_B (theory eq. 7.9), fs.grad = H_ref grad phi_B (the
/// gradient of the active term: normal to its boundary edge, into the body), fs.layer = H_ref.
inline void legacy_boundary_field(const Vec2 p[3], const LegacyBoundaryTri& c, FieldSample& fs) {
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
    shape_gradients(p[0], p[1], p[2], g);
    fs.d = c.h_ref * best;
    fs.grad = c.h_ref * (c.coef[k][0] * g[0] + c.coef[k][1] * g[1] + c.coef[k][2] * g[2]);
}

/// Same, addressed by sub-triangle id of the contact topology.
inline void legacy_boundary_field(const LegacyBoundaryField& lb, int32_t sub, const Vec2 p[3],
                                  FieldSample& fs) {
    legacy_boundary_field(p, lb.sub[static_cast<size_t>(sub)], fs);
}

}  // namespace fdem
