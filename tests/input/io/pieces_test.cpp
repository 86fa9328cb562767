// The per-body `pieces` key (issue #6, docs/scenario.md): a disconnected selection is an input
// error unless pieces = "separate", which makes every piece its own discrete element.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "fdem/error.hpp"
#include "fdem/scenario.hpp"
#include "support/input_errors.hpp"

namespace fdem {
namespace {

using ::testing::HasSubstr;

const std::string kData = FDEM_TEST_DATA_DIR;

// the [[body]] table starts on line 11, mesh is line 14; the group line is 16, the extra line 17
std::string scenario(const std::string& group, const std::string& extra) {
    return R"([simulation]
end_time = 0.01
dt = "auto"

[[material]]
name = "rock"
density = 2500.0
youngs_modulus = 1.0e10
poisson_ratio = 0.25

[[body]]
name = "blocks"
material = "rock"
mesh = "two_pieces.geo"
mesh_size = 0.5
)" + group +
           "\n" + extra + "\n";
}

TEST(Pieces, DisconnectedSelectionIsAnErrorByDefault) {
    const std::string msg = support::scenario_error(scenario("", ""));
    // the mesh key (line 14, column 8) is named, with the count, a node of the second piece and
    // the three remedies
    EXPECT_THAT(msg, HasSubstr("bad.toml:14:8: error: body \"blocks\": the triangles selected from "
                               "mesh '"));
    EXPECT_THAT(msg, HasSubstr("two_pieces.geo' form 2 disconnected pieces (the second one has a "
                               "node at ("));
    EXPECT_THAT(msg, HasSubstr("expected one connected piece: connect the mesh (Gmsh: Coherence "
                               "Mesh;), select one piece with 'group', or set pieces = "
                               "\"separate\""));
}

TEST(Pieces, TheGroupKeyIsNamedWhenItMadeTheSelection) {
    const std::string msg = support::scenario_error(scenario("group = \"both\"", ""));
    EXPECT_THAT(msg, HasSubstr("bad.toml:16:9: error: body \"blocks\": the triangles selected"));
}

TEST(Pieces, OneConnectedPieceIsAccepted) {
    const Scenario sc =
        load_scenario_from_string(scenario("group = \"left\"", ""), "ok.toml", kData);
    EXPECT_EQ(sc.model.num_bodies(), 1);
}

TEST(Pieces, SeparateMakesOneBodyPerPiece) {
    const Scenario sc =
        load_scenario_from_string(scenario("", "pieces = \"separate\""), "ok.toml", kData);
    ASSERT_EQ(sc.model.num_bodies(), 2);
    EXPECT_EQ(sc.model.bodies[0].name, "blocks");
    EXPECT_EQ(sc.model.bodies[1].name, "blocks");
    // the pieces do not share nodes
    EXPECT_EQ(sc.model.bodies[0].node_end, sc.model.bodies[1].node_begin);
}

TEST(Pieces, BadValueIsRejected) {
    const std::string msg = support::scenario_error(scenario("", "pieces = \"split\""));
    EXPECT_THAT(msg, HasSubstr("bad.toml:17:10: error"));
    EXPECT_THAT(msg, HasSubstr("pieces"));
    EXPECT_THAT(msg, HasSubstr("\"one\""));
    EXPECT_THAT(msg, HasSubstr("\"separate\""));
}

}  // namespace
}  // namespace fdem
