// Compressible neo-Hookean-type law used by the Y code (docs/theory.md §2, spec §3.1):
//   W(F) = (mu/2)(tr C - 2 - 2 ln J) + (lambda/4)(J^2 - 1 - 2 ln J)      (theory eq. 2.1)
//   sigma = (mu/J)(B - I) + (lambda/2)(J - 1/J) I                       (theory eq. 2.2)
// Its small-strain limit is linear elasticity, sigma = 2 mu eps + lambda tr(eps) I.
#pragma once

#include <cmath>

#include "fdem/material.hpp"
#include "fdem/math.hpp"

namespace fdem {

/// Strain energy per unit reference area [J/m^3 * m = J/m^2 per unit thickness] (theory eq. 2.1)
/// from J = det F, tr C and ln J: the SIMD CST kernel (element/cst_simd.cpp) keeps J, tr C and
/// ln J of a group of triangles and calls this, so its energy has the same bits as the F version.
inline Real strain_energy_density(Real lambda, Real mu, Real J, Real trC, Real lnJ) {
    return 0.5 * mu * (trC - 2.0 - 2.0 * lnJ) + 0.25 * lambda * (J * J - 1.0 - 2.0 * lnJ);
}

/// The same with lnJ = std::log(J).
inline Real strain_energy_density(Real lambda, Real mu, Real J, Real trC) {
    return strain_energy_density(lambda, mu, J, trC, std::log(J));
}

/// tr C = tr(F^T F) = sum of the squared entries of F, summed in this order (theory eq. 2.1).
inline Real trace_right_cauchy_green(const Mat2& F) {
    return F.xx * F.xx + F.xy * F.xy + F.yx * F.yx + F.yy * F.yy;
}

/// Strain energy per unit reference area (theory eq. 2.1) from F.
inline Real strain_energy_density(Real lambda, Real mu, const Mat2& F) {
    return strain_energy_density(lambda, mu, det(F), trace_right_cauchy_green(F));
}

/// Elastic Cauchy stress [Pa] (theory eq. 2.2). Symmetric; returned as a full Mat2.
inline Mat2 cauchy_stress(Real lambda, Real mu, const Mat2& F) {
    const Real J = det(F);
    const Mat2 B = F * transpose(F);
    const Real a = mu / J;
    const Real p = 0.5 * lambda * (J - 1.0 / J);
    return {a * (B.xx - 1.0) + p, a * B.xy, a * B.yx, a * (B.yy - 1.0) + p};
}

inline Mat2 cauchy_stress(const Material& mat, const Mat2& F) {
    return cauchy_stress(mat.lambda, mat.mu, F);
}

/// Green-Lagrange strain E = (F^T F - I)/2 (output only).
inline Mat2 green_lagrange(const Mat2& F) {
    const Mat2 C = transpose(F) * F;
    return {0.5 * (C.xx - 1.0), 0.5 * C.xy, 0.5 * C.yx, 0.5 * (C.yy - 1.0)};
}

}  // namespace fdem
