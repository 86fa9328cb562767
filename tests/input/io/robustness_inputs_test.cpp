// Input-validation completeness (robustness review): empty and header-only meshes, duplicate
// nodes, disconnected bodies (allowed: one body per component), typos in [checks] and
// [simulation] with "did you mean". Every error is an InputError (the CLI exits with code 2,
// ScenarioErrors.CliExitsWithCode2) with a pinned message.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "fdem/error.hpp"
#include "fdem/scenario.hpp"
#include "support/input_errors.hpp"

namespace fdem {
namespace {

using ::testing::HasSubstr;

std::string write_temp(const std::string& name, const std::string& text) {
    return support::write_temp("robust_" + name, text);
}

/// A one-body scenario around mesh (absolute path), plus extra TOML.
std::string scenario(const std::string& mesh, const std::string& extra = "") {
    return R"([simulation]
end_time = 0.01
dt = "auto"
[[material]]
name = "rock"
density = 2700.0
youngs_modulus = 5e10
poisson_ratio = 0.25
[[body]]
name = "slab"
mesh = ")" +
           mesh + "\"\nmaterial = \"rock\"\n" + extra;
}

std::string error_of(const std::string& text) {
    return support::scenario_error(text, ".");
}

// MSH 2.2 with the given nodes ("id x y z" lines) and triangles ("n1 n2 n3" lines)
std::string msh22(const std::vector<std::string>& nodes, const std::vector<std::string>& tris) {
    std::string s =
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" + std::to_string(nodes.size()) + "\n";
    for (const auto& n : nodes)
        s += n + "\n";
    s += "$EndNodes\n$Elements\n" + std::to_string(tris.size()) + "\n";
    for (size_t i = 0; i < tris.size(); ++i) {
        s += std::to_string(i + 1) + " 2 2 1 1 " + tris[i] + "\n";
    }
    return s + "$EndElements\n";
}

TEST(RobustInputs, EmptyMeshFile) {
    const std::string mesh = write_temp("empty.msh", "");
    EXPECT_EQ(error_of(scenario(mesh)),
              mesh + ": error: mesh file '" + mesh +
                  "' contains no triangles (Gmsh element type 2); a body needs a meshed 2-D "
                  "surface");
}

TEST(RobustInputs, HeaderOnlyMesh) {
    const std::string mesh =
        write_temp("header_only.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
    EXPECT_THAT(error_of(scenario(mesh)), HasSubstr("contains no triangles (Gmsh element type 2)"));
}

TEST(RobustInputs, DuplicateNodesInOneBody) {
    // nodes 2 and 4 coincide; the triangles share node 3 only: one body with a hidden crack
    const std::string mesh = write_temp(
        "dup.msh",
        msh22({"1 0 0 0", "2 1 0 0", "3 0 1 0", "4 1 0 0", "5 1 1 0"}, {"1 2 3", "4 5 3"}));
    EXPECT_THAT(error_of(scenario(mesh)),
                HasSubstr("bad.toml:11:8: error: body \"slab\": mesh '" + mesh +
                          "' has two distinct nodes at the same position (1, 0) in one body "
                          "(nodes #2 and #4 in file order): the elements around them are not "
                          "connected, a hidden crack; merge duplicate nodes (Gmsh: Coherence "
                          "Mesh;)"));
}

// Triangle 2 (nodes 2, 3, 4) lies on the same side of the shared edge 2-3 as triangle 1: it is
// inverted relative to its neighbour and the mesh folds over itself (reorienting each triangle
// counter-clockwise on its own would hide this).
TEST(RobustInputs, InvertedTriangleFoldsTheMesh) {
    const std::string mesh = write_temp(
        "fold.msh", msh22({"1 0 0 0", "2 1 0 0", "3 0 1 0", "4 0.2 0.2 0"}, {"1 2 3", "2 3 4"}));
    const std::string w = error_of(scenario(mesh));
    EXPECT_THAT(w, ::testing::StartsWith(mesh + ": error: "));
    EXPECT_THAT(w, HasSubstr("triangles 1 and 2 of body \"slab\" overlap: they share the edge of "
                             "nodes 2 and 3 and lie on the same side of it, so one of them is "
                             "inverted (the mesh folds over itself); fix the node positions or "
                             "remesh (e.g. with gmsh)"));
}

// A body entry whose triangles form two pieces is an error by default (tests/input/io/
// pieces_test.cpp); with pieces = "separate" each connected component becomes its own body
// (docs/scenario.md [[body]]). Coincident nodes of different bodies are allowed (bodies touching
// at t = 0).
TEST(RobustInputs, DisconnectedBodyBecomesOneBodyPerComponent) {
    const std::string mesh = write_temp(
        "split.msh", msh22({"1 0 0 0", "2 1 0 0", "3 0 1 0", "4 1 0 0", "5 2 0 0", "6 1 1 0"},
                           {"1 2 3", "4 5 6"}));
    EXPECT_THAT(error_of(scenario(mesh)), HasSubstr("form 2 disconnected pieces"));
    const Scenario sc =
        load_scenario_from_string(scenario(mesh, "pieces = \"separate\"\n"), "ok.toml", ".");
    ASSERT_EQ(sc.model.num_bodies(), 2);
    EXPECT_EQ(sc.model.bodies[0].name, "slab");
    EXPECT_EQ(sc.model.bodies[1].name, "slab");
    EXPECT_EQ(sc.model.bodies[0].group, sc.model.bodies[1].group);
    EXPECT_EQ(sc.model.num_nodes(), 6);
}

TEST(RobustInputs, MeshOfLinesOnly) {
    const std::string mesh =
        write_temp("lines.msh",
                   "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n2 1 0 0\n$EndNodes\n"
                   "$Elements\n1\n1 1 2 1 1 1 2\n$EndElements\n");
    EXPECT_THAT(error_of(scenario(mesh)), HasSubstr("contains no triangles (Gmsh element type 2)"));
}

// Fuzz finding (tests/fuzz/crashes/mesh/crash-d605...): Gmsh 4.8 crashed (SEGV) on an MSH 2
// element line with fewer node ids than its type needs; io/msh_precheck.cpp now refuses it.
TEST(RobustInputs, ElementLineShorterThanItsTypeDoesNotCrashGmsh) {
    const std::string mesh =
        write_temp("short_element.msh",
                   "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
                   "$EndNodes\n$Elements\n2\n1 9 2 3 2 1 2\n2 2 2 1 1 1 2 3\n$EndElements\n");
    EXPECT_THAT(error_of(scenario(mesh)),
                HasSubstr(mesh + ":12: error: malformed mesh file '" + mesh +
                          "': element 1 of type 9 with 2 tags needs 11 fields (6 node ids), the "
                          "line has 7"));
    const std::string unknown = write_temp(
        "unknown_type.msh",
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n$Elements\n1\n"
        "1 99 0 1\n$EndElements\n");
    EXPECT_THAT(error_of(scenario(unknown)), HasSubstr("element 1 has unknown element type 99"));
    const std::string count =
        write_temp("bad_count.msh",
                   "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Elements\n5\n1 15 0 1\n$EndElements\n");
    EXPECT_THAT(error_of(scenario(count)),
                HasSubstr(":5: error: malformed mesh file '" + count +
                          "': the $Elements count must be the number of element lines that "
                          "follow"));
}

TEST(RobustInputs, ChecksUnknownKeySuggestsTheClosest) {
    const std::string mesh = std::string(FDEM_TEST_DATA_DIR) + "/square_41_ascii.msh";
    EXPECT_THAT(error_of(scenario(mesh, "[checks]\nenergy_tolerence = 0.2\n")),
                HasSubstr("bad.toml:14:1: error: [checks]: unknown key 'energy_tolerence'; did "
                          "you mean 'energy_tolerance'?"));
}

TEST(RobustInputs, ChecksPenetrationChoiceTypo) {
    const std::string mesh = std::string(FDEM_TEST_DATA_DIR) + "/square_41_ascii.msh";
    EXPECT_THAT(error_of(scenario(mesh, "[checks]\npenetration = \"fial\"\n")),
                HasSubstr("did you mean \"fail\"?"));
}

TEST(RobustInputs, ChecksNegativeTolerance) {
    const std::string mesh = std::string(FDEM_TEST_DATA_DIR) + "/square_41_ascii.msh";
    EXPECT_THAT(error_of(scenario(mesh, "[checks]\nenergy_tolerance = -0.1\n")),
                HasSubstr("bad.toml:14:20: error: [checks]: energy_tolerance must be >= 0"));
}

TEST(RobustInputs, ChecksAsArrayOfTables) {
    const std::string mesh = std::string(FDEM_TEST_DATA_DIR) + "/square_41_ascii.msh";
    EXPECT_THAT(error_of(scenario(mesh, "[[checks]]\nenergy_tolerance = 0.1\n")),
                HasSubstr("'checks' must be a table (write [checks] on its own line)"));
}

TEST(RobustInputs, SimulationUnknownKeySuggestsTheClosest) {
    const std::string mesh = std::string(FDEM_TEST_DATA_DIR) + "/square_41_ascii.msh";
    std::string text = scenario(mesh);
    text.replace(text.find("end_time"), 8, "end_tme");
    EXPECT_THAT(error_of(text), HasSubstr("unknown key 'end_tme'; did you mean 'end_time'?"));
}

}  // namespace
}  // namespace fdem
