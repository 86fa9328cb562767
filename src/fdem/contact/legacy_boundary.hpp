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

// LegacyBoundaryTri (the per-sub-triangle terms of phi_B) is in fdem/contact_model.hpp, the
// field itself, legacy_boundary_field(p, c, fs), in contact/field.hpp next to smooth_field().

/// Baseline B data of a model, parallel to the contact sub-triangles (ContactTopology::sub_tri).
struct LegacyBoundaryField {
    std::vector<LegacyBoundaryTri> sub;  ///< one per contactor sub-triangle
    std::vector<Real> body_h_ref;        ///< H_ref per body [m] (0 for a body with no boundary)
};

/// Build the baseline B field from the contact topology of m (sub_tri, sub_parent,
/// boundary_edges, virtual nodes): H_ref(body) = mean over its boundary edges e of the height
/// 2 A_t / l_e of the triangle t owning e, in the reference configuration (theory eq. 7.8).
/// t is the contact topology of m without its baseline B field (build_topology() calls this).
LegacyBoundaryField build_legacy_boundary_field(const Model& m, const ContactTopology& t);

/// Same, addressed by sub-triangle id of the contact topology.
inline void legacy_boundary_field(const LegacyBoundaryField& lb, int32_t sub, const Vec2 p[3],
                                  FieldSample& fs) {
    legacy_boundary_field(p, lb.sub[static_cast<size_t>(sub)], fs);
}

}  // namespace fdem
