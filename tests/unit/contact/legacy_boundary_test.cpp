// Baseline B (boundary-aware potential, spec §1.3, docs/theory.md §7.4): the field evaluated
// per contactor sub-triangle equals H_ref min_e N_o(e) of the parent mesh triangle, computed
// here independently from the geometry (boundary edges = edges on the bounding box).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "contact/field.hpp"
#include "contact/legacy_boundary.hpp"
#include "fdem/build.hpp"
#include "fdem/mesh.hpp"

namespace fdem {
namespace {

struct Lcg {
    uint64_t s;
    explicit Lcg(uint64_t seed) : s(seed * 2862933555777941757ULL + 3037000493ULL) {}
    Real operator()(Real lo, Real hi) {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        return lo + (hi - lo) * static_cast<Real>(s >> 11) * (1.0 / 9007199254740992.0);
    }
};

Model model_of(MeshData mesh) {
    Model m;
    Material mat;
    mat.name = "rock";
    mat.density = 1000;
    mat.youngs_modulus = 1e9;
    m.materials.push_back(mat);
    m.contact.algorithm = ContactAlgorithm::Smooth;  // builds the shared contact topology
    std::vector<int32_t> ids(mesh.tris.size());
    for (size_t i = 0; i < ids.size(); ++i)
        ids[i] = static_cast<int32_t>(i);
    BodyOptions opt;
    opt.name = "body";
    add_bodies(m, mesh, ids, opt);
    finalize_model(m);
    return m;
}

// position of a contact node (real or virtual) in the reference configuration
// (cm = build_topology(m), built once by the caller: rebuilding it per call made T5 take 120 s
// under ASan)
Vec2 contact_pos(const Model& m, const ContactTopology& cm, NodeId i) {
    if (i < cm.num_real_nodes) return m.node_x0[i];
    const size_t v = static_cast<size_t>(i - cm.num_real_nodes);
    Vec2 x;
    for (int k = 0; k < 3; ++k)
        x += cm.virt_weight[v][k] * m.node_x0[cm.virt_parent[v][k]];
    return x;
}

// boundary-edge predicate from the geometry alone
using EdgePred = std::function<bool(Vec2, Vec2)>;

EdgePred on_box(Vec2 lo, Vec2 hi) {
    return [lo, hi](Vec2 a, Vec2 b) {
        return (a.x == lo.x && b.x == lo.x) || (a.x == hi.x && b.x == hi.x) ||
               (a.y == lo.y && b.y == lo.y) || (a.y == hi.y && b.y == hi.y);
    };
}

// reference phi_B: min over the parent's boundary edges of N of the opposite node
struct Direct {
    Real phi = 0;
    Vec2 grad;
    int terms = 0;
};

Direct direct_phi(const Model& m, TriId t, Vec2 x, const EdgePred& same_face) {
    const ContactTopology topo = build_topology(m);
    const auto& n = m.tri_nodes[t];
    const Vec2 p[3] = {m.node_x0[n[0]], m.node_x0[n[1]], m.node_x0[n[2]]};
    Real N[3];
    Vec2 g[3];
    barycentric(p[0], p[1], p[2], x, N);
    shape_gradients(p[0], p[1], p[2], g);
    Direct d;
    for (int k = 0; k < 3; ++k) {
        if (!same_face(p[k], p[(k + 1) % 3])) continue;
        const int o = (k + 2) % 3;
        if (d.terms == 0 || N[o] < d.phi) {
            d.phi = N[o];
            d.grad = g[o];
        }
        ++d.terms;
    }
    return d;
}

void check_against_direct(const Model& m, const LegacyBoundaryField& lb, Real h_ref,
                          const EdgePred& bnd, int* counts) {
    const ContactTopology topo = build_topology(m);
    const ContactTopology& cm = topo;
    ASSERT_EQ(lb.sub.size(), static_cast<size_t>(cm.num_sub_tris()));
    Lcg rng(3);
    for (int32_t s = 0; s < cm.num_sub_tris(); ++s) {
        const auto& q = cm.sub_tri[s];
        const Vec2 p[3] = {contact_pos(m, cm, q[0]), contact_pos(m, cm, q[1]),
                           contact_pos(m, cm, q[2])};
        for (int sample = 0; sample < 20; ++sample) {
            // random interior point of the sub-triangle
            Real u = rng(0, 1), v = rng(0, 1);
            if (u + v > 1) {
                u = 1 - u;
                v = 1 - v;
            }
            const Vec2 x = p[0] + u * (p[1] - p[0]) + v * (p[2] - p[0]);
            FieldSample fs;
            ASSERT_TRUE(barycentric(p[0], p[1], p[2], x, fs.N));
            legacy_boundary_field(lb, s, p, fs);
            const Direct d = direct_phi(m, cm.sub_parent[s], x, bnd);
            EXPECT_EQ(lb.sub[s].terms, d.terms);
            // 1e-12 of H_ref: two different barycentric evaluations of the same affine function
            EXPECT_NEAR(fs.d, h_ref * d.phi, 1e-12 * h_ref) << "sub " << s;
            EXPECT_NEAR(fs.grad.x, h_ref * d.grad.x, 1e-12 * norm(fs.grad) + 1e-14);
            EXPECT_NEAR(fs.grad.y, h_ref * d.grad.y, 1e-12 * norm(fs.grad) + 1e-14);
            EXPECT_EQ(fs.layer, h_ref);
        }
        ++counts[std::min(lb.sub[s].terms, 3)];
    }
}

// Structured 4 x 2 rectangle of square cells h = 0.5, same diagonal everywhere:
//
//   +---+---+---+---+  (2, 1)     corner triangles at (0,0) and (2,1) have two boundary edges
//   | / | / | / | / |             (their chord is split at its midpoint, spec §4.4), every
//   +---+---+---+---+             other boundary triangle one boundary edge or a vertex only;
//   | / | / | / | / |             all heights over boundary edges are h, so H_ref = h
//   +---+---+---+---+
// (0, 0)
TEST(LegacyBoundaryField, StructuredRectangleMatchesDirectFormula) {
    const Model m = model_of(make_rectangle_mesh(0, 0, 2, 1, 4, 2, false));
    const LegacyBoundaryField lb = build_legacy_boundary_field(m, build_topology(m));
    ASSERT_EQ(lb.body_h_ref.size(), 1u);
    EXPECT_NEAR(lb.body_h_ref[0], 0.5, 1e-15);  // exact heights, one rounding
    int counts[4] = {0, 0, 0, 0};
    check_against_direct(m, lb, 0.5, on_box({0, 0}, {2, 1}), counts);
    EXPECT_GT(counts[0], 0);  // vertex-only triangles exist
    EXPECT_GT(counts[1], 0);
    EXPECT_GT(counts[2], 0);  // the two corner triangles (each split in two by its chord)
}

// In a triangle with one boundary edge on the top face, d_B is the exact depth when the
// triangle height equals H_ref, and grad d_B is the inward unit normal.
TEST(LegacyBoundaryField, DepthBelowAFlatFaceOfARegularMesh) {
    const Model m = model_of(make_rectangle_mesh(0, 0, 2, 1, 4, 2, true));
    const ContactTopology topo = build_topology(m);
    const LegacyBoundaryField lb = build_legacy_boundary_field(m, build_topology(m));
    const ContactTopology& cm = topo;
    int checked = 0;
    for (int32_t s = 0; s < cm.num_sub_tris(); ++s) {
        if (lb.sub[s].terms != 1) continue;
        const auto& q = cm.sub_tri[s];
        const Vec2 p[3] = {contact_pos(m, cm, q[0]), contact_pos(m, cm, q[1]),
                           contact_pos(m, cm, q[2])};
        int top = 0;
        for (const Vec2& v : p)
            top += v.y == 1.0 ? 1 : 0;
        if (top != 2) continue;
        const Vec2 x = (p[0] + p[1] + p[2]) / 3.0;
        FieldSample fs;
        barycentric(p[0], p[1], p[2], x, fs.N);
        legacy_boundary_field(lb, s, p, fs);
        EXPECT_NEAR(fs.d, 1.0 - x.y, 1e-14);  // depth below y = 1, rounding only
        EXPECT_NEAR(fs.grad.x, 0.0, 1e-14);
        EXPECT_NEAR(fs.grad.y, -1.0, 1e-14);
        ++checked;
    }
    EXPECT_GE(checked, 4);
}

// Perturbed interior with alternating diagonals: H_ref is the mean of the boundary heights
// (recomputed here from the geometry), and the field matches the direct formula.
TEST(LegacyBoundaryField, PerturbedMeshMeanHeightAndField) {
    MeshData mesh = make_rectangle_mesh(0, 0, 1.2, 0.3, 12, 3, true);
    // the box from the nodes (the generator may round the far coordinates)
    Vec2 lo = mesh.nodes[0], hi = lo;
    for (const Vec2& p : mesh.nodes) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    Lcg rng(7);
    for (Vec2& p : mesh.nodes) {
        if (p.x == lo.x || p.x == hi.x || p.y == lo.y || p.y == hi.y) continue;
        p.x += rng(-0.03, 0.03);
        p.y += rng(-0.03, 0.03);
    }
    const Model m = model_of(mesh);
    const LegacyBoundaryField lb = build_legacy_boundary_field(m, build_topology(m));

    Real sum = 0;
    int count = 0;
    for (TriId t = 0; t < m.num_tris(); ++t) {
        const auto& n = m.tri_nodes[t];
        for (int k = 0; k < 3; ++k) {
            const Vec2 a = m.node_x0[n[k]], b = m.node_x0[n[(k + 1) % 3]];
            if (!on_box(lo, hi)(a, b)) continue;
            sum += 2.0 * m.tri_area0[t] / norm(b - a);
            ++count;
        }
    }
    EXPECT_EQ(count, 2 * (12 + 3));
    EXPECT_NEAR(lb.body_h_ref[0], sum / count, 1e-14);  // same sum, maybe another order
    int counts[4] = {0, 0, 0, 0};
    check_against_direct(m, lb, lb.body_h_ref[0], on_box(lo, hi), counts);
    EXPECT_GT(counts[0], 0);
    EXPECT_GT(counts[1], 0);
}

// A single-triangle body: three boundary edges, incenter fan of three sub-triangles;
// phi_B = min of the three N's (theory §7.4) and H_ref = mean of the three heights.
TEST(LegacyBoundaryField, SingleTriangleBody) {
    MeshData mesh;
    mesh.file = "single";
    mesh.nodes = {{0, 0}, {1.0, 0.1}, {0.3, 0.7}};
    mesh.tris = {{0, 1, 2}};
    mesh.tri_tag = {1};
    const Model m = model_of(mesh);
    const ContactTopology topo = build_topology(m);
    const LegacyBoundaryField lb = build_legacy_boundary_field(m, topo);
    ASSERT_EQ(topo.num_sub_tris(), 3);
    const Real a2 = 2.0 * m.tri_area0[0];
    const Real href =
        (a2 / norm(mesh.nodes[1] - mesh.nodes[0]) + a2 / norm(mesh.nodes[2] - mesh.nodes[1]) +
         a2 / norm(mesh.nodes[0] - mesh.nodes[2])) /
        3.0;
    EXPECT_NEAR(lb.body_h_ref[0], href, 1e-15);
    int counts[4] = {0, 0, 0, 0};
    check_against_direct(
        m, lb, href, [](Vec2, Vec2) { return true; }, counts);
    EXPECT_EQ(counts[3], 3);
}

}  // namespace
}  // namespace fdem
