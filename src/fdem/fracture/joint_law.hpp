// Constitutive law of a cohesive joint at one integration point (docs/theory.md §9, spec
// fracture.md §3): normal and shear tractions from the opening o and slip s, damage, softening,
// irreversibility (frozen D_max) and the stored energy. Inline: the joint kernel
// (fracture/joints.cpp) and the tests call the same code.
#pragma once

#include <algorithm>
#include <cmath>

#include "fdem/assert.hpp"
#include "fdem/fracture.hpp"

namespace fdem {

/// Validated derived constants; throws std::invalid_argument naming the bad parameter.
JointLaw make_joint_law(const JointMaterial& jm);

/// Evans-Marathe constants a, b, c (theory eq. 9.10).
inline constexpr Real kEmA = 0.63, kEmB = 1.8, kEmC = 6.0;

/// Softening function z(D) for D in [0, 1] (theory eq. 9.10); D is clamped to [0, 1] first, so
/// pow never sees a negative base (spec §9).
inline Real softening_z(SofteningCurve curve, Real D) {
    D = std::clamp(D, Real(0), Real(1));
    if (curve == SofteningCurve::Linear) return 1.0 - D;
    const Real a = kEmA, b = kEmB, c = kEmC;
    const Real e = std::exp(D * (a + c * b) / ((a + b) * (1.0 - a - b)));
    return (1.0 - ((a + b - 1.0) / (a + b)) * e) * (a * (1.0 - D) + b * std::pow(1.0 - D, c));
}

/// Length of the softening branch r - peak for strength f, energy G and elastic limit `peak`
/// (o_p or s_p), by the material's rule (theory eq. 9.12).
inline Real softening_range(const JointLaw& L, Real f, Real G, Real peak) {
    switch (L.length_rule) {
        case SofteningLength::Exact:
            return G / (L.Iz * f);
        case SofteningLength::Total:
            return (G - (2.0 / 3.0) * f * peak) / (L.Iz * f);
        case SofteningLength::YGeo:
            return 3.0 * G / f;
        case SofteningLength::Solidity:
            return std::max(2.0 * peak, 3.0 * G / f);
    }
    return G / (L.Iz * f);
}

/// Tractions and damage of one integration point.
struct JointPoint {
    Real sigma = 0;  ///< normal traction, tension > 0 [Pa] (eq. 9.5)
    Real tau = 0;    ///< shear traction along e [Pa] (eq. 9.8)
    Real Dn = 0;     ///< normal damage <o - o_p>/(o_r - o_p) (eq. 9.9), not clamped
    Real Ds = 0;     ///< shear damage <|s| - s_p>/(s_r - s_p) (eq. 9.9), not clamped
    Real z = 1;      ///< z(D_max) used for the tractions
    Real fs = 0;     ///< shear strength f_s (eq. 9.7)
    Real a_n = 1;    ///< share of the tensile traction (eq. 9.30; 1 with MixedMode::Independent)
    Real a_s = 1;    ///< share of the shear traction (eq. 9.30; 1 with MixedMode::Independent)
};

/// Shares a_n, a_s of MixedMode::Proportional from the largest damage of each mode reached at a
/// point (theory eq. 9.30): with K = sqrt(dn^2 + ds^2) and w = min(1, K/kMixOnset),
/// a_n = 1 - w (1 - dn/K), a_s = 1 - w (1 - ds/K); both 1 at K = 0. A pure mode keeps its own
/// share at exactly 1 (sqrt(dn^2) = dn), so its traction has the bits of MixedMode::Independent.
/// an_min, as_min (null: not applied): the smallest shares the point has had, lowered to these
/// and used instead of them (eq. 9.32). dn/K rises when the opening's damage grows after the
/// slip's (or the converse); a share that rose would raise the stored energy of eq. 9.18 at a
/// fixed separation, i.e. the joint would give back energy it never received (theory §9.3b).
inline void mixed_mode_shares(Real dn, Real ds, JointPoint& r, Real* an_min = nullptr,
                              Real* as_min = nullptr) {
    const Real K = std::sqrt(dn * dn + ds * ds);
    if (K > 0) {  // (no damage yet, or below sqrt of the smallest double: shares 1)
        const Real w = std::min(Real(1), K / kMixOnset);
        r.a_n = 1.0 - w * (1.0 - dn / K);
        r.a_s = 1.0 - w * (1.0 - ds / K);
    }
    if (an_min != nullptr) {  // eq. 9.32 (NaN shares: the history unchanged)
        if (r.a_n < *an_min) *an_min = r.a_n;
        if (r.a_s < *as_min) *as_min = r.a_s;
        r.a_n = *an_min;
        r.a_s = *as_min;
    }
}

/// The law at one point of a joint of current length h (theory eqs. 9.4-9.10): opening o, slip s;
/// dmax (frozen irreversibility, spec §3.8) is raised to the current D. The intact elastic case
/// (dmax = 0, o <= o_p, |s| <= s_p) takes no exp/pow/sqrt. zmax caches z(dmax): it must hold
/// softening_z(L.curve, dmax) where dmax > 0 on entry (any value where dmax = 0) and does so on
/// return; z (an exp and a pow, ~15 % of a fracturing run's step when evaluated at every point of
/// every damaged joint on every step) is evaluated only where dmax rises. The same bits as
/// evaluating z(max(dmax, D)) every time: the same function of the same value.
/// dn_max, ds_max (MixedMode::Proportional only; null otherwise): the point's largest D_n and
/// D_s so far, raised to the current ones, from which the shares a_n, a_s scale the tensile and
/// shear tractions (theory eq. 9.30; the compressive penalty is never scaled); an_min, as_min
/// (with them, or null): the smallest shares so far, which the tractions use (eq. 9.32).
inline JointPoint joint_point(const JointLaw& L, Real h, Real inv_h, Real o, Real s, Real& dmax,
                              Real& zmax, Real* dn_max = nullptr, Real* ds_max = nullptr,
                              Real* an_min = nullptr, Real* as_min = nullptr) {
    JointPoint r;
    bool raised = false;  // dn_max or ds_max rose here
    // eq. 9.5, compressive branch, and eq. 9.7: f_s from the current sigma_c = p o/h
    Real sigma_c = 0;
    if (o < 0) {
        sigma_c = L.p * o * inv_h;
        r.fs = L.c - sigma_c * L.tan_phi;
    } else {
        r.fs = L.c;
    }
    const Real inv_sp = (L.half_ps * inv_h) / r.fs;  // 1/s_p = p_s/(2 h f_s) (eq. 9.4)
    const Real xi = o * L.half_p_over_ft * inv_h;    // o/o_p, eq. 9.4
    const Real abs_s = std::fabs(s);
    const Real eta = abs_s * inv_sp;  // |s|/s_p
    if (xi > 1.0 || eta > 1.0) {
        // eq. 9.9: damage of each mode beyond its elastic limit, combined
        if (xi > 1.0) {
            const Real op = 2.0 * h * L.ft / L.p;
            r.Dn = std::max(Real(0), (o - op) / softening_range(L, L.ft, L.GI, op));
        }
        if (eta > 1.0) {
            const Real sp = 2.0 * h * r.fs / L.ps;
            r.Ds = std::max(Real(0), (abs_s - sp) / softening_range(L, r.fs, L.GII, sp));
        }
        const Real D = std::min(Real(1), std::sqrt(r.Dn * r.Dn + r.Ds * r.Ds));
        // dmax = max(dmax, D) (equal or NaN D: dmax unchanged, as std::max keeps its first)
        if (dmax < D) {
            dmax = D;
            zmax = softening_z(L.curve, D);
        }
        if (dn_max != nullptr) {  // eq. 9.30: each mode's largest damage (NaN: unchanged)
            if (*dn_max < r.Dn) *dn_max = r.Dn, raised = true;
            if (*ds_max < r.Ds) *ds_max = r.Ds, raised = true;
        }
    }
    r.z = dmax > 0 ? zmax : 1.0;
    if (dn_max != nullptr) {
        if (raised || an_min == nullptr) {
            mixed_mode_shares(*dn_max, *ds_max, r, an_min, as_min);
        } else {
            // dn_max, ds_max as when their shares were last lowered into an_min, as_min (every
            // call folds them in, and the history starts at 0, 0 with shares 1): the shares of
            // eq. 9.32 are the kept minima, as mixed_mode_shares() would return (a sqrt and
            // three divisions per point of every damaged joint on every step, saved)
            if constexpr (kAssertsEnabled) {
                JointPoint q = r;
                Real an = *an_min, as = *as_min;
                mixed_mode_shares(*dn_max, *ds_max, q, &an, &as);
                FDEM_ASSERT((q.a_n == *an_min || (q.a_n != q.a_n && *an_min != *an_min)) &&
                                (q.a_s == *as_min || (q.a_s != q.a_s && *as_min != *as_min)),
                            "the kept shares of a joint point are not those of its damage");
            }
            r.a_n = *an_min;
            r.a_s = *as_min;
        }
    }
    // eq. 9.5: compression penalty, parabolic hardening, softening plateau scaled by z(D_max)
    // (and by the tensile share a_n of eq. 9.30: 1 unless MixedMode::Proportional)
    if (o < 0) {
        r.sigma = sigma_c;
    } else if (xi <= 1.0) {
        r.sigma = L.ft * r.z * (xi * (2.0 - xi)) * r.a_n;
    } else {
        r.sigma = L.ft * r.z * r.a_n;
    }
    // eq. 9.8 (times the shear share a_s of eq. 9.30)
    const Real mag = eta <= 1.0 ? r.fs * r.z * (eta * (2.0 - eta)) * r.a_s : r.fs * r.z * r.a_s;
    r.tau = std::copysign(mag, s);
    return r;
}

/// The same without a cache (tests, reference): z(dmax) evaluated here.
inline JointPoint joint_point(const JointLaw& L, Real h, Real inv_h, Real o, Real s, Real& dmax,
                              Real* dn_max = nullptr, Real* ds_max = nullptr,
                              Real* an_min = nullptr, Real* as_min = nullptr) {
    Real zmax = dmax > 0 ? softening_z(L.curve, dmax) : 1.0;
    return joint_point(L, h, inv_h, o, s, dmax, zmax, dn_max, ds_max, an_min, as_min);
}

/// Intact point in its elastic range: the same arithmetic as joint_point with dmax = 0 (same
/// bits), without branches; fills r (z = 1) and returns max(o/o_p, |s|/s_p). The result is
/// valid only when that is <= 1 (otherwise call joint_point).
inline Real joint_point_intact(const JointLaw& L, Real inv_h, Real o, Real s, JointPoint& r) {
    const Real sigma_c = L.p * std::min(o, Real(0)) * inv_h;  // eq. 9.5, o < 0; else 0
    r.fs = L.c - sigma_c * L.tan_phi;                         // eq. 9.7 (= c for o >= 0)
    const Real inv_sp = (L.half_ps * inv_h) / r.fs;           // eq. 9.4
    const Real xi = std::max(o, Real(0)) * L.half_p_over_ft * inv_h;
    const Real eta = std::fabs(s) * inv_sp;
    r.sigma = sigma_c + L.ft * (xi * (2.0 - xi));          // one of the two terms is 0
    r.tau = std::copysign(r.fs * (eta * (2.0 - eta)), s);  // eq. 9.8, z = 1
    r.z = 1;
    r.Dn = r.Ds = 0;
    return std::max(xi, eta);
}

/// Stored (recoverable at fixed D_max) energy per unit length of a point (theory eq. 9.18):
/// psi_n + psi_s from the same o, s, h and the point's z, f_s and shares a_n, a_s (eq. 9.30: at
/// a fixed history the shares are constants, so the law stays the derivative of this energy).
inline Real joint_point_energy(const JointLaw& L, Real h, Real o, Real s, const JointPoint& r) {
    Real psi;
    if (o < 0) {
        psi = 0.5 * L.p * o * o / h;
    } else {
        const Real op = 2.0 * h * L.ft / L.p;
        const Real xi = o / op;
        psi = xi <= 1.0 ? r.z * L.ft * op * (xi * xi - xi * xi * xi / 3.0)
                        : r.z * L.ft * ((2.0 / 3.0) * op + (o - op));
        psi *= r.a_n;
    }
    const Real sp = 2.0 * h * r.fs / L.ps;
    const Real abs_s = std::fabs(s);
    const Real eta = abs_s / sp;
    psi += r.a_s * (eta <= 1.0 ? r.z * r.fs * sp * (eta * eta - eta * eta * eta / 3.0)
                               : r.z * r.fs * ((2.0 / 3.0) * sp + (abs_s - sp)));
    return psi;
}

}  // namespace fdem
