// Second-order meshes (issue #7): Gmsh 6-node triangles (type 9) and 3-node lines (type 8) read
// into MeshData::tri_mid / line_mid, from .msh (2.2 and 4.1) and from a .geo meshed at order 2;
// and the structured generator make_rectangle_mesh_order2.
// Test meshes: tests/data/square.geo (unit square, lc = 0.5); the .msh files were made from it
// with  gmsh -2 -order 2 -format msh22|msh41 square.geo -o square_order2_<22|41>.msh
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "fdem/mesh.hpp"

namespace fdem {
namespace {

const std::string kData = FDEM_TEST_DATA_DIR;

/// Straight-sided second-order mesh: every mid-edge node at the midpoint of its edge, in Gmsh
/// order (mid k on corners k, k+1). 1e-12: Gmsh writes midpoints with ~16 significant digits.
void check_midpoints(const MeshData& m) {
    ASSERT_TRUE(m.second_order());
    ASSERT_EQ(m.tri_mid.size(), m.tris.size());
    for (size_t t = 0; t < m.tris.size(); ++t) {
        for (int k = 0; k < 3; ++k) {
            const Vec2 a = m.nodes[m.tris[t][k]], b = m.nodes[m.tris[t][(k + 1) % 3]];
            const Vec2 q = m.nodes[m.tri_mid[t][k]];
            EXPECT_LT(norm(q - 0.5 * (a + b)), 1e-12) << "triangle " << t << " edge " << k;
        }
    }
    ASSERT_EQ(m.line_mid.size(), m.lines.size());
    for (size_t l = 0; l < m.lines.size(); ++l) {
        const Vec2 a = m.nodes[m.lines[l][0]], b = m.nodes[m.lines[l][1]];
        EXPECT_LT(norm(m.nodes[m.line_mid[l]] - 0.5 * (a + b)), 1e-12) << "line " << l;
    }
}

const PhysicalGroup& group(const MeshData& m, const std::string& name) {
    for (const PhysicalGroup& g : m.groups) {
        if (g.name == name) return g;
    }
    throw std::runtime_error("no group " + name);
}

TEST(GmshOrder2, MshFilesGiveSixNodeTriangles) {
    const MeshData first = read_mesh(kData + "/square_22_ascii.msh");
    EXPECT_FALSE(first.second_order());
    for (const char* f : {"/square_order2_22.msh", "/square_order2_41.msh"}) {
        SCOPED_TRACE(f);
        const MeshData m = read_mesh(kData + f);
        check_midpoints(m);
        // corners tile the unit square (1e-12: sum of O(10) rounded products)
        Real area = 0;
        for (const auto& t : m.tris)
            area += std::abs(signed_area(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]));
        EXPECT_NEAR(area, 1.0, 1e-12);
        // same corner mesh as the first-order file: setOrder only adds nodes
        EXPECT_EQ(m.tris.size(), first.tris.size());
        EXPECT_EQ(m.lines.size(), first.lines.size());
        // boundary group nodes include the mid nodes: lc = 0.5 gives 2 segments on the bottom,
        // so 3 end nodes and 2 mid nodes at x = 0, 0.25, 0.5, 0.75, 1
        const auto bottom = m.group_nodes(group(m, "bottom"));
        ASSERT_EQ(bottom.size(), 5u);
        std::vector<Real> xs;
        for (int32_t n : bottom) {
            EXPECT_NEAR(m.nodes[n].y, 0.0, 1e-12);
            xs.push_back(m.nodes[n].x);
        }
        std::sort(xs.begin(), xs.end());
        // 1e-11: Gmsh's own 1-D mesher places the corner node at 0.499999999998694 (in the file)
        for (int i = 0; i < 5; ++i)
            EXPECT_NEAR(xs[i], 0.25 * i, 1e-11);
        // the surface group covers all nodes (corners and mid-edge nodes)
        EXPECT_EQ(m.group_nodes(group(m, "block")).size(), m.nodes.size());
    }
}

TEST(GmshOrder2, GeoMeshedAtOrderTwo) {
    const MeshData m1 = read_mesh(kData + "/square.geo", 0.25);
    const MeshData m2 = read_mesh(kData + "/square.geo", 0.25, 2);
    EXPECT_FALSE(m1.second_order());
    check_midpoints(m2);
    EXPECT_EQ(m2.tris.size(), m1.tris.size());
    // Euler: nodes = corners + edges; for a triangulated disk edges = (3 T + boundary edges) / 2
    const size_t edges = (3 * m1.tris.size() + m1.lines.size()) / 2;
    EXPECT_EQ(m2.nodes.size(), m1.nodes.size() + edges);
}

TEST(GmshOrder2, RectangleGenerator) {
    const int nx = 3, ny = 2;
    const MeshData m1 = make_rectangle_mesh(0, 0, 3.0, 1.0, nx, ny);
    const MeshData m = make_rectangle_mesh_order2(0, 0, 3.0, 1.0, nx, ny);
    check_midpoints(m);
    EXPECT_EQ(m.tris, m1.tris);  // same corners, same diagonals, same corner ids
    // mid nodes: horizontal nx (ny + 1), vertical ny (nx + 1), diagonal nx ny
    const size_t edges = nx * (ny + 1) + ny * (nx + 1) + nx * ny;
    EXPECT_EQ(m.nodes.size(), m1.nodes.size() + edges);
    EXPECT_EQ(m.group_nodes(group(m, "left")).size(), size_t(2 * ny + 1));
    // alternate diagonals too
    check_midpoints(make_rectangle_mesh_order2(0, 0, 1.0, 1.0, 2, 2, true));
}

}  // namespace
}  // namespace fdem
