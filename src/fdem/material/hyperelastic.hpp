// Compressible neo-Hookean-type law used by the Y code (docs/theory.md §2, spec §3.1):
//   W(F) = (mu/2)(tr C - 2 - 2 ln J) + (lambda/4)(J^2 - 1 - 2 ln J)      (theory eq. 2.1)
//   sigma = (mu/J)(B - I) + (lambda/2)(J - 1/J) I                       (theory eq. 2.2)
// Its small-strain limit is linear elasticity, sigma = 2 mu eps + lambda tr(eps) I.
#pragma once

#include <cmath>

#include "fdem/math.hpp"
#include "fdem/model.hpp"

namespace fdem {

/// Strain energy per unit reference area [J/m^3 * m = J/m^2 per unit thickness] (theory eq. 2.1).
inline Real strain_energy_density(Real lambda, Real mu, const Mat2& F) {
    const Real J = det(F);
    const Real lnJ = std::log(J);
    const Real trC = F.xx * F.xx + F.xy * F.xy + F.yx * F.yx + F.yy * F.yy;
    return 0.5 * mu * (trC - 2.0 - 2.0 * lnJ) + 0.25 * lambda * (J * J - 1.0 - 2.0 * lnJ);
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
