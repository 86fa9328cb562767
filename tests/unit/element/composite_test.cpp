// Composite 6-node triangle kernel (issue #7, docs/theory.md §3.5, spec §3.3): patch test,
// rigid-rotation objectivity, forces = -gradient of the split strain energy (central finite
// differences, which include the coupling of all four sub-triangles through Jbar), small-strain
// limit (Hooke's law), and the stress written for output.
#include "element/composite.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "support/scenes.hpp"

namespace fdem {
namespace {

bool on_boundary(Vec2 p) {
    return p.x < 1e-12 || p.y < 1e-12 || p.x > 1 - 1e-12 || p.y > 1 - 1e-12;
}

// Unit square of 4 x 4 cells, two 6-node triangles per cell (32 composites, 128 sub-triangles),
// every interior node (corner or mid-edge) moved by up to +-0.02 m (8 % of the cell), so the
// patch test is not passed by symmetry alone:
//
//   +---o---+---o---+ ...     + corner node, o mid-edge node; each 6-node triangle is split
//   |     / |     /           into (n1,n2,n6), (n2,n3,n4), (n6,n4,n5), (n2,n4,n6)
//   o   o   o   o
//   | /     | /
//   +---o---+---o---+ ...
Model perturbed_patch(Real nu, PlaneMode plane, ElementKind kind = ElementKind::Composite6) {
    Model m;
    Material mat = scenes::paper_material("p", 1e9, nu);
    mat.plane = plane;
    m.materials.push_back(mat);
    scenes::add_rectangle_order2(m, 0, 0, 1, 1, 4, 4, 0, kind);
    std::mt19937 rng(11);
    std::uniform_real_distribution<Real> u(-0.02, 0.02);
    for (auto& p : m.node_x0) {
        if (!on_boundary(p)) p = p + Vec2{u(rng), u(rng)};
    }
    finalize_model(m);
    return m;
}

std::vector<Vec2> forces(const Model& m, const std::vector<Vec2>& x, ElementPass* pass = nullptr) {
    std::vector<Vec2> f(x.size()), v(x.size());
    const ElementPass p = add_internal_forces(m, x.data(), v.data(), f.data(), 0, m.num_tris());
    if (pass) *pass = p;
    return f;
}

Real energy(const Model& m, const std::vector<Vec2>& x) {
    ElementPass p;
    forces(m, x, &p);
    return p.strain_energy;
}

/// The split law's Cauchy stress for a uniform F, written out independently of the kernel:
/// sigma = (mu/J^2)(B - tr B / 2 I) + (kappa/2)(J - 1/J) I, kappa = lambda + mu (theory eq. 3.8)
Mat2 split_law_stress(const Material& mat, const Mat2& F) {
    const Real J = F.xx * F.yy - F.xy * F.yx;
    const Mat2 B = F * transpose(F);
    const Real kappa = mat.lambda + mat.mu;
    const Real p = 0.5 * kappa * (J - 1.0 / J);
    const Real a = mat.mu / (J * J), h = 0.5 * (B.xx + B.yy);
    return {a * (B.xx - h) + p, a * B.xy, a * B.yx, a * (B.yy - h) + p};
}

Real max_abs(const Mat2& a) {
    return std::max({std::abs(a.xx), std::abs(a.xy), std::abs(a.yx), std::abs(a.yy)});
}

TEST(Composite, PatchTestUniformStretchGivesSplitLawStressAndNoInteriorForce) {
    for (PlaneMode plane : {PlaneMode::Strain, PlaneMode::Stress}) {
        const Model m = perturbed_patch(0.45, plane);
        const Mat2 F = {1.02, 0.01, -0.005, 0.97};
        std::vector<Vec2> x(m.node_x0.size());
        for (size_t i = 0; i < x.size(); ++i)
            x[i] = F * m.node_x0[i];

        // every sub-triangle carries the analytic stress (1e-12 relative: a few rounded
        // products per component)
        const Mat2 expect = split_law_stress(m.materials[0], F);
        for (TriId t = 0; t < m.num_tris(); ++t) {
            const Mat2 s = composite_stress(m, x.data(), t);
            EXPECT_LT(max_abs(s - expect), 1e-12 * max_abs(expect)) << "triangle " << t;
            EXPECT_NEAR(composite_jbar(m, x.data(), t), det(F), 1e-14);
        }

        // interior forces cancel (1e-10 relative to the largest boundary force, spec patch
        // test: the scaled normals around an interior node sum to zero up to rounding)
        const auto f = forces(m, x);
        Real fmax = 0, finterior = 0;
        for (size_t i = 0; i < f.size(); ++i) {
            fmax = std::max(fmax, norm(f[i]));
            if (!on_boundary(m.node_x0[i])) finterior = std::max(finterior, norm(f[i]));
        }
        EXPECT_GT(fmax, 1e5);  // the boundary carries the traction
        EXPECT_LT(finterior, 1e-10 * fmax) << "plane mode " << static_cast<int>(plane);
    }
}

TEST(Composite, RigidRotationIsStressFree) {
    const Model m = perturbed_patch(0.49, PlaneMode::Strain);
    const Real th = 0.7;
    const Mat2 R = {std::cos(th), -std::sin(th), std::sin(th), std::cos(th)};
    std::vector<Vec2> x(m.node_x0.size());
    for (size_t i = 0; i < x.size(); ++i)
        x[i] = R * m.node_x0[i] + Vec2{3.0, -1.0};
    ElementPass p;
    const auto f = forces(m, x, &p);
    // scale M = lambda + 2 mu (~5e10 Pa at nu = 0.49): positions rounded to ~1e-16 of |x| ~ 3 m
    // give strains ~1e-15, so stresses ~1e-15 M, forces ~1e-15 M h (h = 0.25 m) and energies
    // ~1e-15 M A (A = 1 m^2); 1e-13 leaves a factor 100 for the sums. A stretch of 1 % instead
    // gives forces ~1e-2 M h, eleven orders larger.
    const Material& mat = m.materials[0];
    const Real M = mat.lambda + 2 * mat.mu;
    for (size_t i = 0; i < f.size(); ++i)
        EXPECT_LT(norm(f[i]), 1e-13 * M * 0.25) << "node " << i;
    EXPECT_LT(std::abs(p.strain_energy), 1e-13 * M * 1.0);
    for (TriId t = 0; t < m.num_tris(); ++t)
        EXPECT_LT(max_abs(composite_stress(m, x.data(), t)), 1e-13 * M) << "triangle " << t;
}

TEST(Composite, ForcesAreMinusTheGradientOfTheSplitEnergy) {
    // non-uniform deformation of moderate size (strains ~5 %), nearly incompressible material
    // so the volumetric term, coupled over each composite through Jbar, dominates
    const Model m = perturbed_patch(0.49, PlaneMode::Strain);
    std::mt19937 rng(5);
    std::uniform_real_distribution<Real> u(-0.01, 0.01);
    std::vector<Vec2> x(m.node_x0.size());
    for (size_t i = 0; i < x.size(); ++i) {
        const Vec2 X = m.node_x0[i];
        x[i] = Vec2{1.03 * X.x + 0.02 * X.y * X.y, 0.98 * X.y + 0.01 * X.x} + Vec2{u(rng), u(rng)};
    }
    const auto f = forces(m, x);
    Real fmax = 0, err = 0;
    const Real h = 1e-7;  // [m]: truncation O(h^2) ~ 1e-14 relative, rounding ~ eps E_tot / h
    for (size_t i = 0; i < x.size(); ++i) {
        for (int c = 0; c < 2; ++c) {
            auto xp = x, xm = x;
            (c == 0 ? xp[i].x : xp[i].y) += h;
            (c == 0 ? xm[i].x : xm[i].y) -= h;
            const Real g = (energy(m, xp) - energy(m, xm)) / (2 * h);
            const Real fc = c == 0 ? f[i].x : f[i].y;
            err = std::max(err, std::abs(fc + g));
            fmax = std::max(fmax, std::abs(fc));
        }
    }
    RecordProperty("fd_relative_error", std::to_string(err / fmax));
    std::printf(
        "composite forces vs central FD of the energy: max error %.3g N/m, max force "
        "%.3g N/m, relative %.3g\n",
        err, fmax, err / fmax);
    // 1e-6 relative: the energy (~1e6 J/m) is summed to ~1e-16 relative, so the FD quotient
    // carries ~1e-10/h-scale rounding; a missing Jbar coupling term would be O(1) relative
    EXPECT_LT(err, 1e-6 * fmax);
}

TEST(Composite, SmallStrainLimitIsHookesLaw) {
    const Model m = perturbed_patch(0.3, PlaneMode::Strain);
    const Material& mat = m.materials[0];
    const Real e = 1e-6;
    const Mat2 H = {0.7 * e, 0.3 * e, -0.5 * e, -0.2 * e};
    const Mat2 F = identity2() + H;
    std::vector<Vec2> x(m.node_x0.size());
    for (size_t i = 0; i < x.size(); ++i)
        x[i] = F * m.node_x0[i];
    const Real exy = 0.5 * (H.xy + H.yx);
    const Real tr = H.xx + H.yy;
    const Mat2 hooke = {2 * mat.mu * H.xx + mat.lambda * tr, 2 * mat.mu * exy, 2 * mat.mu * exy,
                        2 * mat.mu * H.yy + mat.lambda * tr};
    // nonlinear terms are O(|H|) = 1e-6 relative to the linear stress
    for (TriId t = 0; t < m.num_tris(); ++t) {
        EXPECT_LT(max_abs(composite_stress(m, x.data(), t) - hooke), 1e-5 * max_abs(hooke));
    }
}

TEST(Composite, VolumetricPartIsSharedByTheWholeComposite) {
    // moving one mid-edge node changes the areas of only some sub-triangles of composite 0,
    // yet the pressure (half the trace: the isochoric part is traceless) of all four of its
    // sub-triangles changes by the same amount
    const Model m = perturbed_patch(0.45, PlaneMode::Strain);
    std::vector<Vec2> x = m.node_x0;
    std::vector<Mat2> s0(static_cast<size_t>(m.num_tris()));
    for (TriId t = 0; t < m.num_tris(); ++t)
        s0[t] = composite_stress(m, x.data(), t);
    const NodeId n6 = m.tri_nodes[0][2];  // mid node n6 of composite 0 (model.hpp layout)
    x[n6] = x[n6] + Vec2{1e-4, 1e-4};
    for (TriId t = 0; t < 4; ++t) {
        const Mat2 d = composite_stress(m, x.data(), t) - s0[t];
        // trace part identical for all four: the mean pressure (1e-9 relative: rounding)
        const Mat2 d0 = composite_stress(m, x.data(), 0) - s0[0];
        const Real p = 0.5 * (d.xx + d.yy), p0 = 0.5 * (d0.xx + d0.yy);
        EXPECT_NEAR(p, p0, 1e-9 * std::abs(p0));
        EXPECT_GT(std::abs(p0), 1e3);
    }
}

}  // namespace
}  // namespace fdem
