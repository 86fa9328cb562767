// read_mesh through Gmsh: the four .msh flavours, .geo meshing, physical groups, orientation.
// Test meshes: tests/data/square.geo (unit square, lc = 0.5) and the .msh files made from it.
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "fdem/mesh.hpp"

namespace fdem {
namespace {

const std::string kData = FDEM_TEST_DATA_DIR;

const PhysicalGroup* find_group(const MeshData& m, const std::string& name) {
    for (const PhysicalGroup& g : m.groups) {
        if (g.name == name) {
            return &g;
        }
    }
    return nullptr;
}

Real total_abs_area(const MeshData& m) {
    Real a = 0;
    for (const auto& t : m.tris) {
        a += std::abs(signed_area(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]));
    }
    return a;
}

std::string write_temp(const std::string& name, const std::string& text) {
    const std::string path = ::testing::TempDir() + "/" + name;
    std::ofstream(path) << text;
    return path;
}

/// Checks every variant of the unit square must pass. The .geo is the source of truth:
/// 4 boundary points, lc = 0.5 gives 2 segments per side (8 boundary lines), a physical surface
/// "block", one physical curve per side, "sides" = right + left, "origin" = point (0, 0).
void check_square(const MeshData& m) {
    SCOPED_TRACE(m.file);
    ASSERT_FALSE(m.tris.empty());
    EXPECT_EQ(m.tris.size(), m.tri_tag.size());

    // the triangles tile the unit square: total area 1 (1e-12: sum of O(10) rounded products)
    EXPECT_NEAR(total_abs_area(m), 1.0, 1e-12);
    for (const auto& t : m.tris) {
        EXPECT_NE(signed_area(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]), 0.0);
    }

    // physical groups by name and dimension
    const PhysicalGroup* block = find_group(m, "block");
    ASSERT_NE(block, nullptr);
    EXPECT_EQ(block->dim, 2);
    EXPECT_EQ(block->elements.size(), m.tris.size());
    for (const char* side : {"bottom", "right", "top", "left"}) {
        const PhysicalGroup* g = find_group(m, side);
        ASSERT_NE(g, nullptr) << side;
        EXPECT_EQ(g->dim, 1);
        EXPECT_EQ(g->elements.size(), 2u) << side;  // side length 1 / lc 0.5
        EXPECT_EQ(m.group_nodes(*g).size(), 3u) << side;
    }
    for (const int32_t n : m.group_nodes(*find_group(m, "bottom"))) {
        EXPECT_EQ(m.nodes[n].y, 0.0);
    }
    const PhysicalGroup* sides = find_group(m, "sides");
    ASSERT_NE(sides, nullptr);
    EXPECT_EQ(sides->elements.size(), 4u);
    for (const int32_t n : m.group_nodes(*sides)) {
        EXPECT_TRUE(m.nodes[n].x == 0.0 || m.nodes[n].x == 1.0);
    }
    const PhysicalGroup* origin = find_group(m, "origin");
    ASSERT_NE(origin, nullptr);
    EXPECT_EQ(origin->dim, 0);
    ASSERT_EQ(origin->elements.size(), 1u);
    EXPECT_EQ(m.nodes[m.points[origin->elements[0]]], (Vec2{0, 0}));
    EXPECT_EQ(m.physical.at("block"), (std::pair<int, int>{2, 1}));
}

class MshVariants : public ::testing::TestWithParam<const char*> {};

TEST_P(MshVariants, ReadsUnitSquare) {
    const MeshData m = read_mesh(kData + "/" + GetParam());
    check_square(m);
}

INSTANTIATE_TEST_SUITE_P(AllFormats, MshVariants,
                         ::testing::Values("square_22_ascii.msh", "square_22_bin.msh",
                                           "square_41_ascii.msh", "square_41_bin.msh"));

