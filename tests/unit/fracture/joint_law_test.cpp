// The joint law at one integration point (docs/theory.md §9, spec fracture.md §3, tests U2, U3).
// Expected values are the spec's formulas written out here, not the code under test.
#include "fracture/joint_law.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

namespace fdem {
namespace {

JointMaterial granite() {
    JointMaterial m;
    m.tensile_strength = 1.0e6;
    m.cohesion = 2.0e6;
    m.friction_angle = 30.0 * M_PI / 180.0;
    m.fracture_energy_I = 100.0;
    m.fracture_energy_II = 200.0;
    m.penalty = 1.0e10;
    m.shear_penalty = 2.0e10;
    return m;
}

// granite() with MixedMode::Proportional, and a point of length h = 0.01 m: o_p = 2 h f_t/p,
// s_p = 2 h c/p_s (eq. 9.4)
JointLaw proportional_granite() {
    JointMaterial m = granite();
    m.mixed_mode = MixedMode::Proportional;
    return make_joint_law(m);
}
constexpr Real kGraniteH = 0.01;
constexpr Real kGraniteOp = 2 * kGraniteH * 1e6 / 1e10, kGraniteSp = 2 * kGraniteH * 2e6 / 2e10;

// Strengths and energies of a radial-path test with penalties of 1e15 Pa: o_p, s_p ~ 1e-5 of the
// softening range, the limit of theory eqs. 9.29 and 9.31.
JointMaterial stiff(Real ft, Real c, Real GI, Real GII, MixedMode mixed = MixedMode::Independent) {
    JointMaterial m;
    m.tensile_strength = ft;
    m.cohesion = c;
    m.friction_angle = 30.0 * M_PI / 180.0;
    m.fracture_energy_I = GI;
    m.fracture_energy_II = GII;
    m.penalty = 1.0e15;
    m.shear_penalty = 1.0e15;
    m.mixed_mode = mixed;
    return m;
}

// U2: z(0) = 1, z(1) = 0, z'(0) = 0, monotone, I_z = 0.386307 (spec eq. 3.8)
TEST(JointLaw, EvansMaratheShape) {
    const auto em = SofteningCurve::EvansMarathe;
    EXPECT_DOUBLE_EQ(softening_z(em, 0.0), 1.0);
    EXPECT_EQ(softening_z(em, 1.0), 0.0);
    // z'(0) = 0: the one-sided difference (z(d) - 1)/d is O(d), Richardson removes that term
    // (if z'(0) were not 0, the quotient would tend to it instead of shrinking like d)
    const auto q = [&](double d) { return (softening_z(em, d) - 1.0) / d; };
    EXPECT_NEAR(q(1e-5) / q(1e-4), 0.1, 1e-3);
    EXPECT_NEAR(q(1e-4) / q(1e-3), 0.1, 1e-2);
    // Richardson r(d) = 2 q(d/2) - q(d) = z'(0) + O(d^2): shrinks like d^2 (round-off 4 eps/d
    // ~ 1e-10 at d = 1e-5), so z'(0) = 0 to below 1e-8
    const auto r = [&](double d) { return 2.0 * q(0.5 * d) - q(d); };
    EXPECT_NEAR(r(1e-5) / r(1e-4), 0.01, 1e-3);
    EXPECT_LT(std::fabs(r(1e-5)), 1e-8) << r(1e-5);
    double prev = 1.0;
    for (int i = 1; i <= 10000; ++i) {
        const double z = softening_z(em, i / 10000.0);
        EXPECT_LE(z, prev) << i;
        prev = z;
    }
    // I_z with the code's quadrature against the spec's value, and an independent Gauss-Legendre
    // (5 points on 1000 panels) against both
    const double Iz = softening_integral(em);
    EXPECT_NEAR(Iz, 0.386307, 1e-6);
    const double gx[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                          0.9061798459386640};
    const double gw[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                          0.2369268850561891, 0.2369268850561891};
    double gl = 0;
    const int np = 1000;
    for (int k = 0; k < np; ++k)
        for (int g = 0; g < 5; ++g)
            gl += 0.5 / np * gw[g] * softening_z(em, (k + 0.5 + 0.5 * gx[g]) / np);
    EXPECT_NEAR(Iz, gl, 1e-13);
    // spec §3.7: the "3G/f" rule dissipates 3 I_z G = 1.159 G in softening
    EXPECT_NEAR(3.0 * Iz, 1.159, 5e-4);
    EXPECT_EQ(softening_integral(SofteningCurve::Linear), 0.5);
    EXPECT_DOUBLE_EQ(softening_z(SofteningCurve::Linear, 0.25), 0.75);
}

// theory §9.4: the cached z(D_max) of joint_point(..., dmax, zmax) gives the bits of evaluating
// z(max(D_max, D)) at every call (the reference, written out here from softening_z), along
// seeded random paths that load past the peak, unload into compression, reload and break, in
// both modes and mixed, for both softening curves. A cache that missed a rise of D_max (or was
// refreshed where it did not rise) would carry a z of another D_max and change sigma and tau.
TEST(JointLaw, CachedSofteningIsTheSameBitsAsEvaluatingItEveryTime) {
    for (const SofteningCurve curve : {SofteningCurve::EvansMarathe, SofteningCurve::Linear}) {
        JointMaterial m = granite();
        m.softening = curve;
        const JointLaw L = make_joint_law(m);
        const double h = 0.01, op = 2 * h * 1e6 / 1e10, sp = 2 * h * 2e6 / 2e10;
        std::mt19937_64 rng(7);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        int rises = 0, frozen = 0;
        for (int path = 0; path < 50; ++path) {
            double dmax = 0, zmax = 1.0;  // cached
            double dref = 0;              // reference
            double o = 0, s = 0;
            for (int step = 0; step < 400; ++step) {
                // a random walk biased to open: o_p and s_p per ~20 steps, unloading on the way
                o += op * (0.08 * u(rng) + 0.03);
                s += sp * (0.08 * u(rng) + (path % 3 == 0 ? 0.0 : 0.02));
                const double d_before = dmax;
                const JointPoint c = joint_point(L, h, 1.0 / h, o, s, dmax, zmax);
                // reference: the law's damage, then z of the raised D_max, every call
                const double D = std::min(1.0, std::sqrt(c.Dn * c.Dn + c.Ds * c.Ds));
                dref = std::max(dref, D);
                const double zr = dref > 0 ? softening_z(curve, dref) : 1.0;
                ASSERT_EQ(std::memcmp(&dmax, &dref, sizeof dref), 0) << path << " " << step;
                ASSERT_EQ(std::memcmp(&c.z, &zr, sizeof zr), 0) << path << " " << step;
                // and the uncached form from the state before the call: the same tractions
                double d2 = d_before;
                const JointPoint r = joint_point(L, h, 1.0 / h, o, s, d2);
                ASSERT_EQ(std::memcmp(&c.sigma, &r.sigma, sizeof r.sigma), 0)
                    << path << " " << step;
                ASSERT_EQ(std::memcmp(&c.tau, &r.tau, sizeof r.tau), 0) << path << " " << step;
                rises += dmax > d_before ? 1 : 0;
                frozen += dmax > 0 && dmax == d_before ? 1 : 0;
            }
        }
        // the paths exercise both: rises of D_max and calls at a frozen D_max > 0
        EXPECT_GT(rises, 1000);
        EXPECT_GT(frozen, 1000);
    }
}

// U3: tractions at a point equal spec eqs. 3.2, 3.4, 3.5 (to 1e-12 relative)
TEST(JointLaw, TractionsMatchSpecFormulas) {
    const JointMaterial m = granite();
    const JointLaw L = make_joint_law(m);
    const double h = 0.01, ft = 1e6, c = 2e6, p = 1e10, ps = 2e10, tphi = std::tan(M_PI / 6);
    const double op = 2 * h * ft / p, sp0 = 2 * h * c / ps;
    auto at = [&](double o, double s) {
        double dmax = 0;
        return joint_point(L, h, 1.0 / h, o, s, dmax);
    };
    // peak normal traction at o = o_p, and the parabola below it
    EXPECT_NEAR(at(op, 0).sigma, ft, 1e-12 * ft);
    for (double xi : {0.1, 0.5, 0.9}) {
        EXPECT_NEAR(at(xi * op, 0).sigma, ft * (2 * xi - xi * xi), 1e-12 * ft);
    }
    // compression penalty p o/h, no damage
    EXPECT_NEAR(at(-0.3 * op, 0).sigma, p * (-0.3 * op) / h, 1e-12 * ft);
    // peak shear traction c at s_p without normal stress, sign follows s
    EXPECT_NEAR(at(0, sp0).tau, c, 1e-12 * c);
    EXPECT_NEAR(at(0, -sp0).tau, -c, 1e-12 * c);
    EXPECT_NEAR(at(0, 0.4 * sp0).tau, c * (0.8 - 0.16), 1e-12 * c);
    // Mohr-Coulomb: under sigma_n < 0 the peak is c + |sigma_n| tan(phi) at s_p(f_s)
    for (double sn : {-5e6, -10e6}) {
        const double o = sn * h / p;
        const double fs = c - sn * tphi;
        const double sp = 2 * h * fs / ps;
        const JointPoint r = at(o, sp);
        EXPECT_NEAR(r.sigma, sn, 1e-12 * std::fabs(sn));
        EXPECT_NEAR(r.tau, c + std::fabs(sn) * tphi, 1e-12 * fs);
        EXPECT_EQ(r.Ds, 0.0);
    }
    // softening: D_n = (o - o_p)/(o_r - o_p), o_r - o_p = G_I/(I_z f_t) (eq. 3.9), sigma = f_t z(D)
    const double Iz = softening_integral(SofteningCurve::EvansMarathe);
    const double range = 100.0 / (Iz * ft);
    double dmax = 0;
    const JointPoint r = joint_point(L, h, 1.0 / h, op + 0.3 * range, 0, dmax);
    EXPECT_NEAR(r.Dn, 0.3, 1e-12);
    EXPECT_NEAR(dmax, 0.3, 1e-12);
    EXPECT_NEAR(r.sigma, ft * softening_z(SofteningCurve::EvansMarathe, 0.3), 1e-12 * ft);
    // mixed: D = sqrt(D_n^2 + D_s^2), shear range G_II/(I_z c)
    const double srange = 200.0 / (Iz * c);
    dmax = 0;
    const JointPoint q = joint_point(L, h, 1.0 / h, op + 0.3 * range, sp0 + 0.4 * srange, dmax);
    EXPECT_NEAR(dmax, 0.5, 1e-12);
    const double z5 = softening_z(SofteningCurve::EvansMarathe, 0.5);
    EXPECT_NEAR(q.sigma, ft * z5, 1e-12 * ft);
    EXPECT_NEAR(q.tau, c * z5, 1e-12 * c);
    // frozen: back inside the elastic range, the tractions keep z(D_max)
    const JointPoint back = joint_point(L, h, 1.0 / h, 0.5 * op, 0.5 * sp0, dmax);
    EXPECT_NEAR(dmax, 0.5, 1e-12);  // unchanged by unloading
    EXPECT_NEAR(back.sigma, ft * z5 * 0.75, 1e-12 * ft);
    EXPECT_NEAR(back.tau, c * z5 * 0.75, 1e-12 * c);
}

// the kernel's branch-free path for intact elastic points gives the general law's bits
TEST(JointLaw, IntactPathSameBitsAsGeneral) {
    const JointLaw L = make_joint_law(granite());
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> U(-1, 1);
    const auto bits = [](double v) {
        uint64_t b;
        std::memcpy(&b, &v, sizeof b);
        return b;
    };
    int inside = 0, outside = 0;
    for (int i = 0; i < 20000; ++i) {
        const double h = 0.01 * (1.5 + U(rng));
        const double op = 2 * h * 1e6 / 1e10, sp = 2 * h * 2e6 / 2e10;
        const double o = (i % 7 == 0 ? 0.0 : 1.3 * op * U(rng) - 0.5 * op);
        const double sl = 2.5 * sp * U(rng);
        JointPoint a;
        const double m = joint_point_intact(L, 1.0 / h, o, sl, a);
        double dmax = 0;
        const JointPoint b = joint_point(L, h, 1.0 / h, o, sl, dmax);
        if (m <= 1.0) {
            ++inside;
            EXPECT_EQ(dmax, 0.0);
            EXPECT_EQ(bits(a.sigma), bits(b.sigma)) << o << " " << sl;
            EXPECT_EQ(bits(a.tau), bits(b.tau)) << o << " " << sl;
            EXPECT_EQ(bits(a.fs), bits(b.fs));
            EXPECT_EQ(b.z, 1.0);
        } else {
            ++outside;
            EXPECT_GT(dmax, 0.0);  // the general law damages exactly when the fast path refuses
        }
    }
    EXPECT_GT(inside, 5000);
    EXPECT_GT(outside, 1000);
}

// Work to break one point along a radial path (o, s) = delta (cos theta, sin theta), the law
// integrated by the trapezoid rule, against theory eq. 9.29 (the tractions are capped per
// component, sigma = f_t z(D), tau = f_s z(D), with D = sqrt(D_n^2 + D_s^2)):
//   W(theta) = (f_t cos + f_s sin) / sqrt((f_t cos / G_I)^2 + (f_s sin / G_II)^2)
// in the limit o_p, s_p -> 0 (here a penalty of 1e15 Pa: o_p / (o_r - o_p) ~ 1e-5). Pure modes
// give G_I and G_II; a mixed path costs more than either mode's share: a joint inclined to the
// opening of a mode-I crack pays this premium (example 10's unstructured beam, theory §9.3a).
TEST(JointLaw, MixedModeWorkOfARadialPath) {
    struct Case {
        Real ft, c, GI, GII;
    };
    // example 10's rock (f_s = 3 f_t, G_II = 5 G_I), and the same strengths and energies in both
    // modes (the control runs of theory §9.3a)
    for (const Case k : {Case{1.0e7, 3.0e7, 25.0, 125.0}, Case{1.0e7, 1.0e7, 25.0, 25.0}}) {
        const JointLaw L = make_joint_law(stiff(k.ft, k.c, k.GI, k.GII));
        const Real h = 1e-3;
        for (const Real deg : {0.0, 10.0, 30.0, 60.0, 90.0}) {
            const Real ca = std::cos(deg * M_PI / 180.0), sa = std::sin(deg * M_PI / 180.0);
            const Real expected =
                (k.ft * ca + k.c * sa) / std::hypot(k.ft * ca / k.GI, k.c * sa / k.GII);
            // the point breaks (D = 1) at delta_c = 1 / sqrt((cos/dO)^2 + (sin/dS)^2),
            // dO = G_I/(I_z f_t), dS = G_II/(I_z f_s) (eq. 9.12); integrate to 1.02 delta_c
            const Real dO = k.GI / (L.Iz * k.ft), dS = k.GII / (L.Iz * k.c);
            const Real delta_c = 1.0 / std::hypot(ca / dO, sa / dS);
            const int n = 200000;
            const Real step = 1.02 * delta_c / n;
            Real dmax = 0, work = 0, f_last = 0;
            for (int i = 0; i <= n; ++i) {
                const Real d = i * step;
                const JointPoint r = joint_point(L, h, 1.0 / h, d * ca, d * sa, dmax);
                const Real f = r.sigma * ca + r.tau * sa;  // traction along the path
                if (i > 0) work += 0.5 * (f + f_last) * step;
                f_last = f;
            }
            SCOPED_TRACE(testing::Message() << "G_II/G_I " << k.GII / k.GI << ", theta " << deg);
            EXPECT_NEAR(work / expected, 1.0, 5e-5);  // measured <= 1.1e-5
            EXPECT_GE(dmax, 1.0);                     // broken at the end of the path
        }
    }
}

// The same radial paths with MixedMode::Proportional (theory eqs. 9.30, 9.31): each mode's
// softened traction is scaled by its share r_n = D_n/K, r_s = D_s/K of the damage (constant along
// a radial path), blended in as w = min(1, K/kMixOnset). With K = D = delta/delta_c on the path,
//   W = delta_c [ I_z (f_t cos r_n + f_s sin r_s) + J_w (f_t cos (1 - r_n) + f_s sin (1 - r_s)) ],
//   J_w = integral over [0, kMixOnset] of (1 - D/kMixOnset) z(D) dD (Simpson here),
// whose first term is eq. 9.31, (G_I u^2 + G_II v^2)/(u^2 + v^2), u = f_t cos/G_I,
// v = f_s sin/G_II. Pure modes give G_I and G_II as the independent law does.
TEST(JointLaw, ProportionalWorkOfARadialPath) {
    struct Case {
        Real ft, c, GI, GII;
    };
    const int nq = 1 << 12;  // Simpson panels for J_w
    Real Jw = 0;
    for (int i = 0; i <= nq; ++i) {
        const Real D = kMixOnset * i / nq;
        const Real wq = (i == 0 || i == nq) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        Jw += wq * (1.0 - D / kMixOnset) * softening_z(SofteningCurve::EvansMarathe, D);
    }
    Jw *= kMixOnset / nq / 3.0;
    for (const Case k : {Case{1.0e7, 3.0e7, 25.0, 125.0}, Case{1.0e7, 1.0e7, 25.0, 25.0}}) {
        const JointLaw L = make_joint_law(stiff(k.ft, k.c, k.GI, k.GII, MixedMode::Proportional));
        const Real h = 1e-3;
        for (const Real deg : {0.0, 5.0, 10.0, 20.0, 30.0, 60.0, 90.0}) {
            const Real ca = std::cos(deg * M_PI / 180.0), sa = std::sin(deg * M_PI / 180.0);
            const Real dO = k.GI / (L.Iz * k.ft), dS = k.GII / (L.Iz * k.c);
            const Real delta_c = 1.0 / std::hypot(ca / dO, sa / dS);
            const Real rn = delta_c * ca / dO, rs = delta_c * sa / dS;
            const Real u = k.ft * ca / k.GI, v = k.c * sa / k.GII;
            const Real share = (k.GI * u * u + k.GII * v * v) / (u * u + v * v);  // eq. 9.31
            EXPECT_NEAR(delta_c * L.Iz * (k.ft * ca * rn + k.c * sa * rs) / share, 1.0, 1e-12);
            const Real expected =
                share + delta_c * Jw * (k.ft * ca * (1.0 - rn) + k.c * sa * (1.0 - rs));
            const int n = 200000;
            const Real step = 1.02 * delta_c / n;
            Real dmax = 0, dn = 0, ds = 0, work = 0, f_last = 0;
            for (int i = 0; i <= n; ++i) {
                const Real d = i * step;
                // eq. 9.30 alone: eq. 9.31 is its work (with eq. 9.32 the two elastic limits,
                // crossed at slightly different delta, take up to 8e-5 of the work off)
                const JointPoint r = joint_point(L, h, 1.0 / h, d * ca, d * sa, dmax, &dn, &ds);
                const Real f = r.sigma * ca + r.tau * sa;  // traction along the path
                if (i > 0) work += 0.5 * (f + f_last) * step;
                f_last = f;
            }
            SCOPED_TRACE(testing::Message() << "G_II/G_I " << k.GII / k.GI << ", theta " << deg);
            EXPECT_NEAR(work / expected, 1.0, 5e-5);
            EXPECT_GE(dmax, 1.0);
            // far below eq. 9.29's premium of the independent law on inclined paths
            const Real premium =
                (k.ft * ca + k.c * sa) / std::hypot(k.ft * ca / k.GI, k.c * sa / k.GII);
            if (deg > 0 && deg < 90) {
                EXPECT_LT(work, premium);
            }
            std::printf(
                "[ radial ] G_II/G_I %.0f theta %4.1f: W/G_I %.5f (eq. 9.31 %.5f, "
                "independent eq. 9.29 %.5f)\n",
                k.GII / k.GI, deg, work / k.GI, share / k.GI, premium / k.GI);
        }
    }
}

// MixedMode::Proportional on a pure mode (s = 0, or o = 0) gives the bits of the independent law:
// the share of the loaded mode is exactly 1 (sqrt(dn^2) = dn), the other mode's traction is 0.
// Random loading, unloading and reloading paths of one point, both modes.
TEST(JointLaw, ProportionalPureModesKeepTheIndependentBits) {
    JointMaterial mi = granite();
    JointMaterial mp = granite();
    mp.mixed_mode = MixedMode::Proportional;
    const JointLaw Li = make_joint_law(mi), Lp = make_joint_law(mp);
    const Real h = 0.01;
    const Real op = 2 * h * 1e6 / 1e10, sp = 2 * h * 2e6 / 2e10;
    const auto bits = [](double v) {
        uint64_t b;
        std::memcpy(&b, &v, sizeof b);
        return b;
    };
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> U(0, 1);
    for (int mode = 0; mode < 2; ++mode) {
        for (int path = 0; path < 20; ++path) {
            Real di = 0, dp = 0, dn = 0, ds = 0, an = 1, as = 1, amp = 0;
            int damaged = 0;
            for (int i = 0; i < 400; ++i) {
                amp = std::max(amp, 0.0) + (U(rng) - 0.35) * 40 * (mode == 0 ? op : sp);
                const Real a = std::max(amp, -0.5 * op);
                const Real o = mode == 0 ? a : 0.0, s = mode == 0 ? 0.0 : (i % 2 ? a : -a);
                const JointPoint ri = joint_point(Li, h, 1.0 / h, o, s, di);
                const JointPoint rp = joint_point(Lp, h, 1.0 / h, o, s, dp, &dn, &ds, &an, &as);
                ASSERT_EQ(bits(ri.sigma), bits(rp.sigma)) << mode << " " << i;
                ASSERT_EQ(bits(ri.tau), bits(rp.tau)) << mode << " " << i;
                ASSERT_EQ(bits(di), bits(dp));
                ASSERT_EQ(bits(joint_point_energy(Li, h, o, s, ri)),
                          bits(joint_point_energy(Lp, h, o, s, rp)));
                damaged += dp > 0;
            }
            EXPECT_GT(damaged, 0);
            EXPECT_EQ(mode == 0 ? ds : dn, 0.0);
        }
    }
}

// Eq. 9.32: the tractions use the smallest shares a point has had. Path: slip into the shear
// softening branch (D_s = 0.04, o = 0) and back to s = 0, then open into the normal softening
// branch (D_n up to 0.1), then close. With the shares of eq. 9.30 alone, a_n rises from 0.2 to
// 0.93 while the point opens, which raises the stored energy of eq. 9.18 at a fixed separation
// faster than z(D_max) lowers it (the slip's energy, whose share falls, was given back when it
// unloaded): the dissipation W - psi falls, i.e. the joint gives back energy it never received
// (the expanding ring of example 11 at 300 1/s ended with W_frac = -63 J/m).
// With eq. 9.32 the dissipation never falls on this path or on random mixed paths. Work by the
// trapezoidal rule over 3 x 20 000 steps; psi by joint_point_energy (eq. 9.18).
TEST(JointLaw, ProportionalSharesNeverRise) {
    const JointLaw L = proportional_granite();
    const Real h = kGraniteH, op = kGraniteOp, sp = kGraniteSp;
    const Real dO = 100.0 / (L.Iz * 1e6), dS = 200.0 / (L.Iz * 2e6);  // eq. 9.12, "exact"
    // the largest fall of the dissipation below its running maximum (0: it never falls) and
    // W - psi at the end of the path
    const auto run = [&](bool monotone, const auto& path, int n, Real& end) {
        Real dmax = 0, dn = 0, ds = 0, an = 1, as = 1;
        Real W = 0, o0 = 0, s0 = 0, sig0 = 0, tau0 = 0, diss0 = 0, peak = 0, fall = 0;
        for (int i = 1; i <= n; ++i) {
            Real o, s;
            path(i, o, s);
            const JointPoint r = joint_point(L, h, 1.0 / h, o, s, dmax, &dn, &ds,
                                             monotone ? &an : nullptr, monotone ? &as : nullptr);
            W += 0.5 * (sig0 + r.sigma) * (o - o0) + 0.5 * (tau0 + r.tau) * (s - s0);
            const Real diss = W - joint_point_energy(L, h, o, s, r);
            peak = std::max(peak, diss);
            fall = std::max(fall, peak - diss);
            diss0 = diss;
            o0 = o;
            s0 = s;
            sig0 = r.sigma;
            tau0 = r.tau;
        }
        end = diss0;
        return fall;
    };
    const int n = 20000;
    // D_s = 0.8 K_w < K_w: a_n = 1 - K/K_w = 0.2 after the slip; the opening to D_n = 2 K_w raises
    // it to D_n/K = 0.93 while a_n z(D_max) rises (K_w = 0.2: from 0.2 z(0.16) = 0.15 to
    // 0.93 z(0.43) = 0.35)
    const Real s1 = sp + 0.8 * kMixOnset * dS, o1 = op + 2.0 * kMixOnset * dO;
    const auto path = [&](int i, Real& o, Real& s) {
        const int k = std::min((i - 1) / n, 2);  // phase 0, 1, 2 over steps 1..n, ..., 2n+1..3n
        const Real t = static_cast<Real>(i - k * n) / n;
        if (k == 0) {
            o = 0, s = s1 * (t <= 0.5 ? 2 * t : 2 - 2 * t);
        } else if (k == 1) {
            o = o1 * t, s = 0;
        } else {
            o = o1 * (1 - t), s = 0;
        }
    };
    Real end_raw = 0, end_mono = 0;
    const Real fall_raw = run(false, path, 3 * n, end_raw);
    const Real fall_mono = run(true, path, 3 * n, end_mono);
    const Real scale = 1e6 * dO;  // f_t times the normal softening range [J/m^2]
    std::printf(
        "[ shares ] fall of W - psi / (f_t dO): eq. 9.30 alone %.4f, with eq. 9.32 %.2e; "
        "at the end %.4f / %.4f\n",
        fall_raw / scale, fall_mono / scale, end_raw / scale, end_mono / scale);
    // the trapezoidal rule's own error on the cubic psi of the pre-peak branch is ~1e-6 f_t dO
    // at these steps (it falls 4x when they halve); the rising shares' giving back is 0.029
    // (K_w = 0.2; 0.019 with K_w = 0.05, where the joint also ended with W - psi < 0; at K_w = 0.2
    // the slip to 0.8 K_w dissipates more than the rising share gives back, so the end stays > 0
    // for every slip up to 0.95 K_w tried: the fall below the running maximum is the property)
    EXPECT_GT(fall_raw, 0.01 * scale);  // the path does expose rising shares
    EXPECT_LE(fall_mono, 1e-7 * scale);
    EXPECT_GT(end_mono, 0.0);
    // random mixed loading, unloading and reloading in tension, both slip signs (with o < 0 the
    // shear strength f_s = c - sigma_c tan(phi) of eq. 9.7 depends on the opening, which no stored
    // energy of (o, s) accounts for: a compression-slip cycle can do net work at a fixed history
    // under either rule, so that is not this test's property)
    int raw_falls = 0;  // random paths on which eq. 9.30 alone gives energy back
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> U(-1, 1);
    for (int trial = 0; trial < 20; ++trial) {
        Real ko[9], ks[9];
        for (int k = 0; k < 9; ++k)
            ko[k] = (0.5 + 0.5 * U(rng)) * (op + 0.6 * dO), ks[k] = U(rng) * (sp + 0.6 * dS);
        ko[0] = ks[0] = 0;
        const int seg = 4000;
        const auto rpath = [&](int i, Real& o, Real& s) {
            const int k = std::min(i / seg, 7);
            const Real t = static_cast<Real>(i - k * seg) / seg;
            o = ko[k] + (ko[k + 1] - ko[k]) * t;
            s = ks[k] + (ks[k + 1] - ks[k]) * t;
        };
        Real end = 0;
        const Real fall = run(true, rpath, 8 * seg, end);
        EXPECT_LE(fall, 1e-5 * scale) << "trial " << trial;
        raw_falls += run(false, rpath, 8 * seg, end) > 1e-3 * scale;
    }
    std::printf(
        "[ shares ] random tensile paths where eq. 9.30 alone gives energy back: %d of 20\n",
        raw_falls);
}

// The shares are blended in from 1 (eq. 9.30), so the tractions are continuous through the onset
// of damage on a mixed path: the largest change of either traction between neighbouring points of
// a path through the onset halves when the spacing halves (a jump would not shrink). Without the
// blend (w = 1 at once) the shear traction of this path would drop from 0.98 c to 0 in one step
// when o crosses o_p.
TEST(JointLaw, ProportionalIsContinuousThroughTheOnset) {
    const JointLaw L = proportional_granite();
    const Real h = kGraniteH, op = kGraniteOp, sp = kGraniteSp;
    const Real dO = 100.0 / (L.Iz * 1e6);
    // slip held at 0.85 s_p (pre-peak shear), opening from 0.5 o_p to o_p + 0.2 dO: the onset of
    // normal damage at o = o_p with the shear in its elastic branch, then D_n up to 0.2
    auto largest_jump = [&](int n) {
        Real dmax = 0, dn = 0, ds = 0, an = 1, as = 1, jump = 0, sig_last = 0, tau_last = 0;
        for (int i = 0; i <= n; ++i) {
            const Real o = 0.5 * op + (0.5 * op + 0.2 * dO) * i / n;
            const JointPoint r = joint_point(L, h, 1.0 / h, o, 0.85 * sp, dmax, &dn, &ds, &an, &as);
            if (i > 0)
                jump = std::max(
                    {jump, std::fabs(r.sigma - sig_last) / 1e6, std::fabs(r.tau - tau_last) / 2e6});
            sig_last = r.sigma;
            tau_last = r.tau;
        }
        EXPECT_GT(dn, 0.19);
        EXPECT_EQ(ds, 0.0);
        return jump;
    };
    const Real j1 = largest_jump(2000), j2 = largest_jump(4000), j3 = largest_jump(8000);
    std::printf("[ onset ] largest traction change per step / strength: %.3e %.3e %.3e\n", j1, j2,
                j3);
    EXPECT_LT(j1, 0.05);
    EXPECT_NEAR(j2 / j1, 0.5, 0.05);
    EXPECT_NEAR(j3 / j2, 0.5, 0.05);
}

TEST(JointLaw, SofteningLengthRules) {
    JointMaterial m = granite();
    const double ft = 1e6, G = 100.0, op = 2e-6;
    const double Iz = softening_integral(SofteningCurve::EvansMarathe);
    m.softening_length = SofteningLength::Exact;
    EXPECT_NEAR(softening_range(make_joint_law(m), ft, G, op), G / (Iz * ft), 1e-15);
    m.softening_length = SofteningLength::Total;
    EXPECT_NEAR(softening_range(make_joint_law(m), ft, G, op), (G - 2.0 / 3 * ft * op) / (Iz * ft),
                1e-15);
    m.softening_length = SofteningLength::YGeo;
    EXPECT_NEAR(softening_range(make_joint_law(m), ft, G, op), 3 * G / ft, 1e-15);
    m.softening_length = SofteningLength::Solidity;
    EXPECT_NEAR(softening_range(make_joint_law(m), ft, G, op), 3 * G / ft, 1e-15);
    EXPECT_NEAR(softening_range(make_joint_law(m), ft, G, 1e-3), 2e-3, 1e-15);
}

TEST(JointLaw, RejectsBadParameters) {
    JointMaterial m = granite();
    m.cohesion = 0;
    EXPECT_THROW(make_joint_law(m), std::invalid_argument);
    m = granite();
    m.friction_angle = 0.5 * M_PI;
    EXPECT_THROW(make_joint_law(m), std::invalid_argument);
    m = granite();
    m.failure_points = 4;
    EXPECT_THROW(make_joint_law(m), std::invalid_argument);
    m = granite();
    m.penalty = std::nan("");
    EXPECT_THROW(make_joint_law(m), std::invalid_argument);
}

// spec §3.3 (eq. 3.3) and §3.7 (eq. 3.11) numbers
TEST(JointLaw, EffectiveModulusAndMaxLength) {
    const double E = 5e10;
    EXPECT_NEAR(joint_effective_modulus(E, 10 * E) / E - 1, -0.17, 0.005);
    EXPECT_NEAR(joint_effective_modulus(E, 50 * E) / E - 1, -0.04, 0.005);
    EXPECT_NEAR(joint_effective_modulus(E, 100 * E) / E - 1, -0.02, 0.005);
    EXPECT_DOUBLE_EQ(joint_effective_modulus(E, 10 * E), E / 1.2);
    const JointMaterial m = granite();
    EXPECT_NEAR(joint_max_length(m) / (m.penalty * m.fracture_energy_I / 1e12), 0.647, 5e-4);
}

}  // namespace
}  // namespace fdem
