// Bad [[load]] entries and initial-velocity keys of [[body]] (docs/scenario.md): each is an
// InputError at the offending key with file:line:column, the value and what was expected.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "support/input_errors.hpp"

namespace fdem {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;
using support::scenario_error;

// Lines 1-16 fixed; `body_extra` goes on line 17, the [[load]] keys from line 19 on.
std::string with_load(const std::string& load, const std::string& body_extra = "") {
    return R"([simulation]
end_time = 0.01
dt = "auto"
[[material]]
name = "m"
density = 1000.0
youngs_modulus = 1e9
poisson_ratio = 0.25
[[body]]
name = "bar"
mesh = "loaded_bar.geo"
mesh_size = 0.05
material = "m"
[[body]]
name = "disk"
mesh = "disk.geo"
)" + body_extra + R"(
mesh_size = 0.05
material = "m"
)" + load;
}

std::string load_on(const std::string& group, const std::string& keys) {
    return "[[load]]\nbody = \"bar\"\ngroup = \"" + group + "\"\n" + keys + "\n";
}

TEST(LoadErrors, UnknownGroupSuggestsTheClosest) {
    const std::string w = scenario_error(with_load(load_on("rigth", "pressure = 1e5")));
    EXPECT_THAT(w, StartsWith("bad.toml:22:9: error: load on \"rigth\" of body \"bar\": mesh '"));
    EXPECT_THAT(w, HasSubstr("has no physical group \"rigth\" (did you mean \"right\"?)"));
}

TEST(LoadErrors, InteriorCurveIsNotOnTheBoundary) {
    const std::string w = scenario_error(with_load(load_on("middle", "traction = [1e5, 0]")));
    EXPECT_THAT(w, StartsWith("bad.toml:22:9: error: load on \"middle\" of body \"bar\": the edge "
                              "from (0.5, "));
    EXPECT_THAT(w, HasSubstr("is inside (shared by two triangles) of body \"bar\", not on its "
                             "boundary; a traction or pressure needs a curve on the body's "
                             "outline"));
}

TEST(LoadErrors, PressureOnAPointGroupNeedsACurve) {
    const std::string w = scenario_error(with_load(load_on("tip", "pressure = 1e5")));
    EXPECT_THAT(w, StartsWith("bad.toml:22:9: error: load on \"tip\" of body \"bar\": pressure "
                              "acts on boundary edges, but physical group \"tip\" of mesh '"));
    EXPECT_THAT(w, HasSubstr("is not a curve group (its line elements are the loaded edges); use "
                             "a Physical Curve, or 'force' for a point group"));
}

TEST(LoadErrors, ExactlyOneOfTractionPressureForce) {
    const std::string w =
        scenario_error(with_load(load_on("right", "pressure = 1e5\ntraction = [1, 0]")));
    EXPECT_THAT(w, StartsWith("bad.toml:20:1: error: load on \"right\" of body \"bar\": give "
                              "exactly one of 'traction'"));
    const std::string none = scenario_error(with_load(load_on("right", "")));
    EXPECT_THAT(none, StartsWith("bad.toml:20:1: error: load on \"right\" of body \"bar\": give "
                                 "exactly one of 'traction'"));
}

TEST(LoadErrors, NonMonotoneTableNamesTheEntry) {
    const std::string w = scenario_error(with_load(load_on(
        "right",
        "pressure = 1e5\ntime_function = \"table\"\ntable = [[0, 0], [0.02, 1], [0.01, 1]]")));
    EXPECT_THAT(w, StartsWith("bad.toml:25:29: error: load on \"right\" of body \"bar\": table "
                              "times must be strictly increasing, but entry 3 has t = 0.01 s "
                              "after t = 0.02 s"));
}

TEST(LoadErrors, TableEntryMustBeAPair) {
    const std::string w = scenario_error(with_load(
        load_on("right", "pressure = 1e5\ntime_function = \"table\"\ntable = [[0, 0], [1]]")));
    EXPECT_THAT(w, StartsWith("bad.toml:25:18: error: load on \"right\" of body \"bar\": table "
                              "entry 2 must be [time in s, factor], got [1]"));
}

TEST(LoadErrors, TableMissing) {
    const std::string w =
        scenario_error(with_load(load_on("right", "pressure = 1e5\ntime_function = \"table\"")));
    EXPECT_THAT(w, StartsWith("bad.toml:20:1: error: load on \"right\" of body \"bar\": missing "
                              "required key 'table' (a list of [time in s, factor] pairs"));
}

