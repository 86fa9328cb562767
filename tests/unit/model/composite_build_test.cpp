// Building composite bodies from second-order meshes (issue #7): the sub-triangle layout of the
// Body contract (include/fdem/model.hpp), orientation, element choice, and the layout kept by
// Morton renumbering and by the parallel element schedule.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fdem/build.hpp"
#include "fdem/error.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

/// Check the contract of model.hpp on every composite of every Composite6 body: four
/// counter-clockwise sub-triangles (n1,n2,n6), (n2,n3,n4), (n6,n4,n5), (n2,n4,n6) with
/// n2, n4, n6 the midpoints of n1-n3, n3-n5, n5-n1 (straight-sided meshes), each a quarter of
/// the composite's area. Returns the number of composites checked.
int check_contract(const Model& m) {
    int count = 0;
    for (const Body& b : m.bodies) {
        if (b.element != ElementKind::Composite6) continue;
        EXPECT_EQ((b.tri_end - b.tri_begin) % 4, 0);
        for (TriId c = b.tri_begin; c + 3 < b.tri_end; c += 4) {
            const auto& t0 = m.tri_nodes[c];
            const auto& t1 = m.tri_nodes[c + 1];
            const auto& t2 = m.tri_nodes[c + 2];
            const auto& t3 = m.tri_nodes[c + 3];
            const NodeId n1 = t0[0], n2 = t0[1], n6 = t0[2], n3 = t1[1], n4 = t1[2], n5 = t2[2];
            EXPECT_EQ(t1[0], n2);
            EXPECT_EQ(t2[0], n6);
            EXPECT_EQ(t2[1], n4);
            EXPECT_EQ(t3, (std::array<NodeId, 3>{n2, n4, n6}));
            const auto& X = m.node_x0;
            // 1e-12 relative to the unit-size test meshes: midpoints computed as 0.5 (a + b)
            EXPECT_LT(norm(X[n2] - 0.5 * (X[n1] + X[n3])), 1e-12);
            EXPECT_LT(norm(X[n4] - 0.5 * (X[n3] + X[n5])), 1e-12);
            EXPECT_LT(norm(X[n6] - 0.5 * (X[n5] + X[n1])), 1e-12);
            const Real area = signed_area(X[n1], X[n3], X[n5]);
            EXPECT_GT(area, 0);
            for (TriId s = c; s < c + 4; ++s) {
                const auto& q = m.tri_nodes[s];
                EXPECT_NEAR(signed_area(X[q[0]], X[q[1]], X[q[2]]), 0.25 * area, 1e-12 * area);
                EXPECT_EQ(m.tri_body[s], m.tri_body[c]);
            }
            ++count;
        }
    }
    return count;
}

Model one_material() {
    Model m;
    m.materials.push_back(scenes::paper_material("p", 1e9, 0.3));
    return m;
}

TEST(CompositeBuild, RectangleGivesContractLayout) {
    for (bool alternate : {false, true}) {
        Model m = one_material();
        scenes::add_rectangle_order2(m, 0, 0, 2, 1, 3, 2, 0, ElementKind::Composite6, false, {},
                                     alternate);
        ASSERT_EQ(m.num_bodies(), 1);
        EXPECT_EQ(m.bodies[0].element, ElementKind::Composite6);
        EXPECT_EQ(m.num_tris(), 4 * 2 * 3 * 2);
        // corners 4 x 3, mid-edge nodes 3 * 3 + 2 * 4 + 3 * 2
        EXPECT_EQ(m.num_nodes(), 12 + 9 + 8 + 6);
        finalize_model(m);
        EXPECT_EQ(check_contract(m), 12);
        // lumped masses per sub-triangle add up to rho * area (1e-12 relative: rounding)
        Real mass = 0;
        for (Real mi : m.node_mass)
            mass += mi;
        EXPECT_NEAR(mass, 1000.0 * 2.0, 1e-12 * 2000.0);
    }
}

TEST(CompositeBuild, ElementTakenFromTheMeshByDefault) {
    Model m = one_material();
    const MeshData q = make_rectangle_mesh_order2(0, 0, 1, 1, 2, 2);
    const MeshData l = make_rectangle_mesh(0, 0, 1, 1, 2, 2);
    BodyOptions opt;
    opt.name = "b";
    add_bodies(m, q, {0, 1, 2, 3, 4, 5, 6, 7}, opt);
    opt.name = "c";
    add_bodies(m, l, {0, 1, 2, 3, 4, 5, 6, 7}, opt);
    EXPECT_EQ(m.bodies[0].element, ElementKind::Composite6);
    EXPECT_EQ(m.bodies[1].element, ElementKind::Cst);
    EXPECT_EQ(m.bodies[0].tri_end - m.bodies[0].tri_begin, 32);
    EXPECT_EQ(m.bodies[1].tri_end - m.bodies[1].tri_begin, 8);
}

