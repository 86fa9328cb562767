// The contact topology (paper §2, spec §4.1-4.4, docs/theory.md §6.1-6.2, §6.11-6.12): boundary
// edges, nodes and elements per body, chords and virtual nodes, contactor sub-triangles, frozen
// nodal distances and target force scales. Derived from the Model (mesh, bodies, masses, contact
// parameters) by build_topology(); held in State::topology because it can change during a run
// (fracture, issue #14: a cracked body gets new boundary), where rebuild_topology() rebuilds the
// part of a set of dirty bodies. Bodies are the unit of rebuild until fragments exist.
//
// Node ids used by the contact code: [0, num_real_nodes) are the model's nodes; ids
// num_real_nodes + v are virtual node v (chord midpoints and single-triangle incenters, spec
// §4.4; composite special cases, docs/theory.md §6.1.1). A virtual node has no mass and no
// DOF: its position/velocity is sum_k w_k x_{parent_k} and a force on it goes to the parents
// with the same weights. Every per-body list below is the concatenation of the bodies' lists in
// body order, body b's part starting at body_*_begin[b].
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "fdem/contact_model.hpp"
#include "fdem/math.hpp"

namespace fdem {

struct ContactTopology {
    int32_t num_real_nodes = 0;  ///< = Model::num_nodes()

    /// Scale of the force on each real node as a target: m_j / m_bar (ContactScaling::Mass) or
    /// l_j / l_bar (Length); 0 for nodes that are not on a boundary (Length only).
    std::vector<Real> node_scale;
    Real l_bar = 0;  ///< smallest boundary edge over all bodies [m] (ContactScaling::Length)
    /// Mass of the single-DOF bound of the stable dt: min over movable boundary nodes of
    /// m_j / node_scale[j] (= m_bar for ContactScaling::Mass, docs/theory.md §6.11)
    Real m_dt = 0;

    /// Edge targets (docs/theory.md §6.12): target id edge_target_base + e is the midpoint of
    /// boundary_edges[e], its force goes half to each end node and edge_scale[e] is its force
    /// scale (eq. 6.19); then node_scale holds the share the boundary nodes keep. edge_scale is
    /// empty without edge targets. Target ids: [0, num_real_nodes) boundary nodes, then
    /// [edge_target_base, target_end()) edge midpoints (edge_target_base = num_contact_nodes()).
    NodeId edge_target_base = 0;
    std::vector<Real> edge_scale;
    /// target-side factor of the stable dt (eq. 6.15): largest row sum of the target stiffness
    /// over the node mass, in units of k / m_dt; 1 without edge targets (docs/theory.md §6.12)
    Real target_dt_factor = 1;

    std::vector<std::array<NodeId, 3>> virt_parent;  ///< parents of each virtual node
    std::vector<std::array<Real, 3>> virt_weight;    ///< frozen weights (sum 1)
    std::vector<int32_t> body_virt_begin;  ///< virtual nodes of body b: [begin[b], begin[b+1])

    /// Nodal contact distance [m] (eqs. 1-2 + spec §4.2 fallback), indexed by contact node id
    /// (real then virtual). 0 on boundary nodes; 0 also for inner nodes of non-boundary elements
    /// (they never appear in a contactor triangle).
    std::vector<Real> node_dist;
    /// the boundary edge that gave node_dist (eq. 6.3 candidate or fallback), -1 for boundary
    /// nodes and unused nodes (load-time check of thin bodies, docs/theory.md §6.13)
    std::vector<int32_t> node_dist_edge;
    std::vector<uint8_t> node_on_boundary;  ///< per real node: 1 = boundary node
    int32_t num_fallback_nodes = 0;         ///< nodes whose distance came from the fallback
    std::vector<int32_t> body_fallback;     ///< of which in body b

    std::vector<uint8_t> body_fixed;  ///< per body (copy of Body::fixed for the role rule)
    /// per body: 1 = the body contacts itself under rule X (Body::fracture; docs/theory.md
    /// §6.15): its boundary nodes are also targets of its own sub-triangles
    std::vector<uint8_t> body_self;

