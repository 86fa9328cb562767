// Inputs that used to run and exit 0 doing nothing, crash, or get an unhelpful message (issue
// #12 items 8-11 and 15): each is now an InputError naming file, line, key, value and what was
// expected, or a warning where the input is legal but surely unintended.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "fdem/error.hpp"
#include "fdem/scenario.hpp"
#include "fdem/fdem.hpp"
#include "support/input_errors.hpp"

namespace fdem {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using support::scenario_error;

const std::string kData = FDEM_TEST_DATA_DIR;

// line numbers:  1..20
const std::string kBase = R"([simulation]
end_time = 0.01
dt = "auto"
gravity = [0.0, -9.81]

[[material]]
name = "rock"
density = 2500.0
youngs_modulus = 1.0e9
poisson_ratio = 0.25

[[body]]
name = "block"
mesh = "square_41_ascii.msh"
material = "rock"

[[boundary]]
body = "block"
group = "bottom"
fix = ["x", "y"]
)";

/// kBase with the first occurrence of `from` replaced by `to`.
std::string edit(const std::string& from, const std::string& to, std::string s = kBase) {
    return support::replace_first(std::move(s), from, to);
}

// Two bodies of block_on_base.geo (a block 1 cm above a base), contact as given by `contact`.
std::string two_bodies(const std::string& contact, bool base_fixed = false,
                       bool block_fixed = false) {
    return std::string(R"([simulation]
end_time = 0.01
dt = "auto"
gravity = [0.0, -9.81]

[[material]]
name = "rock"
density = 2500.0
youngs_modulus = 1.0e9
poisson_ratio = 0.25

[[body]]
name = "base"
mesh = "block_on_base.geo"
mesh_size = 0.2
group = "base"
material = "rock"
)") + (base_fixed ? "fixed = true\n" : "") +
           R"(
[[body]]
name = "block"
mesh = "block_on_base.geo"
mesh_size = 0.2
group = "block"
material = "rock"
)" + (block_fixed ? "fixed = true\n" : "") +
           contact;
}

using support::write_temp;

struct CliResult {
    int code = -1;
    std::string out, err;
};

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// fdem with args (shell words), exit code, stdout and stderr.
CliResult cli(const std::string& args, const std::string& tag) {
    const std::string out = ::testing::TempDir() + "/" + tag + ".out";
    const std::string err = ::testing::TempDir() + "/" + tag + ".err";
    const std::string cmd =
        std::string(FDEM_CLI_PATH) + " " + args + " > " + out + " 2> " + err;
    const int status = std::system(cmd.c_str());
    CliResult r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
}

/// kBase with the mesh given by absolute path, written to a temp file, for the CLI.
std::string base_file(const std::string& name, const std::string& text = kBase) {
    return write_temp(name, edit("\"square_41_ascii.msh\"",
                                 "\"" + kData + "/square_41_ascii.msh\"", text));
}

// ---- item 7: meshes too fine, .geo files that never finish ---------------------------------

std::string geo_body(const std::string& geo, const std::string& extra) {
    return edit("mesh = \"square_41_ascii.msh\"\n",
                "mesh = \"" + geo + "\"\nmesh_size = 0.25\n" + extra, kBase);
}

TEST(UnintendedInputs, TinyMeshSizeIsRefusedBeforeMeshing) {
    // before: Gmsh aborted the process (SIGABRT) from its own threads after 45 s (here: still
    // meshing after 120 s)
    const std::string e =
        scenario_error(edit("mesh_size = 0.25", "mesh_size = 1e-6", geo_body("square.geo", "")));
    EXPECT_THAT(e, HasSubstr("bad.toml:15:13: error: body \"block\": mesh_size = 1e-06 m on '"));
    EXPECT_THAT(e, HasSubstr("(bounding box 1 m x 1 m) makes about 2e+12 triangles (2 x area / "
                             "mesh_size^2), more than max_triangles = 2e+06; expected a coarser "
                             "mesh_size (>= 0.001 m), or raise [[body]] max_triangles"));
}

TEST(UnintendedInputs, MaxTrianglesIsOverridable) {
    EXPECT_NO_THROW(
        load_scenario_from_string(geo_body("square.geo", ""), "ok.toml", kData));
    EXPECT_THAT(scenario_error(geo_body("square.geo", "max_triangles = 10\n")),
                HasSubstr("makes about 32 triangles"));
    EXPECT_THAT(scenario_error(edit("mesh = \"square_41_ascii.msh\"\n",
                                    "mesh = \"square_41_ascii.msh\"\nmax_triangles = 10\n")),
                HasSubstr("max_triangles only applies to .geo files"));
}