TEST(ReadMesh, AllFourFormatsGiveTheSameMesh) {
    const MeshData ref = read_mesh(kData + "/square_41_ascii.msh");
    for (const char* f : {"square_22_ascii.msh", "square_22_bin.msh", "square_41_bin.msh"}) {
        const MeshData m = read_mesh(kData + "/" + f);
        SCOPED_TRACE(f);
        EXPECT_EQ(m.tris.size(), ref.tris.size());
        EXPECT_EQ(m.lines.size(), ref.lines.size());
        EXPECT_EQ(m.points.size(), ref.points.size());
        // same node coordinates up to order. ASCII .msh stores 16 significant digits, so a
        // coordinate in [0, 1] may differ from the binary double by < 1e-16: compare to 1e-15
        // after sorting on coordinates rounded to 1e-9 (far finer than the mesh spacing 0.5)
        auto sorted = [](std::vector<Vec2> v) {
            auto key = [](Vec2 a) {
                return std::pair{std::llround(a.x * 1e9), std::llround(a.y * 1e9)};
            };
            std::sort(v.begin(), v.end(), [&](Vec2 a, Vec2 b) { return key(a) < key(b); });
            return v;
        };
        const std::vector<Vec2> a = sorted(m.nodes), b = sorted(ref.nodes);
        ASSERT_EQ(a.size(), b.size());
        for (size_t i = 0; i < a.size(); ++i) {
            EXPECT_NEAR(a[i].x, b[i].x, 1e-15);
            EXPECT_NEAR(a[i].y, b[i].y, 1e-15);
        }
    }
}

TEST(ReadMesh, GeoIsMeshedWithTheGivenSize) {
    // mesh_size 0.25 caps the .geo's lc = 0.5: each unit side gets 1 / 0.25 = 4 equal segments
    const MeshData m = read_mesh(kData + "/square.geo", 0.25);
    EXPECT_NEAR(total_abs_area(m), 1.0, 1e-12);
    const PhysicalGroup* bottom = find_group(m, "bottom");
    ASSERT_NE(bottom, nullptr);
    ASSERT_EQ(bottom->elements.size(), 4u);
    for (const int32_t l : bottom->elements) {
        const auto [a, b] = m.lines[l];
        // 1e-12: Gmsh places curve nodes by parametric interpolation, exact to rounding
        EXPECT_NEAR(norm(m.nodes[b] - m.nodes[a]), 0.25, 1e-12);
    }
    // mesh_size 0 keeps the .geo's own lc = 0.5 (2 segments per side)
    const MeshData coarse = read_mesh(kData + "/square.geo", 0);
    EXPECT_EQ(find_group(coarse, "bottom")->elements.size(), 2u);
    EXPECT_LT(coarse.tris.size(), m.tris.size());
}

TEST(ReadMesh, RepeatedReadsAreIdentical) {
    // Gmsh keeps global state; each read must start from scratch (the option set by the first
    // read must not leak into the second).
    const MeshData a = read_mesh(kData + "/square.geo", 0.2);
    const MeshData b = read_mesh(kData + "/square.geo", 0);
    const MeshData c = read_mesh(kData + "/square.geo", 0.2);
    EXPECT_NE(a.tris.size(), b.tris.size());
    EXPECT_EQ(a.tris, c.tris);
    EXPECT_TRUE(a.nodes == c.nodes);
}

TEST(ReadMesh, KeepsTheCallersOpenMpThreadCount) {
    // Gmsh's General.NumThreads = 1 calls omp_set_num_threads(1) for the calling thread: before
    // the reader restored it, every `fdem run` without --threads stepped on one thread after
    // reading its meshes (found 2026-11-28). A .geo (meshed) and a .msh (read) alike.
    const int before = omp_get_max_threads();
    omp_set_num_threads(3);
    (void)read_mesh(kData + "/square.geo", 0.25);
    EXPECT_EQ(omp_get_max_threads(), 3);
    omp_set_num_threads(2);
    (void)read_mesh(kData + "/square_22_ascii.msh", 0);
    EXPECT_EQ(omp_get_max_threads(), 2);
    omp_set_num_threads(before);
}

TEST(ReadMesh, ClockwiseGeometryGivesConsistentlyOrientedTriangles) {
    // same square with the curve loop running clockwise: Gmsh orients the triangles along the
    // surface normal (-z), so all triangles come out clockwise; add_bodies() fixes that later.
    const std::string path = write_temp("cw_square.geo", R"(
Point(1) = {0, 0, 0, 0.5}; Point(2) = {1, 0, 0, 0.5};
Point(3) = {1, 1, 0, 0.5}; Point(4) = {0, 1, 0, 0.5};
Line(1) = {1, 4}; Line(2) = {4, 3}; Line(3) = {3, 2}; Line(4) = {2, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
)");
    const MeshData m = read_mesh(path);
    int ccw = 0, cw = 0;
    for (const auto& t : m.tris) {
        (signed_area(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]) > 0 ? ccw : cw)++;
    }
    EXPECT_TRUE(ccw == 0 || cw == 0) << ccw << " ccw, " << cw << " cw";
    EXPECT_NEAR(total_abs_area(m), 1.0, 1e-12);
    EXPECT_TRUE(m.groups.empty());  // no physical groups: every element is still read
}

