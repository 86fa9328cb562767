// Baseline A (Munjiza 2004 per-triangle potential, spec §1.2, docs/theory.md §7.1-7.3):
// point potential, exact edge integrals against adaptive quadrature, hand-computed passes,
// momentum balance of a couple, friction, couple search and the time-step entry point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "contact/field.hpp"
#include "contact/legacy_triangle.hpp"
#include "fdem/build.hpp"
#include "fdem/mesh.hpp"

namespace fdem {
namespace {

// deterministic uniform numbers in [lo, hi) (64-bit LCG, independent of the standard library)
struct Lcg {
    uint64_t s;
    explicit Lcg(uint64_t seed) : s(seed * 2862933555777941757ULL + 3037000493ULL) {}
    Real operator()(Real lo, Real hi) {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        return lo + (hi - lo) * static_cast<Real>(s >> 11) * (1.0 / 9007199254740992.0);
    }
};

// phi_p clamped to 0 outside p: the integrand of the brute-force quadrature
Real phi_or_zero(const Vec2 p[3], Vec2 x) {
    Real phi = 0;
    Vec2 g;
    legacy_triangle_potential(p, x, phi, g);
    return std::max(phi, Real(0));
}

// adaptive Simpson of f on [a, b]: exact on linear pieces, bisects only around the kinks, so it
// knows nothing of the break points the code under test computes
template <class F>
Real adaptive_simpson(const F& f, Real a, Real b, Real fa, Real fm, Real fb, Real whole,
                      int depth) {
    const Real m = 0.5 * (a + b);
    const Real lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    const Real flm = f(lm), frm = f(rm);
    const Real left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
    const Real right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    if (depth <= 0 || std::abs(left + right - whole) <= 1e-15 * (b - a)) return left + right;
    return adaptive_simpson(f, a, m, fa, flm, fm, left, depth - 1) +
           adaptive_simpson(f, m, b, fm, frm, fb, right, depth - 1);
}

template <class F>
Real integrate(const F& f, Real a, Real b) {
    // start from 4096 panels so that no clipped sliver hides between the first Simpson nodes
    // (the set below has one of width 1.8e-3)
    Real sum = 0;
    const int n = 4096;
    for (int k = 0; k < n; ++k) {
        const Real x0 = a + (b - a) * k / n, x1 = a + (b - a) * (k + 1) / n;
        const Real f0 = f(x0), f1 = f(x1), fm = f(0.5 * (x0 + x1));
        sum += adaptive_simpson(f, x0, x1, f0, fm, f1, (x1 - x0) / 6.0 * (f0 + 4.0 * fm + f1), 40);
    }
    return sum;
}

// ---- point potential ---------------------------------------------------------------------------

TEST(LegacyTrianglePotential, CentroidEdgesAndSubTriangleGradients) {
    for (int orient = 0; orient < 2; ++orient) {
        Vec2 p[3] = {{0.2, -0.1}, {2.1, 0.3}, {0.7, 1.6}};
        if (orient == 1) std::swap(p[1], p[2]);
        const Vec2 c = (p[0] + p[1] + p[2]) / 3.0;
        Real phi = -1;
        Vec2 g;
        ASSERT_TRUE(legacy_triangle_potential(p, c, phi, g));
        EXPECT_NEAR(phi, 1.0, 1e-14);  // 1 at the centroid (theory eq. 7.1), round-off only
        for (int k = 0; k < 3; ++k) {
            const Vec2 mid = 0.5 * (p[k] + p[(k + 1) % 3]);
            legacy_triangle_potential(p, mid, phi, g);
            EXPECT_NEAR(phi, 0.0, 1e-14);  // 0 on every edge

            // half-way from the edge midpoint to the centroid: phi = 1/2 (area ratio), and the
            // gradient equals 3 grad N of the opposite node, checked by central differences
            // (exact for a linear function, 1e-9 covers the round-off of the difference)
            const Vec2 x = 0.5 * (mid + c);
            legacy_triangle_potential(p, x, phi, g);
            EXPECT_NEAR(phi, 0.5, 1e-14);
            const Real e = 1e-6;
            Real pxp, pxm, pyp, pym;
            Vec2 dummy;
            legacy_triangle_potential(p, x + Vec2{e, 0}, pxp, dummy);
            legacy_triangle_potential(p, x - Vec2{e, 0}, pxm, dummy);
            legacy_triangle_potential(p, x + Vec2{0, e}, pyp, dummy);
            legacy_triangle_potential(p, x - Vec2{0, e}, pym, dummy);
            EXPECT_NEAR(g.x, (pxp - pxm) / (2 * e), 1e-8);
            EXPECT_NEAR(g.y, (pyp - pym) / (2 * e), 1e-8);
            // the gradient is normal to edge k (that sub-triangle's base) and points inwards
            const Vec2 edge = p[(k + 1) % 3] - p[k];
            EXPECT_NEAR(dot(g, edge), 0.0, 1e-12 * norm(g) * norm(edge));
            EXPECT_GT(dot(g, c - mid), 0.0);
        }
    }
}

// ---- edge integral, hand-computed case ---------------------------------------------------------

//   p = (0,0) (3,0) (0,3), centroid (1,1); edge a = (-1,1) -> b = (3,1) along y = 1:
//
//     3 +
//       |\             inside p for x in [0, 2]; phi = 3 min N is the tent
//       | \            0 at x = 0, 1 at x = 1 (centroid), 0 at x = 2, so int phi dx = 1
//   a---+--*--+---b    s = (x + 1) / 4: s_min = 1/4, s_max = 3/4,
//       |    \         I0 = int q ds = (1/3)(1/4) = 1/12, I1 = I0 / 2 (symmetric about s = 1/2)
//     0 +-----+
TEST(LegacyEdgeIntegral, EdgeThroughTheCentroid) {
    const Vec2 p[3] = {{0, 0}, {3, 0}, {0, 3}};
    EdgeIntegral ei;
    ASSERT_TRUE(legacy_edge_integral({-1, 1}, {3, 1}, p, ei));
    // tolerances: a handful of rounding errors on O(1) numbers
    EXPECT_NEAR(ei.s_min, 0.25, 1e-15);
    EXPECT_NEAR(ei.s_max, 0.75, 1e-15);
    EXPECT_NEAR(ei.I0, 1.0 / 12.0, 1e-15);
    EXPECT_NEAR(ei.I1, 1.0 / 24.0, 1e-15);
}

TEST(LegacyEdgeIntegral, MissesTouchesAndRunsAlongAnEdge) {
    const Vec2 p[3] = {{0, 0}, {3, 0}, {0, 3}};
    EdgeIntegral ei;
    EXPECT_FALSE(legacy_edge_integral({-1, -1}, {4, -1}, p, ei));  // below p
    EXPECT_FALSE(legacy_edge_integral({2, 2}, {5, 0}, p, ei));     // beyond the hypotenuse
    EXPECT_FALSE(legacy_edge_integral({-1, 0}, {4, 0}, p, ei));    // along an edge: phi = 0
    EXPECT_FALSE(legacy_edge_integral({-1, 4}, {4, -1}, p, ei));   // on the hypotenuse line
    EXPECT_FALSE(legacy_edge_integral({-1, 1}, {0, 1}, p, ei));    // ends on the boundary
}

// ---- one pass, hand-computed -------------------------------------------------------------------

// Same geometry, the edge belongs to e = (-1,1) (3,1) (1,50) (counter-clockwise, above the edge),
// penalty p: resultant on e = p int phi dGamma = p upwards, split 1/2 : 1/2 by symmetry.
// Reactions: lambda(a) = (1, -1/3, 1/3), lambda(b) = (-1/3, 1, 1/3), so each node of p gets
// -(p/2)(lambda_j(a) + lambda_j(b)) = -p/3 in y.
TEST(LegacyEdgePass, EdgeThroughTheCentroidByHand) {
    const Vec2 xp[3] = {{0, 0}, {3, 0}, {0, 3}};
    const Real pen = 7.0;
    // e = (-1,1) (3,1) (1,3) would also sink its other edges into p; a tall e isolates edge 0
    const Vec2 thin[3] = {{-1, 1}, {3, 1}, {1, 50}};
    Vec2 fe[3], fp[3];
    legacy_edge_pass(thin, xp, pen, fe, fp);
    EdgeIntegral ei;
    ASSERT_FALSE(legacy_edge_integral(thin[1], thin[2], xp, ei));
    ASSERT_FALSE(legacy_edge_integral(thin[2], thin[0], xp, ei));
    // 1e-14: a few roundings of O(p) numbers
    EXPECT_NEAR(fe[0].x, 0.0, 1e-14 * pen);
    EXPECT_NEAR(fe[0].y, pen / 2, 1e-14 * pen);
    EXPECT_NEAR(fe[1].y, pen / 2, 1e-14 * pen);
    EXPECT_EQ(fe[2].y, 0.0);
    for (int j = 0; j < 3; ++j) {
        EXPECT_NEAR(fp[j].x, 0.0, 1e-14 * pen);
        EXPECT_NEAR(fp[j].y, -pen / 3, 1e-14 * pen);
    }
}

// A small triangle e inside one sub-triangle of p: by the divergence theorem the resultant on e
// is -p int_e grad phi_p dA = -3 p A_e grad N_k (theory eq. 7.7), k the node opposite the base.
TEST(LegacyEdgePass, TriangleInsideOneSubTriangle) {
    const Vec2 xp[3] = {{0, 0}, {3, 0}, {0, 3}};
    // near the midpoint of edge 0-1 (y = 0), below the centroid: sub-triangle of edge 0-1,
    // opposite node 2, phi = 3 N_2 = y, grad phi = (0, 1)
    const Vec2 xe[3] = {{1.3, 0.2}, {1.7, 0.25}, {1.45, 0.5}};
    const Real pen = 2.5;
    Vec2 fe[3], fp[3];
    legacy_edge_pass(xe, xp, pen, fe, fp);
    const Vec2 sum = fe[0] + fe[1] + fe[2];
    const Real area = signed_area(xe[0], xe[1], xe[2]);
    // 1e-14 relative: exact integration, rounding only
    EXPECT_NEAR(sum.x, 0.0, 1e-14 * pen);
    EXPECT_NEAR(sum.y, -pen * area, 1e-14 * pen);
}

// ---- random couples: resultant and moment against quadrature, momentum balance ---------------

struct RandomCouple {
    Vec2 a[3], b[3];
};

RandomCouple random_couple(Lcg& rng) {
    RandomCouple c;
    const Vec2 ca{rng(-0.2, 0.2), rng(-0.2, 0.2)};
    const Vec2 cb = ca + Vec2{rng(-0.8, 0.8), rng(-0.8, 0.8)};
    for (int i = 0; i < 3; ++i) {
        const Real t = 2.0944 * i + rng(-0.6, 0.6);
        const Real r = rng(0.5, 1.2);
        c.a[i] = ca + r * Vec2{std::cos(t), std::sin(t)};
        const Real u = 2.0944 * i + rng(-0.6, 0.6) + 1.0;
        c.b[i] = cb + rng(0.4, 1.0) * Vec2{std::cos(u), std::sin(u)};
    }
    // random orientation of b (the kernels accept both)
    if (rng(0, 1) < 0.5) std::swap(c.b[1], c.b[2]);
    return c;
}

TEST(LegacyEdgePass, ResultantAndMomentMatchQuadrature) {
    Lcg rng(11);
    int hits = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const RandomCouple c = random_couple(rng);
        const Real pen = 3.0;
        Vec2 fe[3], fp[3];
        legacy_edge_pass(c.a, c.b, pen, fe, fp);

        // reference: -p int phi_b nu_hat dGamma and its moment, edge by edge, by adaptive
        // Simpson on the unclipped edge (phi clamped to 0 outside b)
        Vec2 ref_f;
        Real ref_m = 0;
        const Real o = signed_area(c.a[0], c.a[1], c.a[2]) > 0 ? 1.0 : -1.0;
        for (int k = 0; k < 3; ++k) {
            const Vec2 a = c.a[k], b = c.a[(k + 1) % 3];
            const Vec2 nu = o * Vec2{b.y - a.y, a.x - b.x};
            auto f0 = [&](Real s) { return phi_or_zero(c.b, (1 - s) * a + s * b); };
            auto f1 = [&](Real s) { return s * phi_or_zero(c.b, (1 - s) * a + s * b); };
            const Real J0 = integrate(f0, 0, 1), J1 = integrate(f1, 0, 1);
            const Vec2 fk = (-pen * J0) * nu;  // = -p (int phi dGamma) nu_hat, dGamma = L ds
            ref_f += fk;
            // moment about the origin of the traction -p phi nu_hat at x(s) = a + s (b - a)
            ref_m += cross(a, fk) + cross(b - a, (-pen * J1) * nu);
            if (J0 > 0) ++hits;
        }
        const Vec2 sum = fe[0] + fe[1] + fe[2];
        const Real msum = cross(c.a[0], fe[0]) + cross(c.a[1], fe[1]) + cross(c.a[2], fe[2]);
        // 1e-10 relative (brief): the quadrature converges to ~1e-14 at the kinks
        const Real scale = pen * 3.0;  // |nu| ~ edge lengths ~ 1-2, phi <= 1
        EXPECT_NEAR(sum.x, ref_f.x, 1e-10 * scale) << "trial " << trial;
        EXPECT_NEAR(sum.y, ref_f.y, 1e-10 * scale) << "trial " << trial;
        EXPECT_NEAR(msum, ref_m, 1e-10 * scale) << "trial " << trial;
    }
    EXPECT_GT(hits, 40);  // the set really exercises contact (about 2 of 3 edges hit)
}

TEST(LegacyTriangleCouple, ForcesSumToZeroWithZeroMoment) {
    Lcg rng(5);
    int nonzero = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const RandomCouple c = random_couple(rng);
        Vec2 va[3], vb[3];
        for (int i = 0; i < 3; ++i) {
            va[i] = {rng(-1, 1), rng(-1, 1)};
            vb[i] = {rng(-1, 1), rng(-1, 1)};
        }
        // friction on, and with a cap that binds in some edges: both force kinds must balance
        LegacyFriction fr{0.3e3, 0.4, 1e-3};
        Real slide[6];
        for (Real& s : slide)
            s = rng(-1e-3, 1e-3);
        Vec2 fa[3], fb[3];
        legacy_triangle_couple(c.a, c.b, 1e3, fa, fb, &fr, va, vb, slide);
        Vec2 sum;
        Real mom = 0, fabs_sum = 0, mabs_sum = 0;
        for (int i = 0; i < 3; ++i) {
            sum += fa[i] + fb[i];
            mom += cross(c.a[i], fa[i]) + cross(c.b[i], fb[i]);
            fabs_sum += norm(fa[i]) + norm(fb[i]);
            mabs_sum += norm(c.a[i]) * norm(fa[i]) + norm(c.b[i]) * norm(fb[i]);
        }
        if (fabs_sum > 0) ++nonzero;
        // 1e-12 relative to the sum of magnitudes (brief): exact cancellation up to rounding
        EXPECT_LE(norm(sum), 1e-12 * fabs_sum) << "trial " << trial;
        EXPECT_LE(std::abs(mom), 1e-12 * mabs_sum) << "trial " << trial;
    }
    EXPECT_GT(nonzero, 100);
}

