// Bad scenarios -> InputError with file:line:column, key, value and expectation (style §4.6).
// Every case edits one line of kBase, so the line numbers below can be read off kBase.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>

#include "fdem/error.hpp"
#include "fdem/scenario.hpp"
#include "support/input_errors.hpp"

namespace fdem {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

const std::string kData = FDEM_TEST_DATA_DIR;

// line numbers:  1..20
const std::string kBase = R"([simulation]
end_time = 0.01
dt = "auto"
gravity = [0.0, -9.81]

[[material]]
name = "steel"
density = 7800.0
youngs_modulus = 2.0e11
poisson_ratio = 0.3

[[body]]
name = "block"
mesh = "square_41_ascii.msh"
material = "steel"

[[boundary]]
body = "block"
group = "bottom"
fix = ["x", "y"]
)";

/// kBase with the first occurrence of `from` replaced by `to`.
std::string edit(const std::string& from, const std::string& to) {
    return support::replace_first(kBase, from, to);
}

/// The InputError thrown for text ("bad.toml", meshes from tests/data), or nullopt.
std::optional<InputError> error_of(const std::string& text) {
    try {
        load_scenario_from_string(text, "bad.toml", kData);
    } catch (const InputError& e) {
        return e;
    }
    return std::nullopt;
}

/// what() of the InputError thrown for text; a test failure if nothing is thrown.
std::string what_of(const std::string& text) {
    return support::scenario_error(text);
}

TEST(ScenarioErrors, BaseScenarioIsValid) {
    EXPECT_NO_THROW(load_scenario_from_string(kBase, "bad.toml", kData));
}

TEST(ScenarioErrors, CompleteMessageFormat) {
    // the full message: location, context, key, expectation, value, echoed line and caret
    const auto e = error_of(edit("density = 7800.0", "density = -1.0"));
    ASSERT_TRUE(e);
    EXPECT_EQ(std::string(e->what()),
              "bad.toml:8:11: error: material \"steel\": density must be > 0, got -1\n"
              " 8 | density = -1.0\n"
              "   |           ^");
    EXPECT_EQ(e->location().line, 8);
    EXPECT_EQ(e->location().column, 11);
    EXPECT_EQ(e->key(), "material[0].density");
}

TEST(ScenarioErrors, TomlSyntaxError) {
    const std::string w = what_of(edit("density = 7800.0", "density = "));
    EXPECT_THAT(w, StartsWith("bad.toml:8:"));
    EXPECT_THAT(w, HasSubstr("TOML syntax error"));
    EXPECT_THAT(w, HasSubstr("8 | density = "));
}

TEST(ScenarioErrors, UnknownTopLevelTableSuggestsTheClosest) {
    const std::string w = what_of(edit("[simulation]", "[simulaton]"));
    EXPECT_THAT(w, StartsWith("bad.toml:1:2: error: "));
    EXPECT_THAT(w, HasSubstr("unknown key 'simulaton'; did you mean 'simulation'?"));
}

TEST(ScenarioErrors, UnknownKeySuggestsTheClosest) {
    const std::string w = what_of(edit("density = 7800.0", "densty = 7800.0"));
    EXPECT_THAT(w, StartsWith("bad.toml:8:1: error: [[material]] #1: unknown key 'densty'; "
                              "did you mean 'density'?"));
}

TEST(ScenarioErrors, UnknownKeyWithoutCloseMatchListsValidKeys) {
    const std::string w = what_of(edit("gravity = [0.0, -9.81]", "colour = \"red\""));
    EXPECT_THAT(w, StartsWith("bad.toml:4:1: error: [simulation]: unknown key 'colour'; "
                              "valid keys are \"end_time\", \"dt\", \"dt_fraction\", "
                              "\"gravity\""));
}

TEST(ScenarioErrors, WrongType) {
    const std::string w = what_of(edit("youngs_modulus = 2.0e11", "youngs_modulus = \"2e11\""));
    EXPECT_THAT(w, StartsWith("bad.toml:9:18: error: material \"steel\": youngs_modulus must be "
                              "a number in Pa, > 0, got a string \"2e11\""));
}