    /// Welded form (bodies with fracture, docs/theory.md §6.15): per real node the
    /// representative of its sector (State::node_sector: the smallest copy id of the copies of
    /// one mesh vertex still joined around it by unbroken joints). Empty = identity (no body has
    /// fracture). Boundary classification, chords and nodal distances of a fracture body are
    /// computed on these ids; boundary edges and sub-triangles keep each triangle's own copies.
    std::vector<NodeId> node_weld;
    /// Welded contactor positions (docs/theory.md §6.15, eq. 6.23): a sub-triangle vertex that is
    /// a copy c of a sector S with more than one copy stands at the sector's mass-weighted mean
    /// xbar_S = sum_{k in S} (m_k / M_S) x_k, so that the triangles around an intact vertex share
    /// it exactly; its reaction goes to the copies with the same shares. Per real node: the index
    /// of its sector's group, -1 = the node stands for itself. Empty without a weld (then every
    /// contactor position is x itself). Group g's copies (ascending) and shares are
    /// weld_copy / weld_share [weld_group_begin[g], weld_group_begin[g+1]). Only sectors some
    /// copy of which is a vertex of a sub-triangle or a parent of a virtual node are grouped.
    std::vector<int32_t> weld_group;
    std::vector<int32_t> weld_group_begin;
    std::vector<NodeId> weld_copy;
    std::vector<Real> weld_share;
    /// real nodes referenced by the contactor geometry (sub-triangle vertices, virtual parents)
    /// that stand for themselves (weld_group -1), ascending; empty without a weld. With the
    /// groups' copies these are the entries of ContactState::xw the step fills.
    std::vector<NodeId> weld_plain;

    /// Boundary nodes (targets) of all bodies, ascending ids; those of body b are
    /// [body_bnode_begin[b], body_bnode_begin[b+1]).
    std::vector<NodeId> boundary_nodes;
    std::vector<int32_t> body_bnode_begin;
    /// Boundary edges, oriented as in their (counter-clockwise) triangle: material on the left;
    /// per body in ascending (min, max) node order.
    std::vector<std::array<NodeId, 2>> boundary_edges;
    std::vector<int32_t> body_bedge_begin;
    /// interior edges joining two boundary nodes, (min, max) ascending (in a composite body: the
    /// central sub-triangle's edges of composites in the special cases; they get a virtual node
    /// only with Split)
    std::vector<std::array<NodeId, 2>> chords;
    std::vector<int32_t> body_chord_begin;
    std::vector<TriId> boundary_tris;  ///< elements with >= 1 boundary node, ascending
    std::vector<int32_t> body_btri_begin;

    /// Contactor sub-triangles (counter-clockwise, contact node ids); those of body b are
    /// [body_sub_begin[b], body_sub_begin[b+1]).
    std::vector<std::array<NodeId, 3>> sub_tri;
    std::vector<BodyId> sub_body;
    /// mesh triangle the sub-triangle was cut from; for a composite fan triangle (which may
    /// cross mesh sub-triangles) the mesh sub-triangle holding its boundary half-edge
    std::vector<TriId> sub_parent;
    std::vector<int32_t> body_sub_begin;

    /// Distinct contact nodes of each body's sub-triangles, for the narrow phase's per-step body
    /// boxes (contact.cpp body_boxes()): those of body b are body_cnode[body_cnode_begin[b] ..
    /// body_cnode_begin[b+1]), its body_cnode_nreal[b] real node ids first (ascending), then its
    /// virtual ones (contact ids, ascending). sub_local[t] = the positions of sub_tri[t]'s
    /// vertices in its body's list (0 = body_cnode_begin[b]). build_body_contact_nodes().
    std::vector<NodeId> body_cnode;
    std::vector<int32_t> body_cnode_begin;
    std::vector<int32_t> body_cnode_nreal;
    std::vector<std::array<int32_t, 3>> sub_local;

    /// Baseline B only (ContactAlgorithm::LegacyBoundary): phi_B per contactor sub-triangle,
    /// parallel to sub_tri (build_legacy_boundary_field(), docs/theory.md §7.4); empty otherwise.
    std::vector<LegacyBoundaryTri> sub_legacy_b;

