// Joint law constants (docs/theory.md §9, spec fracture.md §3).
#include "fracture/joint_law.hpp"

#include <stdexcept>
#include <string>

namespace fdem {

Real softening_integral(SofteningCurve curve) {
    if (curve == SofteningCurve::Linear) return 0.5;
    // eq. 9.11 by composite Simpson on 2^14 intervals: z is smooth on [0, 1], error ~1e-16
    const int n = 1 << 14;
    const Real hq = 1.0 / n;
    Real sum = softening_z(curve, 0.0) + softening_z(curve, 1.0);
    for (int i = 1; i < n; ++i)
        sum += (i % 2 ? 4.0 : 2.0) * softening_z(curve, i * hq);
    return sum * hq / 3.0;
}

Real joint_effective_modulus(Real youngs_modulus, Real penalty, Real c_m) {
    return youngs_modulus / (1.0 + c_m * youngs_modulus / penalty);  // eq. 9.6
}

Real joint_max_length(const JointMaterial& jm) {
    const Real ft = jm.tensile_strength;
    return jm.penalty * jm.fracture_energy_I /
           (4.0 * softening_integral(jm.softening) * ft * ft);  // eq. 9.14
}

JointLaw make_joint_law(const JointMaterial& jm) {
    auto positive = [](Real v, const char* name) {
        if (!(v > 0) || !std::isfinite(v))
            throw std::invalid_argument(std::string("joint material: ") + name +
                                        " must be finite and > 0, got " + std::to_string(v));
    };
    positive(jm.tensile_strength, "tensile_strength");
    positive(jm.cohesion, "cohesion");
    positive(jm.fracture_energy_I, "fracture_energy_I");
    positive(jm.fracture_energy_II, "fracture_energy_II");
    positive(jm.penalty, "penalty");
    positive(jm.shear_penalty, "shear_penalty");
    if (!(jm.friction_angle >= 0 && jm.friction_angle < 0.5 * M_PI))
        throw std::invalid_argument("joint material: friction_angle must be in [0, pi/2), got " +
                                    std::to_string(jm.friction_angle));
    if (jm.failure_points < 1 || jm.failure_points > 3)
        throw std::invalid_argument("joint material: failure_points must be 1, 2 or 3, got " +
                                    std::to_string(jm.failure_points));
    JointLaw L;
    L.ft = jm.tensile_strength;
    L.c = jm.cohesion;
    L.tan_phi = std::tan(jm.friction_angle);
    L.p = jm.penalty;
    L.ps = jm.shear_penalty;
    L.GI = jm.fracture_energy_I;
    L.GII = jm.fracture_energy_II;
    L.Iz = softening_integral(jm.softening);
    L.half_p_over_ft = L.p / (2.0 * L.ft);
    L.half_ps = 0.5 * L.ps;
    L.curve = jm.softening;
    L.length_rule = jm.softening_length;
    L.mixed = jm.mixed_mode;
    L.failure_points = jm.failure_points;
    return L;
}

}  // namespace fdem