TEST(ScenarioErrors, YoungsModulusZero) {
    const std::string w = what_of(edit("youngs_modulus = 2.0e11", "youngs_modulus = 0"));
    EXPECT_THAT(w, StartsWith("bad.toml:9:18: error: material \"steel\": youngs_modulus must be "
                              "> 0, got 0"));
}

TEST(ScenarioErrors, PoissonRatioOutOfRange) {
    const std::string w = what_of(edit("poisson_ratio = 0.3", "poisson_ratio = 0.5"));
    EXPECT_THAT(w, StartsWith("bad.toml:10:17: error: material \"steel\": poisson_ratio must be "
                              "in [0, 0.5), got 0.5"));
    const std::string neg = what_of(edit("poisson_ratio = 0.3", "poisson_ratio = -0.1"));
    EXPECT_THAT(neg, HasSubstr("poisson_ratio must be in [0, 0.5), got -0.1"));
}

TEST(ScenarioErrors, MissingRequiredKeyPointsAtTheTable) {
    const std::string w = what_of(edit("density = 7800.0", "# no density"));
    EXPECT_THAT(w, StartsWith("bad.toml:6:1: error: material \"steel\": missing required key "
                              "'density' (a number in kg/m^3, > 0)"));
    EXPECT_THAT(w, HasSubstr(" 6 | [[material]]"));
}

TEST(ScenarioErrors, MissingEndTime) {
    const std::string w = what_of(edit("end_time = 0.01", "# forever"));
    EXPECT_THAT(w, StartsWith("bad.toml:1:1: error: [simulation]: missing required key "
                              "'end_time' (a number in s, > 0)"));
}

TEST(ScenarioErrors, MissingSimulationTable) {
    const std::string w =
        what_of(edit("[simulation]\nend_time = 0.01\ndt = \"auto\"\n"
                     "gravity = [0.0, -9.81]",
                     "\n\n\n"));
    EXPECT_THAT(w, StartsWith("bad.toml: error: missing required table [simulation]"));
}

TEST(ScenarioErrors, DtNeitherNumberNorAuto) {
    const std::string w = what_of(edit("dt = \"auto\"", "dt = \"fast\""));
    EXPECT_THAT(w, StartsWith("bad.toml:3:6: error: [simulation]: dt must be a number in s "
                              "(> 0) or \"auto\", got \"fast\""));
}

TEST(ScenarioErrors, DtNegative) {
    const std::string w = what_of(edit("dt = \"auto\"", "dt = -1e-6"));
    EXPECT_THAT(w, StartsWith("bad.toml:3:6: error: [simulation]: dt must be > 0, got -1e-06"));
}

TEST(ScenarioErrors, DtAboveStableLimit) {
    const auto e = error_of(edit("dt = \"auto\"", "dt = 1.0"));
    ASSERT_TRUE(e);
    const std::string w = e->what();
    EXPECT_THAT(w, StartsWith("bad.toml:3:6: error: [simulation]: dt = 1 s exceeds the stable "
                              "limit "));
    EXPECT_THAT(w, HasSubstr("of body \"block\", material \"steel\")"));
    EXPECT_THAT(w, HasSubstr("; use dt <= "));
    EXPECT_EQ(e->key(), "simulation.dt");

    // the suggested dt is accepted: parse it back out of the message
    const size_t p = w.find("use dt <= ") + 10;
    const std::string suggested = w.substr(p, w.find(' ', p) - p);
    EXPECT_NO_THROW(
        load_scenario_from_string(edit("dt = \"auto\"", "dt = " + suggested), "ok.toml", kData))
        << suggested;
}

TEST(ScenarioErrors, DtFractionOutOfRange) {
    const std::string w =
        what_of(edit("dt = \"auto\"", "dt = \"auto\"\ndt_fraction = 1.5"));  // line 4
    EXPECT_THAT(w, StartsWith("bad.toml:4:15: error: [simulation]: dt_fraction must be in "
                              "(0, 1], got 1.5"));
}