TEST(LoadErrors, RampTimeWithoutRamp) {
    const std::string w = scenario_error(with_load(load_on("right", "pressure = 1e5\nramp_time = 1")));
    EXPECT_THAT(w, StartsWith("bad.toml:24:13: error: load on \"right\" of body \"bar\": "
                              "ramp_time only applies with time_function = \"ramp\" (here "
                              "\"constant\")"));
}

TEST(LoadErrors, RampNeedsAPositiveTime) {
    const std::string w = scenario_error(with_load(
        load_on("right", "pressure = 1e5\ntime_function = \"ramp\"\nramp_time = 0")));
    EXPECT_THAT(w, StartsWith("bad.toml:25:13: error: load on \"right\" of body \"bar\": "
                              "ramp_time must be > 0"));
}

TEST(LoadErrors, UnknownTimeFunction) {
    const std::string w = scenario_error(
        with_load(load_on("right", "pressure = 1e5\ntime_function = \"rampe\"")));
    EXPECT_THAT(w, StartsWith("bad.toml:24:17: error: load on \"right\" of body \"bar\": "
                              "time_function must be one of"));
    EXPECT_THAT(w, HasSubstr("did you mean \"ramp\"?"));
}

TEST(LoadErrors, UnknownBody) {
    const std::string w = scenario_error(
        with_load("[[load]]\nbody = \"barr\"\ngroup = \"right\"\npressure = 1e5\n"));
    EXPECT_THAT(w, StartsWith("bad.toml:21:8: error: [[load]] #1: unknown body \"barr\"; defined "
                              "bodies: \"bar\", \"disk\"; did you mean \"bar\"?"));
}

TEST(LoadErrors, LoadOnAFixedBodyWouldDoNothing) {
    const std::string w = scenario_error(with_load(
        "[[load]]\nbody = \"disk\"\ngroup = \"rim\"\npressure = 1e5\n", "fixed = true"));
    EXPECT_THAT(w, StartsWith("bad.toml:21:8: error: load on \"rim\" of body \"disk\": body "
                              "\"disk\" is fixed (fixed = true), so a load on it would do "
                              "nothing; load a body that can move"));
}

TEST(LoadErrors, ForceMustBeAVector) {
    const std::string w = scenario_error(with_load(load_on("tip", "force = 5.0")));
    EXPECT_THAT(w, StartsWith("bad.toml:23:9: error: load on \"tip\" of body \"bar\": force must "
                              "be [x, y], two numbers in N/m"));
}

TEST(VelocityFieldErrors, GradientMustBeATwoByTwoMatrix) {
    const std::string w =
        scenario_error(with_load("", "velocity_gradient = [[1, 0], [0]]"));
    EXPECT_THAT(w, StartsWith("bad.toml:17:21: error: body \"disk\": velocity_gradient must be a "
                              "2x2 matrix [[dvx/dx, dvx/dy], [dvy/dx, dvy/dy]] of finite numbers "
                              "in 1/s, got [[1, 0], [0]]"));
}

TEST(VelocityFieldErrors, OriginWithoutSpinOrGradient) {
    const std::string w = scenario_error(with_load("", "origin = [0, 0]"));
    EXPECT_THAT(w, StartsWith("bad.toml:17:10: error: body \"disk\": origin is the point about "
                              "which angular_velocity and velocity_gradient act, but neither is "
                              "given"));
}

TEST(VelocityFieldErrors, OriginStringMustBeCentroid) {
    const std::string w =
        scenario_error(with_load("", "angular_velocity = 3.0\norigin = \"center\""));
    EXPECT_THAT(w, StartsWith("bad.toml:18:10: error: body \"disk\": origin must be [x, y] in m "
                              "or \"centroid\" (each piece's own mass centre), got \"center\""));
}

TEST(VelocityFieldErrors, SpinOfAFixedBody) {
    const std::string w = scenario_error(with_load("", "angular_velocity = 3.0\nfixed = true"));
    EXPECT_THAT(w, StartsWith("bad.toml:17:20: error: body \"disk\": angular_velocity sets an "
                              "initial velocity, but fixed = true holds every node of the body at "
                              "rest; remove one of them"));
}

TEST(VelocityFieldErrors, PieceMotionChoices) {
    const std::string w = scenario_error(
        with_load("", "angular_velocity = 3.0\npiece_motion = \"rigidly\""));
    EXPECT_THAT(w, StartsWith("bad.toml:18:16: error: body \"disk\": piece_motion must be one of"));
}

}  // namespace
}  // namespace fdem
