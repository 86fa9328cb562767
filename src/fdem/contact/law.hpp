// The triangle-to-node contact law of Lei et al. 2020 (paper eqs. 5-19, spec §4.5,
// docs/theory.md §6.4-6.6) for one (target node, contactor body) pair, given the field sample.
// Independent of how d and grad d were obtained, so every potential field shares it.
#pragma once

#include <algorithm>
#include <cmath>

#include "fdem/contact_model.hpp"
#include "fdem/contact_state.hpp"
#include "fdem/math.hpp"

namespace fdem {

/// Loading force function g_L(d) = 2 l (d/l)^alpha (eq. 12 made dimensionally sound; theory
/// eq. 6.6). alpha = 1 gives g = 2d, i.e. phi = d^2 (the paper's default potential).
inline Real contact_g(Real d, Real expo, Real l) {
    if (expo == 1) return 2.0 * d;
    return 2.0 * l * std::pow(d / l, expo);
}

/// Integral of contact_g from 0 to d: 2 l^2 (d/l)^(e+1) / (e+1) [m^2] (theory eq. 6.7).
inline Real contact_phi(Real d, Real expo, Real l) {
    if (expo == 1) return d * d;
    return 2.0 * l * l * std::pow(d / l, expo + 1) / (expo + 1);
}

/// Derivative dg/dd (stiffness factor g', theory eq. 6.13).
inline Real contact_dg(Real d, Real expo, Real l) {
    if (expo == 1) return 2.0;
    return 2.0 * expo * std::pow(d / l, expo - 1);
}

/// Result of the law for one pair.
struct LawResult {
    Vec2 f;               ///< total force on the target node, mass-scaled (eq. 19) [N/m]
    Vec2 f_normal;        ///< penalty + damping part (m/mbar)(f_n + f_d) [N/m]
    Vec2 f_tangent;       ///< its friction part (m/mbar) f_t [N/m]
    Vec2 n;               ///< unit normal grad d / |grad d| (eq. 16), into the contactor
    Real stored = 0;      ///< stored energy of the pair now: (m/mbar)(k_n psi + k_t s^2 / 2) [J/m]
    Real dissipated = 0;  ///< energy dissipated by this evaluation [J/m]
};

/// Evaluate the law for depth d >= 0 and gradient grad (field sample), relative velocity
/// v_r = v_c - v_j (v^{n-1/2}), mass scale m_j / mbar, time step dt. Updates the pair history h
/// (h must be value-initialised for a new contact). d is the depth the law sees, d - d0 of a
/// self pair (theory eq. 9.25): d_max, d_prev, the branch and the stored energy are in that
/// measure, and every branch has g = psi = 0 at d = 0, where d0 moves.
///
/// Energy (theory §6.7): 'stored' is the energy the pair returns if it unloads now; the
/// dissipated part is counted from exact state functions (hysteresis loop, return mapping) and
/// from the damping force times the relative displacement dt v_r of the step.
///
/// Always inlined (issue #16): as a call, the two Vec2 arguments arrive in four registers, which
/// GCC stores as doubles and reloads as pairs, a failed store-to-load forwarding each (~1/3 of
/// the function's time on the saturated pack).
[[gnu::always_inline]] inline LawResult contact_law(const ContactParams& p, Real d, Vec2 grad,
                                                    Vec2 v_r, Real scale, Real dt, PairHistory& h) {
    LawResult r;
    const Real kn = p.penalty;
    const Real l = p.length_scale;

    // normal direction (eq. 16) and tangent t = o x n (eq. 15; contactor triangles are CCW)
    const Real gn = norm(grad);
    if (gn > 0) r.n = grad / gn;
    const Vec2 t = perp(r.n);

    // force function g and stored potential psi: loading / unloading (eq. 12, spec §4.5-4)
    Real g = 0, psi = 0, diss = 0;
    if (p.unloading == UnloadingLaw::Continuous) {
        const Real cb = 1.0 / (p.beta + 1);
        if (d >= h.d_max) {
            // loading: g = g_L(d); the loop area up to d_max is lost for good (theory eq. 6.9)
            g = contact_g(d, p.alpha, l);
            psi = g * d * cb;
            const Real loss_new = contact_phi(d, p.alpha, l) - psi;
            const Real loss_old =
                contact_phi(h.d_max, p.alpha, l) - contact_g(h.d_max, p.alpha, l) * h.d_max * cb;
            diss += kn * (loss_new - loss_old);
            h.d_max = d;
        } else {
            // below the previous maximum: g_U(d) = g_L(d_max) (d/d_max)^beta
            const Real gm = contact_g(h.d_max, p.alpha, l);
            const Real ratio = d / h.d_max;
            const Real rb = p.beta == 1 ? ratio : std::pow(ratio, p.beta);
            g = gm * rb;
            psi = gm * h.d_max * rb * ratio * cb;
        }
    } else {
        // literal eq. 12: branch by the sign of the depth rate; a branch switch at depth d
        // drops (or raises) the stored energy from one curve to the other
        const bool unloading = d < h.d_prev;
        if (unloading != (h.unloading != 0)) {
            const Real e_old = h.unloading ? p.beta : p.alpha;
            const Real e_new = unloading ? p.beta : p.alpha;
            diss += kn * (contact_phi(d, e_old, l) - contact_phi(d, e_new, l));
            h.unloading = unloading ? 1 : 0;
        }
        const Real e = h.unloading ? p.beta : p.alpha;
        g = contact_g(d, e, l);
        psi = contact_phi(d, e, l);
        if (d > h.d_max) h.d_max = d;
    }

    // normal force f_n = -k_n g grad d (eqs. 6-8), acting on the target
    const Vec2 fn = (-kn * g) * grad;

    // damping f_d = gamma v_r (eq. 13), optionally its normal part only. No tension (not in
    // the paper; spec §6.2): the normal damping component may cancel the penalty push but never
    // pull the target in, so c_n <= k_n g |grad d|. Dissipation = minus its work on the relative
    // displacement dt v_r = x^n - x^{n-1} of the step, trapezoidal in the force as the
    // central-difference kinetic energy sees it: (f_d^{n-1} + f_d^n) . v_r dt / 2
    // (theory eq. 6.10; f_d^{n-1} = 0 for a new contact).
    Vec2 fd;
    if (p.damping > 0) {
        const Real push = kn * g * gn;  // |f_n|
        const Real vrn = dot(v_r, r.n);
        const Real cn = std::min(p.damping * vrn, push);
        fd = cn * r.n;
        if (!p.damp_normal_only) fd += p.damping * (v_r - vrn * r.n);
        diss += 0.5 * dot(h.f_damp + fd, v_r) * dt;
    }
    h.f_damp = fd;

    // Coulomb friction with a tangential spring and return mapping (eqs. 14, 17)
    const Real kt = p.tangential_penalty;
    Vec2 ft;
    Real s = 0;
    if (p.friction > 0 && kt > 0) {
        const Real s_trial = h.s + dot(v_r, t) * dt;
        const Real cap = p.friction * kn * g * gn;  // mu |f_n|
        s = s_trial;
        if (kt * std::abs(s_trial) > cap) {
            s = std::copysign(cap / kt, s_trial);
            // dissipation = work of the friction force on the relative tangential displacement
            // of the step, s_trial - h.s (trapezoidal in the force, as the central-difference
            // kinetic energy sees it), minus the change of the stored energy k s^2 / 2
            // (theory eq. 6.11): k (h.s + s)(s_trial - s) / 2. It also books the spring
            // energy released when the cap mu |f_n| falls; zero while sticking (s = s_trial).
            diss += 0.5 * kt * (h.s + s) * (s_trial - s);
        }
        ft = (kt * s) * t;
    }
    h.s = s;
    h.d_prev = d;

    // mass scaling (eq. 19)
    r.f_normal = scale * (fn + fd);
    r.f_tangent = scale * ft;
    r.f = r.f_normal + r.f_tangent;
    r.stored = scale * (kn * psi + 0.5 * kt * s * s);
    r.dissipated = scale * diss;
    h.stored = r.stored;
    return r;
}

/// Energy that leaves the books when a pair separates or is lost: its tangential spring, and
/// (if the node was lost with d > 0) the normal part as well; plus the second half of the
/// trapezoidal damping work of the step from the last evaluation to now (theory eq. 6.10),
/// f_d^{n-1} . v_r dt / 2 with v_r ~ f_d^{n-1} / gamma (the pair is no longer located, so its
/// v_r is not known; exact for the uncapped part, O(dt^2) per separation).
inline Real release_energy(const ContactParams& p, const PairHistory& h, Real scale, bool lost,
                           Real dt) {
    const Real damp = p.damping > 0 ? 0.5 * norm2(h.f_damp) / p.damping * dt : 0.0;
    if (lost) return h.stored + scale * damp;
    return scale * (0.5 * p.tangential_penalty * h.s * h.s + damp);
}

}  // namespace fdem
