// Contact parameters and the immutable contact topology of a model (paper §2, spec §4).
// The topology (boundary entities, virtual nodes, contactor sub-triangles, nodal distances) is
// derived from the mesh once by build_contact_topology() and never changes during a run.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "fdem/math.hpp"

namespace fdem {

enum class ContactAlgorithm {
    None,            ///< no contact
    Smooth,          ///< Lei et al. 2020: nodal distance field, triangle-to-node (spec §4)
    LegacyTriangle,  ///< Munjiza 2004 per-triangle potential, triangle-to-triangle (spec §1.2)
    LegacyBoundary,  ///< boundary-aware potential of Munjiza et al. 2011 (spec §1.3)
};

enum class UnloadingLaw {
    Continuous,  ///< spec §4.5-4 (default): unloading curve through (d_max, g_L(d_max))
    Literal,     ///< paper eq. 12 as written: g = d^alpha loading, d^beta unloading
};

/// Scale factor of the force on a target node (paper eq. 19 and its alternative,
/// docs/theory.md §6.11).
enum class ContactScaling {
    Mass,    ///< paper eq. 19: f = (m_j / mbar) (...), mbar = smallest element mass (default)
    Length,  ///< f = (l_j / lbar) (...): l_j = half the lengths of node j's boundary edges,
             ///< lbar = smallest boundary edge; a uniform pressure gives a uniform depth
};

/// Contact sub-triangulation of a 6-node composite element (ElementKind::Composite6) that has two
/// (paper case 1, Figs. 7-8) or three (case 2, a body of one composite, Figs. 9-10) of its edges on
/// the body boundary, where some mesh sub-triangles have no inner node (paper §2.4,
/// docs/theory.md §6.1.1). Composites with at most one boundary edge are not affected.
enum class CompositeSpecialCase {
    Fan,    ///< paper option (b) (default): case 1 = fan of four triangles around the mid-node of
            ///< the inner edge; case 2 = fan of six triangles around a virtual node at the
            ///< incenter of the corner triangle. Exact distance for straight-sided elements.
    Split,  ///< paper option (a): ten sub-triangles, virtual nodes n7, n8, n9 at the midpoints of
            ///< the edges of the central sub-triangle (n2, n4, n6)
};

/// Contact law parameters (paper eqs. 5-20). SI units; defaults follow spec §4.5.
/// The force function is g(d) = 2 l (d/l)^alpha while loading (docs/theory.md eq. 6.6), so that
/// alpha = 1 gives the paper's default potential phi = d^2 and a force 2 k_n d.
struct ContactParams {
    Real penalty = 0;               ///< k_n [Pa] (with phi = d^2 the force is 2 k_n d); 0 = 5 E_min
    Real alpha = 1;                 ///< loading exponent of g (eq. 12), >= 1
    Real beta = 1;                  ///< unloading exponent of g (eq. 12), >= alpha
    Real length_scale = 1;          ///< l [m] making g = 2 l (d/l)^alpha dimensionally sound, > 0
    Real damping = 0;               ///< gamma [N s/m^2] of f_d = gamma v_r (eq. 13), >= 0
    bool damp_normal_only = false;  ///< damp only (v_r . n) n instead of the full v_r
    Real friction = 0;              ///< Coulomb coefficient mu [-], >= 0
    Real tangential_penalty =
        -1;  ///< k_t [Pa] (f_t = k_t s); < 0 means 0.1 k_n (resolved at build)
    UnloadingLaw unloading = UnloadingLaw::Continuous;
};

/// Baseline B potential phi_B (spec §1.3, docs/theory.md §7.4) of one contactor sub-triangle,
/// written in the sub-triangle's own barycentric coordinates: phi_B(x) = min_{k < terms}
/// sum_i coef[k][i] N_i(x). Each term is the shape function N_o of the parent mesh triangle for
/// one of its boundary edges; coef[k][i] is its value at sub-triangle vertex i (1/0 at real
/// nodes, 1/2 at chord midpoints, the frozen weight at an incenter), so the expression is exact
/// in the deformed configuration as well.
struct LegacyBoundaryTri {
    int32_t terms = 0;  ///< 0 (vertex-only triangle: phi_B = 0), 1, 2, or 3 (single triangle)
    Real coef[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    Real h_ref = 0;  ///< H_ref of the owning body [m] (amplitude of d_B = H_ref phi_B)
};

/// Contact data of a model. The first block is user input (scenario reader); everything below
/// "derived" is written by build_contact_topology() and is read-only afterwards.
///
/// Node ids used by the contact code: [0, num_real_nodes) are the model's nodes; ids
/// num_real_nodes + v are virtual node v (chord midpoints and single-triangle incenters, spec
/// §4.4; composite special cases, docs/theory.md §6.1.1). A virtual node has no mass and no
/// DOF: its position/velocity is sum_k w_k x_{parent_k} and a force on it goes to the parents
/// with the same weights.
struct ContactModel {
    ContactAlgorithm algorithm = ContactAlgorithm::None;
    ContactParams params;  ///< default for every material pair
    /// law of one ordered material pair (contactor material a, target material b), set by a
    /// [[contact.pair]] entry (the reader adds both orders); pairs without one use `params`
    struct PairOverride {
        int32_t a = 0, b = 0;
        ContactParams params;
    };
    std::vector<PairOverride> pair_overrides;  ///< only the pairs that are set (not n^2)
    Real buffer = 0;                           ///< broad-phase skin b [m]; 0 = 0.2 h_min
    /// true: every body is both contactor and target of every other body (spec §4.5-9).
    /// false (one-way): each pair of bodies is evaluated once. If exactly one of the two is
    /// fixed, the fixed body is the contactor and the free body's boundary nodes are the
    /// targets (a rigid platform under a block); otherwise the lower body index is the
    /// contactor. Two fixed bodies never interact. See is_contactor_for() below.
    bool two_way = true;
    Real m_bar = 0;  ///< smallest element mass [kg/m] over all bodies incl. fixed ones (eq. 19)
    Real deep_ratio_limit = 0.5;  ///< d / (largest nodal distance of the triangle) counted as deep
    ContactScaling scaling = ContactScaling::Mass;  ///< target force scale (eq. 19 or length)
    /// sub-triangulation of composite elements in the paper's special cases (smooth contact only;
    /// baseline B always uses the Split layout, see docs/theory.md §6.1.1)
    CompositeSpecialCase composite_special_case = CompositeSpecialCase::Fan;
    /// Targets at the midpoints of the boundary edges besides the boundary nodes, carrying 2/3
    /// of the nodes' force scale (docs/theory.md §6.12, eq. 6.19; smooth contact only): without
    /// them two faces meeting corner to corner in exactly aligned rows never touch
    bool edge_targets = true;
    /// Bodies overlapping at t = 0 (deeper than 1e-6 h_min): false = an input error at load
    /// (scenario key [contact] initial_overlap = "error"), true = allowed, e.g. an intended
    /// prestress ("allow"). Read by the scenario loader only (docs/theory.md §6.14).
    bool allow_initial_overlap = false;

