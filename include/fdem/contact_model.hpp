// Contact parameters of a model (paper §2, spec §4): the law per material pair and the options
// of the contact algorithm, resolved once by finalize_model() and read-only afterwards. The
// contact topology, which can change during a run, is in fdem/contact_topology.hpp.
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

/// Contact parameters of a model. The first block is user input (scenario reader); the second
/// is filled by resolve_contact_params() (called by finalize_model()), after which no field holds
/// a "use the default" value (penalty 0, tangential_penalty < 0, buffer 0, m_bar 0). The contact
/// topology (boundary, virtual nodes, sub-triangles, nodal distances, target scales) is not
/// here: it can change during a run (fracture) and lives in State::topology
/// (fdem/contact_topology.hpp).
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
    /// contactor. Two fixed bodies never interact. See is_contactor_for()
    /// (fdem/contact_topology.hpp).
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

    // ---- resolved (resolve_contact_params) -------------------------------------------------
    /// Laws resolved (every default filled in) per pair of material classes: class 0 = every
    /// material in no override, classes 1..k = the materials named in pair_overrides. Indexed
    /// [class of contactor material * num_classes + class of target material]; (k + 1)^2
    /// entries, so 20 000 materials with a few overrides cost a few entries, not 4e8.
    std::vector<ContactParams> resolved;
    std::vector<int32_t> material_class;  ///< per material
    int32_t num_classes = 0;
    int32_t num_materials = 0;
    Real h_min = 0;  ///< smallest element altitude of the mesh [m]
};

/// Resolved parameters for contactor body material a and target body material b.
inline const ContactParams& pair_parameters(const ContactModel& cm, int32_t a, int32_t b) {
    return cm
        .resolved[static_cast<size_t>(cm.material_class[static_cast<size_t>(a)] * cm.num_classes +
                                      cm.material_class[static_cast<size_t>(b)])];
}

}  // namespace fdem
