// [[probe]] entries (docs/scenario.md): resolved at load; bad ones -> InputError with
// file:line:column, key, value and what was expected.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "fdem/scenario.hpp"
#include "support/input_errors.hpp"

namespace fdem {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using support::scenario_error;

// lines 1..15; a [[probe]] appended starts on line 16
const std::string kBase = R"([simulation]
end_time = 0.01
dt = "auto"

[[material]]
name = "steel"
density = 7800.0
youngs_modulus = 2.0e11
poisson_ratio = 0.3

[[body]]
name = "block"
mesh = "square_41_ascii.msh"
material = "steel"

)";

TEST(ProbeInput, ResolvesNodeGroupAndBodyProbes) {
    const Scenario sc = load_scenario_from_string(kBase + R"([[probe]]
name = "corner"
position = [0.01, -0.01]
[[probe]]
name = "top"
body = "block"
group = "top"
[[probe]]
name = "all"
body = "block"
)",
                                                  "ok.toml", FDEM_TEST_DATA_DIR);
    const auto& p = sc.run.output.probes;
    ASSERT_EQ(p.size(), 3u);
    EXPECT_EQ(p[0].kind, ProbeSpec::Kind::Node);
    ASSERT_EQ(p[0].nodes.size(), 1u);
    const Model& m = sc.model;
    // the square's corner (0, 0) is the node nearest to (0.01, -0.01)
    EXPECT_EQ(m.node_x0[p[0].nodes[0]].x, 0.0);
    EXPECT_EQ(m.node_x0[p[0].nodes[0]].y, 0.0);
    EXPECT_EQ(p[1].kind, ProbeSpec::Kind::Group);
    EXPECT_GT(p[1].nodes.size(), 1u);
    EXPECT_FALSE(p[1].tris.empty());
    EXPECT_EQ(p[2].kind, ProbeSpec::Kind::Body);
    EXPECT_EQ(static_cast<int>(p[2].nodes.size()), m.num_nodes());
    EXPECT_EQ(static_cast<int>(p[2].tris.size()), m.num_tris());
}

TEST(ProbeInput, DuplicateName) {
    EXPECT_EQ(scenario_error(kBase + "[[probe]]\nname = \"a\"\nbody = \"block\"\n"
                                     "[[probe]]\nname = \"a\"\nbody = \"block\"\n"),
              "bad.toml:20:8: error: probe \"a\": duplicate probe name \"a\" (first defined on "
              "line 17)\n 20 | name = \"a\"\n    |        ^");
}

TEST(ProbeInput, PositionAndGroupTogether) {
    EXPECT_THAT(scenario_error(kBase + "[[probe]]\nname = \"a\"\nbody = \"block\"\n"
                                       "position = [0, 0]\ngroup = \"top\"\n"),
                HasSubstr("bad.toml:20:9: error: probe \"a\": give either 'position' (the "
                          "nearest node) or 'group' (a physical group of the body's mesh), not "
                          "both"));
}

TEST(ProbeInput, NothingToProbe) {
    EXPECT_THAT(scenario_error(kBase + "[[probe]]\nname = \"a\"\n"),
                HasSubstr("bad.toml:16:1: error: probe \"a\": give 'position' = [x, y] in m "
                          "(the nearest node), 'body' (a whole body entry) or 'body' and 'group' "
                          "(a physical group of its mesh)"));
}

TEST(ProbeInput, GroupWithoutBody) {
    EXPECT_THAT(scenario_error(kBase + "[[probe]]\nname = \"a\"\ngroup = \"top\"\n"),
                HasSubstr("bad.toml:18:9: error: probe \"a\": 'group' needs 'body': the [[body]] "
                          "whose mesh has the group"));
}

TEST(ProbeInput, UnknownGroupAndBody) {
    EXPECT_THAT(scenario_error(kBase + "[[probe]]\nname = \"a\"\nbody = \"block\"\n"
                                       "group = \"tpo\"\n"),
                AllOf(HasSubstr("bad.toml:19:9: error: probe \"a\": mesh '"),
                      HasSubstr("square_41_ascii.msh' has no physical group \"tpo\" (did you "
                                "mean \"top\"?); available: ")));
    EXPECT_THAT(scenario_error(kBase + "[[probe]]\nname = \"a\"\nbody = \"blok\"\n"),
                HasSubstr("unknown body \"blok\"; defined bodies: \"block\"; did you mean "
                          "\"block\"?"));
}

TEST(ProbeInput, BadPositionAndUnknownKey) {
    EXPECT_THAT(scenario_error(kBase + "[[probe]]\nname = \"a\"\nposition = [0, nan]\n"),
                HasSubstr("bad.toml:18:"));
    EXPECT_THAT(scenario_error(kBase + "[[probe]]\nname = \"a\"\nbody = \"block\"\nnode = 3\n"),
                HasSubstr("bad.toml:19:1: error: "));
}

}  // namespace
}  // namespace fdem