    // ---- derived (build_contact_topology) -------------------------------------------------
    /// Laws resolved (every default filled in) per pair of material classes: class 0 = every
    /// material in no override, classes 1..k = the materials named in pair_overrides. Indexed
    /// [class of contactor material * num_classes + class of target material]; (k + 1)^2
    /// entries, so 20 000 materials with a few overrides cost a few entries, not 4e8.
    std::vector<ContactParams> resolved;
    std::vector<int32_t> material_class;  ///< per material
    int32_t num_classes = 0;
    int32_t num_materials = 0;
    Real h_min = 0;  ///< smallest element altitude of the mesh [m]

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

    int32_t num_real_nodes = 0;                      ///< = Model::num_nodes()
    std::vector<std::array<NodeId, 3>> virt_parent;  ///< parents of each virtual node
    std::vector<std::array<Real, 3>> virt_weight;    ///< frozen weights (sum 1)

    /// Nodal contact distance [m] (eqs. 1-2 + spec §4.2 fallback), indexed by contact node id
    /// (real then virtual). 0 on boundary nodes; 0 also for inner nodes of non-boundary elements
    /// (they never appear in a contactor triangle).
    std::vector<Real> node_dist;
    /// the boundary edge that gave node_dist (eq. 6.3 candidate or fallback), -1 for boundary
    /// nodes and unused nodes (load-time check of thin bodies, docs/theory.md §6.13)
    std::vector<int32_t> node_dist_edge;
    std::vector<uint8_t> node_on_boundary;  ///< per real node: 1 = boundary node
    int32_t num_fallback_nodes = 0;         ///< nodes whose distance came from the fallback