TEST(UnintendedInputs, GeoThatNeverFinishesHitsTheTimeLimit) {
    // before: Gmsh ran for ever (no limit)
    const std::string geo = write_temp("forever.geo", R"(For i In {1:2000000000}
  x = i;
EndFor
)");
    const std::string path = write_temp(
        "forever.toml", geo_body(geo, "mesh_time_limit = 1.0\n"));
    const auto r = cli("check " + path, "forever");
    EXPECT_EQ(r.code, 2);
    EXPECT_THAT(r.err, HasSubstr(geo + ": error: Gmsh did not finish reading and meshing '" + geo +
                                 "' within 1 s ([[body]] mesh_time_limit)"));
}

// ---- item 8: step counts -------------------------------------------------------------------

TEST(UnintendedInputs, HugeEndTimeIsRefusedNotOverflowed) {
    // before: "end time 1e+300 s (-9223372036854775808 steps)", 0 steps run, exit 0
    const std::string e = scenario_error(edit("end_time = 0.01", "end_time = 1e300"));
    EXPECT_THAT(e, HasSubstr("bad.toml:2:12: error: end_time = 1e+300 s needs "));
    EXPECT_THAT(e, HasSubstr("steps of dt = "));
    EXPECT_THAT(e, HasSubstr("more than [simulation] max_steps = 1e+08; dt = \"auto\" = 0.5 x "
                             "the stable limit"));
}

TEST(UnintendedInputs, TinyYoungsModulusGivesNoStepsAndIsRefused) {
    // before: stable dt 6e14 s, "end time 0.01 s (0 steps)", exit 0
    const std::string e =
        scenario_error(edit("youngs_modulus = 1.0e9", "youngs_modulus = 1e-30"));
    EXPECT_THAT(e, HasSubstr("bad.toml:2:12: error: end_time = 0.01 s is shorter than one time "
                             "step (dt = \"auto\" = 0.5 x the stable limit"));
    EXPECT_THAT(e, HasSubstr("material \"rock\" (youngs_modulus = 1e-30 Pa, density = 2500 "
                             "kg/m^3)): the run would take 0 step(s)"));
}

TEST(UnintendedInputs, HugeDensityGivesNoStepsAndIsRefused) {
    const std::string e = scenario_error(edit("density = 2500.0", "density = 1e300"));
    EXPECT_THAT(e, HasSubstr("is shorter than one time step"));
    EXPECT_THAT(e, HasSubstr("density = 1e+300 kg/m^3"));
}

TEST(UnintendedInputs, HugePenaltyPlansTooManyStepsNamingThePenalty) {
    // before: "end time 0.01 s (124803897049021 steps)" without a word
    const std::string e = scenario_error(two_bodies("\n[contact]\nalgorithm = \"smooth\"\npenalty = 1e30\n"));
    EXPECT_THAT(e, HasSubstr("set by the contact penalty (largest k_n = 1e+30 Pa)"));
    EXPECT_THAT(e, HasSubstr("more than [simulation] max_steps = 1e+08"));
}

TEST(UnintendedInputs, MaxStepsRaisesTheLimitAndIsChecked) {
    const std::string more = edit("gravity = [0.0, -9.81]",
                                  "gravity = [0.0, -9.81]\nmax_steps = 1e12",
                                  edit("end_time = 0.01", "end_time = 1e3"));
    EXPECT_NO_THROW(load_scenario_from_string(more, "ok.toml", kData));
    const std::string fewer = edit("gravity = [0.0, -9.81]", "gravity = [0.0, -9.81]\nmax_steps = 10");
    EXPECT_THAT(scenario_error(fewer), HasSubstr("more than [simulation] max_steps = 10;"));
    EXPECT_THAT(scenario_error(edit("gravity = [0.0, -9.81]",
                                    "gravity = [0.0, -9.81]\nmax_steps = 0.5")),
                HasSubstr("bad.toml:5:13: error: [simulation]: max_steps must be >= 1, got 0.5"));
}

TEST(UnintendedInputs, GivenDtLongerThanEndTimeIsRefused) {
    const std::string e = scenario_error(edit("dt = \"auto\"", "dt = 1e-5", edit("end_time = 0.01", "end_time = 1e-6")));
    EXPECT_THAT(e, HasSubstr("bad.toml:2:12: error: end_time = 1e-06 s is shorter than one time "
                             "step (dt = 1e-05 s is given in [simulation])"));
}

