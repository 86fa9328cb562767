// The joint kernel (docs/theory.md §9; spec fracture.md §2, §3, §5, §6, tests U1, U3, U4, U8, V1,
// V2 at the level of one joint driven kinematically). Expected numbers come from the spec's
// formulas written out here.
#include "fracture/joints.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "fdem/error.hpp"
#include "fdem/mesh.hpp"
#include "fracture/joint_mesh.hpp"

namespace fdem {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kH = 0.01, kFt = 1e6, kC = 2e6, kP = 1e10, kPs = 1e10, kGI = 100, kGII = 200;

JointMaterial material(SofteningLength rule = SofteningLength::Exact,
                       MixedMode mixed = MixedMode::Independent) {
    JointMaterial m;
    m.mixed_mode = mixed;
    m.tensile_strength = kFt;
    m.cohesion = kC;
    m.friction_angle = 30.0 * M_PI / 180.0;
    m.fracture_energy_I = kGI;
    m.fracture_energy_II = kGII;
    m.penalty = kP;
    m.shear_penalty = kPs;
    m.softening_length = rule;
    return m;
}

// One joint along x of length kH: A (nodes 0, 1) above, B (nodes 3, 2) below; e = (1, 0),
// n = (0, 1). B stays; A is driven by (slip s, opening o).
struct OneJoint {
    Joints J;
    JointState s;
    std::vector<Vec2> x{{0, 0}, {kH, 0}, {kH, 0}, {0, 0}};
    std::vector<Vec2> f = std::vector<Vec2>(4);
    explicit OneJoint(const JointMaterial& m) {
        J.nodes.push_back({0, 1, 2, 3});
        J.length0.push_back(kH);
        J.law.push_back(0);
        J.laws.push_back(make_joint_law(m));
        finalize_joints(J, 4);
        s = make_joint_state(J);
    }
    // move A to (s, o), evaluate; forces into f (zeroed first)
    JointPass at(double slip, double open, bool energy = false) {
        x[0] = {slip, open};
        x[1] = {kH + slip, open};
        for (auto& v : f)
            v = {0, 0};
        return joint_forces(J, s, x, f, energy);
    }
    // tractions recovered from the forces of a uniform separation: f0 = -(h/2)(sigma n + tau e)
    double sigma() const { return -2.0 * f[0].y / kH; }
    double tau() const { return -2.0 * f[0].x / kH; }
};

// grid of n steps from a to b (inclusive of b, exclusive of a)
std::vector<double> ramp(double a, double b, int n) {
    std::vector<double> r;
    for (int k = 1; k <= n; ++k)
        r.push_back(a + (b - a) * k / n);
    r.back() = b;
    return r;
}

// bounds of |z'| and |z''| on [0, 1] by differences on a fine grid (for the trapezoid error bound)
void z_bounds(double& z1, double& z2) {
    const int n = 20000;
    z1 = z2 = 0;
    for (int i = 1; i < n; ++i) {
        const double d = 1.0 / n, D = i * d;
        const auto z = [](double v) { return softening_z(SofteningCurve::EvansMarathe, v); };
        z1 = std::max(z1, std::fabs(z(D + d) - z(D - d)) / (2 * d));
        z2 = std::max(z2, std::fabs(z(D + d) - 2 * z(D) + z(D - d)) / (d * d));
    }
    z1 *= 1.01;
    z2 *= 1.01;
}

// Mode I to full separation: returns the work per unit length W_J/h_0 at breaking and checks the
// peak, the break and the trapezoid error bound of the discrete work.
double mode_one_gamma(SofteningLength rule, double& peak_rel_err, double& tol_per_length) {
    OneJoint j(material(rule));
    const double op = 2 * kH * kFt / kP;  // spec eq. 3.1
    const double Iz = softening_integral(SofteningCurve::EvansMarathe);
    const double range = rule == SofteningLength::Exact ? kGI / (Iz * kFt) : 3 * kGI / kFt;
    const int n1 = 400, n2 = 40000;
    std::vector<double> path = ramp(0, op, n1);
    const std::vector<double> soft = ramp(op, op + 1.05 * range, n2);
    path.insert(path.end(), soft.begin(), soft.end());
    peak_rel_err = -1;
    for (size_t k = 0; k < path.size(); ++k) {
        j.at(0, path[k]);
        if (k + 1 == static_cast<size_t>(n1)) peak_rel_err = std::fabs(j.sigma() - kFt) / kFt;
        if (j.s.status[0] == JointStatus::Broken) break;
    }
    EXPECT_EQ(j.s.status[0], JointStatus::Broken);
    EXPECT_EQ(j.s.mode[0], JointMode::I);
    // broken: no force now and later
    EXPECT_EQ(j.f[0], (Vec2{0, 0}));
    j.at(0, 0.5 * op);
    for (const Vec2& v : j.f)
        EXPECT_EQ(v, (Vec2{0, 0}));
    // trapezoid error: hardening (d1^2/12) max|sigma''| o_p, softening (d2^2/12) max|sigma''|
    // range, and the last interval where D crosses 1 (sigma ~ f_t |z'(1)| (o_r - o)/range)
    double z1, z2;
    z_bounds(z1, z2);
    const double d1 = op / n1, d2 = 1.05 * range / n2;
    tol_per_length = d1 * d1 / 12 * (2 * kFt / (op * op)) * op + d2 * d2 / 12 * kFt * z2 / range +
                     kFt * z1 * d2 * d2 / range;
    return j.s.work[0] / kH;
}

// V1 / U3 in mode I: peak f_t at o_p; Gamma_I = G_I + (4/3) h f_t^2/p (spec eq. 3.10) with the
// exact softening length; the published 3G/f rule gives 3 I_z G_I = 1.159 G_I in softening.
TEST(Joints, ModeOneFractureEnergy) {
    double peak_err, tol;
    const double gamma = mode_one_gamma(SofteningLength::Exact, peak_err, tol);
    const double expected = kGI + 4.0 / 3.0 * kH * kFt * kFt / kP;
    EXPECT_LT(peak_err, 1e-12);
    EXPECT_NEAR(gamma, expected, tol);
    EXPECT_LT(tol / expected, 1e-6);
    std::printf(
        "[ mode I exact ] Gamma_I/G_I = %.9f (spec eq. 3.10: %.9f), |err| %.2e <= %.2e, "
        "peak err %.1e\n",
        gamma / kGI, expected / kGI, std::fabs(gamma - expected), tol, peak_err);

    double peak_err2, tol2;
    const double gamma_y = mode_one_gamma(SofteningLength::YGeo, peak_err2, tol2);
    const double elastic = 4.0 / 3.0 * kH * kFt * kFt / kP;  // (2/3) f_t o_p
    const double Iz = softening_integral(SofteningCurve::EvansMarathe);
    EXPECT_NEAR(gamma_y - elastic, 3 * Iz * kGI, tol2);
    EXPECT_NEAR((gamma_y - elastic) / kGI, 1.159, 5e-4);  // spec §3.7
    std::printf("[ mode I y-geo ] softening dissipation / G_I = %.6f (3 I_z = %.6f)\n",
                (gamma_y - elastic) / kGI, 3 * Iz);
}

// V2 / U3 in mode II at sigma_n = 0: peak c at s_p; Gamma_II = G_II + (4/3) h c^2/p_s
TEST(Joints, ModeTwoFractureEnergy) {
    OneJoint j(material());
    const double sp = 2 * kH * kC / kPs;
    const double Iz = softening_integral(SofteningCurve::EvansMarathe);
    const double range = kGII / (Iz * kC);
    const int n1 = 400, n2 = 40000;
    std::vector<double> path = ramp(0, sp, n1);
    const std::vector<double> soft = ramp(sp, sp + 1.05 * range, n2);
    path.insert(path.end(), soft.begin(), soft.end());
    double peak = 0;
    for (size_t k = 0; k < path.size(); ++k) {
        j.at(path[k], 0);
        if (k + 1 == static_cast<size_t>(n1)) peak = j.tau();
        EXPECT_EQ(j.sigma(), 0.0);
        if (j.s.status[0] == JointStatus::Broken) break;
    }
    EXPECT_NEAR(peak, kC, 1e-12 * kC);
    EXPECT_EQ(j.s.status[0], JointStatus::Broken);
    EXPECT_EQ(j.s.mode[0], JointMode::II);
    double z1, z2;
    z_bounds(z1, z2);
    const double d1 = sp / n1, d2 = 1.05 * range / n2;
    const double tol = d1 * d1 / 12 * (2 * kC / (sp * sp)) * sp + d2 * d2 / 12 * kC * z2 / range +
                       kC * z1 * d2 * d2 / range;
    const double expected = kGII + 4.0 / 3.0 * kH * kC * kC / kPs;
    EXPECT_NEAR(j.s.work[0] / kH, expected, tol);
    std::printf("[ mode II ] Gamma_II/G_II = %.9f (expected %.9f), peak tau/c - 1 = %.1e\n",
                j.s.work[0] / kH / kGII, expected / kGII, peak / kC - 1);
}

// V2 under normal stress: peak c + |sigma_n| tan(phi) (spec eq. 3.4)
TEST(Joints, ModeTwoPeakUnderCompression) {
    for (double sn : {-5e6, -10e6}) {
        OneJoint j(material());
        const double o = sn * kH / kP;  // sigma = p o/h
        const double fs = kC - sn * std::tan(M_PI / 6);
        const double sp = 2 * kH * fs / kPs;
        const std::vector<double> path = ramp(0, sp, 500);
        for (double s : path)
            j.at(s, o);
        EXPECT_NEAR(j.sigma(), sn, 1e-12 * std::fabs(sn));
        EXPECT_NEAR(j.tau(), kC + std::fabs(sn) * std::tan(M_PI / 6), 1e-12 * fs);
        // on to breaking: pure shear damage, mode II
        for (int k = 1; k < 200000 && j.s.status[0] != JointStatus::Broken; ++k)
            j.at(sp + k * 1e-7, o);
        EXPECT_EQ(j.s.status[0], JointStatus::Broken);
        EXPECT_EQ(j.s.mode[0], JointMode::II);
    }
}

// §3.8 frozen: unloading and reloading follow z(D_max) times the intact curve; a closed
// unload-reload cycle does no net work (the trapezoid retraces the same points), E_joint is the
// stored energy of eq. 6.2, and W_frac does not change over the cycle
TEST(Joints, IrreversibleUnloadReload) {
    OneJoint j(material());
    const double op = 2 * kH * kFt / kP;
    const double Iz = softening_integral(SofteningCurve::EvansMarathe);
    const double range = kGI / (Iz * kFt);
    const double o1 = op + 0.3 * range;
    std::vector<double> load = ramp(0, op, 200);
    const std::vector<double> more = ramp(op, o1, 3000);
    load.insert(load.end(), more.begin(), more.end());
    JointPass p1;
    for (double o : load)
        p1 = j.at(0, o, true);
    const double z = softening_z(SofteningCurve::EvansMarathe, 0.3);
    EXPECT_NEAR(j.s.d_max[0][0], 0.3, 1e-12);
    EXPECT_EQ(j.s.status[0], JointStatus::Softening);
    const double w1 = j.s.work[0];
    // stored energy at o1 (spec eq. 6.2, o > o_p): z f_t ((2/3) o_p + (o - o_p)) per length
    EXPECT_NEAR(p1.elastic_energy, kH * z * kFt * (2.0 / 3.0 * op + (o1 - op)), 1e-12 * w1);
    // unload to slight compression and back, on the same grid
    std::vector<double> cycle;
    for (auto it = load.rbegin() + 1; it != load.rend(); ++it)
        cycle.push_back(*it);
    cycle.push_back(0.0);
    cycle.push_back(-0.5 * op);
    cycle.push_back(0.0);
    cycle.insert(cycle.end(), load.begin(), load.end());
    double sum_abs = 0;  // scale of the summed increments, for the round-off bound
    JointPass p2;
    for (double o : cycle) {
        const double before = j.s.work[0];
        p2 = j.at(0, o, true);
        sum_abs += std::fabs(j.s.work[0] - before);
        const double xi = o / op;
        const double expect = o < 0 ? kP * o / kH : xi <= 1 ? kFt * z * xi * (2 - xi) : kFt * z;
        EXPECT_NEAR(j.sigma(), expect, 1e-12 * kFt) << o;
    }
    EXPECT_NEAR(j.s.d_max[0][0], 0.3, 1e-12);  // unchanged
    EXPECT_NEAR(j.s.work[0], w1, 8 * kEps * sum_abs);
    EXPECT_NEAR(p2.fracture, p1.fracture, 8 * kEps * sum_abs + 1e-12 * w1);
    EXPECT_GT(p1.fracture, 0.0);
}

// MixedMode::Proportional at a mixed point (theory eq. 9.30): loaded along a radial path into
// softening, the stored energy is a_n psi_n + a_s psi_s with the shares of the damage reached
// (eq. 9.18 times the shares, written out here); then a closed loop inside the envelope
// (unloading, a different mixed path, reloading) leaves D_max, the per-mode maxima, the work and
// W_frac where they were: at a fixed history the law is the derivative of that energy.
TEST(Joints, ProportionalMixedPointStoresWhatItDoesNotDissipate) {
    OneJoint j(material(SofteningLength::Exact, MixedMode::Proportional));
    const double op = 2 * kH * kFt / kP, sp = 2 * kH * kC / kPs;  // eq. 9.4
    const double Iz = softening_integral(SofteningCurve::EvansMarathe);
    const double dO = kGI / (Iz * kFt), dS = kGII / (Iz * kC);  // eq. 9.12, exact
    // end point: D_n = 0.24, D_s = 0.18 (D = 0.3), reached along a path that is straight in the
    // damage (D_n, D_s): to both elastic limits (o_p, s_p) at once, then straight to the end
    // point; the shares fall monotonically to D_n/D, D_s/D on it, so eq. 9.32 keeps them
    const double o1 = op + 0.24 * dO, s1 = sp + 0.18 * dS;
    const int n = 20000;
    JointPass p1;
    for (int k = 1; k <= n / 10; ++k)
        j.at(sp * k / (n / 10), op * k / (n / 10), true);
    for (int k = 1; k <= n; ++k)
        p1 = j.at(sp + (s1 - sp) * k / n, op + (o1 - op) * k / n, true);
    EXPECT_EQ(j.s.status[0], JointStatus::Softening);
    for (int q = 0; q < 3; ++q) {
        EXPECT_NEAR(j.s.d_max[0][q], 0.3, 1e-12);
        EXPECT_NEAR(j.s.dn_max[0][q], 0.24, 1e-12);
        EXPECT_NEAR(j.s.ds_max[0][q], 0.18, 1e-12);
    }
    const double z = softening_z(SofteningCurve::EvansMarathe, 0.3);
    const double an = 0.24 / 0.3, as = 0.18 / 0.3;  // K = 0.3 > kMixOnset: w = 1
    EXPECT_NEAR(j.sigma(), an * z * kFt, 1e-9 * kFt);
    EXPECT_NEAR(j.tau(), as * z * kC, 1e-9 * kC);
    const double psi =
        an * z * kFt * (2.0 / 3.0 * op + (o1 - op)) + as * z * kC * (2.0 / 3.0 * sp + (s1 - sp));
    EXPECT_NEAR(p1.elastic_energy, kH * psi, 1e-12 * kH * psi);
    const double w1 = j.s.work[0];
    EXPECT_GT(p1.fracture, 0.05 * w1);  // the softening dissipated
    // the loop, straight legs between corners (o, s) in units of (o1, s1): back to 0.8 of the
    // end point, across to a reversed slip and back, and up to the end point again. Every point
    // has 0 <= o <= 0.8 o1 and |s| <= 0.8 s1 (so D < D_max) until the last leg retraces the
    // first; o >= 0 throughout (in compression f_s depends on o, eq. 9.7: no potential there)
    const double corners[][2] = {{1, 1},     {0.8, 0.8}, {0.1, 0.8}, {0.1, -0.6},
                                 {0.7, 0.0}, {0.8, 0.8}, {1, 1}};
    double sum_abs = 0;
    JointPass p2;
    const int m = 20000;  // points per leg
    for (size_t c = 1; c < std::size(corners); ++c) {
        for (int k = 1; k <= m; ++k) {
            const double t = static_cast<double>(k) / m;
            const double o = o1 * ((1 - t) * corners[c - 1][0] + t * corners[c][0]);
            const double s = s1 * ((1 - t) * corners[c - 1][1] + t * corners[c][1]);
            const double before = j.s.work[0];
            p2 = j.at(s, o, true);
            sum_abs += std::fabs(j.s.work[0] - before);
        }
    }
    EXPECT_NEAR(j.s.d_max[0][0], 0.3, 1e-12);  // no new damage on the loop
    EXPECT_NEAR(j.s.dn_max[0][0], 0.24, 1e-12);
    EXPECT_NEAR(j.s.ds_max[0][0], 0.18, 1e-12);
    // the loop's work vanishes to the trapezoid rule's error (the law is smooth on it)
    EXPECT_NEAR(j.s.work[0], w1, 1e-6 * sum_abs);
    EXPECT_NEAR(p2.fracture, p1.fracture, 1e-6 * sum_abs);
    std::printf("[ loop ] W_frac %.6e -> %.6e J/m, loop |work| %.3e of %.3e summed\n", p1.fracture,
                p2.fracture, std::fabs(j.s.work[0] - w1), sum_abs);
}

// spec §6: the work done by the driven nodes, summed with the same trapezoid rule from the
// forces the kernel applies, equals E_joint + W_frac reported by the kernel, along a mixed,
// non-monotonic path with damage and breaks, to a round-off bound
TEST(Joints, EnergyBalanceOfDrivenNodes) {
    const MeshData mesh = make_rectangle_mesh(0, 0, 4 * kH, 3 * kH, 4, 3, true);
    const SplitMesh sm = split_mesh(mesh.nodes, mesh.tris);
    Joints J;
    J.laws.push_back(make_joint_law(material()));
    add_edge_joints(J, sm.x0, sm.tris, sm.vertex, 0);
    const int32_t nn = static_cast<int32_t>(sm.x0.size());
    finalize_joints(J, nn);
    JointState s = make_joint_state(J);
    // displacement u = a(t) * (smooth field + per-copy jitter), a up and down, growing
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> U(-1, 1);
    std::vector<Vec2> mode(static_cast<size_t>(nn));
    for (NodeId i = 0; i < nn; ++i) {
        const Vec2 X = sm.x0[static_cast<size_t>(i)];
        mode[static_cast<size_t>(i)] = {std::sin(40 * X.y) + 0.3 * U(rng),
                                        std::cos(50 * X.x) + 0.3 * U(rng)};
    }
    const double amp = 2 * kH * kFt / kP;  // o_p
    std::vector<Vec2> x = sm.x0, f(static_cast<size_t>(nn)), fold(static_cast<size_t>(nn)),
                      xold = sm.x0;
    double w_drv = 0, bound = 0;
    JointPass pass;
    const int steps = 6000;
    for (int n = 1; n <= steps; ++n) {
        const double t = static_cast<double>(n) / steps;
        const double a = amp * 400 * t * (0.6 + 0.4 * std::sin(25 * t));
        for (NodeId i = 0; i < nn; ++i)
            x[static_cast<size_t>(i)] =
                sm.x0[static_cast<size_t>(i)] + a * mode[static_cast<size_t>(i)];
        for (auto& v : f)
            v = {0, 0};
        pass = joint_forces(J, s, x, f, true, n);
        // largest separation of a face pair (the kernel differences separations, not positions)
        double dmax = 0;
        for (int32_t j = 0; j < J.num_joints(); ++j) {
            const auto& nd = J.nodes[j];
            dmax = std::max({dmax, norm(x[nd[0]] - x[nd[3]]), norm(x[nd[1]] - x[nd[2]]),
                             norm(xold[nd[0]] - xold[nd[3]]), norm(xold[nd[1]] - xold[nd[2]])});
        }
        // driver force -f; trapezoid work over the step
        for (size_t i = 0; i < x.size(); ++i) {
            const Vec2 fm = 0.5 * (fold[i] + f[i]);
            const Vec2 dx = x[i] - xold[i];
            w_drv -= dot(fm, dx);
            bound += 8 * kEps * norm(fm) * (norm(dx) + 2 * dmax);
        }
        // both sides add one increment per step to a running sum
        bound += 2 * kEps * std::fabs(w_drv);
        fold = f;
        xold = x;
    }
    int broken = 0, softening = 0;
    for (int32_t j = 0; j < J.num_joints(); ++j) {
        broken += s.status[j] == JointStatus::Broken;
        softening += s.status[j] == JointStatus::Softening;
    }
    EXPECT_GT(broken, 0);
    EXPECT_GT(softening + broken, J.num_joints() / 2);
    EXPECT_NEAR(pass.elastic_energy + pass.fracture, w_drv, bound);
    EXPECT_GT(pass.fracture, 0.0);
    std::printf(
        "[ balance ] joints %d, broken %d, W_drv %.6e, E_joint %.6e, W_frac %.6e, "
        "|diff| %.1e <= %.1e\n",
        J.num_joints(), broken, w_drv, pass.elastic_energy, pass.fracture,
        std::fabs(pass.elastic_energy + pass.fracture - w_drv), bound);
}

// U1: rigid motions give no separation, hence no force; sum of forces is zero
TEST(Joints, RigidMotionAndEquilibrium) {
    OneJoint j(material());
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> U(-1, 1);
    for (int trial = 0; trial < 50; ++trial) {
        const double th = M_PI * U(rng);
        const Vec2 c{U(rng), U(rng)};
        const Vec2 ref[4] = {{0, 0}, {kH, 0}, {kH, 0}, {0, 0}};
        for (int k = 0; k < 4; ++k)
            j.x[static_cast<size_t>(k)] = Vec2{std::cos(th) * ref[k].x - std::sin(th) * ref[k].y,
                                               std::sin(th) * ref[k].x + std::cos(th) * ref[k].y} +
                                          c;
        for (auto& v : j.f)
            v = {0, 0};
        joint_forces(j.J, j.s, j.x, j.f, false);
        for (const Vec2& v : j.f)
            EXPECT_LE(norm(v), 1e-12 * kFt * kH);
        // a general separation: sum of the four forces is zero
        j.x[0] += Vec2{0.3 * U(rng), U(rng)} * 1e-6;
        j.x[2] += Vec2{U(rng), U(rng)} * 1e-6;
        for (auto& v : j.f)
            v = {0, 0};
        joint_forces(j.J, j.s, j.x, j.f, false);
        const Vec2 sum = (j.f[0] + j.f[1]) + (j.f[2] + j.f[3]);
        EXPECT_LE(norm(sum), 1e-14 * (norm(j.f[0]) + norm(j.f[1])));
    }
}

TEST(Joints, CollapsedJointThrows) {
    OneJoint j(material());
    j.x = {{0, 0}, {0, 0}, {0, 0}, {0, 0}};
    EXPECT_THROW(joint_forces(j.J, j.s, j.x, j.f, false, 17, 0.5), SimulationError);
    j.x = {{0, 0}, {kH, std::nan("")}, {kH, 0}, {0, 0}};
    EXPECT_THROW(joint_forces(j.J, j.s, j.x, j.f, false), SimulationError);
}

// A sheet of nx x ny cells of size kH, every internal edge a joint of the exact law with `mixed`,
// and a random displacement mode per node drawn from rng: position(n) = x0 + 3 n amp mode softens
// and breaks joints over ~30 calls
struct ShakenSheet {
    SplitMesh sm;
    Joints J;
    int32_t nn = 0;
    std::vector<Vec2> mode;
    double amp = 2 * kH * kFt / kP;