    std::vector<uint8_t> body_fixed;  ///< per body (copy of Body::fixed for the role rule)

    /// Boundary nodes (targets) of all bodies, ascending ids; those of body b are
    /// [body_bnode_begin[b], body_bnode_begin[b+1]).
    std::vector<NodeId> boundary_nodes;
    std::vector<int32_t> body_bnode_begin;
    /// Boundary edges, oriented as in their (counter-clockwise) triangle: material on the left.
    std::vector<std::array<NodeId, 2>> boundary_edges;
    std::vector<int32_t> body_bedge_begin;
    /// interior edges joining two boundary nodes (in a composite body: the central sub-triangle's
    /// edges of composites in the special cases; they get a virtual node only with Split)
    std::vector<std::array<NodeId, 2>> chords;
    std::vector<TriId> boundary_tris;  ///< elements with >= 1 boundary node

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

    int32_t num_virtual() const { return static_cast<int32_t>(virt_parent.size()); }
    int32_t num_contact_nodes() const { return num_real_nodes + num_virtual(); }
    int32_t num_sub_tris() const { return static_cast<int32_t>(sub_tri.size()); }
    int32_t num_edge_targets() const { return static_cast<int32_t>(edge_scale.size()); }
    NodeId target_end() const { return edge_target_base + num_edge_targets(); }
};

/// A real node of target t (docs/theory.md §6.12): t itself for a boundary node, the first end
/// node of the edge for an edge target (same body; used for body look-ups and messages).
inline NodeId target_node(const ContactModel& cm, NodeId t) {
    if (t < cm.num_real_nodes) return t;
    return cm.boundary_edges[static_cast<size_t>(t - cm.edge_target_base)][0];
}

/// Position (or velocity, with v for x) of target t: the node, or the edge midpoint
/// (x_a + x_b) / 2 of an edge target.
inline Vec2 target_point(const ContactModel& cm, const Vec2* x, NodeId t) {
    if (t < cm.num_real_nodes) return x[t];
    const auto& e = cm.boundary_edges[static_cast<size_t>(t - cm.edge_target_base)];
    return 0.5 * (x[e[0]] + x[e[1]]);
}

/// Force scale of target t: m_j / mbar (eq. 19) or l_j / lbar, with edge targets the node's
/// share of it, or edge_scale of an edge target (eq. 6.19).
inline Real target_scale(const ContactModel& cm, NodeId t) {
    if (t < cm.num_real_nodes) return cm.node_scale[static_cast<size_t>(t)];
    return cm.edge_scale[static_cast<size_t>(t - cm.edge_target_base)];
}

/// Does body c act as contactor for the boundary nodes of body t? (role rule of
/// ContactModel::two_way). Never true for c == t.
inline bool is_contactor_for(const ContactModel& cm, BodyId c, BodyId t) {
    if (c == t) return false;
    const bool fc = cm.body_fixed[static_cast<size_t>(c)] != 0;
    const bool ft = cm.body_fixed[static_cast<size_t>(t)] != 0;
    if (fc && ft) return false;  // two fixed bodies: forces would move nothing
    if (cm.two_way) return true;
    if (fc != ft) return fc;
    return c < t;
}

/// Resolved parameters for contactor body material a and target body material b.
inline const ContactParams& pair_parameters(const ContactModel& cm, int32_t a, int32_t b) {
    return cm
        .resolved[static_cast<size_t>(cm.material_class[static_cast<size_t>(a)] * cm.num_classes +
                                      cm.material_class[static_cast<size_t>(b)])];
}

}  // namespace fdem