TEST(CompositeBuild, CstOnSixNodeMeshSplitsIntoFourTriangles) {
    Model a = one_material(), b = one_material();
    scenes::add_rectangle_order2(a, 0, 0, 1, 1, 2, 2, 0, ElementKind::Composite6);
    scenes::add_rectangle_order2(b, 0, 0, 1, 1, 2, 2, 0, ElementKind::Cst);
    EXPECT_EQ(b.bodies[0].element, ElementKind::Cst);
    EXPECT_EQ(a.tri_nodes, b.tri_nodes);  // the same sub-triangles
    EXPECT_EQ(a.node_x0.size(), b.node_x0.size());
}

TEST(CompositeBuild, CompositeOnThreeNodeMeshIsAnInputError) {
    Model m = one_material();
    const MeshData l = make_rectangle_mesh(0, 0, 1, 1, 1, 1);
    BodyOptions opt;
    opt.name = "blk";
    opt.element = ElementKind::Composite6;
    try {
        add_bodies(m, l, {0, 1}, opt);
        FAIL() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("the composite element needs a mesh of 6-node "
                                             "triangles (Gmsh type 9)"),
                  std::string::npos)
            << e.what();
    }
}

TEST(CompositeBuild, ClockwiseSixNodeTrianglesAreReoriented) {
    // the order-2 rectangle with every triangle reversed, Gmsh style: corners (0, 2, 1), so the
    // mid-edge nodes on 0-2, 2-1, 1-0 are the old mid[2], mid[1], mid[0]
    MeshData q = make_rectangle_mesh_order2(0, 0, 1, 1, 2, 2, true);
    for (size_t t = 0; t < q.tris.size(); ++t) {
        std::swap(q.tris[t][1], q.tris[t][2]);
        std::swap(q.tri_mid[t][0], q.tri_mid[t][2]);
    }
    Model m = one_material();
    BodyOptions opt;
    opt.name = "r";
    std::vector<int32_t> all(q.tris.size());
    for (size_t i = 0; i < all.size(); ++i)
        all[i] = static_cast<int32_t>(i);
    add_bodies(m, q, all, opt);
    finalize_model(m);
    EXPECT_EQ(check_contract(m), 8);
}

TEST(CompositeBuild, MisplacedMidNodeIsAnInputError) {
    // a mid-edge node pushed across the opposite chord inverts a sub-triangle
    MeshData q = make_rectangle_mesh_order2(0, 0, 1, 1, 1, 1);
    q.nodes[static_cast<size_t>(q.tri_mid[0][0])] = {0.5, 0.9};  // mid of (0,0)-(1,0)
    Model m = one_material();
    BodyOptions opt;
    opt.name = "bent";
    try {
        add_bodies(m, q, {0, 1}, opt);
        FAIL() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("has a degenerate or inverted sub-triangle"),
                  std::string::npos)
            << e.what();
    }
}

TEST(CompositeBuild, RenumberingAndScheduleKeepCompositesWhole) {
    // 24 x 24 cells: 4608 sub-triangles >= kRenumberMinTris, so Morton renumbering runs; a
    // second, small composite body and a CST body test the small-body chunk merging
    Model m = one_material();
    scenes::add_rectangle_order2(m, 0, 0, 1, 1, 24, 24, 0);
    scenes::add_rectangle_order2(m, 2, 0, 1, 1, 2, 2, 0, ElementKind::Composite6, false, {}, false,
                                 "small");
    scenes::add_rectangle(m, 4, 0, 1, 1, 2, 2, 0);
    const std::vector<std::array<NodeId, 3>> before = m.tri_nodes;
    finalize_model(m);
    EXPECT_NE(m.tri_nodes, before);  // renumbered
    EXPECT_EQ(check_contract(m), 24 * 24 * 2 + 8);

    // every chunk covers whole composites of composite bodies, never mixes element kinds
    const ElementSchedule& sc = m.element_schedule;
    for (int32_t k = 0; k < sc.num_chunks(); ++k) {
        const auto [lo, hi] = sc.chunk_tris[k];
        const Body& first = m.bodies[m.tri_body[lo]];
        for (TriId t = lo; t < hi; ++t)
            EXPECT_EQ(m.bodies[m.tri_body[t]].element, first.element) << "chunk " << k;
        if (first.element == ElementKind::Composite6) {
            EXPECT_EQ((lo - first.tri_begin) % 4, 0) << "chunk " << k;
            const Body& last = m.bodies[m.tri_body[hi - 1]];
            EXPECT_EQ((hi - last.tri_begin) % 4, 0) << "chunk " << k;
        }
    }
}

}  // namespace
}  // namespace fdem