TEST(ScenarioErrors, GravityNotAPair) {
    const std::string w = what_of(edit("gravity = [0.0, -9.81]", "gravity = [0.0, -9.81, 0.0]"));
    EXPECT_THAT(w, StartsWith("bad.toml:4:11: error: [simulation]: gravity must be [x, y], two "
                              "numbers in m/s^2, got [0, -9.81, 0]"));
}

TEST(ScenarioErrors, MaterialAsPlainTable) {
    const std::string w = what_of(edit("[[material]]", "[material]"));
    EXPECT_THAT(w, StartsWith("bad.toml:6:"));
    EXPECT_THAT(w, HasSubstr("'material' must be an array of tables: write [[material]]"));
}

TEST(ScenarioErrors, DuplicateMaterialName) {
    const std::string w = what_of(kBase + R"(
[[material]]
name = "steel"
density = 1.0
youngs_modulus = 1.0
poisson_ratio = 0.0
)");  // the second name is on line 23
    EXPECT_THAT(w, StartsWith("bad.toml:23:8: error: material \"steel\": duplicate material "
                              "name \"steel\" (first defined on line 7)"));
}

TEST(ScenarioErrors, DuplicateBodyName) {
    const std::string w = what_of(kBase + R"(
[[body]]
name = "block"
mesh = "square_22_ascii.msh"
material = "steel"
)");
    EXPECT_THAT(w, StartsWith("bad.toml:23:8: error: body \"block\": duplicate body name "
                              "\"block\" (first defined on line 13)"));
}

TEST(ScenarioErrors, UnknownMaterial) {
    const std::string w = what_of(edit("material = \"steel\"", "material = \"stel\""));
    EXPECT_THAT(w, StartsWith("bad.toml:15:12: error: body \"block\": unknown material \"stel\"; "
                              "defined materials: \"steel\"; did you mean \"steel\"?"));
}

TEST(ScenarioErrors, UnknownBodyInBoundary) {
    const std::string w = what_of(edit("body = \"block\"", "body = \"blok\""));
    EXPECT_THAT(w, StartsWith("bad.toml:18:8: error: [[boundary]] #1: unknown body \"blok\"; "
                              "defined bodies: \"block\"; did you mean \"block\"?"));
}

TEST(ScenarioErrors, UnknownPhysicalGroupListsAvailable) {
    const std::string w = what_of(edit("group = \"bottom\"", "group = \"botom\""));
    EXPECT_THAT(w, StartsWith("bad.toml:19:9: error: boundary \"botom\" of body \"block\": mesh "));
    EXPECT_THAT(w, HasSubstr("square_41_ascii.msh' has no physical group \"botom\" (did you mean "
                             "\"bottom\"?); available: \"origin\" (point), \"bottom\" (curve)"));
    EXPECT_THAT(w, HasSubstr("\"block\" (surface)"));
}

TEST(ScenarioErrors, BodyGroupMustBeASurface) {
    const std::string w =
        what_of(edit("material = \"steel\"\n", "material = \"steel\"\ngroup = \"bottom\"\n"));
    EXPECT_THAT(w, StartsWith("bad.toml:16:9: error: body \"block\": \"bottom\" is a curve "));
    EXPECT_THAT(w, HasSubstr("\"bottom\" is a curve physical group of mesh"));
    EXPECT_THAT(w, HasSubstr("expected a surface group (Physical Surface)"));
}

TEST(ScenarioErrors, GroupOnAnotherBody) {
    // block and base come from one .geo; the base's bottom curve has no node of the block
    const std::string w = what_of(kBase + R"(
[[body]]
name = "base"
mesh = "block_on_base.geo"
mesh_size = 0.1
group = "base"
material = "steel"

[[body]]
name = "top"
mesh = "block_on_base.geo"
mesh_size = 0.1
group = "block"
material = "steel"

[[boundary]]
body = "top"
group = "base_bottom"
fix = ["y"]
)");
    EXPECT_THAT(w, StartsWith("bad.toml:38:9: error: boundary \"base_bottom\" of body \"top\": "
                              "physical group \"base_bottom\" selects none of the nodes of body "
                              "\"top\""));
}