// Two passes of the symmetric configuration: swapping the roles of a and b swaps the forces.
TEST(LegacyTriangleCouple, RoleSwapGivesTheSameForces) {
    Lcg rng(99);
    for (int trial = 0; trial < 20; ++trial) {
        const RandomCouple c = random_couple(rng);
        Vec2 fa[3], fb[3], ga[3], gb[3];
        legacy_triangle_couple(c.a, c.b, 1.0, fa, fb);
        legacy_triangle_couple(c.b, c.a, 1.0, gb, ga);
        for (int i = 0; i < 3; ++i) {
            // the sum order differs, so allow rounding (1e-14 of O(1) forces)
            EXPECT_NEAR(fa[i].x, ga[i].x, 1e-14);
            EXPECT_NEAR(fa[i].y, ga[i].y, 1e-14);
            EXPECT_NEAR(fb[i].x, gb[i].x, 1e-14);
            EXPECT_NEAR(fb[i].y, gb[i].y, 1e-14);
        }
    }
}

// ---- stored energy (theory eq. 7.10) -----------------------------------------------------------

// Munjiza's force field is the gradient of E = p int_S (phi_a + phi_b) dA for rigid motions:
// the resultant on a equals -dE/du and its moment -dE/dtheta (central differences of the exact
// polygon integral; E is C1, so the O(eps^2) error is ~1e-10 relative with eps = 1e-6, and kinks
// of E'' add O(eps): 1e-6 relative covers both).
TEST(LegacyCoupleEnergy, ForcesAreMinusTheRigidMotionGradient) {
    Lcg rng(21);
    int checked = 0;
    for (int trial = 0; trial < 60; ++trial) {
        const RandomCouple c = random_couple(rng);
        const Real pen = 5.0;
        Vec2 fa[3], fb[3];
        legacy_triangle_couple(c.a, c.b, pen, fa, fb);
        const Vec2 F = fa[0] + fa[1] + fa[2];
        const Vec2 ctr = (c.a[0] + c.a[1] + c.a[2]) / 3.0;
        Real M = 0;
        for (int i = 0; i < 3; ++i)
            M += cross(c.a[i] - ctr, fa[i]);
        const Real E = legacy_couple_energy(c.a, c.b, pen);
        if (E == 0) {
            EXPECT_EQ(norm(F), 0.0);
            continue;
        }
        const Real eps = 1e-6;
        auto moved = [&](Vec2 u, Real th) {
            Vec2 a[3];
            const Real cs = std::cos(th), sn = std::sin(th);
            for (int i = 0; i < 3; ++i) {
                const Vec2 r = c.a[i] - ctr;
                a[i] = ctr + u + Vec2{cs * r.x - sn * r.y, sn * r.x + cs * r.y};
            }
            return legacy_couple_energy(a, c.b, pen);
        };
        const Real dEx = (moved({eps, 0}, 0) - moved({-eps, 0}, 0)) / (2 * eps);
        const Real dEy = (moved({0, eps}, 0) - moved({0, -eps}, 0)) / (2 * eps);
        const Real dEt = (moved({}, eps) - moved({}, -eps)) / (2 * eps);
        const Real scale = norm(F) + std::abs(M) + 1e-3 * pen;
        EXPECT_NEAR(F.x, -dEx, 1e-6 * scale) << "trial " << trial;
        EXPECT_NEAR(F.y, -dEy, 1e-6 * scale) << "trial " << trial;
        EXPECT_NEAR(M, -dEt, 1e-6 * scale) << "trial " << trial;
        ++checked;
    }
    EXPECT_GT(checked, 30);
}

