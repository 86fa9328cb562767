// T2-T4 (spec §8): contact topology counts, nodal contact distances (paper eqs. 1-2 + spec §4.2
// fallback) and distance-field patch tests (spec §6.5).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>

#include "contact/validate.hpp"
#include "fdem/assert.hpp"
#include "fdem/error.hpp"
#include "support/topology_compare.hpp"
#include "unit/contact/contact_fixture.hpp"

namespace fdem {
namespace {

using testing::ModelBuilder;

struct Counts {
    size_t bedges, bnodes, btris, chords, virt, subs;
};

Counts counts(const ContactTopology& c) {
    return {c.boundary_edges.size(),
            c.boundary_nodes.size(),
            c.boundary_tris.size(),
            c.chords.size(),
            static_cast<size_t>(c.num_virtual()),
            c.sub_tri.size()};
}

// every sub-triangle is counter-clockwise in the reference configuration
void expect_ccw(const Model& m, const ContactTopology& topo) {
    for (const auto& q : topo.sub_tri) {
        EXPECT_GT(signed_area(testing::contact_node_x0(m, topo, q[0]),
                              testing::contact_node_x0(m, topo, q[1]),
                              testing::contact_node_x0(m, topo, q[2])),
                  0);
    }
}

//   3 +---+ 2     one square, two triangles, diagonal 0-2 joins two boundary nodes: a chord
//     | / |
//   0 +---+ 1
TEST(ContactTopology, TwoTriangleSquare) {
    ModelBuilder b;
    b.add_body(make_rectangle_mesh(0, 0, 1, 1, 1, 1));
    const Model& m = b.finalize();
    const ContactTopology& topo = b.topo;
    const Counts c = counts(topo);
    EXPECT_EQ(c.bedges, 4u);
    EXPECT_EQ(c.bnodes, 4u);
    EXPECT_EQ(c.btris, 2u);
    EXPECT_EQ(c.chords, 1u);
    EXPECT_EQ(c.virt, 1u);
    EXPECT_EQ(c.subs, 4u);                     // 1-chord split of both triangles = centre fan
    EXPECT_DOUBLE_EQ(topo.node_dist[4], 0.5);  // the chord midpoint is the centre
    EXPECT_EQ(topo.num_fallback_nodes, 0);
    expect_ccw(m, topo);
}

// Edge targets (docs/theory.md §6.12, eq. 6.19) of the two-triangle unit square: corner masses
// m/3 (nodes 1, 3: one triangle) and 2m/3 (nodes 0, 2), m = mbar = one triangle's mass, so node
// scales 1/3 and 2/3 split half to each edge; nodes keep a third, midpoints get 2/3 of the sum.
TEST(ContactTopology, EdgeTargetsSimpsonShares) {
    for (bool on : {false, true}) {
        ModelBuilder b;
        b.m.contact.edge_targets = on;
        b.add_body(make_rectangle_mesh(0, 0, 1, 1, 1, 1));
        const Model& m = b.finalize();
        const ContactTopology& topo = b.topo;
        const ContactTopology& c = topo;
        EXPECT_EQ(c.num_virtual(), 1);  // the chord midpoint only: edge targets are not nodes
        EXPECT_EQ(c.edge_target_base, c.num_contact_nodes());
        if (!on) {
            EXPECT_EQ(c.num_edge_targets(), 0);
            EXPECT_EQ(c.target_dt_factor, 1.0);
            EXPECT_DOUBLE_EQ(c.node_scale[0], 2.0 / 3.0);
            continue;
        }
        ASSERT_EQ(c.num_edge_targets(), 4);
        EXPECT_DOUBLE_EQ(c.node_scale[0], 2.0 / 9.0);
        EXPECT_DOUBLE_EQ(c.node_scale[1], 1.0 / 9.0);
        Real total = 0;
        for (NodeId i : c.boundary_nodes)
            total += c.node_scale[i];
        for (int32_t e = 0; e < c.num_edge_targets(); ++e) {
            EXPECT_DOUBLE_EQ(c.edge_scale[e], 1.0 / 3.0) << "edge " << e;  // (2/3)(1/3 + 1/6)
            total += c.edge_scale[e];
            // the target sits at the edge midpoint and belongs to the body
            const NodeId t = c.edge_target_base + e;
            const Vec2 p = target_point(c, m.node_x0.data(), t);
            const auto& be = c.boundary_edges[e];
            EXPECT_EQ(p.x, 0.5 * (m.node_x0[be[0]].x + m.node_x0[be[1]].x));
            EXPECT_EQ(p.y, 0.5 * (m.node_x0[be[0]].y + m.node_x0[be[1]].y));
            EXPECT_EQ(target_node(c, t), be[0]);
            EXPECT_EQ(target_scale(c, t), c.edge_scale[e]);
        }
        EXPECT_NEAR(total, 2.0, 1e-15);  // unchanged: 2 (1/3 + 2/3)
        // row sum of node 1: 1/9 + 2 x (1/3) / 2 = 4/9 over its mass share 1/3
        EXPECT_NEAR(c.target_dt_factor, 4.0 / 3.0, 1e-15);
    }
}

// A long uniform face: interior face nodes keep the node-only target-side dt factor 1
TEST(ContactTopology, EdgeTargetsUniformFaceKeepsScale) {
    ModelBuilder b;
    b.m.contact.scaling = ContactScaling::Length;
    b.add_body(make_rectangle_mesh(0, 0, 4, 1, 8, 2));
    b.finalize();
    const ContactTopology& c = b.topo;
    // length scaling: Simpson's rule exactly, w_e = (2/3) l_e / lbar, nodes keep l_j / (6 lbar)
    for (int32_t e = 0; e < c.num_edge_targets(); ++e)
        EXPECT_NEAR(c.edge_scale[e], 2.0 / 3.0, 1e-14);
    for (NodeId i : c.boundary_nodes)
        EXPECT_NEAR(c.node_scale[i], 1.0 / 3.0, 1e-14);
}

TEST(ContactTopology, SingleTriangleIncenterFan) {
    // scalene triangle 3-4-5: inradius r = 2A / perimeter = 12 / 12 = 1, incenter (1, 1)
    ModelBuilder b;
    b.add_body(testing::mesh_of({{0, 0}, {4, 0}, {0, 3}}, {{0, 1, 2}}));
    const Model& m = b.finalize();
    const ContactTopology& topo = b.topo;
    const Counts c = counts(topo);
    EXPECT_EQ(c.bedges, 3u);
    EXPECT_EQ(c.chords, 0u);
    EXPECT_EQ(c.virt, 1u);
    EXPECT_EQ(c.subs, 3u);
    const Vec2 inc = testing::contact_node_x0(m, topo, 3);
    EXPECT_NEAR(inc.x, 1.0, 1e-15);
    EXPECT_NEAR(inc.y, 1.0, 1e-15);
    EXPECT_NEAR(topo.node_dist[3], 1.0, 1e-15);
    expect_ccw(m, topo);
}

TEST(ContactTopology, FourByFourSquare) {
    // diagonals (i,j)-(i+1,j+1): the corner cells (3,0) and (0,3) have a chord
    ModelBuilder b;
    b.add_body(make_rectangle_mesh(0, 0, 4, 4, 4, 4));
    const Model& m = b.finalize();
    const ContactTopology& topo = b.topo;
    const Counts c = counts(topo);
    EXPECT_EQ(c.bedges, 16u);
    EXPECT_EQ(c.bnodes, 16u);
    EXPECT_EQ(c.btris, 24u);  // 12 ring cells x 2; the central 2x2 cells touch no boundary node
    EXPECT_EQ(c.chords, 2u);
    EXPECT_EQ(c.virt, 2u);
    EXPECT_EQ(c.subs, 28u);  // 4 triangles adjacent to the chords are split in two
    // every inner node of the first layer is at depth 1 (structured mesh, eq. 1)
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        const Vec2 x = m.node_x0[i];
        const Real exact = std::min({x.x, x.y, 4 - x.x, 4 - x.y});
        if (exact == 1.0) {
            EXPECT_DOUBLE_EQ(topo.node_dist[i], 1.0) << i;
        }
    }
    expect_ccw(m, topo);
}

// ring of n quads between radii 1 and 2, each split in two: one element thick, every
// interior edge (radial or diagonal) joins an inner-ring node to an outer-ring node
TEST(ContactTopology, AnnulusOneElementThick) {
    const int n = 16;
    std::vector<Vec2> nodes;
    std::vector<std::array<int32_t, 3>> tris;
    for (int k = 0; k < n; ++k) {
        const Real a = 2 * M_PI * k / n;
        nodes.push_back({std::cos(a), std::sin(a)});
        nodes.push_back({2 * std::cos(a), 2 * std::sin(a)});
    }
    for (int k = 0; k < n; ++k) {
        const int32_t i0 = 2 * k, o0 = 2 * k + 1, i1 = 2 * ((k + 1) % n), o1 = i1 + 1;
        tris.push_back({i0, o0, o1});
        tris.push_back({i0, o1, i1});
    }
    ModelBuilder b;
    b.add_body(testing::mesh_of(nodes, tris));
    const Model& m = b.finalize();
    const ContactTopology& topo = b.topo;
    const Counts c = counts(topo);
    EXPECT_EQ(c.bedges, 2u * n);
    EXPECT_EQ(c.bnodes, 2u * n);
    EXPECT_EQ(c.btris, 2u * n);
    EXPECT_EQ(c.chords, 2u * n);
    EXPECT_EQ(c.subs, 6u * n);  // 2-chord split: 3 sub-triangles per element
    expect_ccw(m, topo);
    // no interior point of the ring has d = 0 any more: mid-radius points are positive
    for (int k = 0; k < 64; ++k) {
        const Real a = 2 * M_PI * (k + 0.37) / 64;
        FieldSample fs;
        ASSERT_TRUE(testing::field_at(m, topo, 0, {1.5 * std::cos(a), 1.5 * std::sin(a)}, fs));
        EXPECT_GT(fs.d, 0.3);  // chord midpoints sit ~0.5 deep; polygonal ring, so not exact
    }
}

TEST(ContactTopology, LShape) {
    //  +---+
    //  |   |          2x2 grid without the upper-right cell: 8 nodes, all on the boundary
    //  +---+---+
    //  |   |   |
    //  +---+---+
    MeshData g = make_rectangle_mesh(0, 0, 2, 2, 2, 2);
    std::vector<int32_t> keep;
    for (int32_t t = 0; t < static_cast<int32_t>(g.tris.size()); ++t) {
        const auto& n = g.tris[t];
        const Vec2 cen = (g.nodes[n[0]] + g.nodes[n[1]] + g.nodes[n[2]]) / 3.0;
        if (!(cen.x > 1 && cen.y > 1)) keep.push_back(t);
    }
    ModelBuilder b;
    BodyOptions opt;
    opt.name = "L";
    add_bodies(b.m, g, keep, opt);
    const Model& m = b.finalize();
    const ContactTopology& topo = b.topo;
    const Counts c = counts(topo);
    EXPECT_EQ(m.num_nodes(), 8);
    EXPECT_EQ(c.bedges, 8u);
    EXPECT_EQ(c.bnodes, 8u);
    EXPECT_EQ(c.btris, 6u);
    EXPECT_EQ(c.chords, 5u);  // (3*6 - 8)/2 interior edges, all between boundary nodes
    expect_ccw(m, topo);
}

TEST(ContactTopology, StripOneElementThick) {
    ModelBuilder b;
    b.add_body(make_rectangle_mesh(0, 0, 4, 1, 4, 1));
    const Model& m = b.finalize();
    const ContactTopology& topo = b.topo;
    const Counts c = counts(topo);
    EXPECT_EQ(c.bedges, 10u);
    EXPECT_EQ(c.bnodes, 10u);
    EXPECT_EQ(c.btris, 8u);
    EXPECT_EQ(c.chords, 7u);  // 3 verticals + 4 diagonals
    expect_ccw(m, topo);
    // the mid-line of the strip is 0.5 deep at the vertical chords
    FieldSample fs;
    ASSERT_TRUE(testing::field_at(m, topo, 0, {2.0, 0.5}, fs));
    EXPECT_NEAR(fs.d, 0.5, 1e-12);
}

// T3: perturbed 12x3 rectangle (boundary nodes on the faces): every node whose distance comes
// from eq. 1 or the fallback equals its exact distance to the (convex) rectangle boundary
TEST(ContactTopology, NodalDistancesPerturbedMesh) {
    for (bool alternate : {false, true}) {
        MeshData g = make_rectangle_mesh(0, 0, 12, 3, 12, 3, alternate);
        testing::perturb_interior(g, 0.2, 3);
        ModelBuilder b;
        b.add_body(g);
        const Model& m = b.finalize();
        const ContactTopology& topo = b.topo;
        const std::vector<Vec2> rect{{0, 0}, {12, 0}, {12, 3}, {0, 3}};
        int inner = 0;
        for (NodeId i = 0; i < m.num_nodes(); ++i) {
            if (topo.node_on_boundary[i]) {
                EXPECT_EQ(topo.node_dist[i], 0.0);
                continue;
            }
            const Real exact = testing::polygon_distance(rect, m.node_x0[i]);
            // eq. 1 gives the depth below one face line: >= the distance to the rectangle
            EXPECT_GE(topo.node_dist[i], exact - 1e-12) << i;
            // first layer away from the corners: only one face nearby, so exact (1e-12: round-off)
            const Vec2 x = m.node_x0[i];
            if (x.x > 1.5 && x.x < 10.5) {
                EXPECT_NEAR(topo.node_dist[i], exact, 1e-12) << i;
                ++inner;
            }
        }
        EXPECT_EQ(inner, 2 * 9);  // columns i = 2..10 of rows j = 1, 2
        // alternating diagonals leave nodes without an opposite boundary edge (spec §4.2)
        if (alternate) {
            EXPECT_GT(topo.num_fallback_nodes, 0);
        }
        std::printf("[ info ] alternate=%d: %d fallback nodes\n", alternate,
                    topo.num_fallback_nodes);
    }
}

// T4: the interpolated field equals the exact distance to the boundary in the patch cases of
// spec §6.5 (10 000 random points each, tolerance 1e-12 x size: round-off)
void patch_test(const MeshData& mesh, const std::vector<Vec2>& poly, Real size, unsigned seed) {
    ModelBuilder b;
    b.add_body(mesh);
    const Model& m = b.finalize();
    const ContactTopology& topo = b.topo;
    Vec2 lo = poly[0], hi = lo;
    for (const Vec2& p : poly) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> ux(lo.x, hi.x), uy(lo.y, hi.y);
    int n = 0;
    Real err = 0;
    while (n < 10000) {
        const Vec2 x{ux(rng), uy(rng)};
        FieldSample fs;
        if (!testing::field_at(m, topo, 0, x, fs)) continue;
        err = std::max(err, std::abs(fs.d - testing::polygon_distance(poly, x)));
        ++n;
    }
    EXPECT_LE(err, 1e-12 * size);
}

TEST(ContactField, PatchScaleneTriangleIncenterFan) {
    patch_test(testing::mesh_of({{0, 0}, {4, 0}, {0.7, 3}}, {{0, 1, 2}}),
               {{0, 0}, {4, 0}, {0.7, 3}}, 4, 1);
}

TEST(ContactField, PatchSquareAndRhombusChordSplit) {
    patch_test(make_rectangle_mesh(0, 0, 1, 1, 1, 1), {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 1, 2);
    // rhombus split along its long diagonal: the chord midpoint is the incenter
    const std::vector<Vec2> rh{{0, 0}, {2, -1}, {4, 0}, {2, 1}};
    patch_test(testing::mesh_of(rh, {{0, 1, 2}, {0, 2, 3}}), rh, 4, 3);
}

TEST(ContactField, PatchRegularHexagonFan) {
    std::vector<Vec2> nodes{{0, 0}}, poly;
    std::vector<std::array<int32_t, 3>> tris;
    for (int k = 0; k < 6; ++k) {
        poly.push_back({std::cos(M_PI * k / 3), std::sin(M_PI * k / 3)});
        nodes.push_back(poly.back());
        tris.push_back({0, 1 + k, 1 + (k + 1) % 6});
    }
    patch_test(testing::mesh_of(nodes, tris), poly, 1, 4);
}

TEST(ContactField, PatchHalfPlaneLayerPerturbedMesh) {
    // points in the bottom boundary layer away from the sides: d = y for any mesh
    MeshData g = make_rectangle_mesh(0, 0, 12, 3, 12, 3, true);
    testing::perturb_interior(g, 0.2, 9);
    ModelBuilder b;
    b.add_body(g);
    const Model& m = b.finalize();
    const ContactTopology& topo = b.topo;
    std::mt19937 rng(5);
    std::uniform_real_distribution<Real> ux(2.5, 9.5), uy(0, 0.7);
    Real err = 0;
    for (int n = 0; n < 10000; ++n) {
        const Vec2 x{ux(rng), uy(rng)};
        FieldSample fs;
        ASSERT_TRUE(testing::field_at(m, topo, 0, x, fs));
        err = std::max(err, std::abs(fs.d - x.y));
        EXPECT_NEAR(fs.grad.x, 0.0, 1e-12);
        EXPECT_NEAR(fs.grad.y, 1.0, 1e-12);
    }
    EXPECT_LE(err, 1e-12 * 12);
}

TEST(ContactField, RectangleTwoByOneIsNotExact) {
    // chord split of a 2x1 rectangle: centre fan with apex at (1, 0.5); the short sides see
    // |grad d| = 0.5 (spec §4.4), so the error is nonzero; report it
    ModelBuilder b;
    b.add_body(make_rectangle_mesh(0, 0, 2, 1, 1, 1));
    const Model& m = b.finalize();
    const ContactTopology& topo = b.topo;
    const std::vector<Vec2> poly{{0, 0}, {2, 0}, {2, 1}, {0, 1}};
    std::mt19937 rng(8);
    std::uniform_real_distribution<Real> ux(0, 2), uy(0, 1);
    Real err = 0, gmin = 1e9, gmax = 0;
    for (int n = 0; n < 10000; ++n) {
        const Vec2 x{ux(rng), uy(rng)};
        FieldSample fs;
        ASSERT_TRUE(testing::field_at(m, topo, 0, x, fs));
        err = std::max(err, std::abs(fs.d - testing::polygon_distance(poly, x)));
        gmin = std::min(gmin, norm(fs.grad));
        gmax = std::max(gmax, norm(fs.grad));
    }
    std::printf("[ info ] 2x1 rectangle: max |d - exact| = %.3f, |grad d| in [%.3f, %.3f]\n", err,
                gmin, gmax);
    EXPECT_GT(err, 0.01);
    EXPECT_NEAR(gmin, 0.5, 1e-12);
    EXPECT_NEAR(gmax, 1.0, 1e-12);
}

// continuity: every sub-edge used by one sub-triangle only is a boundary edge or borders an
// unsplit non-boundary element (conforming split, no hanging virtual node), and shared edges
// carry the same nodal values by construction, so d is C0 across all interior edges
TEST(ContactField, ConformingSubTriangulation) {
    MeshData g = make_rectangle_mesh(0, 0, 6, 3, 6, 3, true);
    testing::perturb_interior(g, 0.2, 1);
    ModelBuilder b;
    b.add_body(g);
    b.add_body(make_rectangle_mesh(10, 0, 4, 1, 4, 1));  // strip
    const Model& m = b.finalize();
    const ContactTopology& topo = b.topo;
    const ContactTopology& cm = topo;
    std::map<std::array<NodeId, 2>, int> use;
    for (const auto& q : cm.sub_tri) {
        for (int k = 0; k < 3; ++k) {
            const NodeId a = q[k], c = q[(k + 1) % 3];
            use[{std::min(a, c), std::max(a, c)}]++;
        }
    }
    std::map<std::array<NodeId, 2>, int> mesh_use;
    for (const auto& t : m.tri_nodes) {
        for (int k = 0; k < 3; ++k) {
            const NodeId a = t[k], c = t[(k + 1) % 3];
            mesh_use[{std::min(a, c), std::max(a, c)}]++;
        }
    }
    for (const auto& [e, n] : use) {
        EXPECT_LE(n, 2);
        if (n == 1) {
            ASSERT_LT(e[1], cm.num_real_nodes) << "hanging virtual node";
            EXPECT_TRUE(mesh_use.count(e)) << "sub-edge not on a mesh edge";
        }
    }
}

}  // namespace
}  // namespace fdem