TEST(ScenarioErrors, OverlappingBodies) {
    const std::string w = what_of(kBase + R"(
[[body]]
name = "again"
mesh = "square_41_ascii.msh"
material = "steel"
)");
    EXPECT_THAT(w, StartsWith("bad.toml:24:8: error: body \"again\": triangles of mesh "));
    EXPECT_THAT(w, HasSubstr("are already used by body \"block\""));
}

TEST(ScenarioErrors, MissingMeshFile) {
    const std::string w = what_of(edit("square_41_ascii.msh", "nothere.msh"));
    EXPECT_THAT(w, StartsWith("bad.toml:14:8: error: body \"block\": cannot open mesh file '" +
                              kData + "/nothere.msh': No such file"));
}

TEST(ScenarioErrors, MeshSizeRequiredForGeo) {
    const std::string w = what_of(edit("square_41_ascii.msh", "square.geo"));
    EXPECT_THAT(w, StartsWith("bad.toml:12:1: error: body \"block\": missing required key "
                              "'mesh_size' (a number in m, > 0)"));
}

TEST(ScenarioErrors, MeshSizeRejectedForMsh) {
    const std::string w =
        what_of(edit("material = \"steel\"\n", "material = \"steel\"\nmesh_size = 0.1\n"));
    EXPECT_THAT(w, StartsWith("bad.toml:16:13: error: body \"block\": mesh_size only applies to "
                              ".geo files"));
}

TEST(ScenarioErrors, MeshWithUnsupportedExtension) {
    const std::string w = what_of(edit("square_41_ascii.msh", "square.stl"));
    EXPECT_THAT(w, StartsWith("bad.toml:14:8: error: body \"block\": mesh must be a Gmsh .msh or "
                              ".geo file, got \"square.stl\""));
}

TEST(ScenarioErrors, BadComponent) {
    const std::string w = what_of(edit("fix = [\"x\", \"y\"]", "fix = [\"x\", \"z\"]"));
    EXPECT_THAT(w, StartsWith("bad.toml:20:13: error: boundary \"bottom\" of body \"block\": fix "
                              "entries must be \"x\" or \"y\", got \"z\""));
}

TEST(ScenarioErrors, FixAndVelocityTogether) {
    const std::string w =
        what_of(edit("fix = [\"x\", \"y\"]", "fix = [\"x\"]\nvelocity = [1.0, 0.0]"));
    EXPECT_THAT(w, StartsWith("bad.toml:17:1: error: boundary \"bottom\" of body \"block\": give "
                              "exactly one of 'fix'"));
}

TEST(ScenarioErrors, BoundaryEndBeforeStart) {
    const std::string w =
        what_of(edit("fix = [\"x\", \"y\"]", "fix = [\"y\"]\nstart = 0.5\nend = 0.1"));
    EXPECT_THAT(w, StartsWith("bad.toml:22:7: error: boundary \"bottom\" of body \"block\": end "
                              "must be > start = 0.5 s, got 0.1"));
}

TEST(ScenarioErrors, ContactAlgorithmTypo) {
    const std::string w = what_of(kBase + "\n[contact]\nalgorithm = \"smoth\"\n");
    EXPECT_THAT(w, StartsWith("bad.toml:23:13: error: [contact]: algorithm must be one of "
                              "\"none\", \"smooth\", \"legacy-triangle\", \"legacy-boundary\", "
                              "got \"smoth\"; did you mean \"smooth\"?"));
}

TEST(ScenarioErrors, ContactMissingAlgorithm) {
    const std::string w = what_of(kBase + "\n[contact]\npenalty = 1e9\n");
    EXPECT_THAT(w, StartsWith("bad.toml:22:1: error: [contact]: missing required key "
                              "'algorithm'"));
}

