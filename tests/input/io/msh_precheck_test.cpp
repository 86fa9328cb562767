// .msh files that made Gmsh 4.8 crash or allocate without bound (fuzzing and crafted files,
// io/msh_precheck.hpp): each is an InputError naming the file, the section, the byte offset or
// line and what was expected, before Gmsh reads it. The offsets and sizes expected below are
// counted from the way each file is put together here.
#include <gmock/gmock.h>
#include <gmsh.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fdem/error.hpp"
#include "fdem/mesh.hpp"
#include "support/input_errors.hpp"

namespace fdem {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

std::string write_temp(const std::string& name, const std::string& bytes) {
    return support::write_temp("precheck_" + name, bytes);
}

std::string mesh_error(const std::string& path) {
    return support::mesh_error(path);
}

/// "path:line: error: malformed mesh file 'path': " for an error on line `line`.
std::string prefix(const std::string& path, int line) {
    return path + ":" + std::to_string(line) + ": error: malformed mesh file '" + path + "': ";
}

/// 1-based line of byte offset `at` in `bytes`.
int line_at(const std::string& bytes, size_t at) {
    return 1 + static_cast<int>(std::count(bytes.begin(), bytes.begin() + at, '\n'));
}

template <class T>
std::string raw(T v) {
    std::string s(sizeof v, '\0');
    std::memcpy(s.data(), &v, sizeof v);
    return s;
}
std::string i32(int32_t v) {
    return raw(v);
}
std::string u64(uint64_t v) {
    return raw(v);
}
std::string f64(double v) {
    return raw(v);
}

// ---- binary MSH 2.2: format line, then int 1 (byte-order mark) -------------------------------
const std::string kHead22 = "$MeshFormat\n2.2 1 8\n" + i32(1) + "\n$EndMeshFormat\n";

std::string nodes22() {
    std::string s = "$Nodes\n3\n";
    const double xy[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    for (int i = 0; i < 3; ++i) {
        s += i32(i + 1) + f64(xy[i][0]) + f64(xy[i][1]) + f64(0);
    }
    return s + "\n$EndNodes\n";
}

/// $Elements with `count`, one block header (type, n, ntags) and the triangle record
/// {id, tags..., nodes} = {1, 1, 1, 1, 2, 3}.
std::string elements22(int count, int32_t type, int32_t n, int32_t ntags) {
    std::string s = "$Elements\n" + std::to_string(count) + "\n" + i32(type) + i32(n) + i32(ntags);
    for (int32_t v : {1, 1, 1, 1, 2, 3})
        s += i32(v);
    return s + "\n$EndElements\n";
}

TEST(MshPrecheck, ValidBinaryMsh22StillLoads) {
    const std::string path = write_temp("ok22.msh", kHead22 + nodes22() + elements22(1, 2, 1, 2));
    const MeshData mesh = read_mesh(path, 0);
    EXPECT_EQ(mesh.nodes.size(), 3u);
    EXPECT_EQ(mesh.tris.size(), 1u);
}

// Gmsh 4.8 silently drops the 3-node triangles of an MSH 2 elementary entity that also holds
// 6-node triangles (checked by hand: the mesh below loaded as one composite, the second triangle
// gone), so mixing the orders is refused before Gmsh reads the file.
TEST(MshPrecheck, Msh22MixingTriangleOrdersIsRefused) {
    const std::string ascii = write_temp("mixed_ascii.msh", R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
9
1 0 0 0
2 1 0 0
3 0 1 0
4 0.5 0 0
5 0.5 0.5 0
6 0 0.5 0
7 2 0 0
8 3 0 0
9 2 1 0
$EndNodes
$Elements
2
1 9 2 1 1 1 2 3 4 5 6
2 2 2 1 1 7 8 9
$EndElements
)");
    EXPECT_THAT(mesh_error(ascii),
                StartsWith(prefix(ascii, 19) + "element 2 is a 3-node triangle, but earlier "
                                               "elements are 6-node triangles; a mesh must be "
                                               "entirely first or second order (gmsh -order 1 or "
                                               "-order 2)"));

    // binary: a block of one 3-node triangle, then a block of one 6-node triangle
    std::string elements = "$Elements\n2\n" + i32(2) + i32(1) + i32(2);
    for (int32_t v : {1, 1, 1, 1, 2, 3})
        elements += i32(v);
    const std::string second_block = kHead22 + nodes22() + elements;
    elements += i32(9) + i32(1) + i32(2);
    for (int32_t v : {2, 1, 1, 1, 2, 3, 1, 2, 3})
        elements += i32(v);
    const std::string binary =
        write_temp("mixed_bin.msh", kHead22 + nodes22() + elements + "\n$EndElements\n");
    EXPECT_THAT(mesh_error(binary),
                StartsWith(prefix(binary, 9) + "$Elements (binary) block at byte " +
                           std::to_string(second_block.size()) +
                           " (type 9, count 1, tags 2): 3-node and 6-node triangles (types 2 and "
                           "9) in one file"));
}

// No false alarm on what Gmsh itself writes: MSH 2.2 and 4.1, ASCII and binary, parametric nodes,
// second order; each file gives the triangles Gmsh had in memory when it wrote it.
TEST(MshPrecheck, GmshWrittenFilesOfEveryFlavourLoad) {
    struct Flavour {
        const char* name;
        double version;
        int binary, parametric, order;
    };
    const Flavour flavours[] = {{"22a", 2.2, 0, 0, 1},  {"22b", 2.2, 1, 0, 1},
                                {"41a", 4.1, 0, 0, 1},  {"41b", 4.1, 1, 0, 1},
                                {"41p", 4.1, 0, 1, 1},  {"41pb", 4.1, 1, 1, 1},
                                {"22o2", 2.2, 1, 0, 2}, {"41o2", 4.1, 1, 0, 2}};
    std::vector<std::size_t> triangles;  // per flavour, as Gmsh counts them
    const char* args[] = {"test", "-v", "0"};
    gmsh::initialize(3, const_cast<char**>(args), false);
    gmsh::option::setNumber("General.Terminal", 0);
    for (const Flavour& f : flavours) {
        gmsh::clear();
        gmsh::open(std::string(FDEM_TEST_DATA_DIR) + "/block_on_base.geo");
        gmsh::option::setNumber("Mesh.MeshSizeMax", 0.1);
        gmsh::option::setNumber("Mesh.ElementOrder", f.order);
        gmsh::model::mesh::generate(2);
        gmsh::option::setNumber("Mesh.MshFileVersion", f.version);
        gmsh::option::setNumber("Mesh.Binary", f.binary);
        gmsh::option::setNumber("Mesh.SaveParametric", f.parametric);
        gmsh::write(::testing::TempDir() + "/precheck_gmsh_" + f.name + ".msh");
        std::vector<std::size_t> tags, nodes;
        gmsh::model::mesh::getElementsByType(f.order == 1 ? 2 : 9, tags, nodes);
        triangles.push_back(tags.size());
    }
    gmsh::finalize();
    for (size_t i = 0; i < std::size(flavours); ++i) {
        const Flavour& f = flavours[i];
        const std::string path = ::testing::TempDir() + "/precheck_gmsh_" + f.name + ".msh";
        try {
            const MeshData mesh = read_mesh(path, 0);
            EXPECT_GT(triangles[i], 0u);
            EXPECT_EQ(mesh.tris.size(), triangles[i]) << f.name;
        } catch (const InputError& e) {
            ADD_FAILURE() << f.name << ": " << e.what();
        }
    }
}

// The fuzz finding (tests/fuzz/crashes/mesh/oom-257a84a...): the 9th block header of $Elements
// (byte 783, line 20 holds "$Elements") says 1 line element with -254 tags; Gmsh 4.8 computed
// the record as 1 + (-254) + 2 ints, unsigned: malloc(17179868180).
TEST(MshPrecheck, FuzzFindingNegativeTagCountInBinaryMsh22) {
    const std::string path =
        std::string(FDEM_SOURCE_DIR) +
        "/tests/fuzz/crashes/mesh/oom-257a84a246ca5b2948728817a601b6f3c6900be1";
    const std::string copy = write_temp("oom.msh", [&] {
        std::ifstream in(path, std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    }());
    const std::string w = mesh_error(copy);
    EXPECT_THAT(w, StartsWith(prefix(copy, 20) +
                              "$Elements (binary) block at byte 783 (type 1, count 1, tags -254): "
                              "the number of tags must be >= 0"));
    EXPECT_THAT(w, HasSubstr("20 | $Elements"));
}

TEST(MshPrecheck, BinaryMsh22TagCountLargerThanTheFile) {
    const std::string head = kHead22 + nodes22() + "$Elements\n1\n";
    const std::string bytes = kHead22 + nodes22() + elements22(1, 2, 1, 1000000000);
    const std::string path = write_temp("tags22.msh", bytes);
    const size_t block = head.size();
    const size_t left = bytes.size() - block - 12;
    EXPECT_EQ(mesh_error(path),
              prefix(path, 9) + "$Elements (binary) block at byte " + std::to_string(block) +
                  " (type 2, count 1, tags 1000000000): 1 element records of 4000000016 bytes "
                  "each need 4000000016 bytes; only " +
                  std::to_string(left) + " bytes are left in the file\n 9 | $Elements");
}

TEST(MshPrecheck, BinaryMsh22BlockCountBeyondTheSectionCount) {
    const std::string head = kHead22 + nodes22() + "$Elements\n1\n";
    const std::string path =
        write_temp("count22.msh", kHead22 + nodes22() + elements22(1, 2, 2000000000, 2));
    EXPECT_THAT(mesh_error(path),
                StartsWith(prefix(path, 9) + "$Elements (binary) block at byte " +
                           std::to_string(head.size()) +
                           " (type 2, count 2000000000, tags 2): the element count must be 1 to 1 "
                           "(the $Elements count 1 less the 0 elements of the blocks before)"));
}

TEST(MshPrecheck, BinaryMsh22UnknownElementType) {
    const std::string head = kHead22 + nodes22() + "$Elements\n1\n";
    const std::string path =
        write_temp("type22.msh", kHead22 + nodes22() + elements22(1, 99, 1, 2));
    EXPECT_THAT(mesh_error(path), StartsWith(prefix(path, 9) + "$Elements (binary) block at byte " +
                                             std::to_string(head.size()) +
                                             " (type 99, count 1, tags 2): unknown element type"));
}

TEST(MshPrecheck, BinaryMsh22NodeCountLargerThanTheFile) {
    std::string nodes = nodes22();
    nodes.replace(nodes.find("\n3\n"), 3, "\n2000000000\n");
    const std::string bytes = kHead22 + nodes + elements22(1, 2, 1, 2);
    const std::string path = write_temp("nodes22.msh", bytes);
    const size_t at = kHead22.size();  // "$Nodes" on line 5
    const size_t left = bytes.size() - (at + std::string("$Nodes\n2000000000\n").size());
    EXPECT_THAT(mesh_error(path),
                StartsWith(prefix(path, 5) + "$Nodes (binary) at byte " + std::to_string(at) +
                           " declares 2000000000 nodes of 28 bytes (int tag, 3 doubles), "
                           "56000000000 bytes; only " +
                           std::to_string(left) + " bytes are left in the file"));
}

// Fuzz finding (tests/fuzz/crashes/mesh/crash-9fc0a50...): $Nodes says 11 nodes (ids 1..11),
// a triangle uses node 12; Gmsh 4.8's dense-vector bound check let id 12 through and crashed
// (SEGV in GModel::_associateEntityWithMeshVertices). Binary and ASCII.
TEST(MshPrecheck, FuzzFindingMsh22ElementNodeOneBeyondTheLast) {
    std::string bytes = kHead22 + nodes22();
    const std::string head = bytes + "$Elements\n1\n";
    bytes += "$Elements\n1\n" + i32(2) + i32(1) + i32(2);
    for (int32_t v : {5, 1, 1, 1, 2, 4})
        bytes += i32(v);
    bytes += "\n$EndElements\n";
    const std::string path = write_temp("node4.msh", bytes);
    EXPECT_THAT(mesh_error(path),
                StartsWith(prefix(path, 9) + "$Elements (binary) block at byte " +
                           std::to_string(head.size()) +
                           " (type 2, count 1, tags 2): element 5 (record at byte " +
                           std::to_string(head.size() + 12) +
                           ") references node 4, which $Nodes does not define"));
    const std::string ascii =
        write_temp("node4_ascii.msh",
                   "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n"
                   "3 0 1 0\n$EndNodes\n$Elements\n1\n5 2 2 1 1 1 2 4\n$EndElements\n");
    EXPECT_EQ(mesh_error(ascii), prefix(ascii, 12) +
                                     "element 5 references node 4, which $Nodes does not define"
                                     "\n 12 | 5 2 2 1 1 1 2 4");
}

TEST(MshPrecheck, BinaryByteOrderMarkMustBeOne) {
    const std::string path =
        write_temp("bom.msh", "$MeshFormat\n2.2 1 8\n" + i32(7) + "\n$EndMeshFormat\n" + nodes22());
    EXPECT_THAT(mesh_error(path),
                StartsWith(prefix(path, 2) +
                           "the binary byte-order mark after the format line (byte 20) must be "
                           "the int 1, got 7"));
}

// ---- format and sections ----------------------------------------------------------------------
TEST(MshPrecheck, UnsupportedVersionsAndFileTypes) {
    const std::string v3 = write_temp("v3.msh", "$MeshFormat\n3.0 0 8\n$EndMeshFormat\n");
    EXPECT_EQ(mesh_error(v3), prefix(v3, 2) +
                                  "MSH version 3 is not supported; fdem reads MSH 2.2 and 4.1 "
                                  "(gmsh -format msh22 or msh41)\n 2 | 3.0 0 8");
    const std::string v40 = write_temp("v40.msh", "$MeshFormat\n4 0 8\n$EndMeshFormat\n");
    EXPECT_THAT(mesh_error(v40), HasSubstr("MSH version 4 is not supported"));
    const std::string type = write_temp("type.msh", "$MeshFormat\n4.1 2 8\n$EndMeshFormat\n");
    EXPECT_THAT(mesh_error(type),
                StartsWith(prefix(type, 2) + "file type 2; expected 0 (ASCII) or 1 (binary)"));
    const std::string size = write_temp("size.msh", "$MeshFormat\n4.1 1 4\n$EndMeshFormat\n");
    EXPECT_THAT(mesh_error(size),
                StartsWith(prefix(size, 2) + "binary data size 4; expected 8 (8-byte doubles "
                                             "and integers, as Gmsh writes on this machine)"));
    const std::string garbled = write_temp("garbled.msh", "$MeshFormat\nfour point one\n");
    EXPECT_THAT(mesh_error(garbled),
                StartsWith(prefix(garbled, 2) + "the line after $MeshFormat must be 'version "
                                                "file-type data-size', e.g. '4.1 0 8'"));
}

TEST(MshPrecheck, FirstSectionMustBeMeshFormatAndOnlyOnce) {
    const std::string first =
        write_temp("first.msh", "$Nodes\n1\n1 0 0 0\n$EndNodes\n$MeshFormat\n2.2 0 8\n");
    EXPECT_THAT(mesh_error(first),
                StartsWith(prefix(first, 1) + "the file must start with a $MeshFormat section "
                                              "(MSH 2.2 or 4.1), found '$Nodes'"));
    const std::string twice =
        write_temp("twice.msh",
                   "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$MeshFormat\n2.2 1 8\n$EndMeshFormat\n");
    EXPECT_THAT(mesh_error(twice),
                StartsWith(prefix(twice, 4) + "a second $MeshFormat section; a file holds one "
                                              "mesh"));
}

TEST(MshPrecheck, SectionsFdemDoesNotReadAreRefused) {
    for (const std::string section : {"Periodic", "NodeData", "ParametricNodes"}) {
        const std::string path =
            write_temp(section + ".msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$" + section +
                                             "\n1\n$End" + section + "\n");
        EXPECT_THAT(mesh_error(path),
                    StartsWith(prefix(path, 4) + "section '$" + section +
                               "' is not supported: fdem reads $MeshFormat, $PhysicalNames, "
                               "$Entities, $Nodes and $Elements; save the mesh without it"));
    }
    const std::string part = write_temp(
        "part.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PartitionedEntities\n2\n0\n");
    EXPECT_THAT(mesh_error(part), HasSubstr("section '$PartitionedEntities' is not supported"));
}

// Fuzz finding (tests/fuzz/crashes/mesh/crash-776e4e7...): "$PhysicalNames" entry "5 7 \"origin\""
// of an MSH 4.1 file; Gmsh 4.8 indexed its 4 per-dimension iterators with 5 (SEGV).
TEST(MshPrecheck, FuzzFindingPhysicalNameDimensionBeyond3) {
    const std::string path =
        write_temp("physdim.msh",
                   "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n2 1 \"block\"\n"
                   "5 7 \"origin\"\n$EndPhysicalNames\n");
    EXPECT_EQ(mesh_error(path), prefix(path, 7) +
                                    "$PhysicalNames entry 2 (tag 7) has dimension 5; expected 0 "
                                    "to 3\n 7 | 5 7 \"origin\"");
    const std::string v22 =
        write_temp("physdim22.msh",
                   "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n-1 7 \"origin\"\n");
    EXPECT_THAT(mesh_error(v22),
                StartsWith(prefix(v22, 6) + "$PhysicalNames entry 1 (tag 7) has dimension -1; "
                                            "expected 0 to 3"));
}

/// A copy of a committed fuzz finding with a .msh name (read_mesh wants the extension).
std::string finding(const std::string& name) {
    std::ifstream in(std::string(FDEM_SOURCE_DIR) + "/tests/fuzz/crashes/mesh/" + name,
                     std::ios::binary);
    EXPECT_TRUE(in.good()) << name;
    return write_temp(name + ".msh", std::string((std::istreambuf_iterator<char>(in)),
                                                 std::istreambuf_iterator<char>()));
}

// The committed findings themselves, each refused before Gmsh reads it (the replay test
// fuzz.replay_mesh runs them through read_mesh too). crash-95d6050: a section line "$Physic"
// followed by binary bytes; Gmsh takes the name up to the first NUL ("Physic"), skips to
// "$EndPhysicalNames" and then reads a binary $Entities whose curve 4 declares 2^41 bounding
// entities: operator new(0x80000000000) (8 TiB, 4 bytes each).
TEST(MshPrecheck, CommittedFuzzFindingsAreRefused) {
    EXPECT_THAT(mesh_error(finding("crash-776e4e71104026cfad9dd2bccec8ce6ddadfa2f2")),
                HasSubstr(":6: error: malformed mesh file '"));
    EXPECT_THAT(mesh_error(finding("crash-776e4e71104026cfad9dd2bccec8ce6ddadfa2f2")),
                HasSubstr("': $PhysicalNames entry 1 (tag 7) has dimension 5; expected 0 to 3"));
    EXPECT_THAT(mesh_error(finding("crash-9fc0a503036c9a8f1ab48b2f88338cb780ec264a")),
                HasSubstr("references node 12, which $Nodes does not define"));
    const std::string w = mesh_error(finding("crash-95d6050c31b8d2c8533057ef228ba7ac108ffa99"));
    EXPECT_THAT(w, HasSubstr(":20: error: malformed mesh file '"));
    EXPECT_THAT(w, HasSubstr("': $Entities (binary): entity 4 of dimension 1 at byte 899 declares "
                             "2199023255552 bounding-entity tags (4 bytes each); only 606 bytes "
                             "are left in the file"));
    EXPECT_THAT(mesh_error(finding("crash-d605729d127815367c52284a02eeb6f875030f04")),
                HasSubstr("element 6 of type 9 with 2 tags needs 11 fields (6 node ids), the "
                          "line has 7"));
}

// ---- ASCII MSH 4.1 ----------------------------------------------------------------------------
const std::string kHead41 = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
const std::string kEntities41 = "$Entities\n0 0 1 0\n1 0 0 0 1 1 0 1 1 0\n$EndEntities\n";
const std::string kNodes41 = "$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n";
const std::string kElements41 = "$Elements\n1 1 1 1\n2 1 2 1\n1 1 2 3\n$EndElements\n";

TEST(MshPrecheck, ValidAsciiMsh41StillLoads) {
    const std::string path = write_temp("ok41.msh", kHead41 + kEntities41 + kNodes41 + kElements41);
    EXPECT_EQ(read_mesh(path, 0).tris.size(), 1u);
}

// Gmsh allocates its node cache (16 bytes per node) from the header total before reading.
TEST(MshPrecheck, Msh41NodeTotalLargerThanTheFile) {
    std::string nodes = kNodes41;
    nodes.replace(nodes.find("1 3 1 3"), 7, "1 2000000000 1 3");
    const std::string bytes = kHead41 + kEntities41 + nodes + kElements41;
    const std::string path = write_temp("total41.msh", bytes);
    const size_t left = bytes.size() - (bytes.find("1 2000000000 1 3") + 16);
    EXPECT_THAT(mesh_error(path),
                StartsWith(prefix(path, 8) +
                           "the $Nodes header declares 2000000000 nodes of at least 2 bytes each; "
                           "only " +
                           std::to_string(left) + " bytes are left in the file"));
}

// More nodes in the blocks than the header's total: Gmsh writes past its node cache.
TEST(MshPrecheck, Msh41NodeBlockBeyondTheHeaderTotal) {
    std::string nodes = kNodes41;
    nodes.replace(nodes.find("1 3 1 3"), 7, "1 1 1 3");
    const std::string path = write_temp("block41.msh", kHead41 + kEntities41 + nodes + kElements41);
    EXPECT_THAT(mesh_error(path),
                StartsWith(prefix(path, 10) +
                           "the $Nodes block of entity 1 declares 3 nodes, more than the 1 left "
                           "of the section header's total 1"));
    std::string fewer = kNodes41;
    fewer.replace(fewer.find("1 3 1 3"), 7, "1 4 1 3");
    const std::string path2 =
        write_temp("fewer41.msh", kHead41 + kEntities41 + fewer + kElements41);
    EXPECT_THAT(mesh_error(path2),
                StartsWith(prefix(path2, 8) + "the $Nodes header declares 4 nodes, its blocks "
                                              "hold 3"));
}

// A node tag beyond the int range: Gmsh 4.8 crashed (SEGV in getMeshVertexByTag(int)).
TEST(MshPrecheck, Msh41TagsBeyondTheIntRange) {
    std::string nodes = kNodes41;
    nodes.replace(nodes.find("\n3\n0 0 0"), 3, "\n20000000000\n");
    const std::string path = write_temp("tag41.msh", kHead41 + kEntities41 + nodes + kElements41);
    EXPECT_EQ(mesh_error(path), prefix(path, 13) +
                                    "node tag 20000000000; expected 1 to 2147483647\n"
                                    " 13 | 20000000000");
    std::string elements = kElements41;
    elements.replace(elements.find("1 1 2 3"), 7, "1 1 2 -3");
    const std::string path2 =
        write_temp("elemtag41.msh", kHead41 + kEntities41 + kNodes41 + elements);
    EXPECT_THAT(mesh_error(path2),
                StartsWith(prefix(path2, 21) + "element 1 references node tag "
                                               "18446744073709551613; expected 1 to 2147483647"));
}

TEST(MshPrecheck, Msh41ElementTotalAndUnknownType) {
    std::string elements = kElements41;
    elements.replace(elements.find("1 1 1 1"), 7, "1 2000000000 1 1");
    const std::string bytes = kHead41 + kEntities41 + kNodes41 + elements;
    const std::string path = write_temp("etotal41.msh", bytes);
    const size_t left = bytes.size() - (bytes.find("1 2000000000 1 1") + 16);
    EXPECT_THAT(mesh_error(path), StartsWith(prefix(path, 18) +
                                             "the $Elements header declares 2000000000 elements "
                                             "of at least 2 bytes each; only " +
                                             std::to_string(left) + " bytes are left in the file"));
    std::string type = kElements41;
    type.replace(type.find("2 1 2 1"), 7, "2 1 77 1");
    const std::string path2 = write_temp("etype41.msh", kHead41 + kEntities41 + kNodes41 + type);
    EXPECT_THAT(mesh_error(path2),
                StartsWith(prefix(path2, 20) + "the $Elements block of entity 1 has unknown "
                                               "element type 77"));
}

// ---- binary MSH 4.1: size_t counts and tags ----------------------------------------------------
const std::string kHead41b = "$MeshFormat\n4.1 1 8\n" + i32(1) + "\n$EndMeshFormat\n";

/// One surface entity (tag 1): tag, bounding box, `phys` physical tags, no bounding curves.
std::string entities41b(uint64_t phys) {
    std::string s = "$Entities\n" + u64(0) + u64(0) + u64(1) + u64(0) + i32(1);
    for (int k = 0; k < 6; ++k)
        s += f64(k < 3 ? 0.0 : 1.0);
    s += u64(phys) + i32(1) + u64(0);
    return s + "\n$EndEntities\n";
}

std::string nodes41b(uint64_t total, uint64_t in_block, uint64_t last_tag = 3) {
    std::string s = "$Nodes\n" + u64(1) + u64(total) + u64(1) + u64(3);
    s += i32(2) + i32(1) + i32(0) + u64(in_block) + u64(1) + u64(2) + u64(last_tag);
    for (double c : {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0})
        s += f64(c);
    return s + "\n$EndNodes\n";
}

std::string elements41b(uint64_t total) {
    return "$Elements\n" + u64(1) + u64(total) + u64(1) + u64(1) + i32(2) + i32(1) + i32(2) +
           u64(1) + u64(1) + u64(1) + u64(2) + u64(3) + "\n$EndElements\n";
}

TEST(MshPrecheck, ValidBinaryMsh41StillLoads) {
    const std::string path =
        write_temp("ok41b.msh", kHead41b + entities41b(1) + nodes41b(3, 3) + elements41b(1));
    EXPECT_EQ(read_mesh(path, 0).tris.size(), 1u);
}

TEST(MshPrecheck, BinaryMsh41EntityPhysicalCountLargerThanTheFile) {
    const std::string bytes = kHead41b + entities41b(2000000000) + nodes41b(3, 3) + elements41b(1);
    const std::string path = write_temp("phys41b.msh", bytes);
    const size_t entity = kHead41b.size() + std::string("$Entities\n").size() + 32;
    const size_t left = bytes.size() - (entity + 4 + 48 + 8);
    EXPECT_THAT(
        mesh_error(path),
        StartsWith(prefix(path, 5) + "$Entities (binary): entity 1 of dimension 2 at byte " +
                   std::to_string(entity) +
                   " declares 2000000000 physical tags (4 bytes each); only " +
                   std::to_string(left) + " bytes are left in the file"));
}

TEST(MshPrecheck, BinaryMsh41NodeCountsAndTags) {
    const std::string ent = kHead41b + entities41b(1);
    const std::string head_line = std::to_string(line_at(ent, ent.size()));
    // header total larger than the file
    const std::string big = ent + nodes41b(2000000000, 3) + elements41b(1);
    const std::string p1 = write_temp("ntotal41b.msh", big);
    const size_t left = big.size() - (ent.size() + std::string("$Nodes\n").size() + 32);
    EXPECT_THAT(mesh_error(p1), StartsWith(prefix(p1, line_at(big, ent.size())) +
                                           "the $Nodes (binary) header declares 2000000000 "
                                           "nodes of at least 32 bytes each; only " +
                                           std::to_string(left) + " bytes are left in the file"));
    // block larger than the header total (Gmsh writes past its node cache)
    const std::string over = ent + nodes41b(1, 3) + elements41b(1);
    const std::string p2 = write_temp("nblock41b.msh", over);
    const size_t block = ent.size() + std::string("$Nodes\n").size() + 32;
    EXPECT_THAT(mesh_error(p2),
                StartsWith(prefix(p2, line_at(over, ent.size())) +
                           "the $Nodes (binary) block at byte " + std::to_string(block) +
                           " (entity 1) declares 3 nodes, more than the 1 left of "
                           "the section header's total 1"));
    // node tag -1 as size_t
    const std::string neg = ent + nodes41b(3, 3, static_cast<uint64_t>(-1)) + elements41b(1);
    const std::string p3 = write_temp("ntag41b.msh", neg);
    EXPECT_THAT(
        mesh_error(p3),
        StartsWith(prefix(p3, line_at(neg, ent.size())) + "the $Nodes (binary) block at byte " +
                   std::to_string(block) + " (entity 1): node tag 18446744073709551615 at byte " +
                   std::to_string(block + 20 + 16) + "; expected 1 to 2147483647"));
}

TEST(MshPrecheck, BinaryMsh41ElementTotalLargerThanTheFile) {
    const std::string before = kHead41b + entities41b(1) + nodes41b(3, 3);
    const std::string bytes = before + elements41b(2000000000);
    const std::string path = write_temp("etotal41b.msh", bytes);
    const size_t left = bytes.size() - (before.size() + std::string("$Elements\n").size() + 32);
    EXPECT_THAT(mesh_error(path), StartsWith(prefix(path, line_at(bytes, before.size())) +
                                             "the $Elements (binary) header declares 2000000000 "
                                             "elements of at least 16 bytes each; only " +
                                             std::to_string(left) + " bytes are left in the file"));
}

}  // namespace
}  // namespace fdem