TEST(ReadMesh, ConcurrentReadsAreSerialized) {
    // Gmsh has global state; read_mesh holds a lock, so parallel callers get correct meshes
    std::vector<MeshData> out(4);
    std::vector<std::thread> threads;
    for (size_t i = 0; i < out.size(); ++i) {
        threads.emplace_back([&out, i] {
            out[i] = i % 2 ? read_mesh(kData + "/square.geo", 0.25)
                           : read_mesh(kData + "/square_41_bin.msh");
        });
    }
    for (auto& t : threads) {
        t.join();
    }
    const MeshData geo = read_mesh(kData + "/square.geo", 0.25);
    const MeshData msh = read_mesh(kData + "/square_41_bin.msh");
    for (size_t i = 0; i < out.size(); ++i) {
        EXPECT_EQ(out[i].tris, (i % 2 ? geo : msh).tris) << i;
    }
}

// ---- many physical names (issue #16 item 4) ------------------------------------------------
// From 1000 names on, read_mesh hands Gmsh a copy without $PhysicalNames and names the groups
// itself (Gmsh 4.8's name lookup is quadratic). The names must be Gmsh's: first name of a tag
// wins, a name already used in the dimension is not given again, a tag without an entry has none.

/// MSH 2.2 of n two-triangle blocks, block i in physical and elementary surface i + 1, with
/// the $PhysicalNames lines `names` (already formatted).
std::string blocks_msh(int n, const std::vector<std::string>& names) {
    std::string s = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n";
    s += std::to_string(names.size()) + "\n";
    for (const std::string& l : names)
        s += l + "\n";
    s += "$EndPhysicalNames\n$Nodes\n" + std::to_string(4 * n) + "\n";
    for (int i = 0; i < n; ++i) {
        const double x = 1.5 * i;
        for (int k = 0; k < 4; ++k) {
            s += std::to_string(4 * i + k + 1) + " " + std::to_string(x + (k == 1 || k == 2)) +
                 " " + std::to_string(k >= 2 ? 1 : 0) + " 0\n";
        }
    }
    s += "$EndNodes\n$Elements\n" + std::to_string(2 * n) + "\n";
    for (int i = 0; i < n; ++i) {
        const int b = 4 * i, tag = i + 1;
        s += std::to_string(2 * i + 1) + " 2 2 " + std::to_string(tag) + " " + std::to_string(tag) +
             " " + std::to_string(b + 1) + " " + std::to_string(b + 2) + " " +
             std::to_string(b + 3) + "\n";
        s += std::to_string(2 * i + 2) + " 2 2 " + std::to_string(tag) + " " + std::to_string(tag) +
             " " + std::to_string(b + 1) + " " + std::to_string(b + 3) + " " +
             std::to_string(b + 4) + "\n";
    }
    return s + "$EndElements\n";
}

/// Name entries of n blocks with the awkward cases among the first 20: tags 6 and 10 both
/// "dup", tag 12 twice (first "first12", then "second12"), tag 15 without an entry.
std::vector<std::string> awkward_names(int n) {
    std::vector<std::string> out;
    for (int t = 1; t <= n; ++t) {
        if (t == 15) continue;
        out.push_back(t == 6 || t == 10 ? "2 " + std::to_string(t) + " \"dup\""
                      : t == 12         ? "2 12 \"first12\""
                                : "2 " + std::to_string(t) + " \"b" + std::to_string(t) + "\"");
    }
    out.push_back("2 12 \"second12\"");
    return out;
}