TEST(ScenarioErrors, ContactBetaBelowAlpha) {
    const std::string w =
        what_of(kBase + "\n[contact]\nalgorithm = \"smooth\"\nalpha = 2.0\nbeta = 1.5\n");
    EXPECT_THAT(w, StartsWith("bad.toml:25:8: error: [contact]: beta must be >= alpha"));
    EXPECT_THAT(w, HasSubstr("got alpha = 2, beta = 1.5"));
}

TEST(ScenarioErrors, ContactNegativeFriction) {
    const std::string w = what_of(kBase + "\n[contact]\nalgorithm = \"smooth\"\nfriction = -0.3\n");
    EXPECT_THAT(w, StartsWith("bad.toml:24:12: error: [contact]: friction must be >= 0, got "
                              "-0.3"));
}

TEST(ScenarioErrors, ContactPairUnknownMaterial) {
    const std::string w = what_of(kBase + R"(
[contact]
algorithm = "smooth"
[[contact.pair]]
materials = ["steel", "rock"]
friction = 0.5
)");
    EXPECT_THAT(w, StartsWith("bad.toml:25:23: error: [[contact.pair]] #1: unknown material "
                              "\"rock\"; defined materials: \"steel\""));
}

TEST(ScenarioErrors, ContactPairUnknownKey) {
    const std::string w = what_of(kBase + R"(
[contact]
algorithm = "smooth"
[[contact.pair]]
materials = ["steel", "steel"]
frction = 0.5
)");
    EXPECT_THAT(w, StartsWith("bad.toml:26:1: error: [[contact.pair]] #1: unknown key 'frction'; "
                              "did you mean 'friction'?"));
}

TEST(ScenarioErrors, DampingNeedsBothKeys) {
    const std::string w = what_of(kBase + "\n[damping]\nmass_proportional = 10.0\n");
    EXPECT_THAT(w, StartsWith("bad.toml:22:1: error: [damping]: missing required key 'until' (a "
                              "number in s, >= 0)"));
}

TEST(ScenarioErrors, KickUnknownBody) {
    const std::string w =
        what_of(kBase + "\n[[kick]]\nbody = \"nobody\"\ntime = 0.1\nvelocity = [1, 0]\n");
    EXPECT_THAT(w, StartsWith("bad.toml:23:8: error: [[kick]] #1: unknown body \"nobody\""));
}

TEST(ScenarioErrors, OutputIntervalNotPositive) {
    const std::string w = what_of(kBase + "\n[output]\ninterval = 0\n");
    EXPECT_THAT(w, StartsWith("bad.toml:23:12: error: [output]: interval must be > 0, got 0"));
}

TEST(ScenarioErrors, NonFiniteNumber) {
    const std::string w = what_of(edit("density = 7800.0", "density = nan"));
    EXPECT_THAT(w, StartsWith("bad.toml:8:11: error: material \"steel\": density must be a "
                              "finite number, got nan"));
}

TEST(ScenarioErrors, MissingScenarioFile) {
    try {
        load_scenario("/nonexistent/dir/scenario.toml");
        FAIL() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "/nonexistent/dir/scenario.toml: error: cannot open scenario file "
                  "'/nonexistent/dir/scenario.toml': No such file");
    }
}

TEST(ScenarioErrors, CliExitsWithCode2) {
    const std::string dir = ::testing::TempDir();
    const std::string path = dir + "/cli_bad.toml";
    std::ofstream(path) << edit("poisson_ratio = 0.3", "poisson_ratio = 0.7");
    const std::string err = dir + "/cli_bad.err";
    const std::string cmd =
        std::string(FDEM_CLI_PATH) + " check " + path + " > /dev/null 2> " + err;
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2);
    std::ifstream in(err);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_THAT(text, HasSubstr(path + ":10:17: error: material \"steel\": poisson_ratio must be "
                                       "in [0, 0.5), got 0.7"));
}

}  // namespace
}  // namespace fdem
