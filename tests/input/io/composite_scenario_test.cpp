// The per-body `element` key (issue #7, docs/scenario.md): accepted combinations with the mesh
// order, and the pinned messages of the rejected ones (file:line:column, key, value, expected).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "fdem/error.hpp"
#include "fdem/mesh.hpp"
#include "fdem/scenario.hpp"
#include "support/input_errors.hpp"

namespace fdem {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

const std::string kData = FDEM_TEST_DATA_DIR;

// line numbers: the [[body]] table starts on line 11, the element key (when given) is line 15
std::string scenario(const std::string& mesh, const std::string& element_line) {
    return R"([simulation]
end_time = 0.01
dt = "auto"

[[material]]
name = "rock"
density = 2500.0
youngs_modulus = 1.0e10
poisson_ratio = 0.45

[[body]]
name = "block"
material = "rock"
)" + mesh + "\n" +
           element_line + "\n";
}

const Body& only_body(const Scenario& sc) {
    EXPECT_EQ(sc.model.num_bodies(), 1);
    return sc.model.bodies.at(0);
}

TEST(CompositeScenario, ElementOmittedIsTakenFromTheMesh) {
    const Scenario a = load_scenario_from_string(scenario("mesh = \"square_order2_22.msh\"", ""),
                                                 "ok.toml", kData);
    EXPECT_EQ(only_body(a).element, ElementKind::Composite6);
    EXPECT_EQ(a.model.num_tris() % 4, 0);
    const Scenario b =
        load_scenario_from_string(scenario("mesh = \"square_22_ascii.msh\"", ""), "ok.toml", kData);
    EXPECT_EQ(only_body(b).element, ElementKind::Cst);
    // a .geo without the key is meshed at order 1: CST
    const Scenario c = load_scenario_from_string(
        scenario("mesh = \"square.geo\"\nmesh_size = 0.25", ""), "ok.toml", kData);
    EXPECT_EQ(only_body(c).element, ElementKind::Cst);
}

TEST(CompositeScenario, CompositeMeshesGeoAtOrderTwo) {
    const Scenario c = load_scenario_from_string(
        scenario("mesh = \"square.geo\"\nmesh_size = 0.25", "element = \"composite\""), "ok.toml",
        kData);
    const Scenario l = load_scenario_from_string(
        scenario("mesh = \"square.geo\"\nmesh_size = 0.25", "element = \"cst\""), "ok.toml", kData);
    EXPECT_EQ(only_body(c).element, ElementKind::Composite6);
    EXPECT_EQ(only_body(l).element, ElementKind::Cst);
    EXPECT_EQ(c.model.num_tris(), 4 * l.model.num_tris());  // same corner mesh, 4 sub-triangles
}

TEST(CompositeScenario, CstOnSixNodeMeshSplitsEachIntoFourTriangles) {
    const Scenario c = load_scenario_from_string(
        scenario("mesh = \"square_order2_22.msh\"", "element = \"composite\""), "ok.toml", kData);
    const Scenario l = load_scenario_from_string(
        scenario("mesh = \"square_order2_22.msh\"", "element = \"cst\""), "ok.toml", kData);
    EXPECT_EQ(only_body(l).element, ElementKind::Cst);
    EXPECT_EQ(l.model.tri_nodes, c.model.tri_nodes);
}

TEST(CompositeScenario, CompositeOnThreeNodeMshIsRejected) {
    const std::string w = support::scenario_error(
        scenario("mesh = \"square_22_ascii.msh\"", "element = \"composite\""));
    EXPECT_THAT(w, StartsWith("bad.toml:15:11: error: body \"block\": element = \"composite\" "
                              "needs 6-node triangles (Gmsh type 9), but mesh '" +
                              kData +
                              "/square_22_ascii.msh' has 3-node triangles; expected a "
                              "second-order mesh (gmsh -2 -order 2, or a .geo file, which is "
                              "then meshed at order 2) or element = \"cst\""));
    EXPECT_THAT(w, HasSubstr("15 | element = \"composite\""));
}

TEST(CompositeScenario, UnknownElementIsRejected) {
    const std::string w =
        support::scenario_error(scenario("mesh = \"square_22_ascii.msh\"", "element = \"cts\""));
    EXPECT_THAT(w, StartsWith("bad.toml:15:11: error: body \"block\": element must be one of "
                              "\"cst\", \"composite\", got \"cts\"; did you mean \"cst\"?"));
}

TEST(CompositeScenario, ElementMustBeAString) {
    const std::string w =
        support::scenario_error(scenario("mesh = \"square_22_ascii.msh\"", "element = 6"));
    EXPECT_THAT(w, StartsWith("bad.toml:15:11: error: body \"block\": element must be one of "
                              "\"cst\", \"composite\", got a number 6"));
}

std::string mesh_error(const std::string& name, const std::string& text) {
    return support::mesh_error(support::write_temp(name, text));
}

// unit square as one 3-node and one 6-node triangle in two elementary entities (MSH 2.2;
// $Elements on line 16). Gmsh 4.8 itself drops elements of a second order from a shared
// entity, so the two orders sit in entities 1 and 2.
//   4 --7-- 3
//   |     / |
//   8   6   5      element 2: (1, 2, 3) as a 6-node triangle with mid nodes 9, 5, 6
//   | /     |      element 1: (1, 3, 4) as a 3-node triangle
//   1 --9-- 2
constexpr const char* kMixedMsh = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
9
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
5 1 0.5 0
6 0.5 0.5 0
7 0.5 1 0
8 0 0.5 0
9 0.5 0 0
$EndNodes
$Elements
2
1 2 2 1 1 1 3 4
2 9 2 1 2 1 2 3 9 5 6
$EndElements
)";

TEST(CompositeMesh, MixedTriangleOrdersAreRejected) {
    const std::string w = mesh_error("mixed_order.msh", kMixedMsh);
    // MSH 2 files are refused by the pre-check (io/msh_precheck.cpp) at the first element of
    // the other order, before Gmsh reads them (Gmsh drops triangles when the orders share an
    // entity); the reader's own check (gmsh_reader.cpp) remains for MSH 4.1
    EXPECT_THAT(w, HasSubstr("mixed_order.msh:19: error: malformed mesh file '"));
    EXPECT_THAT(w, HasSubstr("element 2 is a 6-node triangle, but earlier elements are 3-node "
                             "triangles; a mesh must be entirely first or second order (gmsh "
                             "-order 1 or -order 2)"));
}

TEST(CompositeMesh, FirstOrderLinesOnSecondOrderTrianglesAreRejected) {
    // one 6-node triangle and a 2-node line on its bottom edge
    const std::string text = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
6
1 0 0 0
2 1 0 0
3 0 1 0
4 0.5 0 0
5 0.5 0.5 0
6 0 0.5 0
$EndNodes
$Elements
2
1 1 2 2 1 1 2
2 9 2 1 1 1 2 3 4 5 6
$EndElements
)";
    const std::string w = mesh_error("line_order.msh", text);
    EXPECT_THAT(w, HasSubstr("line_order.msh:13: error: mesh file '"));
    EXPECT_THAT(w, HasSubstr("has 6-node triangles but 2-node lines (type 1); lines must have "
                             "the order of the triangles (gmsh -order 2)"));
}

}  // namespace
}  // namespace fdem