// Hand case: b = a (identical triangles) stores p (int_a phi dA) * 2 = 2 p A (the mean of
// 3 min N over a triangle is 1/3: pyramid of height 1 over the triangle)
TEST(LegacyCoupleEnergy, IdenticalTriangles) {
    const Vec2 a[3] = {{0, 0}, {2, 0}, {0.5, 1.5}};
    const Real area = signed_area(a[0], a[1], a[2]);
    EXPECT_NEAR(legacy_couple_energy(a, a, 3.0), 2.0 * 3.0 * area / 3.0, 1e-14);
    const Vec2 far[3] = {{5, 5}, {6, 5}, {5, 6}};
    EXPECT_EQ(legacy_couple_energy(a, far, 3.0), 0.0);
}

// ---- friction (spec §1.2 step 9) ---------------------------------------------------------------

// Thin contactor of the hand case sliding at v in +x over a fixed p: one step stores
// s = v dt, the tangential force on the edge is -p_t s in x (stick), split 1/2 : 1/2; a large
// step slides and caps it at mu |F| = mu p (F from the hand case).
TEST(LegacyEdgePass, FrictionStickThenSlip) {
    const Vec2 xp[3] = {{0, 0}, {3, 0}, {0, 3}};
    const Vec2 thin[3] = {{-1, 1}, {3, 1}, {1, 50}};
    const Vec2 ve[3] = {{2, 0}, {2, 0}, {2, 0}};
    const Vec2 vp[3] = {};
    const Real pen = 10, pt = 1, mu = 0.5;

    LegacyFriction fr{pt, mu, 1e-3};
    Real slide[3] = {0, 0, 0};
    Vec2 fe[3], fp[3];
    Real diss = legacy_edge_pass(thin, xp, pen, fe, fp, &fr, ve, vp, slide);
    EXPECT_NEAR(slide[0], 2e-3, 1e-15);  // v dt, rounding only
    EXPECT_NEAR(fe[0].x + fe[1].x, -pt * 2e-3, 1e-15);
    EXPECT_NEAR(fe[0].x, fe[1].x, 1e-15);  // F_a = F_b by symmetry
    EXPECT_EQ(diss, 0.0);                  // sticking: nothing dissipated

    fr.dt = 10.0;  // trial spring 20 + 2e-3 >> cap mu p / p_t = 5
    for (Vec2& f : fe)
        f = {};
    for (Vec2& f : fp)
        f = {};
    diss = legacy_edge_pass(thin, xp, pen, fe, fp, &fr, ve, vp, slide);
    EXPECT_NEAR(slide[0], mu * pen / pt, 1e-12);
    EXPECT_NEAR(fe[0].x + fe[1].x, -mu * pen, 1e-12);  // |f_t| = mu |f_n|, |f_n| = p
    const Real trial = 2e-3 + 20.0;
    EXPECT_NEAR(diss, 0.5 * pt * (trial * trial - 25.0), 1e-9);
    // friction reaction on p: equal and opposite
    EXPECT_NEAR(fp[0].x + fp[1].x + fp[2].x, mu * pen, 1e-12);

    // out of contact: the spring resets
    const Vec2 far[3] = {{10, 10}, {11, 10}, {10, 11}};
    legacy_edge_pass(far, xp, pen, fe, fp, &fr, ve, vp, slide);
    EXPECT_EQ(slide[0], 0.0);
}

