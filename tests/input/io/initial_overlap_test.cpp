// Bodies overlapping at t = 0 (issue #12 item 6, docs/theory.md §6.14): refused at load with
// both bodies, a point, its position and depth and the remedy, unless [contact]
// initial_overlap = "allow"; bodies that only touch load; bodies with fracture count as welded.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "fdem/error.hpp"
#include "fdem/scenario.hpp"
#include "support/input_errors.hpp"

namespace fdem {
namespace {

using ::testing::HasSubstr;
using ::testing::MatchesRegex;
using ::testing::StartsWith;

// two meshes of the unit square (written by Gmsh from the same square.geo, MSH 2.2 and 4.1)
// occupying the same region; the second [[body]] is on line 13
std::string scenario(const std::string& contact_extra) {
    return R"([simulation]
end_time = 0.001
dt = "auto"
[[material]]
name = "rock"
density = 2700.0
youngs_modulus = 5e10
poisson_ratio = 0.25
[[body]]
name = "first"
mesh = "square_22_ascii.msh"
material = "rock"
[[body]]
name = "second"
mesh = "square_41_ascii.msh"
material = "rock"
[contact]
algorithm = "smooth"
)" + contact_extra;
}

TEST(InitialOverlap, CoincidentMeshesAreRefusedNamingBothBodies) {
    const std::string w = support::scenario_error(scenario(""));
    EXPECT_THAT(w, StartsWith("bad.toml:9:1: error: bodies 0 \"first\" and 1 \"second\" overlap at "
                              "t = 0: the centroid of boundary element "));
    EXPECT_THAT(
        w, MatchesRegex("(.|\n)*overlap at t = 0: the centroid of boundary element [0-9]+ \\(node "
                        "[0-9]+\\) of body 0 at \\([0-9.e+-]+, [0-9.e+-]+\\) m lies [0-9.e+-]+ m "
                        "inside body 1 \\(touching counts up to [0-9.e+-]+ m = 1e-6 x the smallest "
                        "element altitude\\); the contact penalty would push them apart at once "
                        "with energy that is not in the balance. Move the meshes apart, or set "
                        "\\[contact\\] initial_overlap = \"allow\" if the prestress is "
                        "intended(.|\n)*"));
}

TEST(InitialOverlap, AllowLetsAPrestressThrough) {
    const Scenario sc = load_scenario_from_string(scenario("initial_overlap = \"allow\"\n"),
                                                  "ok.toml", FDEM_TEST_DATA_DIR);
    EXPECT_TRUE(sc.model.contact.allow_initial_overlap);
    const std::string w = support::scenario_error(scenario("initial_overlap = \"alow\"\n"));
    EXPECT_THAT(w, StartsWith("bad.toml:19:19: error: [contact]: initial_overlap must be one of "
                              "\"error\", \"allow\", got \"alow\""));
}

// block_on_base.geo: the block 0.01 m above the base loads; nothing is checked with contact off
TEST(InitialOverlap, SeparateBodiesLoad) {
    const std::string text = R"([simulation]
end_time = 0.001
dt = "auto"
[[material]]
name = "rubber"
density = 1000.0
youngs_modulus = 1e7
poisson_ratio = 0.2
[[body]]
name = "base"
mesh = "block_on_base.geo"
mesh_size = 0.1
group = "base"
material = "rubber"
fixed = true
[[body]]
name = "block"
mesh = "block_on_base.geo"
mesh_size = 0.1
group = "block"
material = "rubber"
[contact]
algorithm = "smooth"
)";
    const Scenario sc = load_scenario_from_string(text, "ok.toml", FDEM_TEST_DATA_DIR);
    EXPECT_EQ(sc.model.num_bodies(), 2);
    const std::string off = scenario("");
    EXPECT_NO_THROW(load_scenario_from_string(
        off.substr(0, off.find("algorithm = ")) + "algorithm = \"none\"\n", "ok.toml",
        FDEM_TEST_DATA_DIR));
}

// A body with fracture (every internal edge a joint) is welded over its intact joints at t = 0:
// the depth of a point inside it is measured to its outer boundary. punch.geo's tip lies 0.1 m
// inside square.geo's square between its boundary nodes, and no point of the square lies inside
// the wedge; measured against every joint face (before 2026-12-03) the check reported another
// point of the wedge 0.0226 m deep (the distance to the nearest joint face).
TEST(InitialOverlap, DepthInsideABodyWithFractureIsToItsOuterBoundary) {
    const std::string text = R"([simulation]
end_time = 0.001
dt = "auto"
[[material]]
name = "rock"
density = 2700.0
youngs_modulus = 5e10
poisson_ratio = 0.25
[material.fracture]
tensile_strength = 1e7
cohesion = 3e7
friction_angle = 30.0
fracture_energy_I = 50.0
fracture_energy_II = 250.0
penalty = "auto"
[[material]]
name = "steel"
density = 7800.0
youngs_modulus = 2e11
poisson_ratio = 0.3
[[body]]
name = "square"
mesh = "square.geo"
mesh_size = 0.1
group = "block"
material = "rock"
[[body]]
name = "punch"
mesh = "punch.geo"
mesh_size = 0.05
group = "punch"
material = "steel"
[contact]
algorithm = "smooth"
)";
    const std::string w = support::scenario_error(text);
    EXPECT_THAT(w,
                MatchesRegex("bad.toml:27:1: error: bodies 1 \"punch\" and 0 \"square\" overlap at "
                             "t = 0: node [0-9]+ of body 1 at \\(0.3, 0.9\\) m lies 0.1 m inside "
                             "body 0 (.|\n)*"));
}

}  // namespace
}  // namespace fdem
