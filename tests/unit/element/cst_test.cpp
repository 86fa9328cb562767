// CST element kernel: patch test, objectivity, consistency with the strain energy, small strain.
// (issue "engine foundation", spec T12, docs/theory.md §2-3)
#include "element/cst.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "fdem/simulate.hpp"
#include "material/hyperelastic.hpp"
#include "support/hash.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

// 4 x 4 square of side 1 with interior nodes perturbed by up to 20 % of the cell size, so the
// patch test is not passed by symmetry alone.
Model perturbed_patch(Real nu, PlaneMode plane) {
    Model m;
    Material mat = scenes::paper_material("p", 1e9, nu);
    mat.plane = plane;
    m.materials.push_back(mat);
    scenes::add_rectangle(m, 0, 0, 1, 1, 4, 4, 0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<Real> u(-0.05, 0.05);
    for (auto& p : m.node_x0) {
        const bool boundary = p.x < 1e-12 || p.y < 1e-12 || p.x > 1 - 1e-12 || p.y > 1 - 1e-12;
        if (!boundary) p = p + Vec2{u(rng), u(rng)};
    }
    finalize_model(m);
    return m;
}

bool on_boundary(Vec2 p) {
    return p.x < 1e-12 || p.y < 1e-12 || p.x > 1 - 1e-12 || p.y > 1 - 1e-12;
}

std::vector<Vec2> forces(const Model& m, const std::vector<Vec2>& x, ElementPass* pass = nullptr) {
    std::vector<Vec2> f(x.size()), v(x.size());
    const ElementPass p = add_internal_forces(m, x.data(), v.data(), f.data(), 0, m.num_tris());
    if (pass) *pass = p;
    return f;
}

TEST(Cst, PatchTestUniformStretchGivesUniformStressAndNoInteriorForce) {
    const Model m = perturbed_patch(0.3, PlaneMode::Strain);
    const Mat2 F = {1.02, 0.01, -0.005, 0.97};
    std::vector<Vec2> x(m.node_x0.size());
    for (size_t i = 0; i < x.size(); ++i)
        x[i] = F * m.node_x0[i];

    const std::vector<Vec2> f = forces(m, x);
    const Mat2 sigma = cauchy_stress(m.materials[0], F);
    // reference force scale: stress times a cell edge (1/4)
    const Real scale = std::sqrt(ddot(sigma, sigma)) * 0.25;
    for (size_t i = 0; i < x.size(); ++i) {
        if (on_boundary(m.node_x0[i])) continue;
        // 1e-10 relative: interior forces cancel exactly up to round-off
        EXPECT_LT(norm(f[i]), 1e-10 * scale) << "node " << i;
    }
    for (TriId t = 0; t < m.num_tris(); ++t) {
        const Mat2 Ft = deformation_gradient(m, x.data(), t);
        const Mat2 st = cauchy_stress(m.materials[0], Ft);
        EXPECT_NEAR(st.xx, sigma.xx, 1e-10 * scale * 4);
        EXPECT_NEAR(st.xy, sigma.xy, 1e-10 * scale * 4);
        EXPECT_NEAR(st.yy, sigma.yy, 1e-10 * scale * 4);
    }
}

TEST(Cst, RigidRotationBy90DegreesGivesZeroStressAndForce) {
    const Model m = perturbed_patch(0.25, PlaneMode::Strain);
    const Mat2 R = {0, -1, 1, 0};
    std::vector<Vec2> x(m.node_x0.size());
    for (size_t i = 0; i < x.size(); ++i)
        x[i] = R * m.node_x0[i] + Vec2{3, -2};
    ElementPass pass;
    const std::vector<Vec2> f = forces(m, x, &pass);
    for (const Vec2& fi : f)
        EXPECT_LT(norm(fi), 1e-6);  // E = 1e9: 1e-6 N/m is 1e-15 relative
    EXPECT_LT(std::abs(pass.strain_energy), 1e-6);
    for (TriId t = 0; t < m.num_tris(); ++t) {
        const Mat2 s = cauchy_stress(m.materials[0], deformation_gradient(m, x.data(), t));
        EXPECT_LT(std::sqrt(ddot(s, s)), 1e-5);  // 1e-14 of E
    }
}

TEST(Cst, NodalForcesAreMinusTheGradientOfTheStrainEnergy) {
    for (const PlaneMode plane : {PlaneMode::Strain, PlaneMode::Stress}) {
        const Model m = perturbed_patch(0.3, plane);
        std::mt19937 rng(11);
        std::uniform_real_distribution<Real> u(-0.03, 0.03);
        std::vector<Vec2> x(m.node_x0.size());
        for (size_t i = 0; i < x.size(); ++i)
            x[i] = m.node_x0[i] + Vec2{u(rng), u(rng)};

        const std::vector<Vec2> f = forces(m, x);
        auto energy = [&](const std::vector<Vec2>& y) {
            ElementPass p;
            forces(m, y, &p);
            return p.strain_energy;
        };
        const Real h = 1e-6;
        Real fmax = 0;
        for (const Vec2& fi : f)
            fmax = std::max(fmax, norm(fi));
        for (size_t i = 0; i < x.size(); ++i) {
            for (int c = 0; c < 2; ++c) {
                std::vector<Vec2> xp = x, xm = x;
                (c == 0 ? xp[i].x : xp[i].y) += h;
                (c == 0 ? xm[i].x : xm[i].y) -= h;
                const Real fd = -(energy(xp) - energy(xm)) / (2 * h);
                const Real fi = c == 0 ? f[i].x : f[i].y;
                // 1e-6 relative to the largest force: central differences are O(h^2) accurate
                EXPECT_NEAR(fi, fd, 1e-6 * fmax) << "node " << i << " component " << c;
            }
        }
    }
}

TEST(Cst, SmallStrainUniaxialStressMatchesHookesLaw) {
    const Real E = 1e9, nu = 0.3, eps = 1e-4;
    // plane stress: uniaxial stress with lateral strain -nu eps gives sigma_xx = E eps
    {
        Material mat = scenes::paper_material("s", E, nu);
        mat.plane = PlaneMode::Stress;
        compute_lame(mat);
        const Mat2 s = cauchy_stress(mat, {1 + eps, 0, 0, 1 - nu * eps});
        // 1e-3 relative: geometric nonlinearity is O(eps) = 1e-4
        EXPECT_NEAR(s.xx, E * eps, 1e-3 * E * eps);
        EXPECT_NEAR(s.yy, 0.0, 1e-3 * E * eps);
    }
    // plane strain: lateral strain -nu/(1-nu) eps gives sigma_xx = E eps / (1 - nu^2)
    {
        Material mat = scenes::paper_material("p", E, nu);
        mat.plane = PlaneMode::Strain;
        compute_lame(mat);
        const Mat2 s = cauchy_stress(mat, {1 + eps, 0, 0, 1 - nu / (1 - nu) * eps});
        const Real expect = E * eps / (1 - nu * nu);
        EXPECT_NEAR(s.xx, expect, 1e-3 * expect);
        EXPECT_NEAR(s.yy, 0.0, 1e-3 * expect);
    }
}

TEST(Cst, CriticalTimeStepIsAltitudeOverWaveSpeed) {
    Model m;
    m.materials.push_back(scenes::paper_material());
    scenes::add_rectangle(m, 0, 0, 1, 1, 1, 1, 0);  // two right triangles with legs 1
    finalize_model(m);
    // smallest altitude of a right isosceles triangle with legs 1 is 1/sqrt(2); c_p = 1000 m/s
    EXPECT_NEAR(element_critical_dt(m, 0), (1 / std::sqrt(2.0)) / 1000.0, 1e-15);
}

// ---- the element schedule's units (build_element_schedule, docs/performance.md "Stop 50") ----

TEST(ElementSchedule, UnitsGrowWithTheModelUpTo16Chunks) {
    // the largest power of two <= 16 that leaves >= 256 units
    EXPECT_EQ(element_unit_chunks(0), 1);
    EXPECT_EQ(element_unit_chunks(64), 1);  // 16 k triangles: one chunk per unit, as before
    EXPECT_EQ(element_unit_chunks(511), 1);
    EXPECT_EQ(element_unit_chunks(512), 2);  // 131 k triangles
    EXPECT_EQ(element_unit_chunks(1024), 4);
    EXPECT_EQ(element_unit_chunks(2047), 4);
    EXPECT_EQ(element_unit_chunks(2048), 8);
    EXPECT_EQ(element_unit_chunks(4096), 16);  // 10^6 triangles
    EXPECT_EQ(element_unit_chunks(1 << 20), 16);
}

// 262 144 triangles (1 024 chunks, units of 4)
Model big_block(bool viscous) {
    scenes::BlockOptions o;
    o.num_tris = 1 << 18;
    o.viscosity = viscous ? 50.0 : 0.0;
    return scenes::make_block(o);
}

// Two 200 x 200-cell blocks (80 000 triangles each) with a fixed strip between them in the
// triangle ids: 626 chunks, units of 2, one of them across the fixed body's ids
Model blocks_around_a_fixed_body() {
    Model m;
    m.materials.push_back(scenes::paper_material("rock", 1e9, 0.25));
    scenes::add_rectangle(m, 0, 0, 1, 1, 200, 200, 0);
    scenes::add_rectangle(m, 0, -0.1, 1, 0.05, 20, 2, 0, /*fixed=*/true);
    scenes::add_rectangle(m, 1.1, 0, 1, 1, 200, 200, 0);
    finalize_model(m);
    return m;
}

// The schedule's invariants: every triangle of a non-fixed body in exactly one chunk, units of
// at most element_unit_chunks() chunks ascending in triangle ids, units of one color sharing no
// node and in unit order.
void expect_valid_units(const Model& m) {
    const ElementSchedule& sc = m.element_schedule;
    const int32_t nc = sc.num_chunks();
    const int32_t per = element_unit_chunks(nc);
    const size_t nu = sc.unit_begin.size() - 1;
    EXPECT_EQ(nu, (static_cast<size_t>(nc) + per - 1) / per);
    ASSERT_EQ(sc.unit_begin.front(), 0);
    ASSERT_EQ(sc.unit_begin.back(), nc);
    ASSERT_EQ(sc.color_units.front(), 0);
    ASSERT_EQ(static_cast<size_t>(sc.color_units.back()), nu);
    std::vector<int> tri_seen(static_cast<size_t>(m.num_tris()), 0);
    for (size_t c = 0; c + 1 < sc.color_units.size(); ++c) {
        std::vector<int> node_unit(static_cast<size_t>(m.num_nodes()), -1);
        TriId last_unit_start = -1;
        for (int32_t u = sc.color_units[c]; u < sc.color_units[c + 1]; ++u) {
            const int32_t k0 = sc.unit_begin[static_cast<size_t>(u)];
            const int32_t k1 = sc.unit_begin[static_cast<size_t>(u) + 1];
            ASSERT_GE(k1 - k0, 1);
            ASSERT_LE(k1 - k0, per);
            // units of a color in triangle order; a unit's chunks ascending in ids
            EXPECT_GT(sc.chunk_tris[k0][0], last_unit_start);
            last_unit_start = sc.chunk_tris[k0][0];
            for (int32_t k = k0; k < k1; ++k) {
                if (k > k0) EXPECT_GE(sc.chunk_tris[k][0], sc.chunk_tris[k - 1][1]);
                for (TriId t = sc.chunk_tris[k][0]; t < sc.chunk_tris[k][1]; ++t) {
                    ++tri_seen[static_cast<size_t>(t)];
                    for (NodeId n : m.tri_nodes[t]) {
                        int& owner = node_unit[static_cast<size_t>(n)];
                        EXPECT_TRUE(owner == -1 || owner == u)
                            << "node " << n << " in units " << owner << " and " << u << " of color "
                            << c;
                        owner = u;
                    }
                }
            }
        }
    }
    for (TriId t = 0; t < m.num_tris(); ++t) {
        const bool fixed = m.bodies[m.tri_body[t]].fixed;
        ASSERT_EQ(tri_seen[static_cast<size_t>(t)], fixed ? 0 : 1) << "triangle " << t;
    }
}

TEST(ElementSchedule, UnitsOfAColorShareNoNodeAndRunConsecutiveChunks) {
    const Model m = big_block(false);
    ASSERT_EQ(m.element_schedule.num_chunks(), 1024);
    ASSERT_EQ(element_unit_chunks(1024), 4);
    EXPECT_EQ(m.element_schedule.unit_begin.size(), 257u);
    expect_valid_units(m);
    const Model two = blocks_around_a_fixed_body();
    ASSERT_EQ(element_unit_chunks(two.element_schedule.num_chunks()), 2);
    expect_valid_units(two);
}

// The pass adds each node's forces in schedule order (color, chunk, triangle) on any thread
// count: the reference runs the chunks one after the other in that order on one thread.
TEST(ElementSchedule, PassOfUnitsIsTheScheduleOrderOnAnyThreadCount) {
    for (const int scene : {0, 1, 2}) {
        const bool viscous = scene == 1;
        const Model m = scene == 2 ? blocks_around_a_fixed_body() : big_block(viscous);
        ASSERT_GT(element_unit_chunks(m.element_schedule.num_chunks()), 1);
        const State s0 = scenes::strained_state(m, 1e-4);
        std::vector<Vec2> ref(s0.f.size(), Vec2{});
        for (const auto& [b, e] : m.element_schedule.chunk_tris)
            add_internal_forces(m, s0.x.data(), s0.v.data(), ref.data(), b, e);
        for (const int threads : {1, 2, 3}) {
            omp_set_num_threads(threads);
            State s = s0;
            add_internal_forces(m, s);
            EXPECT_EQ(std::memcmp(s.f.data(), ref.data(), ref.size() * sizeof(Vec2)), 0)
                << threads << " threads, scene " << scene;
        }
    }
    omp_set_num_threads(omp_get_num_procs());
}

}  // namespace
}  // namespace fdem