// ---- item 9: contradictory keys ------------------------------------------------------------

TEST(UnintendedInputs, FixedBodyWithVelocityIsAContradiction) {
    const std::string e = scenario_error(
        edit("material = \"rock\"\n", "material = \"rock\"\nfixed = true\nvelocity = [1.0, 0.0]\n",
             edit("dt = \"auto\"", "dt = 1e-6")));
    EXPECT_THAT(e, HasSubstr("bad.toml:17:12: error: body \"block\": velocity contradicts fixed "
                             "= true"));
}

TEST(UnintendedInputs, KickOfAFixedBodyIsAContradiction) {
    // before: the kick was skipped silently (apply_kicks ignores fixed bodies)
    const std::string fixed = edit("material = \"rock\"\n", "material = \"rock\"\nfixed = true\n",
                                   edit("dt = \"auto\"", "dt = 1e-6"));
    EXPECT_THAT(scenario_error(fixed + "\n[[kick]]\nbody = \"block\"\ntime = 0.0\nvelocity = "
                                       "[1.0, 0.0]\n"),
                HasSubstr("bad.toml:24:8: error: [[kick]] #1: body \"block\" is fixed (fixed = "
                          "true): a kick would not move it"));
}

TEST(UnintendedInputs, KickAfterEndTimeIsRefused) {
    const std::string e =
        scenario_error(kBase + "\n[[kick]]\nbody = \"block\"\ntime = 5.0\nvelocity = [1.0, 0.0]\n");
    EXPECT_THAT(e, HasSubstr("bad.toml:24:8: error: kick of body \"block\": time = 5 s is not "
                             "before end_time = 0.01 s: the kick would never act"));
}

TEST(UnintendedInputs, OutputIntervalShorterThanDtWarns) {
    const Scenario sc = load_scenario_from_string(
        kBase + "\n[output]\ninterval = 1e-9\n", "ok.toml", kData);
    ASSERT_EQ(sc.warnings.size(), 1u);
    EXPECT_THAT(sc.warnings[0], HasSubstr("ok.toml:23:12: warning: [output]: interval = 1e-09 s "
                                          "is shorter than the time step dt = "));
    EXPECT_THAT(sc.warnings[0], HasSubstr("a frame is written after every step"));
    const Scenario fine =
        load_scenario_from_string(kBase + "\n[output]\ninterval = 1e-3\n", "ok.toml", kData);
    EXPECT_TRUE(fine.warnings.empty());
}

TEST(UnintendedInputs, CliRefusesNanEmptyAndNegativeValues) {
    const std::string path = base_file("cli_values.toml");
    const std::string out = ::testing::TempDir() + "/cli_values_out";
    // before: nan accepted (run to the scenario's end_time, exit 0); --out "" wrote to ./out;
    // -1 printed a 309-digit bound
    auto r = cli("run " + path + " --out " + out + " --end-time nan", "end_nan");
    EXPECT_EQ(r.code, 2);
    EXPECT_THAT(r.err, HasSubstr("--end-time: expected a finite number of seconds > 0, got nan"));
    r = cli("run " + path + " --out " + out + " --checkpoint-every nan", "ck_nan");
    EXPECT_EQ(r.code, 2);
    EXPECT_THAT(r.err,
                HasSubstr("--checkpoint-every: expected a finite number of seconds > 0, got nan"));
    r = cli("run " + path + " --out ''", "out_empty");
    EXPECT_EQ(r.code, 2);
    EXPECT_THAT(r.err, HasSubstr("--out: expected a non-empty folder path, got \"\""));
    r = cli("run " + path + " --out " + out + " --end-time -1", "end_neg");
    EXPECT_EQ(r.code, 2);
    EXPECT_THAT(r.err, HasSubstr("--end-time: expected a finite number of seconds > 0, got -1"));
    EXPECT_LT(r.err.size(), 200u);
    r = cli("run " + path + " --out " + out + " --end-time 1e300", "end_huge");
    EXPECT_EQ(r.code, 2);
    EXPECT_THAT(r.err, HasSubstr("--end-time: error: end_time = 1e+300 s needs"));
}

// ---- item 10: messages -----------------------------------------------------------------------

TEST(UnintendedInputs, ScenarioPathThatIsADirectory) {
    // before: "missing required table [simulation] (end_time, dt)"
    try {
        load_scenario(kData);
        ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_THAT(e.what(), HasSubstr("cannot read scenario file '" + kData +
                                        "': it is a directory; expected a TOML scenario file"));
    }
}

