// Jointed meshes: split_mesh, add_edge_joints (spec fracture.md §1.2, §7; theory eq. 9.1).
#include "fracture/joint_mesh.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "fdem/mesh.hpp"

namespace fdem {
namespace {

TEST(JointMesh, EveryInternalEdgeOnceWithSpecNodeOrder) {
    const int nx = 5, ny = 3;
    const MeshData mesh = make_rectangle_mesh(0, 0, 5.0, 3.0, nx, ny, true);
    const SplitMesh sm = split_mesh(mesh.nodes, mesh.tris);
    ASSERT_EQ(sm.x0.size(), 3 * mesh.tris.size());
    for (size_t t = 0; t < sm.tris.size(); ++t)
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(sm.tris[t][k], static_cast<NodeId>(3 * t + k));
            EXPECT_EQ(sm.vertex[3 * t + k], mesh.tris[t][k]);
            EXPECT_EQ(sm.x0[3 * t + k], mesh.nodes[static_cast<size_t>(mesh.tris[t][k])]);
        }
    Joints J;
    add_edge_joints(J, sm.x0, sm.tris, sm.vertex, 0);
    // internal edges of the structured mesh: horizontal, vertical, one diagonal per cell
    EXPECT_EQ(J.num_joints(), nx * (ny - 1) + (nx - 1) * ny + nx * ny);
    for (int32_t j = 0; j < J.num_joints(); ++j) {
        const auto& n = J.nodes[j];
        // 0 faces 3, 1 faces 2 (coincide, distinct copies)
        EXPECT_EQ(sm.x0[n[0]], sm.x0[n[3]]);
        EXPECT_EQ(sm.x0[n[1]], sm.x0[n[2]]);
        EXPECT_NE(n[0], n[3]);
        EXPECT_NE(n[1], n[2]);
        EXPECT_EQ(J.length0[j], norm(sm.x0[n[1]] - sm.x0[n[0]]));
        // A (the triangle of nodes 0, 1) is the lower id; n = perp(e) points into A
        const int32_t ta = n[0] / 3, tb = n[3] / 3;
        EXPECT_EQ(n[1] / 3, ta);
        EXPECT_EQ(n[2] / 3, tb);
        EXPECT_LT(ta, tb);
        Vec2 ca{0, 0};
        for (NodeId v : sm.tris[static_cast<size_t>(ta)])
            ca += sm.x0[v] / 3.0;
        const Vec2 e = sm.x0[n[1]] - sm.x0[n[0]];
        EXPECT_GT(dot(perp(e), ca - sm.x0[n[0]]), 0.0);
        if (j > 0) {  // ordered by A
            EXPECT_LE(J.nodes[j - 1][0] / 3, ta);
        }
    }
    finalize_joints(J, static_cast<int32_t>(sm.x0.size()));
    // every copy is in at most 2 joints (its two edges), entries ascending in joint id
    for (size_t g = 0; g < J.gather_node.size(); ++g) {
        const int32_t cnt = J.gather_begin[g + 1] - J.gather_begin[g];
        EXPECT_GE(cnt, 1);
        EXPECT_LE(cnt, 2);
        for (int32_t q = J.gather_begin[g]; q < J.gather_begin[g + 1]; ++q) {
            const int32_t e = J.gather_entry[static_cast<size_t>(q)];
            EXPECT_EQ(J.nodes[e >> 2][e & 3], J.gather_node[g]);
            if (q > J.gather_begin[g]) {
                EXPECT_LT(J.gather_entry[static_cast<size_t>(q) - 1] >> 2, e >> 2);
            }
        }
    }
}

TEST(JointMesh, RejectsOppositeOrientation) {
    const std::vector<Vec2> x{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const std::vector<std::array<NodeId, 3>> tris{{0, 1, 2}, {0, 3, 2}};  // second clockwise
    const SplitMesh sm = split_mesh(x, tris);
    Joints J;
    EXPECT_THROW(add_edge_joints(J, sm.x0, sm.tris, sm.vertex, 0), std::invalid_argument);
}

}  // namespace
}  // namespace fdem
