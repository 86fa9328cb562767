// Six-node composite triangle (Lei et al. 2016) with selective integration: the isochoric part of
// the strain energy per sub-triangle, the volumetric part from the whole composite
// (docs/theory.md §3.5, eqs. 3.5-3.10; spec §3.3). Layout of the sub-triangles: Body contract in
// include/fdem/model.hpp (four consecutive triangles per composite).
#pragma once

#include "element/cst.hpp"
#include "fdem/model.hpp"

namespace fdem {

/// Add the internal forces f_i = sum_s 1/2 sigma_s n_i^s (theory eq. 3.9) of the composite
/// elements whose sub-triangles are [begin, end) to f, serially in triangle order. [begin, end)
/// lies in one Composite6 body, covers whole composites (begin - tri_begin and end - tri_begin
/// multiples of 4) and has one material. sigma_s includes the viscous part eta D of each
/// sub-triangle (theory eq. 2.4) from velocities v. The strain energy (theory eq. 3.5) is summed
/// into out only when with_energy; min_jacobian tracks det F of the sub-triangles.
void add_composite_forces(const Model& m, const Vec2* x, const Vec2* v, Vec2* f, TriId begin,
                          TriId end, bool with_energy, ElementPass& out);

/// True if triangle t is a sub-triangle of a Composite6 body (false for hand-built models whose
/// triangles name no existing body, as some output tests make).
inline bool is_composite_tri(const Model& m, TriId t) {
    const BodyId b = m.tri_body[static_cast<size_t>(t)];
    return b >= 0 && b < m.num_bodies() &&
           m.bodies[static_cast<size_t>(b)].element == ElementKind::Composite6;
}

/// Mean dilatation Jbar = A_c / A_c0 of the composite that owns sub-triangle t (theory eq. 3.6).
Real composite_jbar(const Model& m, const Vec2* x, TriId t);

/// Elastic Cauchy stress [Pa] of sub-triangle t of a Composite6 body: its isochoric stress plus
/// the composite's pressure U'(Jbar) I (theory eq. 3.8), without the viscous part.
Mat2 composite_stress(const Model& m, const Vec2* x, TriId t);

/// Isochoric strain energy per unit reference area, W_iso = (mu/2)(tr C / J - 2) (eq. 3.7).
inline Real isochoric_energy_density(Real mu, const Mat2& F) {
    const Real J = det(F);
    const Real trC = F.xx * F.xx + F.xy * F.xy + F.yx * F.yx + F.yy * F.yy;
    return 0.5 * mu * (trC / J - 2.0);
}

/// Volumetric energy per unit reference area, U = (kappa/4)(J^2 - 1 - 2 ln J) (eq. 3.7).
inline Real volumetric_energy_density(Real kappa, Real J) {
    return 0.25 * kappa * (J * J - 1.0 - 2.0 * std::log(J));
}

/// Pressure p = U'(J) = (kappa/2)(J - 1/J) [Pa] (eq. 3.8).
inline Real volumetric_pressure(Real kappa, Real J) {
    return 0.5 * kappa * (J - 1.0 / J);
}

/// Isochoric Cauchy stress sigma_iso = (mu/J^2)(B - 1/2 tr B I) [Pa], traceless (eq. 3.8).
inline Mat2 isochoric_stress(Real mu, const Mat2& F) {
    const Real J = det(F);
    const Real a = mu / (J * J);
    const Real bxx = F.xx * F.xx + F.xy * F.xy;
    const Real byy = F.yx * F.yx + F.yy * F.yy;
    const Real bxy = F.xx * F.yx + F.xy * F.yy;
    const Real h = 0.5 * (bxx - byy);
    return {a * h, a * bxy, a * bxy, -a * h};
}

/// 2-D bulk modulus kappa = lambda + mu (eq. 3.7): with it the small-strain limit of the split
/// law is Hooke's law sigma = 2 mu eps + lambda tr(eps) I (theory eq. 2.3). lambda is the
/// effective 2-D constant (plane stress: the reduced one, theory eq. 2.5).
inline Real bulk_modulus_2d(const Material& mat) {
    return mat.lambda + mat.mu;
}

}  // namespace fdem
