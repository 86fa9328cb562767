// No volumetric locking (issue #7, docs/theory.md §3.5): a nearly incompressible (nu = 0.499)
// plane-strain cantilever under its own weight. The composite element's tip deflection is
// within 5 % of a refined reference (the same composite element on a mesh 4x finer in each
// direction; Timoshenko beam theory printed for orientation), while plain CSTs on exactly the
// same nodes (element = "cst" on the same 6-node mesh) are much stiffer.
//
//   y ^   clamped at x = 0 (all nodes of the left edge), gravity -y, L = 10 m, H = 1 m
//     |#+---o---+---o---+---o---+ ... +
//     |#|   /   |   /   |   /         |     each cell: two 6-node triangles
//     |#o  o  o o  o  o o             o     (4 sub-triangles each)
//     |#| /     | /     | /           |
//     |#+---o---+---o---+---o---+ ... +  --> x
//
// Static equilibrium of the small load (E = 10 GPa: tip deflection ~1e-3 L, linear regime),
// linearized at the reference configuration, by conjugate gradients on K u = f_gravity, with K p =
// -(f_int(X + e p) - f_int(X - e p)) / (2 e) applied matrix-free through the element kernel itself
// (add_internal_forces), so the test exercises exactly the forces of the time stepper.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "element/cst.hpp"
#include "fdem/build.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

constexpr Real kL = 10.0, kH = 1.0, kE = 1e10, kNu = 0.499, kRho = 1000.0, kG = 9.81;

struct Beam {
    Model m;
    std::vector<char> fixed;  // per node: clamped
    NodeId tip = kNone;       // node at (L, 0)
};

Beam make_beam(int nx, int ny, ElementKind kind, Real nu) {
    Beam b;
    Material mat = scenes::paper_material("soft", kE, nu, kRho);
    b.m.materials.push_back(mat);
    scenes::add_rectangle_order2(b.m, 0, 0, kL, kH, nx, ny, 0, kind);
    finalize_model(b.m);
    b.fixed.assign(static_cast<size_t>(b.m.num_nodes()), 0);
    for (NodeId i = 0; i < b.m.num_nodes(); ++i) {
        const Vec2 X = b.m.node_x0[i];
        if (X.x < 1e-12) b.fixed[i] = 1;
        if (std::abs(X.x - kL) < 1e-12 && std::abs(X.y) < 1e-12) b.tip = i;
    }
    return b;
}

/// K p for the free degrees of freedom (clamped ones zeroed), by a central difference of the
/// internal forces: exact for the linear part, O(e^2) error from the nonlinear terms.
void apply_k(const Beam& b, const std::vector<Vec2>& p, std::vector<Vec2>& out,
             std::vector<Vec2>& xp, std::vector<Vec2>& fp, std::vector<Vec2>& fm) {
    const Model& m = b.m;
    Real pmax = 0;
    for (const Vec2& q : p)
        pmax = std::max(pmax, norm(q));
    const Real e = pmax > 0 ? 1e-6 * kH / pmax : 0;  // displacements ~1e-6 H
    const std::vector<Vec2> v(p.size());
    for (int sgn : {1, -1}) {
        std::vector<Vec2>& f = sgn > 0 ? fp : fm;
        for (size_t i = 0; i < p.size(); ++i) {
            xp[i] = m.node_x0[i] + (sgn * e) * p[i];
            f[i] = {0, 0};
        }
        add_internal_forces(m, xp.data(), v.data(), f.data(), 0, m.num_tris());
    }
    for (size_t i = 0; i < p.size(); ++i) {
        out[i] = b.fixed[i] ? Vec2{0, 0} : (-1.0 / (2 * e)) * (fp[i] - fm[i]);
    }
}

Real dot(const std::vector<Vec2>& a, const std::vector<Vec2>& c) {
    Real s = 0;
    for (size_t i = 0; i < a.size(); ++i)
        s += a[i].x * c[i].x + a[i].y * c[i].y;
    return s;
}

/// Tip deflection [m] (downwards positive) under gravity, conjugate gradients to a relative
/// residual of 1e-8 (the K p products are accurate to ~1e-9 relative).
Real tip_deflection(const Beam& b) {
    const Model& m = b.m;
    const size_t n = static_cast<size_t>(m.num_nodes());
    std::vector<Vec2> u(n), r(n), p(n), kp(n), xp(n), fp(n), fm(n);
    for (size_t i = 0; i < n; ++i)
        r[i] = b.fixed[i] ? Vec2{0, 0} : Vec2{0, -kG * m.node_mass[i]};
    p = r;
    Real rr = dot(r, r);
    const Real rr0 = rr;
    int it = 0;
    for (; it < 200000 && rr > 1e-16 * rr0; ++it) {
        apply_k(b, p, kp, xp, fp, fm);
        const Real alpha = rr / dot(p, kp);
        for (size_t i = 0; i < n; ++i) {
            u[i] += alpha * p[i];
            r[i] -= alpha * kp[i];
        }
        const Real rr1 = dot(r, r);
        for (size_t i = 0; i < n; ++i)
            p[i] = r[i] + (rr1 / rr) * p[i];
        rr = rr1;
    }
    EXPECT_LE(rr, 1e-16 * rr0) << "CG did not converge in " << it << " iterations";
    return -u[static_cast<size_t>(b.tip)].y;
}

TEST(CompositeLocking, NearlyIncompressibleCantileverDoesNotLock) {
    // Timoshenko beam, uniform load q = rho g H, plane strain E' = E / (1 - nu^2):
    // w = q L^4 / (8 E' I) + q L^2 / (2 k G H), k = 5/6 (orientation only: the clamped
    // continuum end differs from the beam's clamp by O(H/L))
    const Real q = kRho * kG * kH, I = kH * kH * kH / 12.0;
    const Real Ep = kE / (1 - kNu * kNu), G = kE / (2 * (1 + kNu));
    const Real w_beam =
        q * std::pow(kL, 4) / (8 * Ep * I) + q * kL * kL / (2 * (5.0 / 6.0) * G * kH);

    const Real w_ref = tip_deflection(make_beam(80, 8, ElementKind::Composite6, kNu));
    const Real w_comp = tip_deflection(make_beam(20, 2, ElementKind::Composite6, kNu));
    const Real w_cst = tip_deflection(make_beam(20, 2, ElementKind::Cst, kNu));
    std::printf(
        "cantilever nu = %.3f tip deflection [m]: beam theory %.5e, reference "
        "(composite 80x8) %.5e, composite 20x2 %.5e (%.2f %% of ref), CST on the same "
        "nodes %.5e (%.2f %% of ref)\n",
        kNu, w_beam, w_ref, w_comp, 100 * w_comp / w_ref, w_cst, 100 * w_cst / w_ref);
    RecordProperty("w_ref", std::to_string(w_ref));
    RecordProperty("w_composite", std::to_string(w_comp));
    RecordProperty("w_cst", std::to_string(w_cst));

    // measured (Release): beam 1.1227e-2, reference 1.0999e-2, composite 100.6 %, CST 5.6 %;
    // the refined reference agrees with beam theory to the O(H/L) clamp effect (10 %)
    EXPECT_NEAR(w_ref, w_beam, 0.10 * w_beam);
    // issue #7: within 5 % of the refined reference
    EXPECT_NEAR(w_comp, w_ref, 0.05 * w_ref);
    // locking: CST on the same nodes is measurably stiffer (less than half the deflection)
    EXPECT_LT(w_cst, 0.5 * w_ref);
}

}  // namespace
}  // namespace fdem
