// Sectors and fragments of a jointed mesh (fracture/sectors.hpp; spec fracture.md §4.1-4.2, test
// U5): expected values from the geometry of the mesh (which side of a crack line a triangle lies
// on), never from the functions under test; the incremental forms against the full forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "fracture/sectors.hpp"
#include "support/jointed.hpp"

namespace fdem {
namespace {

using testing::add_jointed_body;
using testing::all_edges;
using testing::statuses;

// A 4 x 4 block of 32 right triangles (alternating diagonals), every internal edge jointed:
//
//   y=4 +---+---+---+---+
//       | / | \ | / | \ |
//   y=2 +===+===+===+===+   <- crack line y = 2 (8 joints on horizontal edges)
//       | \ | / | \ | / |
//   y=0 +---+---+---+---+
//       x=0             x=4
Model jointed_block(const testing::JointedEdge& jointed = all_edges) {
    Model m;
    Material mat;
    mat.name = "rock";
    mat.density = 1000;
    mat.youngs_modulus = 1e9;
    m.materials.push_back(mat);
    m.contact.algorithm = ContactAlgorithm::Smooth;
    add_jointed_body(m, make_rectangle_mesh(0, 0, 4, 4, 4, 4, true), jointed);
    finalize_model(m);
    return m;
}

Vec2 centroid(const Model& m, TriId t) {
    const auto& n = m.tri_nodes[t];
    return (m.node_x0[n[0]] + m.node_x0[n[1]] + m.node_x0[n[2]]) / 3.0;
}

// joints whose reference edge lies on the line y = yc between x = xa and xb
std::vector<int32_t> joints_on_line(const Model& m, Real yc, Real xa = -1e9, Real xb = 1e9) {
    std::vector<int32_t> out;
    for (int32_t j = 0; j < m.joints.num_joints(); ++j) {
        const Vec2 a = m.node_x0[m.joints.nodes[j][0]], b = m.node_x0[m.joints.nodes[j][1]];
        if (a.y == yc && b.y == yc && std::min(a.x, b.x) >= xa && std::max(a.x, b.x) <= xb)
            out.push_back(j);
    }
    return out;
}

// triangle of each node (every node of a fully jointed mesh is in exactly one)
std::vector<TriId> node_tri(const Model& m) {
    std::vector<TriId> t(static_cast<size_t>(m.num_nodes()), kNone);
    for (TriId k = 0; k < m.num_tris(); ++k) {
        for (NodeId n : m.tri_nodes[k])
            t[n] = k;
    }
    return t;
}

TEST(Sectors, IntactJointsGiveTheVertex) {
    const Model m = jointed_block();
    ASSERT_EQ(m.num_nodes(), 96);  // 3 per triangle
    ASSERT_EQ(m.joints.num_joints(), 40);
    std::vector<NodeId> sec;
    compute_node_sectors(m, statuses(m), sec);
    EXPECT_EQ(sec, m.node_vertex);
}

TEST(Sectors, EmptyJointsClear) {
    Model m;
    std::vector<NodeId> sec = {1, 2, 3};
    compute_node_sectors(m, {}, sec);
    EXPECT_TRUE(sec.empty());
}

TEST(Sectors, CrackLineSplitsItsVertices) {
    const Model m = jointed_block();
    const std::vector<int32_t> crack = joints_on_line(m, 2.0);
    ASSERT_EQ(crack.size(), 4u);
    std::vector<NodeId> sec;
    compute_node_sectors(m, statuses(m, crack), sec);
    // expected: copies of a vertex on y = 2 split by the side of their triangle; others whole
    const std::vector<TriId> tri = node_tri(m);
    for (NodeId n = 0; n < m.num_nodes(); ++n) {
        NodeId want = kNone;
        const bool on_line = m.node_x0[n].y == 2.0;
        const bool above = centroid(m, tri[n]).y > 2.0;
        for (NodeId c = 0; c < m.num_nodes() && want == kNone; ++c) {
            if (m.node_vertex[c] != m.node_vertex[n]) continue;
            if (on_line && (centroid(m, tri[c]).y > 2.0) != above) continue;
            want = c;
        }
        EXPECT_EQ(sec[n], want) << "node " << n;
    }
}

TEST(Sectors, PartialCrackTipStaysOneSector) {
    const Model m = jointed_block();
    // crack from the left edge to the interior vertex (2, 2): that vertex (the tip) is cut once
    const std::vector<int32_t> crack = joints_on_line(m, 2.0, 0.0, 2.0);
    ASSERT_EQ(crack.size(), 2u);
    std::vector<NodeId> sec;
    compute_node_sectors(m, statuses(m, crack), sec);
    for (NodeId n = 0; n < m.num_nodes(); ++n) {
        const Vec2 p = m.node_x0[n];
        if (p == Vec2{2, 2} || p.y != 2.0 || p.x > 2.0) {
            EXPECT_EQ(sec[n], m.node_vertex[n]) << n;
        }
    }
    // (0, 2) and (1, 2): two sectors each
    for (const Vec2 p : {Vec2{0, 2}, Vec2{1, 2}}) {
        std::vector<NodeId> reps;
        for (NodeId n = 0; n < m.num_nodes(); ++n) {
            if (m.node_x0[n] == p) reps.push_back(sec[n]);
        }
        std::sort(reps.begin(), reps.end());
        reps.erase(std::unique(reps.begin(), reps.end()), reps.end());
        EXPECT_EQ(reps.size(), 2u);
    }
}

// the incremental form, fed random batches of breaks in random order, equals the full form
TEST(Sectors, IncrementalEqualsFull) {
    const Model m = jointed_block();
    std::mt19937 rng(7);
    for (int trial = 0; trial < 20; ++trial) {
        std::vector<int32_t> order(static_cast<size_t>(m.joints.num_joints()));
        std::iota(order.begin(), order.end(), 0);
        std::shuffle(order.begin(), order.end(), rng);
        std::vector<JointStatus> st = statuses(m);
        std::vector<NodeId> inc, full;
        compute_node_sectors(m, st, inc);
        for (size_t k = 0; k < order.size();) {
            const size_t batch = std::min(order.size() - k, size_t{1} + rng() % 4);
            std::vector<int32_t> now(order.begin() + static_cast<long>(k),
                                     order.begin() + static_cast<long>(k + batch));
            for (const int32_t j : now)
                st[static_cast<size_t>(j)] = JointStatus::Broken;
            update_node_sectors(m, st, now, inc);
            compute_node_sectors(m, st, full);
            ASSERT_EQ(inc, full) << "trial " << trial << " after " << k + batch << " breaks";
            k += batch;
        }
        // all broken: every node is its own sector
        for (NodeId n = 0; n < m.num_nodes(); ++n)
            EXPECT_EQ(full[n], n);
    }
}

// U5: synthetic break sets -> the expected components, ids the smallest triangle id
TEST(Fragments, CrackLineGivesTwoHalves) {
    const Model m = jointed_block();
    std::vector<TriId> frag;
    compute_fragments(m, statuses(m), frag);
    for (TriId t = 0; t < m.num_tris(); ++t)
        EXPECT_EQ(frag[t], 0);

    compute_fragments(m, statuses(m, joints_on_line(m, 2.0)), frag);
    TriId low = kNone, high = kNone;
    for (TriId t = 0; t < m.num_tris(); ++t) {
        TriId& first = centroid(m, t).y < 2.0 ? low : high;
        if (first == kNone) first = t;
        EXPECT_EQ(frag[t], first) << t;
    }
    EXPECT_NE(low, high);

    // a partial crack does not split
    compute_fragments(m, statuses(m, joints_on_line(m, 2.0, 0.0, 3.0)), frag);
    for (TriId t = 0; t < m.num_tris(); ++t)
        EXPECT_EQ(frag[t], 0);
}

TEST(Fragments, OneTriangleCutFree) {
    const Model m = jointed_block();
    const TriId lone = 13;
    std::vector<int32_t> around;
    const auto& n = m.tri_nodes[lone];
    for (int32_t j = 0; j < m.joints.num_joints(); ++j) {
        for (NodeId k : m.joints.nodes[j]) {
            if (k == n[0] || k == n[1] || k == n[2]) {
                around.push_back(j);
                break;
            }
        }
    }
    ASSERT_EQ(around.size(), 3u);  // an interior triangle: three jointed edges
    std::vector<TriId> frag;
    compute_fragments(m, statuses(m, around), frag);
    for (TriId t = 0; t < m.num_tris(); ++t)
        EXPECT_EQ(frag[t], t == lone ? lone : 0) << t;
}

// largest_fragment_mass_fraction: the 16 m^2 block (density 1000, lumped masses rho A/3 per
// node) is one fragment (1), two halves of 8 m^2 after the crack line (1/2), and after one
// triangle of 0.5 m^2 is cut free the rest holds 15.5/16 = 0.96875 (round-off of the lumped
// thirds only)
TEST(Fragments, LargestFragmentMassFraction) {
    const Model m = jointed_block();
    std::vector<TriId> frag;
    std::vector<TriId> node_frag(static_cast<size_t>(m.num_nodes()));
    std::vector<Real> frag_mass(static_cast<size_t>(m.num_tris()));
    compute_fragments(m, statuses(m), frag);
    EXPECT_NEAR(largest_fragment_mass_fraction(m, frag, node_frag, frag_mass), 1.0, 1e-14);
    compute_fragments(m, statuses(m, joints_on_line(m, 2.0)), frag);
    EXPECT_NEAR(largest_fragment_mass_fraction(m, frag, node_frag, frag_mass), 0.5, 1e-14);
    const auto& n = m.tri_nodes[13];
    std::vector<int32_t> around;
    for (int32_t j = 0; j < m.joints.num_joints(); ++j) {
        for (NodeId k : m.joints.nodes[j]) {
            if (k == n[0] || k == n[1] || k == n[2]) {
                around.push_back(j);
                break;
            }
        }
    }
    compute_fragments(m, statuses(m, around), frag);
    EXPECT_NEAR(largest_fragment_mass_fraction(m, frag, node_frag, frag_mass), 0.96875, 1e-14);
    // scratch left from another state does not leak into the next call
    compute_fragments(m, statuses(m, joints_on_line(m, 2.0)), frag);
    EXPECT_NEAR(largest_fragment_mass_fraction(m, frag, node_frag, frag_mass), 0.5, 1e-14);
}

// ids do not depend on the order of the breaks; the incremental form equals the full form
TEST(Fragments, IndependentOfBreakOrder) {
    const Model m = jointed_block();
    std::vector<int32_t> set = joints_on_line(m, 2.0);
    const std::vector<int32_t> more = joints_on_line(m, 3.0);
    set.insert(set.end(), more.begin(), more.end());
    std::vector<TriId> want;
    compute_fragments(m, statuses(m, set), want);
    std::mt19937 rng(3);
    for (int trial = 0; trial < 10; ++trial) {
        std::shuffle(set.begin(), set.end(), rng);
        std::vector<JointStatus> st = statuses(m);
        std::vector<TriId> frag;
        compute_fragments(m, st, frag);
        for (const int32_t j : set) {
            st[static_cast<size_t>(j)] = JointStatus::Broken;
            const int32_t one[1] = {j};
            update_fragments(m, st, one, frag);
        }
        EXPECT_EQ(frag, want) << trial;
    }
    // three bands: y < 2, 2 < y < 3, y > 3
    std::vector<TriId> ids(want);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    EXPECT_EQ(ids.size(), 3u);
}

// a body jointed only along the crack line keeps shared nodes elsewhere
TEST(Fragments, PartlyJointedBody) {
    const MeshData mesh = make_rectangle_mesh(0, 0, 4, 4, 4, 4, true);
    const Model c = jointed_block(
        [&](int32_t a, int32_t b) { return mesh.nodes[a].y == 2.0 && mesh.nodes[b].y == 2.0; });
    EXPECT_EQ(c.joints.num_joints(), 4);
    EXPECT_EQ(c.num_nodes(), 30);  // the 5 vertices of the line doubled
    std::vector<TriId> frag;
    compute_fragments(c, statuses(c, joints_on_line(c, 2.0)), frag);
    for (TriId t = 0; t < c.num_tris(); ++t)
        EXPECT_EQ(frag[t], centroid(c, t).y < 2.0 ? frag[0] : frag[c.num_tris() - 1]) << t;
    EXPECT_NE(frag[0], frag[c.num_tris() - 1]);
    std::vector<NodeId> sec;
    compute_node_sectors(c, statuses(c, joints_on_line(c, 2.0)), sec);
    for (NodeId n = 0; n < c.num_nodes(); ++n)
        EXPECT_EQ(sec[n], n);
}

}  // namespace
}  // namespace fdem