// ---- couples and the time-step entry point -----------------------------------------------------

Model three_blocks() {
    Model m;
    Material mat;
    mat.name = "rock";
    mat.density = 1000;
    mat.youngs_modulus = 1e9;
    m.materials.push_back(mat);
    m.contact.algorithm = ContactAlgorithm::Smooth;  // builds the shared contact topology
    m.contact.params.friction = 0.3;
    auto add = [&](Real x0, Real y0, int nx, int ny, bool fixed) {
        const MeshData mesh = make_rectangle_mesh(x0, y0, 0.1 * nx, 0.1 * ny, nx, ny, true);
        std::vector<int32_t> ids(mesh.tris.size());
        for (size_t i = 0; i < ids.size(); ++i)
            ids[i] = static_cast<int32_t>(i);
        BodyOptions opt;
        opt.name = "b";
        opt.fixed = fixed;
        add_bodies(m, mesh, ids, opt);
    };
    add(0, 0, 8, 2, true);               // fixed base
    add(0.13, 0.19, 3, 3, false);        // block overlapping the base by 0.01
    add(0.42, 0.195, 2, 2, false);       // second block, overlapping block 1 and the base
    add(0.05, 0.25 + 0.3, 2, 2, false);  // far above
    finalize_model(m);
    return m;
}