TEST(UnintendedInputs, PointGroupUsedAsABodyIsNamedAsSuch) {
    // before: 'has no surface physical group "origin" (did you mean "origin"?)'
    const std::string e =
        scenario_error(edit("material = \"rock\"\n", "material = \"rock\"\ngroup = \"origin\"\n"));
    EXPECT_THAT(e, HasSubstr("\"origin\" is a point physical group of mesh"));
    EXPECT_THAT(e, HasSubstr("expected a surface group (Physical Surface)"));
    EXPECT_THAT(e, Not(HasSubstr("did you mean")));
}

TEST(UnintendedInputs, SupersonicBoundaryVelocityIsRefused) {
    // before: "step 1 ...: element inverted ...; reduce dt", exit 1
    const std::string e = scenario_error(edit("fix = [\"x\", \"y\"]", "velocity = [1e9, 0.0]"));
    EXPECT_THAT(e, HasSubstr("bad.toml:20:12: error: boundary \"bottom\" of body \"block\": the "
                             "prescribed speed 1e+09 m/s is not below the P-wave speed c_p = "));
}

TEST(UnintendedInputs, TruncatedMshNamesTheOpenSection) {
    // before: "cannot read mesh file '...': Error loading '...'"
    const std::string full = slurp(kData + "/square_22_ascii.msh");
    const std::string mesh = write_temp("truncated_22.msh", full.substr(0, 300));
    const std::string e =
        scenario_error(edit("\"square_41_ascii.msh\"", "\"" + mesh + "\""));
    EXPECT_THAT(e, HasSubstr("the file ends inside section $"));
    EXPECT_THAT(e, HasSubstr("it is truncated or incomplete"));
}

TEST(UnintendedInputs, NanCoordinateIsNotCalledADegenerateTriangle) {
    // before: 'triangle 3 (nodes 1, 5, 10) of body "block" is degenerate (area nan m^2)'
    std::string text = slurp(kData + "/square_41_ascii.msh");
    const std::string from = "\n0.499999999998694 0 0\n";
    ASSERT_NE(text.find(from), std::string::npos);
    text.replace(text.find(from), from.size(), "\nnan 0 0\n");
    const std::string mesh = write_temp("nan_node.msh", text);
    const std::string e = scenario_error(edit("\"square_41_ascii.msh\"", "\"" + mesh + "\""));
    EXPECT_THAT(e, HasSubstr(":26: error: mesh file '" + mesh +
                             "': node 5 has the coordinates (nan, 0); expected finite numbers"));
}

TEST(UnintendedInputs, UnwritableOutputFolderIsAnInputError) {
    // before: "error: step 0 (t = 0 s): .../history.csv: cannot write history file", exit 1.
    // /proc/self exists and nobody (root included) can create files in it.
    const auto r = cli("run " + base_file("ro_out.toml") + " --quiet --out /proc/self", "ro_out");
    EXPECT_EQ(r.code, 2);
    EXPECT_THAT(r.err, HasSubstr("--out: error: cannot write into the output folder '/proc/self'"));
}

TEST(UnintendedInputs, RestartIntoAnotherFolderKeepsTheSeriesComplete) {
    const std::string path = base_file("restart_move.toml");
    const std::string a = ::testing::TempDir() + "/restart_move_a";
    const std::string b = ::testing::TempDir() + "/restart_move_b";
    std::filesystem::remove_all(a);
    std::filesystem::remove_all(b);
    auto r = cli("run " + path + " --quiet --out " + a + " --end-time 0.005 --checkpoint-every 0.005",
                 "restart_a");
    ASSERT_EQ(r.code, 0) << r.err;
    r = cli("run " + path + " --quiet --out " + b + " --restart " + a + "/checkpoint.fdck",
            "restart_b");
    ASSERT_EQ(r.code, 0) << r.err;
    // before: series.pvd of b listed frame_000000.vtu ... of a as if they were in b
    const std::string pvd = slurp(b + "/series.pvd");
    EXPECT_THAT(pvd, HasSubstr("file=\"../restart_move_a/frame_000000.vtu\""));
    EXPECT_THAT(pvd, HasSubstr("file=\"frame_000025.vtu\""));
    // history.csv of b starts at step 1 like an uninterrupted run (before: at the restart step)
    const std::string hist = slurp(b + "/history.csv");
    EXPECT_THAT(hist.substr(0, hist.find('\n', hist.find('\n') + 1)), HasSubstr("\n1,"));
}

