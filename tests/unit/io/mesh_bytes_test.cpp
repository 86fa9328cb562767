// io/mesh_bytes: a MeshData to bytes and back is the same mesh, bit for bit (what a distributed
// run's processes receive from process 0, parallel/mesh_broadcast.hpp); a damaged string throws.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <string>

#include "fdem/mesh.hpp"
#include "io/mesh_bytes.hpp"

namespace fdem {
namespace {

const std::string kData = FDEM_TEST_DATA_DIR;

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expect_same(const MeshData& a, const MeshData& b) {
    EXPECT_EQ(a.file, b.file);
    EXPECT_TRUE(same_bits(a.nodes, b.nodes));
    EXPECT_TRUE(same_bits(a.tris, b.tris));
    EXPECT_TRUE(same_bits(a.tri_mid, b.tri_mid));
    EXPECT_TRUE(same_bits(a.tri_tag, b.tri_tag));
    EXPECT_TRUE(same_bits(a.lines, b.lines));
    EXPECT_TRUE(same_bits(a.line_mid, b.line_mid));
    EXPECT_TRUE(same_bits(a.line_tag, b.line_tag));
    EXPECT_TRUE(same_bits(a.points, b.points));
    EXPECT_TRUE(same_bits(a.point_tag, b.point_tag));
    EXPECT_EQ(a.physical, b.physical);
    ASSERT_EQ(a.groups.size(), b.groups.size());
    for (size_t g = 0; g < a.groups.size(); ++g) {
        EXPECT_EQ(a.groups[g].name, b.groups[g].name);
        EXPECT_EQ(a.groups[g].dim, b.groups[g].dim);
        EXPECT_EQ(a.groups[g].tag, b.groups[g].tag);
        EXPECT_EQ(a.groups[g].elements, b.groups[g].elements);
    }
}

TEST(MeshBytes, RoundTripIsTheSameMeshBitForBit) {
    // a .geo meshed by Gmsh (irrational coordinates, physical groups of every dimension it has)
    // and a second-order .msh (mid-edge nodes of triangles and lines)
    for (const MeshData& m : {read_mesh(kData + "/jointed_blocks.geo", 0.1),
                              read_mesh(kData + "/square_order2_41.msh")}) {
        ASSERT_FALSE(m.tris.empty());
        ASSERT_FALSE(m.groups.empty());
        const std::string bytes = mesh_to_bytes(m);
        expect_same(m, mesh_from_bytes(bytes));
        EXPECT_EQ(mesh_to_bytes(mesh_from_bytes(bytes)), bytes);
    }
    EXPECT_FALSE(read_mesh(kData + "/square_order2_41.msh").tri_mid.empty());
}

TEST(MeshBytes, EmptyMeshRoundTrips) {
    const MeshData empty;
    expect_same(empty, mesh_from_bytes(mesh_to_bytes(empty)));
}

TEST(MeshBytes, DamagedBytesThrowInsteadOfReadingPastTheEnd) {
    const std::string bytes = mesh_to_bytes(read_mesh(kData + "/square_41_ascii.msh"));
    // every truncation (the length fields then point past the end), and one byte too many
    for (size_t n = 0; n < bytes.size(); n += 7) {
        EXPECT_THROW(mesh_from_bytes(bytes.substr(0, n)), std::runtime_error) << n;
    }
    EXPECT_THROW(mesh_from_bytes(bytes + "x"), std::runtime_error);
    std::string wrong = bytes;
    wrong[0] ^= 1;  // not the magic number
    EXPECT_THROW(mesh_from_bytes(wrong), std::runtime_error);
}

}  // namespace
}  // namespace fdem