    void position(int n, std::vector<Vec2>& x) const {
        for (NodeId i = 0; i < nn; ++i)
            x[static_cast<size_t>(i)] =
                sm.x0[static_cast<size_t>(i)] + (amp * 3 * n) * mode[static_cast<size_t>(i)];
    }
};

ShakenSheet shaken_sheet(int nx, int ny, MixedMode mixed, std::mt19937_64& rng) {
    ShakenSheet sh;
    const MeshData mesh = make_rectangle_mesh(0, 0, nx * kH, ny * kH, nx, ny, true);
    sh.sm = split_mesh(mesh.nodes, mesh.tris);
    sh.J.laws.push_back(make_joint_law(material(SofteningLength::Exact, mixed)));
    add_edge_joints(sh.J, sh.sm.x0, sh.sm.tris, sh.sm.vertex, 0);
    sh.nn = static_cast<int32_t>(sh.sm.x0.size());
    finalize_joints(sh.J, sh.nn);
    std::uniform_real_distribution<double> U(-1, 1);
    sh.mode.resize(static_cast<size_t>(sh.nn));
    for (auto& m : sh.mode)
        m = {U(rng), U(rng)};
    return sh;
}

// U8: 1, 2, 3 threads give bitwise the same forces, state and sums (several chunks, breaks)
TEST(Joints, ThreadCountBitwise) {
    for (const MixedMode mixed : {MixedMode::Independent, MixedMode::Proportional}) {
        SCOPED_TRACE(mixed == MixedMode::Proportional ? "proportional" : "independent");
        std::mt19937_64 rng(11);
        const ShakenSheet sh = shaken_sheet(40, 40, mixed, rng);
        const Joints& J = sh.J;
        const int32_t nn = sh.nn;
        ASSERT_GT(J.num_joints(), 2 * kJointChunk);
        auto run = [&](int threads, std::vector<Vec2>& f_out, JointState& s,
                       std::vector<Real>& sums) {
            const int saved = omp_get_max_threads();
            omp_set_num_threads(threads);
            s = make_joint_state(J);
            std::vector<Vec2> x = sh.sm.x0;
            for (int n = 1; n <= 30; ++n) {
                sh.position(n, x);
                f_out.assign(static_cast<size_t>(nn), Vec2{0.25, -0.5});
                const JointPass p = joint_forces(J, s, x, f_out, n % 3 == 0, n);
                sums.insert(sums.end(),
                            {p.elastic_energy, p.work, p.fracture,
                             static_cast<Real>(p.newly_broken), static_cast<Real>(p.softening)});
            }
            omp_set_num_threads(saved);
        };
        std::vector<Vec2> f1, f2, f3;
        JointState s1, s2, s3;
        std::vector<Real> q1, q2, q3;
        run(1, f1, s1, q1);
        run(2, f2, s2, q2);
        run(3, f3, s3, q3);
        int broken = 0;
        for (auto st : s1.status)
            broken += st == JointStatus::Broken;
        EXPECT_GT(broken, 0);
        EXPECT_LT(broken, J.num_joints());
        // (empty vectors, dn_max and ds_max of the independent rule, have no data to compare:
        // memcmp of a null pointer is undefined even for 0 bytes)
        const auto same = [](const auto& a, const auto& b) {
            return a.size() == b.size() &&
                   (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
        };
        for (const auto* o : {&f2, &f3})
            EXPECT_TRUE(same(f1, *o));
        for (const auto* o : {&q2, &q3})
            EXPECT_TRUE(same(q1, *o));
        for (const auto* o : {&s2, &s3}) {
            EXPECT_TRUE(same(s1.d_max, o->d_max));
            EXPECT_TRUE(same(s1.work, o->work));
            EXPECT_TRUE(same(s1.status, o->status));
            EXPECT_TRUE(same(s1.mode, o->mode));
            EXPECT_TRUE(same(s1.break_step, o->break_step));
            EXPECT_EQ(s1.total_work, o->total_work);
            EXPECT_TRUE(same(s1.dn_max, o->dn_max));
            EXPECT_TRUE(same(s1.ds_max, o->ds_max));
        }
        // the per-mode history exists with the proportional law only (theory eq. 9.30)
        EXPECT_EQ(s1.dn_max.size(),
                  mixed == MixedMode::Proportional ? static_cast<size_t>(J.num_joints()) : 0u);
    }
}

// A distributed run's share of the joints (JointSubset, docs/parallel.md "Joints"): for 1-4
// simulated processes with spatial strips and with a random owner per node (partial ranges in
// every chunk), 1 and 2 threads, over a loading that softens and breaks joints: every owned
// node's force, the history of every joint a process runs, and the sums over the processes
// (work, E_joint, breaks) are the serial kernel's bits; every chunk is summed by one process.
TEST(JointSubset, OwnedForcesHistoryAndSumsAreSerialForAnyPartition) {
    std::mt19937_64 rng(5);  // (the mode, then the random owners below)
    const ShakenSheet sh = shaken_sheet(60, 40, MixedMode::Proportional, rng);
    const Joints& J = sh.J;
    const SplitMesh& sm = sh.sm;
    const int32_t nn = sh.nn;
    const int32_t nc = (J.num_joints() + kJointChunk - 1) / kJointChunk;
    ASSERT_GE(nc, 4);
    for (const int threads : {1, 2}) {
        const int saved = omp_get_max_threads();
        omp_set_num_threads(threads);
        for (int procs = 1; procs <= 4; ++procs) {
            for (const bool random : {false, true}) {
                SCOPED_TRACE(testing::Message()
                             << threads << " thread(s), " << procs << " processes, "
                             << (random ? "random" : "strips"));
                std::vector<int32_t> owner(static_cast<size_t>(nn));
                for (NodeId i = 0; i < nn; ++i) {
                    owner[static_cast<size_t>(i)] =
                        random ? static_cast<int32_t>(rng() % static_cast<unsigned>(procs))
                               : std::min(procs - 1,
                                          static_cast<int32_t>(sm.x0[static_cast<size_t>(i)].x /
                                                               (60 * kH) * procs));
                }
                std::vector<JointSubset> sub;
                std::vector<JointState> st;
                int counted = 0;
                for (int r = 0; r < procs; ++r) {
                    sub.push_back(joint_subset(J, owner, r));
                    st.push_back(make_joint_state(J));
                    for (const uint8_t c : sub.back().counts)
                        counted += c;
                }
                EXPECT_EQ(counted, nc);  // every chunk summed by exactly one process
                if (random && procs > 1) {
                    EXPECT_FALSE(sub[0].ranges.empty());
                }
                JointState serial = make_joint_state(J);
                std::vector<Vec2> x(static_cast<size_t>(nn)), f_serial, f;
                int broken_steps = 0;
                ExactSum running;
                for (int n = 1; n <= 30; ++n) {
                    sh.position(n, x);
                    const bool energy = n % 3 == 0;
                    f_serial.assign(static_cast<size_t>(nn), Vec2{0.25, -0.5});
                    const JointPass ref = joint_forces(J, serial, x, f_serial, energy, n);
                    ExactSum work, elastic;
                    int32_t broken = 0;
                    for (int r = 0; r < procs; ++r) {
                        f.assign(static_cast<size_t>(nn), Vec2{0.25, -0.5});
                        const JointSubsetPass p = joint_forces(J, st[r], x, f, energy, sub[r], n);
                        EXPECT_EQ(p.bad, -1);
                        work.add(p.work);
                        elastic.add(p.elastic);
                        broken += p.newly_broken;
                        bool forces = true;
                        for (NodeId i = 0; i < nn; ++i) {
                            if (owner[static_cast<size_t>(i)] != r) continue;
                            forces = forces && std::memcmp(&f[static_cast<size_t>(i)],
                                                           &f_serial[static_cast<size_t>(i)],
                                                           sizeof(Vec2)) == 0;
                        }
                        EXPECT_TRUE(forces) << "step " << n << ", process " << r;
                        // the history of every joint it runs
                        bool history = true;
                        const auto check = [&](int32_t j) {
                            const auto k = static_cast<size_t>(j);
                            history = history &&
                                      std::memcmp(&st[r].d_max[k], &serial.d_max[k], 24) == 0 &&
                                      std::memcmp(&st[r].dn_max[k], &serial.dn_max[k], 24) == 0 &&
                                      std::memcmp(&st[r].work[k], &serial.work[k], 8) == 0 &&
                                      std::memcmp(&st[r].f_prev[k], &serial.f_prev[k], 32) == 0 &&
                                      st[r].status[k] == serial.status[k] &&
                                      st[r].mode[k] == serial.mode[k] &&
                                      st[r].break_step[k] == serial.break_step[k];
                        };
                        for_each_joint_range(sub[r], J.num_joints(), [&](int32_t b, int32_t e) {
                            for (int32_t j = b; j < e; ++j)
                                check(j);
                        });
                        EXPECT_TRUE(history) << "step " << n << ", process " << r;
                    }
                    // the running sum of the work over the processes and E_joint: the serial
                    // bits
                    running.add(work);
                    EXPECT_EQ(running.value(), ref.work) << "step " << n;
                    if (energy) {
                        EXPECT_EQ(elastic.value(), ref.elastic_energy) << "step " << n;
                    }
                    EXPECT_EQ(broken, ref.newly_broken) << "step " << n;
                    broken_steps += ref.newly_broken > 0;
                }
                EXPECT_GT(broken_steps, 0);
            }
        }
        omp_set_num_threads(saved);
    }
}

// The blocked path (8 intact elastic joints at a time, portable and AVX-512) gives the bits of
// the scalar path: forces, sums and state over a loading that takes joints from intact through
// softening to broken (blocks then mix elastic, softening and broken joints, and fall back),
// with 1 and 2 threads (scatter and gather), energy on some steps.
// (the blocks of softening and broken joints, kDamaged in joints.cpp, run on the steps
// without energy; mixed: law 0 has MixedMode::Proportional, whose kept shares they load)
void expect_blocked_path_same_bits(MixedMode mixed) {
    constexpr int kSteps = 60;
    const MeshData mesh = make_rectangle_mesh(0, 0, 40 * kH, 40 * kH, 40, 40, true);
    const SplitMesh sm = split_mesh(mesh.nodes, mesh.tris);
    Joints J;
    J.laws.push_back(make_joint_law(material(SofteningLength::Exact, mixed)));
    J.laws.push_back(make_joint_law(material(SofteningLength::YGeo)));
    add_edge_joints(J, sm.x0, sm.tris, sm.vertex, 0);
    for (int32_t j = 0; j < J.num_joints(); j += 37)
        J.law[static_cast<size_t>(j)] = 1;  // a block with two laws goes scalar
    const int32_t nn = static_cast<int32_t>(sm.x0.size());
    finalize_joints(J, nn);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> U(-1, 1);
    std::vector<Vec2> mode(static_cast<size_t>(nn));
    for (auto& m : mode)
        m = {U(rng), U(rng)};
    // small random jitter per step on top of a growing mode: intact joints see both signs of
    // opening and slip, and after a while some soften and break
    const double amp = 2 * kH * kFt / kP;
    struct Run {
        std::vector<Vec2> f;
        JointState s;
        std::vector<Real> sums;
        int64_t blocked = 0;  ///< joint-steps done by the blocked path
    };
    auto run = [&](detail::JointPath path, int threads, bool damaged = true) {
        Run r;
        const int saved = omp_get_max_threads();
        omp_set_num_threads(threads);
        detail::set_joint_path(path);
        detail::set_damaged_blocks(damaged);
        r.s = make_joint_state(J);
        std::vector<Vec2> x = sm.x0;
        std::mt19937_64 jr(9);
        for (int n = 1; n <= kSteps; ++n) {
            // the left quarter is driven to breaking, the rest stays elastic (|o| < 0.6 o_p);
            // from step 41 the drive is back at 0.1: the softened joints unload elastically
            const double a = n <= 20 ? 0.02 * n : n <= 40 ? 0.4 + 3.0 * (n - 20) : 0.1;
            for (NodeId i = 0; i < nn; ++i)
                x[static_cast<size_t>(i)] =
                    sm.x0[static_cast<size_t>(i)] +
                    (amp * (sm.x0[static_cast<size_t>(i)].x < 10 * kH ? a : std::min(a, 0.2))) *
                        mode[static_cast<size_t>(i)] +
                    (0.05 * amp) * Vec2{U(jr), U(jr)};
            r.f.assign(static_cast<size_t>(nn), Vec2{0.25, -0.5});
            const JointPass p = joint_forces(J, r.s, x, r.f, n % 3 == 0, n);
            r.sums.insert(r.sums.end(),
                          {p.elastic_energy, p.work, p.fracture, static_cast<Real>(p.newly_broken),
                           static_cast<Real>(p.softening)});
            r.f.insert(r.f.end(), r.f.begin(), r.f.begin() + nn);  // keep every step's forces
            r.blocked += p.blocked;
        }
        detail::set_joint_path(detail::JointPath::Auto);
        detail::set_damaged_blocks(true);
        omp_set_num_threads(saved);
        return r;
    };
    const auto same = [](const auto& a, const auto& b) {
        return a.size() == b.size() &&
               std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
    };
    const Run ref = run(detail::JointPath::Scalar, 1);
    int broken = 0, softening = 0;
    for (auto st : ref.s.status) {
        broken += st == JointStatus::Broken;
        softening += st == JointStatus::Softening;
    }
    std::printf("[ joints ] %d, broken %d, softening %d\n", J.num_joints(), broken, softening);
    EXPECT_GT(broken, 0);
    EXPECT_GT(J.num_joints() - broken - softening, J.num_joints() / 4);  // many stay intact
    EXPECT_EQ(ref.blocked, 0);
    std::vector<detail::JointPath> paths = {detail::JointPath::Portable};
    if (detail::joint_avx512_supported()) paths.push_back(detail::JointPath::Avx512);
    if (detail::joint_avx2_supported()) paths.push_back(detail::JointPath::Avx2);
    for (const auto path : paths) {
        // blocks of softening and broken joints ran: more joint-steps blocked than without them
        const int64_t intact_only = run(path, 1, false).blocked;
        for (const int threads : {1, 2}) {
            const Run o = run(path, threads);
            EXPECT_GT(o.blocked, intact_only + J.num_joints() / 2);
            SCOPED_TRACE(testing::Message()
                         << "path " << static_cast<int>(path) << ", threads " << threads);
            // the blocked path ran for most joint-steps, and not for all (fallbacks tested too)
            EXPECT_GT(o.blocked, kSteps * J.num_joints() / 3);
            EXPECT_LT(o.blocked, kSteps * J.num_joints());
            EXPECT_TRUE(same(ref.f, o.f));
            EXPECT_TRUE(same(ref.sums, o.sums));
            EXPECT_TRUE(same(ref.s.d_max, o.s.d_max));
            EXPECT_TRUE(same(ref.s.work, o.s.work));
            EXPECT_TRUE(same(ref.s.f_prev, o.s.f_prev));
            EXPECT_TRUE(same(ref.s.d_prev, o.s.d_prev));
            EXPECT_TRUE(same(ref.s.status, o.s.status));
            EXPECT_TRUE(same(ref.s.mode, o.s.mode));
            EXPECT_TRUE(same(ref.s.break_step, o.s.break_step));
            EXPECT_EQ(std::memcmp(&ref.s.total_work, &o.s.total_work, sizeof(Real)), 0);
            if (mixed == MixedMode::Proportional) {
                EXPECT_TRUE(same(ref.s.dn_max, o.s.dn_max));
                EXPECT_TRUE(same(ref.s.an_min, o.s.an_min));
                EXPECT_TRUE(same(ref.s.as_min, o.s.as_min));
            }
        }
    }
}

TEST(Joints, BlockedPathSameBits) {
    expect_blocked_path_same_bits(MixedMode::Independent);
}

TEST(Joints, BlockedPathSameBitsProportionalMixedMode) {
    expect_blocked_path_same_bits(MixedMode::Proportional);
}

// spec §5: the Gershgorin bound of eq. 5.1 bounds omega_max^2 of M^-1 K measured by power
// iteration with the kernel's own forces (small displacements about the reference state)
TEST(Joints, StableTimeStepBound) {
    const MeshData mesh = make_rectangle_mesh(0, 0, 8 * kH, 8 * kH, 8, 8, false);
    const SplitMesh sm = split_mesh(mesh.nodes, mesh.tris);
    Joints J;
    J.laws.push_back(make_joint_law(material()));
    add_edge_joints(J, sm.x0, sm.tris, sm.vertex, 0);
    const size_t nn = sm.x0.size();
    finalize_joints(J, static_cast<int32_t>(nn));
    const double rho = 2700;
    std::vector<Real> mass(nn, rho * 0.5 * kH * kH / 3);  // rho A / 3
    const double dt = joint_critical_dt(J, mass);
    const double bound_w2 = 4.0 / (dt * dt);
    EXPECT_NEAR(bound_w2, 2 * kP / mass[0], 1e-9 * bound_w2);  // 2 joints per interior copy
    // power iteration on M^-1 K, K u = -(f(+eps u) - f(-eps u))/(2 eps)
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> U(-1, 1);
    std::vector<Vec2> u(nn), x(nn), fp(nn), fm(nn);
    for (auto& v : u)
        v = {U(rng), U(rng)};
    const double eps = 1e-6 * 2 * kH * kFt / kP;
    double lambda = 0;
    for (int it = 0; it < 400; ++it) {
        double un = 0;
        for (auto& v : u)
            un = std::max(un, norm(v));
        for (auto& v : u)
            v = v / un;
        for (int sgn : {1, -1}) {
            JointState s = make_joint_state(J);
            for (size_t i = 0; i < nn; ++i)
                x[i] = sm.x0[i] + (sgn * eps) * u[i];
            auto& ff = sgn > 0 ? fp : fm;
            ff.assign(nn, Vec2{0, 0});
            joint_forces(J, s, x, ff, false);
        }
        double num = 0, den = 0;
        for (size_t i = 0; i < nn; ++i) {
            const Vec2 ku = (-1.0 / (2 * eps)) * (fp[i] - fm[i]);
            const Vec2 w = ku / mass[i];
            num += dot(u[i], ku);
            den += mass[i] * dot(u[i], u[i]);
            u[i] = w;
        }
        lambda = num / den;  // Rayleigh quotient of M^-1 K
    }
    EXPECT_LE(lambda, bound_w2 * (1 + 1e-6));
    EXPECT_GT(lambda, 0.5 * bound_w2);
    std::printf("[ dt ] power iteration omega^2 / Gershgorin bound = %.4f\n", lambda / bound_w2);
}

// U4 (spec §11): a fully jointed block under a uniform stress. Under a hydrostatic stress sigma I
// every joint carries the traction sigma n and no shear, so its separation is the same function
// of h for every orientation: delta = o n with o = sigma h/p in compression (eq. 9.5, linear) and
// o = xi o_p, o_p = 2 h f_t/p, f_t (2 xi - xi^2) = sigma in tension (eqs. 9.4-9.5). With
// h n = the edge vector turned by 90 degrees, the jumps around an interior vertex sum to the
// turned sum of its edge vectors, zero on the structured meshes (symmetric stars), so the state
// "every triangle translated rigidly by c_k, uniform stress sigma in every triangle" exists. The
// test builds it (c_k propagated through the joints from triangle 0, every joint then checked)
// and asks for equilibrium of every node copy: the joint forces of the kernel plus the CST
// forces of the uniform stress (f_i = -A sigma grad N_i, written out here) plus the consistent
// load of the traction sigma n on the block's outer edges. Joints that did not transmit the
// triangles' traction (a wrong Simpson weight, sign, orientation or length) leave a residual;
// by uniqueness of the linear equilibrium the uniform stress is then the block's solution.
TEST(Joints, UniformStressPatch) {
    for (const bool alternate : {false, true}) {
        for (const double sig : {-0.5 * kFt, 0.3 * kFt}) {
            const int n = 5;
            const MeshData mesh = make_rectangle_mesh(0, 0, n * kH, n * kH, n, n, alternate);
            const SplitMesh sm = split_mesh(mesh.nodes, mesh.tris);
            Joints J;
            J.laws.push_back(make_joint_law(material()));
            add_edge_joints(J, sm.x0, sm.tris, sm.vertex, 0);
            const size_t nn = sm.x0.size(), nt = sm.tris.size();
            finalize_joints(J, static_cast<int32_t>(nn));
            // separation per unit joint length (eqs. 9.4, 9.5)
            const double xi = sig > 0 ? 1 - std::sqrt(1 - sig / kFt) : 0;
            const double o_per_h = sig > 0 ? xi * 2 * kFt / kP : sig / kP;
            // triangle of every node copy
            std::vector<int> tri_of(nn, -1);
            for (size_t t = 0; t < nt; ++t)
                for (NodeId a : sm.tris[t])
                    tri_of[a] = static_cast<int>(t);
            // c_A - c_B = o n_A h-scaled (eq. 9.2: delta = x0 - x3, n into A), breadth first
            std::vector<Vec2> c(nt);
            std::vector<char> done(nt, 0);
            done[0] = 1;
            for (bool grew = true; grew;) {
                grew = false;
                for (const auto& q : J.nodes) {
                    const int A = tri_of[q[0]], B = tri_of[q[3]];
                    const Vec2 e = 0.5 * (sm.x0[q[1]] + sm.x0[q[2]] - sm.x0[q[0]] - sm.x0[q[3]]);
                    const Vec2 jump = o_per_h * Vec2{-e.y, e.x};  // o n with h n = (-e_y, e_x) h
                    if (done[A] && !done[B]) {
                        c[B] = c[A] - jump, done[B] = 1, grew = true;
                    } else if (done[B] && !done[A]) {
                        c[A] = c[B] + jump, done[A] = 1, grew = true;
                    }
                }
            }
            std::vector<Vec2> x(nn), f(nn, Vec2{0, 0});
            for (size_t i = 0; i < nn; ++i)
                x[i] = sm.x0[i] + c[tri_of[i]];
            JointState s = make_joint_state(J);
            const JointPass pass = joint_forces(J, s, x, f, false);
            // elements: f_i = -A sigma grad N_i = -(sigma/2) (edge opposite i turned outwards)
            for (const auto& t : sm.tris) {
                for (int k = 0; k < 3; ++k) {
                    const Vec2 a = sm.x0[t[(k + 1) % 3]], b = sm.x0[t[(k + 2) % 3]];
                    const Vec2 out{b.y - a.y, a.x - b.x};  // |b - a| times the outward normal
                    f[t[k]] = f[t[k]] + (sig / 2) * out;
                }
            }
            // outer edges: traction sigma n_out, half of it on each end copy
            const double L = n * kH;
            for (const auto& t : sm.tris) {
                for (int k = 0; k < 3; ++k) {
                    const Vec2 a = sm.x0[t[k]], b = sm.x0[t[(k + 1) % 3]];
                    const bool outer = (a.x == 0 && b.x == 0) || (a.x == L && b.x == L) ||
                                       (a.y == 0 && b.y == 0) || (a.y == L && b.y == L);
                    if (!outer) continue;
                    const Vec2 load = (sig / 2) * Vec2{b.y - a.y, a.x - b.x};
                    f[t[k]] = f[t[k]] + load;
                    f[t[(k + 1) % 3]] = f[t[(k + 1) % 3]] + load;
                }
            }
            double worst = 0;
            for (const Vec2& r : f)
                worst = std::max(worst, norm(r));
            const double scale = std::abs(sig) * kH;  // the force of one edge
            EXPECT_LE(worst, 1e-10 * scale) << "alternate " << alternate << ", sigma " << sig;
            EXPECT_EQ(pass.newly_broken, 0);
            EXPECT_EQ(pass.softening, 0);
            std::printf(
                "[ U4 ] alternate %d, sigma/f_t = %+.2f: max residual / (|sigma| h) = %.2e\n",
                alternate, sig / kFt, worst / scale);
        }
    }
}

}  // namespace
}  // namespace fdem
