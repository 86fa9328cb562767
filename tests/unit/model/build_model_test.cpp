// add_bodies / add_bodies_mapped (src/fdem/model/build_model.cpp): the sparse node map of
// issue #16 item 4 (its size is that of the selected triangles, not of the mesh) and the
// bodies it makes from a selection of a larger mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "fdem/build.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

Model one_material() {
    Model m;
    m.materials.push_back(scenes::paper_material("p", 1e9, 0.3));
    return m;
}

BodyOptions options(const char* name) {
    BodyOptions opt;
    opt.name = name;
    opt.velocity = {0.5, -0.25};
    return opt;
}

// Two triangles far apart in a 40 x 40 mesh (6561 nodes): two bodies, a map of their 6 nodes.
TEST(AddBodiesMapped, MapHasTheSelectedNodesOnly) {
    const MeshData mesh = make_rectangle_mesh(0, 0, 1, 1, 80, 80);
    ASSERT_EQ(mesh.nodes.size(), 81u * 81u);
    const std::vector<int32_t> tris = {7, static_cast<int32_t>(mesh.tris.size()) - 3};
    std::set<int32_t> expected;
    for (const int32_t t : tris)
        for (const int32_t q : mesh.tris[static_cast<size_t>(t)])
            expected.insert(q);
    ASSERT_EQ(expected.size(), 6u);

    Model m = one_material();
    const MeshNodeMap map = add_bodies_mapped(m, mesh, tris, options("two"));
    EXPECT_EQ(m.num_bodies(), 2);
    EXPECT_EQ(m.num_nodes(), 6);
    EXPECT_EQ(m.num_tris(), 2);
    EXPECT_EQ(std::vector<int32_t>(expected.begin(), expected.end()), map.mesh_nodes);
    ASSERT_EQ(map.model_nodes.size(), map.mesh_nodes.size());
    std::set<NodeId> model(map.model_nodes.begin(), map.model_nodes.end());
    EXPECT_EQ(model.size(), 6u);  // distinct model nodes
    for (size_t k = 0; k < map.mesh_nodes.size(); ++k) {
        const NodeId id = map[map.mesh_nodes[k]];
        EXPECT_EQ(id, map.model_nodes[k]);
        // the model node sits where the mesh node does and moves with the entry's velocity
        EXPECT_EQ(m.node_x0[static_cast<size_t>(id)].x,
                  mesh.nodes[static_cast<size_t>(map.mesh_nodes[k])].x);
        EXPECT_EQ(m.node_x0[static_cast<size_t>(id)].y,
                  mesh.nodes[static_cast<size_t>(map.mesh_nodes[k])].y);
        EXPECT_EQ(m.node_v0[static_cast<size_t>(id)].x, 0.5);
    }
    for (const int32_t q : {0, 1, 100, static_cast<int32_t>(mesh.nodes.size()) - 1}) {
        if (!expected.count(q)) {
            EXPECT_EQ(map[q], kNone) << q;
        }
    }
    EXPECT_EQ(map[-1], kNone);
    EXPECT_EQ(map[static_cast<int32_t>(mesh.nodes.size())], kNone);
}

// The dense add_bodies map agrees with the sparse one, and both number the nodes of a piece in
// order of first use by its triangles in file order, pieces in order of their first triangle.
TEST(AddBodiesMapped, DenseMapAndNumberingOrder) {
    const MeshData mesh = make_rectangle_mesh_order2(0, 0, 2, 1, 6, 3);
    // the last column of cells and the first: two pieces (6-node triangles, mid nodes included)
    std::vector<int32_t> tris;
    for (int32_t t = 0; t < static_cast<int32_t>(mesh.tris.size()); ++t) {
        const auto& n = mesh.tris[static_cast<size_t>(t)];
        const Real cx = (mesh.nodes[n[0]].x + mesh.nodes[n[1]].x + mesh.nodes[n[2]].x) / 3;
        if (cx < 1.0 / 3 || cx > 5.0 / 3) tris.push_back(t);
    }
    std::reverse(tris.begin(), tris.end());  // selection order does not matter

    Model a = one_material(), b = one_material();
    const MeshNodeMap sparse = add_bodies_mapped(a, mesh, tris, options("cols"));
    const std::vector<NodeId> dense = add_bodies(b, mesh, tris, options("cols"));
    ASSERT_EQ(a.num_bodies(), 2);
    ASSERT_EQ(b.num_bodies(), 2);
    EXPECT_EQ(a.tri_nodes, b.tri_nodes);
    ASSERT_EQ(dense.size(), mesh.nodes.size());
    size_t used = 0;
    for (int32_t q = 0; q < static_cast<int32_t>(dense.size()); ++q) {
        EXPECT_EQ(dense[static_cast<size_t>(q)], sparse[q]) << q;
        used += dense[static_cast<size_t>(q)] != kNone;
    }
    EXPECT_EQ(used, sparse.mesh_nodes.size());
    // piece 0 holds the lowest triangle (x < 1/3); its first node is the first corner of that
    // triangle after orientation, model node 0
    const auto& t0 = mesh.tris[static_cast<size_t>(*std::min_element(tris.begin(), tris.end()))];
    EXPECT_LT(a.node_x0[0].x, 1.0 / 3 + 1e-12);
    EXPECT_EQ(sparse[t0[0]], 0);
    EXPECT_LT(a.node_x0[static_cast<size_t>(a.bodies[1].node_begin)].x, 2.0 + 1e-12);
    EXPECT_GT(a.node_x0[static_cast<size_t>(a.bodies[1].node_begin)].x, 5.0 / 3 - 1e-12);
}

}  // namespace
}  // namespace fdem
