// Parameters of the cohesive joints of discrete fracture (docs/theory.md §9, spec fracture.md
// §3, §10). Public because a scenario or the Python module will fill them per material; the joint
// arrays and the kernel are internal (src/fdem/fracture/).
#pragma once

#include <cstdint>

#include "fdem/math.hpp"

namespace fdem {

/// Shape z(D) of the softening branch (theory eq. 9.10).
enum class SofteningCurve : uint8_t {
    EvansMarathe,  ///< Evans & Marathe 1968, a, b, c = 0.63, 1.8, 6.0 (Munjiza 2004 p. 240)
    Linear,        ///< z = 1 - D (tests: integral 1/2)
};

/// Length of the softening branch (theory eq. 9.12, spec §3.7).
enum class SofteningLength : uint8_t {
    Exact,     ///< o_r - o_p = G_I/(I_z f_t): the softening branch dissipates exactly G (default)
    Total,     ///< o_r - o_p = (G_I - 2/3 f_t o_p)/(I_z f_t): the whole curve dissipates G
    YGeo,      ///< o_r - o_p = 3 G_I/f_t (Y-Geo): dissipates 3 I_z G = 1.159 G
    Solidity,  ///< o_r - o_p = max(2 o_p, 3 G_I/f_t) (Y, Solidity)
};

/// How damage is remembered (spec §3.8). Only Frozen is implemented: per integration point
/// D_max <- max(D_max, D) and the tractions use z(D_max).
enum class Irreversibility : uint8_t { Frozen };

/// Joint parameters of one material (spec §3.1, §10). Units: Pa, rad, J/m^2.
struct JointMaterial {
    Real tensile_strength = 0;    ///< f_t > 0
    Real cohesion = 0;            ///< c > 0
    Real friction_angle = 0;      ///< phi in [0, pi/2) [rad]
    Real fracture_energy_I = 0;   ///< G_I > 0
    Real fracture_energy_II = 0;  ///< G_II > 0
    Real penalty = 0;             ///< p > 0 (a stress; spec default 10 E)
    Real shear_penalty = 0;       ///< p_s > 0 (spec default p)
    SofteningCurve softening = SofteningCurve::EvansMarathe;
    SofteningLength softening_length = SofteningLength::Exact;
    Irreversibility irreversibility = Irreversibility::Frozen;
    int32_t failure_points = 2;  ///< 1..3 integration points with D >= 1 break the joint
};

/// I_z = integral of z(D) over [0, 1] (theory eq. 9.11): 0.38631 for Evans-Marathe, 1/2 linear.
Real softening_integral(SofteningCurve curve);

/// Effective Young's modulus of a jointed body, E/(1 + c_m E/p) (theory eq. 9.6); c_m = 2 for a
/// structured right-triangle mesh under uniaxial stress with nu = 0.
Real joint_effective_modulus(Real youngs_modulus, Real penalty, Real c_m = 2.0);

/// Largest joint length for which the softening branch is at least 2 o_p long with the "exact"
/// rule: h_max = p G_I / (4 I_z f_t^2) (theory eq. 9.14).
Real joint_max_length(const JointMaterial& jm);

}  // namespace fdem
