// Load-time contact geometry checks (contact/checks.cpp, docs/theory.md §6.13-6.14): bodies
// overlapping at t = 0 beyond the touching tolerance, and contact layers whose inner nodes take
// their distance from the opposite face (thin bodies).
#include <gtest/gtest.h>

#include <cmath>

#include "contact/checks.hpp"
#include "unit/contact/contact_fixture.hpp"

namespace fdem {
namespace {

// the load-time checks on the topology of m as loaded (the scenario reader's call)
InitialOverlap overlap_of(const Model& m) {
    return find_initial_overlap(m, build_topology(m));
}
std::vector<ThinLayer> thin_layers_of(const Model& m) {
    return find_thin_layers(m, build_topology(m));
}

using testing::ModelBuilder;

// A = [0, 1] x [0, 1] and B = [1 + gap, 2 + gap] x [0, 1], 4 x 4 cells each: the faces meet
// edge to edge in aligned rows (the geometry of docs/theory.md §6.12)
Model two_squares(Real gap, Real dy = 0, bool fixed_a = false, bool fixed_b = false) {
    ModelBuilder b;
    b.add_body(make_rectangle_mesh(0, 0, 1, 1, 4, 4), fixed_a);
    b.add_body(make_rectangle_mesh(1 + gap, dy, 1, 1, 4, 4), fixed_b);
    return b.finalize();
}

TEST(InitialOverlap, ToleranceIsAMillionthOfTheSmallestAltitude) {
    const Model m = two_squares(0.1);
    const Real h_min = 0.25 / std::sqrt(2.0);  // right triangles of 0.25 x 0.25 cells
    EXPECT_NEAR(m.contact.h_min, h_min, 1e-15);
    const InitialOverlap o = overlap_of(m);
    EXPECT_FALSE(o.found);
    EXPECT_NEAR(o.tolerance, 1e-6 * h_min, 1e-20);
}

// both sides of the tolerance: exactly touching and overlapping by half of it are accepted,
// twice of it is an overlap (the nodes inside the other face, not the corners on its edge lines)
TEST(InitialOverlap, TouchingIsAcceptedBothSidesOfTheTolerance) {
    const Real tol = 1e-6 * 0.25 / std::sqrt(2.0);
    EXPECT_FALSE(overlap_of(two_squares(0.0)).found);
    EXPECT_FALSE(overlap_of(two_squares(-0.5 * tol)).found);
    const Model m = two_squares(-2 * tol);
    const InitialOverlap o = overlap_of(m);
    ASSERT_TRUE(o.found);
    EXPECT_NEAR(o.depth, 2 * tol, 1e-3 * tol);
    // the first point at the deepest depth, in (body pair, body, point) order: a boundary node
    // of A on its right face (inside B)
    EXPECT_EQ(o.body, 0);
    EXPECT_EQ(o.other, 1);
    EXPECT_EQ(o.point, InitialOverlap::Point::Node);
    EXPECT_NEAR(o.where.x, 1.0, 1e-15);
    EXPECT_GT(o.where.y, 0.0);
    EXPECT_LT(o.where.y, 1.0);
}

// coincident meshes (two meshes occupying the same region): every boundary point lies on the
// other's boundary (depth 0), the centroids of the boundary elements are deep inside
TEST(InitialOverlap, CoincidentMeshesAreFoundByCentroids) {
    ModelBuilder b;
    b.add_body(make_rectangle_mesh(0, 0, 1, 1, 4, 4));
    b.add_body(make_rectangle_mesh(0, 0, 1, 1, 4, 4));
    const Model& m = b.finalize();
    const InitialOverlap o = overlap_of(m);
    ASSERT_TRUE(o.found);
    EXPECT_EQ(o.point, InitialOverlap::Point::Centroid);
    EXPECT_EQ(o.body, 0);
    EXPECT_EQ(o.other, 1);
    EXPECT_GT(o.depth, 0.1);  // a centroid one cell in: 1/4 + 1/12 from the faces
}

// a body deep inside another (no boundary point of either in the other's contact layer)
TEST(InitialOverlap, BodyInsideAnotherIsFound) {
    ModelBuilder b;
    b.add_body(make_rectangle_mesh(0, 0, 10, 10, 10, 10));
    b.add_body(make_rectangle_mesh(4.2, 4.2, 1, 1, 2, 2));
    const Model& m = b.finalize();
    const InitialOverlap o = overlap_of(m);
    ASSERT_TRUE(o.found);
    EXPECT_EQ(o.body, 1);
    EXPECT_EQ(o.other, 0);
    EXPECT_GT(o.depth, 4.0);
}

// Bodies with more than 256 boundary edges are tested through horizontal strips of their edges
// and points (checks.cpp Strips; a wall ring around 10^6 particles made the load quadratic). A
// 10 x 10 square meshed with 10 (40 boundary edges: plain loops) and 100 cells per side (400:
// strips), 100 small squares around it at a gap, and: nothing more (no overlap); a square 0.47
// deep inside it (its bottom nodes are the deepest points: the even-odd test through the
// strips; both meshes find the same point); a square sunk 0.03 through its bottom face (a tie
// of depths, which the points of the big body win by coming first: with 100 cells an edge
// midpoint of the big body lies in the small square, picked through the strips; with 10 cells
// none does and the small square's node is reported).
TEST(InitialOverlap, LargeBodiesGiveTheSameResultThroughStrips) {
    for (const int variant : {0, 1, 2}) {
        SCOPED_TRACE(variant);
        InitialOverlap found[2];
        for (int k = 0; k < 2; ++k) {
            const int cells = k == 0 ? 10 : 100;
            ModelBuilder b;
            b.add_body(make_rectangle_mesh(0, 0, 10, 10, cells, cells));
            for (int i = 0; i < 25; ++i) {  // a ring of small squares 0.05 off the faces
                const Real t = 0.4 * i;
                b.add_body(make_rectangle_mesh(t, -0.45, 0.3, 0.4, 2, 2));
                b.add_body(make_rectangle_mesh(t, 10.05, 0.3, 0.4, 2, 2));
                b.add_body(make_rectangle_mesh(-0.45, t, 0.4, 0.3, 2, 2));
                b.add_body(make_rectangle_mesh(10.05, t, 0.4, 0.3, 2, 2));
            }
            if (variant == 1) b.add_body(make_rectangle_mesh(6.23, 9.53, 0.2, 0.2, 1, 1));
            if (variant == 2) b.add_body(make_rectangle_mesh(3.51, -0.04, 0.08, 0.07, 1, 1));
            found[k] = overlap_of(b.finalize());
        }
        ASSERT_EQ(found[0].found, variant != 0);
        ASSERT_EQ(found[1].found, variant != 0);
        if (variant == 1) {
            for (const InitialOverlap& o : found) {
                EXPECT_EQ(o.body, 101);
                EXPECT_EQ(o.other, 0);
                EXPECT_NEAR(o.depth, 0.47, 1e-12);
                EXPECT_EQ(o.point, InitialOverlap::Point::Node);
            }
            EXPECT_EQ(found[0].where.x, found[1].where.x);
            EXPECT_EQ(found[0].where.y, found[1].where.y);
        }
        if (variant == 2) {
            EXPECT_EQ(found[0].body, 101);
            EXPECT_EQ(found[0].point, InitialOverlap::Point::Node);
            EXPECT_EQ(found[1].body, 0);
            EXPECT_EQ(found[1].other, 101);
            EXPECT_EQ(found[1].point, InitialOverlap::Point::EdgeMidpoint);
            EXPECT_NEAR(found[1].where.x, 3.55, 1e-12);
            EXPECT_EQ(found[1].where.y, 0.0);
            for (const InitialOverlap& o : found)
                EXPECT_NEAR(o.depth, 0.03, 1e-12);
        }
    }
}

// two fixed bodies never interact: their overlap is not reported
TEST(InitialOverlap, TwoFixedBodiesAreNotCompared) {
    EXPECT_FALSE(overlap_of(two_squares(-0.3, 0, true, true)).found);
    EXPECT_TRUE(overlap_of(two_squares(-0.3, 0, true, false)).found);
}

// A slab two elements thick with perturbed middle nodes: in a top-layer element a middle node
// nearer to the bottom face takes its distance from there (eq. 6.3 keeps the smaller height).
TEST(ThinLayer, TwoElementSlabIsReported) {
    MeshData mesh = make_rectangle_mesh(0, 0, 2, 0.2, 20, 2);
    testing::perturb_interior(mesh, 0.03, 7);
    ModelBuilder b;
    b.add_body(mesh);
    const Model& m = b.finalize();
    const std::vector<ThinLayer> t = thin_layers_of(m);
    ASSERT_EQ(t.size(), 1u);
    EXPECT_EQ(t[0].body, 0);
    EXPECT_GT(t[0].count, 0);
    EXPECT_LT(t[0].dist, kThinLayerRatio * t[0].near_dist);
    // the far face: its outward normal is opposite to the face the element lies on
    EXPECT_EQ(thin_layer_warning(m, build_topology(m), t[0])
                  .rfind("warning: body 0 \"b0\" is too thin for its "
                         "contact layer: in ",
                         0),
              0u);
    EXPECT_NE(thin_layer_warning(m, build_topology(m), t[0])
                  .find("Remedy: make the body thicker (at least three "
                        "elements through its thickness) or refine the "
                        "mesh there"),
              std::string::npos);
}

// the same slab structured (middle nodes equidistant: a tie tilts nothing), four elements thick
// (perturbed), and a block with 90-degree corners are not reported
TEST(ThinLayer, ThickOrSymmetricBodiesAreNotReported) {
    {
        ModelBuilder b;
        b.add_body(make_rectangle_mesh(0, 0, 2, 0.2, 20, 2));
        EXPECT_TRUE(thin_layers_of(b.finalize()).empty());
    }
    {
        MeshData mesh = make_rectangle_mesh(0, 0, 2, 0.4, 20, 4);
        testing::perturb_interior(mesh, 0.03, 7);
        ModelBuilder b;
        b.add_body(mesh);
        EXPECT_TRUE(thin_layers_of(b.finalize()).empty());
    }
    {
        MeshData mesh = make_rectangle_mesh(0, 0, 1, 1, 6, 6);
        testing::perturb_interior(mesh, 0.03, 3);
        ModelBuilder b;
        b.add_body(mesh);
        EXPECT_TRUE(thin_layers_of(b.finalize()).empty());
    }
}

}  // namespace
}  // namespace fdem
