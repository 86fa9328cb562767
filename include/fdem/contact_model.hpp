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

/// Contact law parameters (paper eqs. 5-20). SI units; defaults follow spec §4.5.
struct ContactParams {
    Real penalty = 0;             ///< k_n [Pa] (with phi = d^2 the force is 2 k_n d); 0 = 5 E_min
    Real alpha = 1;               ///< loading exponent of g (eq. 12), >= 1
    Real beta = 1;                ///< unloading exponent of g (eq. 12), >= alpha
    Real length_scale = 1;        ///< l [m] making g = l (d/l)^alpha dimensionally sound
    Real damping = 0;             ///< gamma [N s/m^2] of f_d = gamma v_r (eq. 13)
    bool damp_normal_only = false;///< damp only (v_r . n) n
    Real friction = 0;            ///< Coulomb coefficient mu [-]
    Real tangential_penalty = -1; ///< k_t [Pa/m]; < 0 means 0.1 k_n
    UnloadingLaw unloading = UnloadingLaw::Continuous;
};

struct ContactModel {
    ContactAlgorithm algorithm = ContactAlgorithm::None;
    ContactParams params;                    ///< default for every material pair
    std::vector<ContactParams> pair_params;  ///< num_materials^2, [a * n + b]; symmetric
    Real buffer = 0;                         ///< broad-phase skin b [m]; 0 = 0.2 h_min
    bool two_way = true;                     ///< every body is both contactor and target
    Real m_bar = 0;                          ///< smallest element mass [kg/m] (eq. 19)
};

}  // namespace fdem