TEST(ReadMesh, ManyPhysicalNamesAreNamedAsGmshNamesThem) {
    // 20 blocks: Gmsh's own names; 1500: fdem's; 1500 with one entry Gmsh reads the same but
    // fdem does not take as plain (text after the quote): Gmsh's own names again
    const MeshData few = read_mesh(write_temp("few_names.msh", blocks_msh(20, awkward_names(20))));
    const MeshData many =
        read_mesh(write_temp("many_names.msh", blocks_msh(1500, awkward_names(1500))));
    std::vector<std::string> odd = awkward_names(1500);
    odd[100] += " trailing";
    const MeshData gmsh_many = read_mesh(write_temp("many_names_gmsh.msh", blocks_msh(1500, odd)));
    ASSERT_EQ(few.groups.size(), 20u);
    ASSERT_EQ(many.groups.size(), 1500u);
    ASSERT_EQ(gmsh_many.groups.size(), 1500u);
    for (size_t g = 0; g < many.groups.size(); ++g) {
        const PhysicalGroup& a = many.groups[g];
        const PhysicalGroup& b = gmsh_many.groups[g];
        EXPECT_EQ(a.tag, b.tag);
        EXPECT_EQ(a.name, b.name) << "tag " << a.tag;
        EXPECT_EQ(a.elements, b.elements) << "tag " << a.tag;
        if (g < few.groups.size()) {
            EXPECT_EQ(a.name, few.groups[g].name) << "tag " << a.tag;
            EXPECT_EQ(a.elements, few.groups[g].elements) << "tag " << a.tag;
        }
        EXPECT_EQ(a.elements, (std::vector<int32_t>{static_cast<int32_t>(2 * g),
                                                    static_cast<int32_t>(2 * g + 1)}));
    }
    // what Gmsh does with the awkward entries, seen through the small file
    EXPECT_EQ(few.groups[5].name, "dup");
    EXPECT_EQ(few.groups[9].name, "");
    EXPECT_EQ(few.groups[11].name, "first12");
    EXPECT_EQ(few.groups[14].name, "");
    EXPECT_EQ(many.groups[1499].name, "b1500");
    EXPECT_EQ(many.physical, gmsh_many.physical);
    EXPECT_TRUE(many.nodes == gmsh_many.nodes);
    EXPECT_EQ(many.tris, gmsh_many.tris);
    EXPECT_EQ(many.tri_tag, gmsh_many.tri_tag);
    // the temporary copy is gone
    const std::string prefix = "fdem-" + std::to_string(static_cast<long>(::getpid())) + "-";
    for (const auto& e :
         std::filesystem::directory_iterator(std::filesystem::temp_directory_path())) {
        EXPECT_NE(e.path().filename().string().rfind(prefix, 0), 0u) << e.path();
    }
}

TEST(RectangleMesh, CountsGroupsAndOrientation) {
    for (const bool alternate : {false, true}) {
        const int nx = 5, ny = 3;
        const MeshData m = make_rectangle_mesh(-1.0, 2.0, 2.5, 1.5, nx, ny, alternate);
        EXPECT_EQ(m.nodes.size(), size_t((nx + 1) * (ny + 1)));
        EXPECT_EQ(m.tris.size(), size_t(2 * nx * ny));
        EXPECT_EQ(m.lines.size(), size_t(2 * (nx + ny)));
        Real area = 0;
        for (const auto& t : m.tris) {
            const Real a = signed_area(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]]);
            // every cell is 0.5 x 0.5 and split in half: 1e-15 relative rounding of the coords
            EXPECT_NEAR(a, 0.5 * 0.5 * 0.5, 1e-15);
            area += a;
        }
        EXPECT_NEAR(area, 2.5 * 1.5, 1e-13);
        const std::pair<const char*, size_t> sides[] = {
            {"bottom", nx + 1}, {"right", ny + 1}, {"top", nx + 1}, {"left", ny + 1}};
        for (const auto& [name, count] : sides) {
            const PhysicalGroup* g = find_group(m, name);
            ASSERT_NE(g, nullptr);
            EXPECT_EQ(m.group_nodes(*g).size(), count) << name;
        }
        for (const int32_t n : m.group_nodes(*find_group(m, "top"))) {
            EXPECT_EQ(m.nodes[n].y, 3.5);
        }
        for (const int32_t n : m.group_nodes(*find_group(m, "right"))) {
            EXPECT_EQ(m.nodes[n].x, 1.5);
        }
        EXPECT_EQ(find_group(m, "domain")->elements.size(), m.tris.size());
    }
    // alternate diagonals: cell (1, 0) is split along the other diagonal, so its first
    // triangle is (a, b, d) = (node 1, node 2, node 7) instead of (1, 2, 8)
    const MeshData alt = make_rectangle_mesh(0, 0, 5, 3, 5, 3, true);
    EXPECT_EQ(alt.tris[2], (std::array<int32_t, 3>{1, 2, 7}));
    const MeshData plain = make_rectangle_mesh(0, 0, 5, 3, 5, 3, false);
    EXPECT_EQ(plain.tris[2], (std::array<int32_t, 3>{1, 2, 8}));
}

}  // namespace
}  // namespace fdem