TEST(LegacyCouples, GridMatchesBruteForce) {
    const Model m = three_blocks();
    const ContactTopology topo = build_topology(m);
    ASSERT_GT(topo.boundary_tris.size(), 10u);
    LegacyTriangleState a, b;
    find_legacy_couples(m, topo, m.node_x0.data(), a);
    find_legacy_couples_brute_force(m, topo, m.node_x0.data(), b);
    ASSERT_EQ(a.couples.size(), b.couples.size());
    ASSERT_GT(a.couples.size(), 0u);
    for (size_t k = 0; k < a.couples.size(); ++k) {
        EXPECT_EQ(a.couples[k].a, b.couples[k].a);
        EXPECT_EQ(a.couples[k].b, b.couples[k].b);
        EXPECT_NE(m.tri_body[a.couples[k].a], m.tri_body[a.couples[k].b]);
    }
}

TEST(LegacyCouples, StepForcesBalanceAndPushBlocksApart) {
    const Model m = three_blocks();
    State s;
    s.topology = build_topology(m);
    s.x = m.node_x0;
    s.v.assign(m.node_x0.size(), Vec2{});
    s.f.assign(m.node_x0.size(), Vec2{});
    s.f_contact.assign(m.node_x0.size(), Vec2{});
    s.dt = 1e-6;
    for (NodeId i = m.bodies[1].node_begin; i < m.bodies[1].node_end; ++i)
        s.v[i] = {0.5, 0};
    LegacyTriangleState ls;
    add_legacy_triangle_forces(m, s, ls);
    EXPECT_GT(ls.active, 0);

    Vec2 total, body1;
    Real mags = 0;
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        total += s.f_contact[i];
        mags += norm(s.f_contact[i]);
        if (m.node_body[i] == 1) body1 += s.f_contact[i];
        EXPECT_EQ(s.f[i].x, s.f_contact[i].x);
    }
    EXPECT_LE(norm(total), 1e-12 * mags);  // action = reaction, rounding only
    EXPECT_GT(body1.y, 0.0);               // block 1 pushed up out of the base
    EXPECT_LT(body1.x, 0.0);               // friction opposes its sliding in +x
    // body 3 is far away: no force
    for (NodeId i = m.bodies[3].node_begin; i < m.bodies[3].node_end; ++i) {
        EXPECT_EQ(norm(s.f_contact[i]), 0.0);
    }

    // same forces as legacy_triangle_couple summed over the couples by hand (fresh couples:
    // zero sliding history), in the same order, so equal to rounding
    std::vector<Vec2> ref(m.node_x0.size());
    const ContactParams& p = pair_parameters(m.contact, 0, 0);
    const LegacyFriction fr{p.tangential_penalty, p.friction, s.dt};
    for (const LegacyCouple& c : ls.couples) {
        Vec2 xa[3], xb[3], va[3], vb[3], fa[3], fb[3];
        for (int k = 0; k < 3; ++k) {
            xa[k] = s.x[m.tri_nodes[c.a][k]];
            xb[k] = s.x[m.tri_nodes[c.b][k]];
            va[k] = s.v[m.tri_nodes[c.a][k]];
            vb[k] = s.v[m.tri_nodes[c.b][k]];
        }
        Real slide[6] = {0, 0, 0, 0, 0, 0};
        legacy_triangle_couple(xa, xb, p.penalty, fa, fb, &fr, va, vb, slide);
        for (int k = 0; k < 3; ++k) {
            ref[m.tri_nodes[c.a][k]] += fa[k];
            ref[m.tri_nodes[c.b][k]] += fb[k];
        }
    }
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        EXPECT_NEAR(ref[i].x, s.f_contact[i].x, 1e-12 * mags);
        EXPECT_NEAR(ref[i].y, s.f_contact[i].y, 1e-12 * mags);
    }
}

}  // namespace
}  // namespace fdem