    /// Sector of real node i (i itself without a weld).
    NodeId weld(NodeId i) const {
        return node_weld.empty() ? i : node_weld[static_cast<size_t>(i)];
    }
    bool welded() const { return !weld_group.empty(); }
    /// body_cnode lists every body's contact nodes (build_body_contact_nodes() ran)
    bool lists_contact_nodes() const {
        return body_cnode_begin.size() == body_sub_begin.size() && body_cnode_begin.size() > 1;
    }
    int32_t num_virtual() const { return static_cast<int32_t>(virt_parent.size()); }
    int32_t num_contact_nodes() const { return num_real_nodes + num_virtual(); }
    int32_t num_sub_tris() const { return static_cast<int32_t>(sub_tri.size()); }
    int32_t num_edge_targets() const { return static_cast<int32_t>(edge_scale.size()); }
    NodeId target_end() const { return edge_target_base + num_edge_targets(); }
};

/// A real node of target t (docs/theory.md §6.12): t itself for a boundary node, the first end
/// node of the edge for an edge target (same body; used for body look-ups and messages).
inline NodeId target_node(const ContactTopology& ct, NodeId t) {
    if (t < ct.num_real_nodes) return t;
    return ct.boundary_edges[static_cast<size_t>(t - ct.edge_target_base)][0];
}

/// Position (or velocity, with v for x) of target t: the node, or the edge midpoint
/// (x_a + x_b) / 2 of an edge target.
inline Vec2 target_point(const ContactTopology& ct, const Vec2* x, NodeId t) {
    if (t < ct.num_real_nodes) return x[t];
    const auto& e = ct.boundary_edges[static_cast<size_t>(t - ct.edge_target_base)];
    return 0.5 * (x[e[0]] + x[e[1]]);
}

/// Force scale of target t: m_j / mbar (eq. 19) or l_j / lbar, with edge targets the node's
/// share of it, or edge_scale of an edge target (eq. 6.19).
inline Real target_scale(const ContactTopology& ct, NodeId t) {
    if (t < ct.num_real_nodes) return ct.node_scale[static_cast<size_t>(t)];
    return ct.edge_scale[static_cast<size_t>(t - ct.edge_target_base)];
}

/// Does body c act as contactor for the boundary nodes of body t? (role rule of
/// ContactModel::two_way). Never true for c == t: a body's self-contact (body_self) is decided
/// per pair by rule_x_allows().
inline bool is_contactor_for(const ContactModel& cm, const ContactTopology& ct, BodyId c,
                             BodyId t) {
    if (c == t) return false;
    const bool fc = ct.body_fixed[static_cast<size_t>(c)] != 0;
    const bool ft = ct.body_fixed[static_cast<size_t>(t)] != 0;
    if (fc && ft) return false;  // two fixed bodies: forces would move nothing
    if (cm.two_way) return true;
    if (fc != ft) return fc;
    return c < t;
}

/// Rule X (docs/theory.md §6.15, spec fracture.md §4.3): may target t act against contactor
/// sub-triangle s of its own body (body_self)? Yes iff no node of s's parent mesh triangle
/// (sub_parent) is in the sector of the target's node (of either end node for an edge target):
/// a node can only reach the triangles around its own vertex through intact-joint compliance,
/// and across a crack the other face's triangles hold other sectors. tri_nodes = Model::tri_nodes.
inline bool rule_x_allows(const ContactTopology& ct, const std::array<NodeId, 3>* tri_nodes,
                          NodeId t, int32_t s) {
    const auto& n = tri_nodes[ct.sub_parent[static_cast<size_t>(s)]];
    const NodeId w0 = ct.weld(n[0]), w1 = ct.weld(n[1]), w2 = ct.weld(n[2]);
    auto touches = [&](NodeId i) {
        const NodeId w = ct.weld(i);
        return w == w0 || w == w1 || w == w2;
    };
    if (t < ct.num_real_nodes) return !touches(t);
    const auto& e = ct.boundary_edges[static_cast<size_t>(t - ct.edge_target_base)];
    return !touches(e[0]) && !touches(e[1]);
}

}  // namespace fdem