namespace fdem {
namespace {

using testing::differing_fields;

TEST(ContactParameters, DefaultsResolvedAtBuildTime) {
    testing::ModelBuilder b;  // E = 1 GPa, rho = 1000
    b.add_body(make_rectangle_mesh(0, 0, 1, 1, 20, 20));
    const Model& m = b.finalize();
    const ContactParams& p = pair_parameters(m.contact, 0, 0);
    EXPECT_DOUBLE_EQ(p.penalty, 5e9);                                   // k_n = 5 E (spec §4.5)
    EXPECT_DOUBLE_EQ(p.tangential_penalty, 5e8);                        // k_t = 0.1 k_n
    EXPECT_NEAR(m.contact.buffer, 0.2 * 0.05 / std::sqrt(2.0), 1e-15);  // 0.2 h_min
    EXPECT_NEAR(m.contact.m_bar, 1000 * 0.05 * 0.05 / 2, 1e-12);
}

TEST(ContactParameters, PairParametersAndValidation) {
    testing::ModelBuilder b;
    const int32_t soft = b.add_material(1e8, 1000);
    b.add_body(make_rectangle_mesh(0, 0, 1, 1, 2, 2));
    b.add_body(make_rectangle_mesh(2, 0, 1, 1, 2, 2), false, {}, soft);
    ContactParams law;
    law.friction = 0.3;
    b.m.contact.pair_overrides.push_back({0, 1, law});  // contactor material 0, target material 1
    const Model& m = b.finalize();
    EXPECT_DOUBLE_EQ(pair_parameters(m.contact, 0, 1).friction, 0.3);
    EXPECT_DOUBLE_EQ(pair_parameters(m.contact, 0, 1).penalty, 5e8);  // 5 x the smaller E
    // a pair without an override takes the [contact] law: k_n = 5 x the smallest E of the model
    // (docs/scenario.md); before the sparse table (#12 item 10) every pair of a model with any
    // override took 5 x the smaller E of its own two materials (5e9 here), against the docs
    EXPECT_DOUBLE_EQ(pair_parameters(m.contact, 0, 0).penalty, 5e8);
    EXPECT_DOUBLE_EQ(pair_parameters(m.contact, 0, 0).friction, 0.0);
    EXPECT_DOUBLE_EQ(pair_parameters(m.contact, 1, 0).friction, 0.0);  // only the pair set

    testing::ModelBuilder bad;
    bad.add_body(make_rectangle_mesh(0, 0, 1, 1, 2, 2));
    bad.m.contact.params.alpha = 0.5;
    try {
        bad.finalize();
        FAIL() << "alpha < 1 accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.key(), "contact.alpha");
        EXPECT_NE(std::string(e.what()).find("alpha must be >= 1, got 0.5"), std::string::npos);
    }
}

// ---- rebuild_topology (issue #14 item 1, spec fracture.md U6) ----------------------------------

// Four bodies: a perturbed 3 x 2 rectangle, a single triangle, a 4 x 2 rectangle and a composite
// 2 x 1 rectangle (Split: virtual nodes of its own), so that virtual node and boundary edge ids
// of later bodies depend on the earlier ones.
Model four_bodies(ContactAlgorithm algorithm, ContactScaling scaling) {
    testing::ModelBuilder b;
    b.m.contact.algorithm = algorithm;
    b.m.contact.scaling = scaling;
    b.m.contact.composite_special_case = CompositeSpecialCase::Split;
    MeshData r = make_rectangle_mesh(0, 0, 3, 2, 3, 2);
    testing::perturb_interior(r, 0.1, 11);
    b.add_body(r);
    b.add_body(testing::mesh_of({{5, 0}, {6, 0}, {5.2, 0.9}}, {{{0, 1, 2}}}));
    b.add_body(make_rectangle_mesh(0, 3, 4, 2, 4, 2));
    b.add_body(make_rectangle_mesh_order2(7, 0, 2, 1, 2, 1));
    return b.finalize();
}

// The same bodies with body 0's inner nodes moved (new nodal distances) and one diagonal of
// body 2 flipped so that it joins two boundary nodes (a new chord: one more virtual node, which
// shifts the virtual ids of body 3).
Model cracked(const Model& m0) {
    Model m = m0;
    const Body& b0 = m.bodies[0];
    const ContactTopology t0 = build_topology(m0);
    for (NodeId i = b0.node_begin; i < b0.node_end; ++i) {
        if (!t0.node_on_boundary[i]) m.node_x0[i] += Vec2{0.05, -0.03};
    }
    const Body& b2 = m.bodies[2];
    for (TriId t1 = b2.tri_begin; t1 < b2.tri_end; ++t1) {
        for (TriId t2 = t1 + 1; t2 < b2.tri_end; ++t2) {
            for (int k = 0; k < 3; ++k) {
                const auto n1 = m.tri_nodes[t1];
                const NodeId p = n1[k], q = n1[(k + 1) % 3], r = n1[(k + 2) % 3];
                const auto& n2 = m.tri_nodes[t2];
                for (int l = 0; l < 3; ++l) {
                    if (n2[l] != q || n2[(l + 1) % 3] != p) continue;
                    const NodeId s = n2[(l + 2) % 3];
                    // p-q interior, r and s boundary nodes: the flipped diagonal r-s is a chord
                    if (!t0.node_on_boundary[r] || !t0.node_on_boundary[s]) continue;
                    if (t0.node_on_boundary[p] && t0.node_on_boundary[q]) continue;
                    m.tri_nodes[t1] = {r, p, s};
                    m.tri_nodes[t2] = {s, q, r};
                    return m;
                }
            }
        }
    }
    ADD_FAILURE() << "no diagonal to flip";
    return m;
}

TEST(RebuildTopology, UnchangedMeshAnySubsetIsBitwiseTheFreshBuild) {
    for (ContactAlgorithm a : {ContactAlgorithm::Smooth, ContactAlgorithm::LegacyBoundary}) {
        for (ContactScaling sc : {ContactScaling::Mass, ContactScaling::Length}) {
            const Model m = four_bodies(a, sc);
            const ContactTopology fresh = build_topology(m);
            ASSERT_GT(fresh.num_virtual(), 0);
            const std::vector<std::vector<BodyId>> subsets = {
                {}, {0}, {1}, {3}, {0, 2}, {1, 3}, {3, 0, 3}, {0, 1, 2, 3}};
            for (const auto& dirty : subsets) {
                ContactTopology t = fresh;
                rebuild_topology(m, dirty, t);
                EXPECT_EQ(differing_fields(t, fresh), "") << dirty.size() << " dirty";
                EXPECT_TRUE(validate_topology(m, t).empty());
            }
        }
    }
}

TEST(RebuildTopology, ChangedBodiesRebuiltGiveTheFreshBuildOfTheChangedMesh) {
    for (ContactScaling sc : {ContactScaling::Mass, ContactScaling::Length}) {
        const Model m0 = four_bodies(ContactAlgorithm::Smooth, sc);
        const Model m1 = cracked(m0);
        const ContactTopology before = build_topology(m0);
        const ContactTopology fresh = build_topology(m1);
        ASSERT_TRUE(validate_topology(m1, fresh).empty());
        ASSERT_EQ(fresh.num_virtual(), before.num_virtual() + 1);  // the new chord's mid-node
        ASSERT_NE(differing_fields(fresh, before), "");

        ContactTopology t = before;
        rebuild_topology(m1, std::vector<BodyId>{2, 0}, t);
        EXPECT_EQ(differing_fields(t, fresh), "");
        const auto bad = validate_topology(m1, t);
        EXPECT_TRUE(bad.empty()) << bad.front();

        // the test can fail: a changed body left out keeps its old (now wrong) part
        auto partial_differs = [&](const std::vector<BodyId>& partial) {
            ContactTopology p = before;
            rebuild_topology(m1, partial, p);  // checked builds: may stop in its validator
            return differing_fields(p, fresh) != "";
        };
        for (const std::vector<BodyId>& partial : {std::vector<BodyId>{0}, {2}, {1, 3}}) {
            if constexpr (kAssertsEnabled) {
                // checked builds (debug, asan): rebuild_topology's FDEM_ASSERT of
                // validate_topology() aborts on the stale part, or the result differs
                GTEST_FLAG_SET(death_test_style, "threadsafe");
                EXPECT_DEATH(
                    {
                        if (partial_differs(partial)) {
                            std::fputs("internal error: differs from the fresh build\n", stderr);
                            std::abort();
                        }
                    },
                    "internal error")
                    << partial.front();
            } else {
                EXPECT_TRUE(partial_differs(partial)) << partial.front();
            }
        }
    }
}

TEST(RebuildTopology, BodyOutOfRangeIsRejected) {
    const Model m = four_bodies(ContactAlgorithm::Smooth, ContactScaling::Mass);
    ContactTopology t = build_topology(m);
    EXPECT_THROW(rebuild_topology(m, std::vector<BodyId>{4}, t), std::invalid_argument);
    EXPECT_THROW(rebuild_topology(m, std::vector<BodyId>{-1}, t), std::invalid_argument);
}

}  // namespace
}  // namespace fdem
