// Constant-strain triangle kernel (docs/theory.md §3). Reference: Munjiza 2004 §4.6, spec §3.1.
#include "element/cst.hpp"

#include <algorithm>
#include <cmath>

#include "material/hyperelastic.hpp"

namespace fdem {

ElementPass add_internal_forces(const Model& m, const Vec2* x, const Vec2* v, Vec2* f, TriId begin,
                                TriId end) {
    ElementPass out;
    const auto* tri = m.tri_nodes.data();
    const auto* dm_inv = m.tri_dm_inv.data();
    const Real* area0 = m.tri_area0.data();
    const Real* eta = m.tri_eta.data();
    const int32_t* mat = m.tri_material.data();
    const BodyId* body = m.tri_body.data();

    for (TriId t = begin; t < end; ++t) {
        if (m.bodies[body[t]].fixed) continue;
        const auto [a, b, c] = tri[t];
        const Material& mt = m.materials[mat[t]];

        // current edge matrix and deformation gradient (theory eq. 3.1)
        const Vec2 e1 = x[b] - x[a];
        const Vec2 e2 = x[c] - x[a];
        const Mat2 Ds = columns(e1, e2);
        const Mat2 F = Ds * dm_inv[t];
        const Real J = det(F);
        if (J < out.min_jacobian) {
            out.min_jacobian = J;
            out.min_jacobian_tri = t;
        }
        if (!(J > 0)) continue;  // inverted: reported by the caller, no force from a log of < 0

        // elastic Cauchy stress and strain energy (theory eqs. 2.1, 2.2)
        Mat2 sigma = cauchy_stress(mt.lambda, mt.mu, F);
        out.strain_energy += area0[t] * strain_energy_density(mt.lambda, mt.mu, F);

        // viscous stress eta D, D = sym(L), L = [v1-v0, v2-v0] Ds^-1 (theory eq. 2.4)
        if (eta[t] > 0) {
            const Mat2 L = columns(v[b] - v[a], v[c] - v[a]) * inverse(Ds);
            const Real dxy = 0.5 * (L.xy + L.yx);
            const Mat2 D = {L.xx, dxy, dxy, L.yy};
            sigma = sigma + eta[t] * D;
            out.viscous_power += J * area0[t] * eta[t] * ddot(D, D);
        }

        // nodal forces f_i = 1/2 sigma n_i, n_i = outward scaled normal of the edge opposite
        // node i in the current configuration (theory eq. 3.3)
        const Vec2 xa = x[a], xb = x[b], xc = x[c];
        const Vec2 na = {xc.y - xb.y, xb.x - xc.x};
        const Vec2 nb = {xa.y - xc.y, xc.x - xa.x};
        const Vec2 nc = {xb.y - xa.y, xa.x - xb.x};
        f[a] += 0.5 * (sigma * na);
        f[b] += 0.5 * (sigma * nb);
        f[c] += 0.5 * (sigma * nc);
    }
    return out;
}

Real element_critical_dt(const Model& m, TriId t) {
    const auto& n = m.tri_nodes[t];
    const Vec2 p0 = m.node_x0[n[0]], p1 = m.node_x0[n[1]], p2 = m.node_x0[n[2]];
    const Real l01 = norm(p1 - p0), l12 = norm(p2 - p1), l20 = norm(p0 - p2);
    const Real lmax = std::max({l01, l12, l20});
    const Real h_min = 2.0 * m.tri_area0[t] / lmax;  // smallest altitude
    const Material& mt = m.materials[m.tri_material[t]];
    const Real cp = std::sqrt((mt.lambda + 2.0 * mt.mu) / mt.density);
    Real dt = h_min / cp;  // theory eq. 5.3: omega_max ~ 2 c_p / h_min, dt <= 2/omega_max
    // viscous damping lowers the limit: dt <= (2/omega)(sqrt(1+xi^2) - xi), theory eq. 5.4
    const Real eta = m.tri_eta[t];
    if (eta > 0) {
        const Real omega = 2.0 * cp / h_min;
        // damping ratio of the highest mode: xi = eta omega / (2 (lambda + 2 mu))
        const Real xi = eta * omega / (2.0 * (mt.lambda + 2.0 * mt.mu));
        dt *= std::sqrt(1.0 + xi * xi) - xi;
    }
    return dt;
}

}  // namespace fdem
