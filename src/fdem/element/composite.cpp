// Six-node composite triangle kernel (docs/theory.md §3.5; spec §3.3; Lei et al. 2016 as
// summarised in paper §2.1). Energy-consistent selective integration: the isochoric energy of
// each sub-triangle plus the volumetric energy of the composite's mean dilatation,
//   W = sum_s A_s0 W_iso(F_s) + A_c0 U(Jbar),  Jbar = A_c / A_c0        (theory eqs. 3.5-3.7)
// so that f_i = sum_s 1/2 (sigma_iso(F_s) + U'(Jbar) I) n_i^s = -dW/dx_i exactly (eq. 3.9).
#include "element/composite.hpp"

#include <cmath>

namespace fdem {

namespace {

/// Deformation gradient and reference area of the four sub-triangles of composite c (first
/// sub-triangle id), the composite's reference area and mean dilatation (theory eq. 3.6).
struct CompositeKinematics {
    Mat2 F[4];
    Real J[4];
    Real area0_c = 0;  ///< A_c0 [m^2]
    Real jbar = 0;     ///< A_c / A_c0
};

inline CompositeKinematics kinematics(const Model& m, const Vec2* x, TriId c) {
    CompositeKinematics k;
    Real area_c = 0;
    for (int s = 0; s < 4; ++s) {
        const TriId t = c + s;
        const auto& n = m.tri_nodes[t];
        k.F[s] = columns(x[n[1]] - x[n[0]], x[n[2]] - x[n[0]]) * m.tri_dm_inv[t];  // eq. 3.1
        k.J[s] = det(k.F[s]);
        k.area0_c += m.tri_area0[t];
        area_c += k.J[s] * m.tri_area0[t];  // A_s = J_s A_s0
    }
    k.jbar = area_c / k.area0_c;
    return k;
}

/// First sub-triangle of the composite that owns sub-triangle t (model.hpp layout).
inline TriId composite_of(const Model& m, TriId t) {
    const TriId b = m.bodies[m.tri_body[t]].tri_begin;
    return b + (t - b) / 4 * 4;
}

template <bool kViscous, bool kEnergy>
void composite_range(const Model& m, const Vec2* __restrict x, const Vec2* __restrict v,
                     Vec2* __restrict f, TriId begin, TriId end, Real kappa, Real mu,
                     ElementPass& out) {
    const auto* __restrict tri = m.tri_nodes.data();
    const Real* __restrict area0 = m.tri_area0.data();
    const Real* __restrict eta = m.tri_eta.data();
    Real energy = 0, power = 0;
    Real min_j = out.min_jacobian;
    TriId min_t = out.min_jacobian_tri;

    for (TriId c = begin; c < end; c += 4) {
        // sub-triangle deformation gradients and the composite's mean dilatation (eq. 3.6)
        const CompositeKinematics k = kinematics(m, x, c);

        // composite pressure p = U'(Jbar) (eq. 3.8); an inverted composite (Jbar <= 0) is
        // reported through min_jacobian by the caller and gets no volumetric force
        const bool vol_ok = k.jbar > 0;
        const Real p = vol_ok ? volumetric_pressure(kappa, k.jbar) : 0.0;
        if constexpr (kEnergy) {
            if (vol_ok) energy += k.area0_c * volumetric_energy_density(kappa, k.jbar);
        }

        for (int s = 0; s < 4; ++s) {
            const TriId t = c + s;
            const auto [a, b, cc] = tri[t];
            const Vec2 xa = x[a], xb = x[b], xc = x[cc];
            const Real J = k.J[s];
            if (J < min_j) {
                min_j = J;
                min_t = t;
            }

            // sigma_s = sigma_iso(F_s) + p I (eq. 3.8); the isochoric part needs J_s > 0
            Mat2 sigma = {p, 0, 0, p};
            if (J > 0) {
                sigma = sigma + isochoric_stress(mu, k.F[s]);
                if constexpr (kEnergy) energy += area0[t] * isochoric_energy_density(mu, k.F[s]);

                // viscous stress eta D of the sub-triangle, as for the CST (theory eq. 2.4)
                if constexpr (kViscous) {
                    if (eta[t] > 0) {
                        const Mat2 D = rate_of_deformation(v, a, b, cc, columns(xb - xa, xc - xa));
                        sigma = sigma + eta[t] * D;
                        power += J * area0[t] * eta[t] * ddot(D, D);
                    }
                }
            }

            // f_i += 1/2 sigma_s n_i^s of sub-triangle s (eq. 3.9, theory eq. 3.3)
            add_triangle_forces(f, a, b, cc, xa, xb, xc, sigma);
        }
    }
    out.strain_energy += energy;
    out.viscous_power += power;
    out.min_jacobian = min_j;
    out.min_jacobian_tri = min_t;
}

}  // namespace

void add_composite_forces(const Model& m, const Vec2* x, const Vec2* v, Vec2* f, TriId begin,
                          TriId end, bool with_energy, ElementPass& out) {
    if (begin >= end) return;
    const Material& mt = m.materials[m.tri_material[begin]];
    const Real kappa = bulk_modulus_2d(mt);
    // eta > 0 exactly when the material has a viscosity or a damping ratio (theory eq. 2.6)
    const bool viscous = mt.viscosity > 0 || mt.damping_ratio > 0;
    if (viscous && with_energy) {
        composite_range<true, true>(m, x, v, f, begin, end, kappa, mt.mu, out);
    } else if (viscous) {
        composite_range<true, false>(m, x, v, f, begin, end, kappa, mt.mu, out);
    } else if (with_energy) {
        composite_range<false, true>(m, x, v, f, begin, end, kappa, mt.mu, out);
    } else {
        composite_range<false, false>(m, x, v, f, begin, end, kappa, mt.mu, out);
    }
}

Real composite_jbar(const Model& m, const Vec2* x, TriId t) {
    return kinematics(m, x, composite_of(m, t)).jbar;
}

Mat2 composite_stress(const Model& m, const Vec2* x, TriId t) {
    const TriId c = composite_of(m, t);
    const CompositeKinematics k = kinematics(m, x, c);
    const Material& mt = m.materials[m.tri_material[t]];
    const Real p = k.jbar > 0 ? volumetric_pressure(bulk_modulus_2d(mt), k.jbar) : 0.0;
    Mat2 sigma = {p, 0, 0, p};
    if (k.J[t - c] > 0) sigma = sigma + isochoric_stress(mt.mu, k.F[t - c]);  // eq. 3.8
    return sigma;
}

}  // namespace fdem
