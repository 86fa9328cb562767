// Bad meshes -> InputError naming the mesh file (and the line where Gmsh or the file says it).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "fdem/error.hpp"
#include "fdem/mesh.hpp"
#include "fdem/scenario.hpp"
#include "support/input_errors.hpp"

namespace fdem {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

using support::mesh_error;
using support::write_temp;

/// A one-body scenario around a mesh file given by absolute path.
std::string scenario_error(const std::string& mesh, const std::string& extra = "") {
    const std::string text = R"([simulation]
end_time = 0.01
dt = "auto"
[[material]]
name = "rock"
density = 2700.0
youngs_modulus = 5e10
poisson_ratio = 0.25
[[body]]
name = "slab"
mesh = ")" + mesh + "\"\nmaterial = \"rock\"\n" +
                             extra;
    try {
        load_scenario_from_string(text, "mesh.toml", ".");
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no InputError for " << mesh;
    return {};
}

const char* kSquareGeo = R"(Point(1) = {0, 0, 0, 0.5}; Point(2) = {1, 0, 0, 0.5};
Point(3) = {1, 1, 0, 0.5}; Point(4) = {0, 1, 0, 0.5};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
)";

TEST(MeshErrors, MissingFile) {
    EXPECT_EQ(mesh_error("/nonexistent/block.msh"),
              "/nonexistent/block.msh: error: cannot open mesh file '/nonexistent/block.msh': "
              "No such file");
}

TEST(MeshErrors, TruncatedNodesSection) {
    const std::string path = write_temp("truncated.msh", R"($MeshFormat
4.1 0 8
$EndMeshFormat
$Nodes
1 3 1 3
2 1 0 3
1
2
xx
)");
    // Gmsh says "Could not read nodes" without a line: we point at the $Nodes header (line 4)
    // and say that the file ends there (issue #12 item 10)
    EXPECT_THAT(mesh_error(path),
                StartsWith(path + ":4: error: cannot read mesh file '" + path +
                           "': the file ends inside section $Nodes (no $EndNodes follows): it is "
                           "truncated or incomplete"));
    EXPECT_THAT(mesh_error(path), HasSubstr("(Gmsh: Could not read nodes)"));
    EXPECT_THAT(mesh_error(path), HasSubstr(" 4 | $Nodes"));
}

TEST(MeshErrors, ElementWithUndefinedNode) {
    // MSH 4.1: element 1 uses node 9, but $Nodes defines nodes 1-3
    const std::string v41 = write_temp("undefined_node41.msh", R"($MeshFormat
4.1 0 8
$EndMeshFormat
$Nodes
1 3 1 3
2 1 0 3
1
2
3
0 0 0
1 0 0
0 1 0
$EndNodes
$Elements
1 1 1 1
2 1 2 1
1 1 2 9
$EndElements
)");
    EXPECT_THAT(mesh_error(v41), StartsWith(v41 + ":14: error: cannot read mesh file '" + v41 +
                                            "': Unknown node 9 in element 1"));
    // MSH 2.2: the same mistake
    const std::string v22 = write_temp("undefined_node22.msh", R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
3
1 0 0 0
2 1 0 0
3 0 1 0
$EndNodes
$Elements
1
1 2 2 0 1 1 2 9
$EndElements
)");
    // (refused by io/msh_precheck.cpp: Gmsh 4.8's own MSH 2 check let node 4 of 3 through and
    // crashed, see MshPrecheck.FuzzFindingMsh22ElementNodeOneBeyondTheLast)
    EXPECT_THAT(mesh_error(v22), StartsWith(v22 + ":12: error: malformed mesh file '" + v22 +
                                            "': element 1 references node 9, which $Nodes does "
                                            "not define"));
}

TEST(MeshErrors, GeoSyntaxErrorCarriesGmshLine) {
    const std::string path = write_temp("syntax.geo", "Point(1) = {0, 0, 0};\nLine(1) = {1, 2;\n");
    const std::string w = mesh_error(path, 0.1);
    EXPECT_THAT(w,
                StartsWith(path + ":2: error: cannot read mesh file '" + path + "': syntax error"));
    EXPECT_THAT(w, HasSubstr(" 2 | Line(1) = {1, 2;"));
}

TEST(MeshErrors, NoTriangles) {
    const std::string path = write_temp("lines_only.geo", R"(Point(1) = {0, 0, 0, 0.1};
Point(2) = {1, 0, 0, 0.1};
Line(1) = {1, 2};
)");
    EXPECT_THAT(mesh_error(path, 0.1),
                StartsWith(path + ": error: mesh file '" + path +
                           "' contains no triangles (Gmsh element type 2); a body needs a meshed "
                           "2-D surface (define a Plane Surface in the .geo file)"));
}

TEST(MeshErrors, ThirdOrderTrianglesAreRejected) {
    // 6-node triangles are read (composite element, issue #7); higher orders are not
    const std::string path =
        write_temp("order3.geo", std::string(kSquareGeo) + "Mesh.ElementOrder = 3;\n");
    const std::string w = mesh_error(path);
    EXPECT_THAT(w, HasSubstr("(Triangle 10), which is not supported; use first- or second-order "
                             "triangles (3-node or 6-node; gmsh -order 1 or 2)"));
    EXPECT_THAT(w, HasSubstr(path));
}

TEST(MeshErrors, QuadrilateralsAreRejected) {
    const std::string path =
        write_temp("quads.geo", std::string(kSquareGeo) + "Recombine Surface{1};\n");
    EXPECT_THAT(mesh_error(path), HasSubstr("has type 3 (Quadrilateral 4), which is not "
                                            "supported; use first- or second-order triangles "
                                            "(3-node or 6-node; gmsh -order 1 or 2; for .geo "
                                            "files remove Recombine)"));
}

TEST(MeshErrors, NodeOutOfPlane) {
    const std::string path = write_temp("tilted.msh", R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
3
1 0 0 0
2 1 0 0
3 0 1 0.5
$EndNodes
$Elements
1
1 2 2 0 1 1 2 3
$EndElements
)");
    EXPECT_THAT(mesh_error(path), StartsWith(path + ":4: error: mesh file '" + path +
                                             "': node 3 has z = 0.5; fdem is 2-D"));
}

TEST(MeshErrors, DegenerateTriangleThroughScenario) {
    // triangle 2 has three collinear nodes (0,0), (1,0), (2,0)
    const std::string path = write_temp("degenerate.msh", R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
4
1 0 0 0
2 1 0 0
3 2 0 0
4 0 1 0
$EndNodes
$Elements
2
1 2 2 0 1 1 2 4
2 2 2 0 1 1 2 3
$EndElements
)");
    const std::string w = scenario_error(path);
    EXPECT_THAT(w, StartsWith(path + ": error: "));
    EXPECT_THAT(w, HasSubstr("of body \"slab\" is degenerate"));
}

TEST(MeshErrors, UnreadableMeshThroughScenario) {
    const std::string path = write_temp("garbage.msh", "$MeshFormat\nnot a mesh at all\n");
    const std::string w = scenario_error(path);
    EXPECT_THAT(w, HasSubstr(path));
    EXPECT_THAT(w, HasSubstr("error: "));
}

TEST(MeshErrors, NoTrianglesThroughScenario) {
    const std::string path = write_temp("only_line.geo",
                                        "Point(1) = {0,0,0};\nPoint(2) = "
                                        "{1,0,0};\nLine(1) = {1,2};\n");
    const std::string w = scenario_error(path, "mesh_size = 0.2\n");
    EXPECT_THAT(w, HasSubstr("contains no triangles"));
}

}  // namespace
}  // namespace fdem
