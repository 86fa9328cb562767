// Bitwise comparison of two contact topologies, field by field (rebuild tests, spec fracture.md
// U6).
#pragma once

#include <cstring>
#include <string>
#include <vector>

#include "fdem/contact_topology.hpp"

namespace fdem::testing {

template <typename T>
inline bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}
template <typename T>
inline bool same_bits(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// Names of the fields of a and b that differ in any bit (every field of ContactTopology).
inline std::string differing_fields(const ContactTopology& a, const ContactTopology& b) {
    std::string d;
    auto cmp = [&](const char* name, bool same) {
        if (!same) d += std::string(name) + " ";
    };
#define FDEM_CMP(f) cmp(#f, same_bits(a.f, b.f))
    FDEM_CMP(num_real_nodes);
    FDEM_CMP(node_scale);
    FDEM_CMP(l_bar);
    FDEM_CMP(m_dt);
    FDEM_CMP(edge_target_base);
    FDEM_CMP(edge_scale);
    FDEM_CMP(target_dt_factor);
    FDEM_CMP(virt_parent);
    FDEM_CMP(virt_weight);
    FDEM_CMP(body_virt_begin);
    FDEM_CMP(node_dist);
    FDEM_CMP(node_dist_edge);
    FDEM_CMP(node_on_boundary);
    FDEM_CMP(num_fallback_nodes);
    FDEM_CMP(body_fallback);
    FDEM_CMP(body_fixed);
    FDEM_CMP(body_self);
    FDEM_CMP(node_weld);
    FDEM_CMP(weld_group);
    FDEM_CMP(weld_group_begin);
    FDEM_CMP(weld_copy);
    FDEM_CMP(weld_share);
    FDEM_CMP(weld_plain);
    FDEM_CMP(boundary_nodes);
    FDEM_CMP(body_bnode_begin);
    FDEM_CMP(boundary_edges);
    FDEM_CMP(body_bedge_begin);
    FDEM_CMP(chords);
    FDEM_CMP(body_chord_begin);
    FDEM_CMP(boundary_tris);
    FDEM_CMP(body_btri_begin);
    FDEM_CMP(sub_tri);
    FDEM_CMP(sub_body);
    FDEM_CMP(sub_parent);
    FDEM_CMP(body_sub_begin);
    FDEM_CMP(body_cnode);
    FDEM_CMP(body_cnode_begin);
    FDEM_CMP(body_cnode_nreal);
    FDEM_CMP(sub_local);
#undef FDEM_CMP
    // LegacyBoundaryTri has padding after `terms`: compare its members
    bool legacy = a.sub_legacy_b.size() == b.sub_legacy_b.size();
    for (size_t k = 0; legacy && k < a.sub_legacy_b.size(); ++k) {
        const LegacyBoundaryTri &p = a.sub_legacy_b[k], &q = b.sub_legacy_b[k];
        legacy = p.terms == q.terms && same_bits(p.coef, q.coef) && same_bits(p.h_ref, q.h_ref);
    }
    cmp("sub_legacy_b", legacy);
    return d;
}

}  // namespace fdem::testing