TEST(UnintendedInputs, TwentyThousandMaterialsLoad) {
    // before: std::bad_alloc, exit 1 (the material-pair table was num_materials^2)
    std::string text = kBase;
    std::string mats;
    for (int i = 0; i < 20000; ++i) {
        mats += "[[material]]\nname = \"m" + std::to_string(i) +
                "\"\ndensity = 2500.0\nyoungs_modulus = 1.0e9\npoisson_ratio = 0.25\n\n";
    }
    text = edit("[[body]]", mats + "[[body]]", text);
    text += "\n[contact]\nalgorithm = \"smooth\"\n[[contact.pair]]\nmaterials = [\"m1\", \"m2\"]\n"
            "friction = 0.3\n";
    const Scenario sc = load_scenario_from_string(text, "ok.toml", kData);
    EXPECT_EQ(sc.model.materials.size(), 20001u);
}

// ---- item 11: contact on by default ----------------------------------------------------------

TEST(UnintendedInputs, ContactIsOnByDefaultWhenTwoBodiesCanMeet) {
    // before: no [contact] = no contact: a disk fell through a slab, exit 0
    const Scenario on = load_scenario_from_string(two_bodies(""), "ok.toml", kData);
    EXPECT_EQ(on.model.contact.algorithm, ContactAlgorithm::Smooth);
    EXPECT_TRUE(on.contact_default);
    const Scenario fixed_base = load_scenario_from_string(two_bodies("", true), "ok.toml", kData);
    EXPECT_EQ(fixed_base.model.contact.algorithm, ContactAlgorithm::Smooth);
    const Scenario off = load_scenario_from_string(
        two_bodies("\n[contact]\nalgorithm = \"none\"\n"), "ok.toml", kData);
    EXPECT_EQ(off.model.contact.algorithm, ContactAlgorithm::None);
    EXPECT_FALSE(off.contact_default);
    const Scenario one = load_scenario_from_string(kBase, "ok.toml", kData);
    EXPECT_EQ(one.model.contact.algorithm, ContactAlgorithm::None);
    const Scenario both_fixed = load_scenario_from_string(
        edit("dt = \"auto\"", "dt = 1e-6", two_bodies("", true, true)), "ok.toml", kData);
    EXPECT_EQ(both_fixed.model.contact.algorithm, ContactAlgorithm::None);
}

TEST(UnintendedInputs, DefaultContactStopsTheBlockOnTheBase) {
    // the block falls 1 cm onto the fixed base: without contact it would pass through it
    Scenario sc = load_scenario_from_string(
        edit("end_time = 0.01", "end_time = 0.15", two_bodies("", true)), "ok.toml", kData);
    ASSERT_EQ(sc.model.contact.algorithm, ContactAlgorithm::Smooth);
    State s = make_state(sc.model, sc.run.dt);
    while (s.time < sc.run.end_time)
        step(sc.model, s);
    const Body& block = sc.model.bodies[1];
    Real ymin = 1e9;
    for (NodeId n = block.node_begin; n < block.node_end; ++n)
        ymin = std::min(ymin, s.x[static_cast<size_t>(n)].y);
    EXPECT_GT(ymin, 0.19);  // the base's top is at 0.2 m; free fall would reach 0.21 - 0.11
}

// ---- item 15: fdem check lists the bodies --------------------------------------------------

TEST(UnintendedInputs, CheckListsEveryBodyAndTheContactChoice) {
    const std::string path = write_temp(
        "check_list.toml",
        edit("mesh = \"block_on_base.geo\"", "mesh = \"" + kData + "/block_on_base.geo\"",
             edit("mesh = \"block_on_base.geo\"", "mesh = \"" + kData + "/block_on_base.geo\"",
                  two_bodies("", true))));
    const auto r = cli("check " + path, "check_list");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr("contact    smooth (default without [contact]: two or more "
                                 "bodies, at least one movable; [contact] algorithm = \"none\" "
                                 "switches it off)"));
    EXPECT_THAT(r.out, HasSubstr("body list  id  name  triangles  mass [kg/m]  fixed  contact\n"));
    EXPECT_THAT(r.out, ::testing::ContainsRegex("\n +0  \"base\"  [0-9]+  1000  yes  yes\n"));
    EXPECT_THAT(r.out, ::testing::ContainsRegex("\n +1  \"block\"  [0-9]+  625  no  yes\n"));
}

}  // namespace
}  // namespace fdem
