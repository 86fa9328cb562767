// Fracture keys of a scenario (docs/scenario.md [material.fracture], [[body]] fracture keys,
// [fracture]; spec fracture.md §10): values read into Material::fracture and
// RunSettings::fracture, and every bad value an InputError with file:line:column, key, value
// and expectation. Every case edits one line of kBase, so line numbers can be read off kBase.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "fdem/error.hpp"
#include "fdem/mesh.hpp"
#include "fdem/scenario.hpp"
#include "support/input_errors.hpp"

namespace fdem {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

const std::string kData = FDEM_TEST_DATA_DIR;

// line numbers:  1..33
const std::string kBase = R"([simulation]
end_time = 0.01
dt = "auto"

[[material]]
name = "rock"
density = 2700.0
youngs_modulus = 5.0e10
poisson_ratio = 0.25

[material.fracture]
tensile_strength = 1.0e7
cohesion = 3.0e7
friction_angle = 30.0
fracture_energy_I = 50.0
fracture_energy_II = 250.0

[[material]]
name = "steel"
density = 7800.0
youngs_modulus = 2.0e11
poisson_ratio = 0.3

[[body]]
name = "blocks"
mesh = "jointed_blocks.geo"
mesh_size = 0.25
material = "rock"

[[boundary]]
body = "blocks"
group = "bottom"
fix = ["x", "y"]
)";

std::string edit(const std::string& from, const std::string& to) {
    return support::replace_first(kBase, from, to);
}

std::string what_of(const std::string& text) {
    return support::scenario_error(text, kData);
}

Scenario load(const std::string& text) {
    return load_scenario_from_string(text, "bad.toml", kData);
}

TEST(FractureInput, ParametersAndDefaults) {
    const Scenario sc = load(kBase);
    const Material& rock = sc.model.materials[0];
    ASSERT_TRUE(rock.has_fracture);
    EXPECT_FALSE(sc.model.materials[1].has_fracture);
    const JointMaterial& j = rock.fracture;
    EXPECT_EQ(j.tensile_strength, 1.0e7);
    EXPECT_EQ(j.cohesion, 3.0e7);
    EXPECT_DOUBLE_EQ(j.friction_angle, 30.0 * std::acos(-1.0) / 180.0);  // degrees -> rad
    EXPECT_EQ(j.fracture_energy_I, 50.0);
    EXPECT_EQ(j.fracture_energy_II, 250.0);
    EXPECT_EQ(j.penalty, 5.0e11);        // "auto" = 10 E
    EXPECT_EQ(j.shear_penalty, 5.0e11);  // "auto" = penalty
    EXPECT_EQ(j.softening, SofteningCurve::EvansMarathe);
    EXPECT_EQ(j.softening_length, SofteningLength::Exact);
    EXPECT_EQ(j.irreversibility, Irreversibility::Frozen);
    EXPECT_EQ(j.failure_points, 2);
    EXPECT_FALSE(j.allow_coarse);
    EXPECT_EQ(j.mixed_mode, MixedMode::Proportional);  // theory §9.3d
    EXPECT_EQ(sc.run.fracture.output_joints, JointOutput::Damaged);
    EXPECT_EQ(sc.run.fracture.fragments, FragmentOutput::Interval);
    EXPECT_TRUE(sc.warnings.empty());
}

TEST(FractureInput, EveryOptionalKey) {
    const Scenario sc = load(edit("fracture_energy_II = 250.0\n",
                                  "fracture_energy_II = 250.0\n"
                                  "penalty = 2.0e11\n"
                                  "shear_penalty = 1.0e11\n"
                                  "softening = \"linear\"\n"
                                  "softening_length = \"y-geo\"\n"
                                  "irreversibility = \"frozen\"\n"
                                  "failure_points = 3\n"
                                  "residual_friction = 0.0\n"
                                  "allow_coarse = true\n"
                                  "mixed_mode = \"independent\"\n"
                                  "\n[fracture]\n"
                                  "crack_contact = \"self\"\n"
                                  "contact_targets = \"copies\"\n"
                                  "output_joints = \"all\"\n"
                                  "fragments = \"end\"\n"));
    const JointMaterial& j = sc.model.materials[0].fracture;
    EXPECT_EQ(j.penalty, 2.0e11);
    EXPECT_EQ(j.shear_penalty, 1.0e11);
    EXPECT_EQ(j.softening, SofteningCurve::Linear);
    EXPECT_EQ(j.softening_length, SofteningLength::YGeo);
    EXPECT_EQ(j.failure_points, 3);
    EXPECT_TRUE(j.allow_coarse);
    EXPECT_EQ(j.mixed_mode, MixedMode::Independent);
    EXPECT_EQ(sc.run.fracture.output_joints, JointOutput::All);
    EXPECT_EQ(sc.run.fracture.fragments, FragmentOutput::End);
    for (const auto& [rule, want] : {std::pair{"solidity", SofteningLength::Solidity},
                                     std::pair{"total", SofteningLength::Total}}) {
        const Scenario s2 =
            load(edit("fracture_energy_II = 250.0", std::string("fracture_energy_II = 250.0\n"
                                                                "softening_length = \"") +
                                                        rule + "\""));
        EXPECT_EQ(s2.model.materials[0].fracture.softening_length, want) << rule;
    }
    const Scenario s3 = load(edit("fracture_energy_II = 250.0",
                                  "fracture_energy_II = 250.0\n[fracture]\noutput_joints = "
                                  "\"none\""));
    EXPECT_EQ(s3.run.fracture.output_joints, JointOutput::None);
}

/// Line elements of the curve group `name` of tests/data/jointed_blocks.geo at mesh_size 0.25.
size_t curve_edges(const std::string& name) {
    const MeshData mesh = read_mesh(kData + "/jointed_blocks.geo", 0.25);
    size_t n = 0;
    for (const PhysicalGroup& g : mesh.groups) {
        if (g.name == name && g.dim == 1) n += g.elements.size();
    }
    return n;
}

TEST(FractureInput, GroupsReachTheModel) {
    // a curve fracture_group: joints on its edges only; prebroken: those joints broken at t = 0
    const Scenario sc = load(edit("material = \"rock\"",
                                  "material = \"rock\"\nfracture_group = \"joint\"\n"
                                  "prebroken = [\"notch\"]"));
    ASSERT_EQ(sc.model.num_bodies(), 1);
    EXPECT_TRUE(sc.model.bodies[0].fracture);
    EXPECT_EQ(static_cast<size_t>(sc.model.joints.num_joints()), curve_edges("joint"));
    EXPECT_EQ(sc.model.prebroken_joints.size(), curve_edges("notch"));
    EXPECT_GT(curve_edges("notch"), 0u);
    EXPECT_LT(curve_edges("notch"), curve_edges("joint"));
    // a surface fracture_group: joints only between its triangles, none on the joint line
    const Scenario upper =
        load(edit("material = \"rock\"", "material = \"rock\"\nfracture_group = \"upper\""));
    const Model& m = upper.model;
    ASSERT_GT(m.joints.num_joints(), 0);
    for (int32_t j = 0; j < m.joints.num_joints(); ++j) {
        for (const NodeId n : m.joints.nodes[static_cast<size_t>(j)])
            EXPECT_GE(m.node_x0[static_cast<size_t>(n)].y, 0.5) << "joint " << j;
    }
    // fracture = false: no joints
    EXPECT_EQ(load(edit("material = \"rock\"", "material = \"rock\"\nfracture = false"))
                  .model.joints.num_joints(),
              0);
}

TEST(FractureInput, SupportsAndLoadsTakeEveryNodeCopy) {
    // every internal edge jointed: each vertex has one node copy per triangle around it; the
    // support on "bottom" must hold all copies of its vertices, the traction on "top" finds the
    // top edges on the split mesh, a probe group takes every copy
    const Scenario sc = load(kBase +
                             "\n[[load]]\nbody = \"blocks\"\ngroup = \"top\"\n"
                             "traction = [0.0, 1.0e6]\n"
                             "\n[[probe]]\nname = \"corner\"\nbody = \"blocks\"\n"
                             "group = \"corner\"\n");
    const Model& m = sc.model;
    ASSERT_GT(m.joints.num_joints(), 0);
    ASSERT_EQ(m.num_nodes(), 3 * m.num_tris());  // every triangle its own nodes
    size_t on_bottom = 0, at_corner = 0;
    for (const Vec2& x : m.node_x0) {
        on_bottom += x.y == 0.0 ? 1 : 0;
        at_corner += x.x == 0.0 && x.y == 0.0 ? 1 : 0;
    }
    ASSERT_EQ(m.bcs.size(), 1u);
    EXPECT_EQ(m.bcs[0].nodes.size(), on_bottom);
    for (const NodeId n : m.bcs[0].nodes)
        EXPECT_EQ(m.node_x0[static_cast<size_t>(n)].y, 0.0);
    ASSERT_EQ(m.loads.size(), 1u);
    EXPECT_EQ(m.loads[0].edges.size(), curve_edges("top"));
    double length = 0;
    for (const double l : m.loads[0].edge_length0)
        length += l;
    EXPECT_NEAR(length, 1.0, 1e-12);
    ASSERT_EQ(sc.run.output.probes.size(), 1u);
    EXPECT_EQ(sc.run.output.probes[0].nodes.size(), at_corner);
    EXPECT_GE(at_corner, 1u);
}

TEST(FractureInput, SurfaceGroupSupportTakesOnlyItsOwnCopies) {
    // joints on the line y = 0.5 only: its vertices have a copy below and one above; a support
    // on the surface group "upper" holds the upper copies and leaves the lower ones free
    const Scenario sc =
        load(edit("material = \"rock\"", "material = \"rock\"\nfracture_group = \"joint\"") +
             "\n[[boundary]]\nbody = \"blocks\"\ngroup = \"upper\"\n"
             "velocity = [0.0, 1.0e-3]\n");
    const Model& m = sc.model;
    ASSERT_GT(m.joints.num_joints(), 0);
    // expected: the nodes of the triangles above the line (centroid y > 0.5), from the model
    std::vector<NodeId> upper;
    for (const auto& n : m.tri_nodes) {
        const double cy =
            (m.node_x0[static_cast<size_t>(n[0])].y + m.node_x0[static_cast<size_t>(n[1])].y +
             m.node_x0[static_cast<size_t>(n[2])].y) /
            3;
        if (cy > 0.5) upper.insert(upper.end(), n.begin(), n.end());
    }
    std::sort(upper.begin(), upper.end());
    upper.erase(std::unique(upper.begin(), upper.end()), upper.end());
    ASSERT_EQ(m.bcs.size(), 2u);
    EXPECT_EQ(m.bcs[1].nodes, upper);
    // the joints' lower faces (nodes 3, 2 on triangle B) or upper faces: one face each is held
    for (const auto& jn : m.joints.nodes) {
        const bool a = std::binary_search(upper.begin(), upper.end(), jn[0]);
        const bool b = std::binary_search(upper.begin(), upper.end(), jn[3]);
        EXPECT_NE(a, b) << "a joint with both faces or none in the support";
    }
}

TEST(FractureInput, UnknownKeySuggestsTheClosest) {
    EXPECT_THAT(what_of(edit("tensile_strength = 1.0e7", "tensile_strenght = 1.0e7")),
                StartsWith("bad.toml:12:1: error: material \"rock\" [material.fracture]: "
                           "unknown key 'tensile_strenght'; did you mean 'tensile_strength'?"));
}

struct Case {
    const char* from;  ///< a line of kBase
    const char* to;    ///< its replacement
    const char* what;  ///< start of the message, '*' standing for any text; "" = legal
};

/// Test names by case index: the default printer names a struct parameter by its bytes
/// (pointers), which change from build to build, so ctest names were not stable.
std::string case_name(const ::testing::TestParamInfo<Case>& info) {
    return "case" + std::to_string(info.index);
}

/// msg starts with pattern, where '*' in pattern stands for any text (the mesh folder).
bool matches(const std::string& msg, const std::string& pattern) {
    size_t at = 0, from = 0;
    for (bool first = true;; first = false) {
        const size_t star = pattern.find('*', from);
        const std::string part =
            pattern.substr(from, star == std::string::npos ? star : star - from);
        const size_t found = msg.find(part, at);
        if (found == std::string::npos || (first && found != 0)) return false;
        at = found + part.size();
        if (star == std::string::npos) return true;
        from = star + 1;
    }
}

const char* const kLast = "fracture_energy_II = 250.0";  // line 16: keys added after it are on 17

class FractureErrors : public ::testing::TestWithParam<Case> {};

TEST_P(FractureErrors, PinnedMessage) {
    const Case& c = GetParam();
    if (*c.what == '\0') {  // legal
        EXPECT_NO_THROW(load(edit(c.from, c.to))) << c.to;
    } else {
        const std::string w = what_of(edit(c.from, c.to));
        EXPECT_TRUE(matches(w, c.what)) << c.to << "\n got: " << w << "\n want: " << c.what;
    }
}

// [material.fracture]: ranges, types, required keys, choices, options not implemented
INSTANTIATE_TEST_SUITE_P(
    MaterialFracture, FractureErrors,
    ::testing::Values(
        Case{"tensile_strength = 1.0e7", "tensile_strength = 0.0",
             "bad.toml:12:20: error: material \"rock\" [material.fracture]: tensile_strength must "
             "be > 0, got 0"},
        Case{"tensile_strength = 1.0e7", "tensile_strength = \"high\"",
             "bad.toml:12:20: error: material \"rock\" [material.fracture]: tensile_strength must "
             "be a number in Pa, > 0, got a string \"high\""},
        Case{"tensile_strength = 1.0e7", "",
             "bad.toml:11:1: error: material \"rock\" [material.fracture]: missing required key "
             "'tensile_strength' (a number in Pa, > 0)"},
        Case{"cohesion = 3.0e7", "cohesion = -1.0",
             "bad.toml:13:12: error: material \"rock\" [material.fracture]: cohesion must be > 0, "
             "got -1"},
        Case{"friction_angle = 30.0", "friction_angle = 90.0",
             "bad.toml:14:18: error: material \"rock\" [material.fracture]: friction_angle must be "
             "in [0, 90), got 90"},
        Case{"friction_angle = 30.0", "friction_angle = -5.0",
             "bad.toml:14:18: error: material \"rock\" [material.fracture]: friction_angle must be "
             "in [0, 90), got -5"},
        Case{"friction_angle = 30.0", "friction_angle = 0.5236",  // radians by mistake: legal
             ""},
        Case{"fracture_energy_I = 50.0", "fracture_energy_I = 0",
             "bad.toml:15:21: error: material \"rock\" [material.fracture]: fracture_energy_I "
             "must be > 0, got 0"},
        Case{kLast, "fracture_energy_II = -250.0",
             "bad.toml:16:22: error: material \"rock\" [material.fracture]: fracture_energy_II "
             "must be > 0, got -250"},
        Case{kLast, "fracture_energy_II = 250.0\npenalty = 0.0",
             "bad.toml:17:11: error: material \"rock\" [material.fracture]: penalty must be > 0, "
             "got 0"},
        Case{kLast, "fracture_energy_II = 250.0\npenalty = \"10E\"",
             "bad.toml:17:11: error: material \"rock\" [material.fracture]: penalty must be a "
             "number in Pa (> 0) or \"auto\" (10 x youngs_modulus), got \"10E\""},
        Case{kLast, "fracture_energy_II = 250.0\nshear_penalty = -1e11",
             "bad.toml:17:17: error: material \"rock\" [material.fracture]: shear_penalty must be "
             "> 0, got -100000000000"},
        Case{kLast, "fracture_energy_II = 250.0\nfailure_points = 0",
             "bad.toml:17:18: error: material \"rock\" [material.fracture]: failure_points must be "
             "in [1, 3], got 0"},
        Case{kLast, "fracture_energy_II = 250.0\nfailure_points = 4",
             "bad.toml:17:18: error: material \"rock\" [material.fracture]: failure_points must be "
             "in [1, 3], got 4"},
        Case{kLast, "fracture_energy_II = 250.0\nfailure_points = 2.5",
             "bad.toml:17:18: error: material \"rock\" [material.fracture]: failure_points must be "
             "an integer 1, 2 or 3 (integration points with D >= 1 that break a joint), got 2.5"},
        Case{kLast, "fracture_energy_II = 250.0\nirreversibility = \"none\"",
             "bad.toml:17:19: error: material \"rock\" [material.fracture]: irreversibility = "
             "\"none\" is not implemented; only \"frozen\" is (per integration point the largest "
             "damage reached is kept, docs/theory.md §9.4)"},
        Case{kLast, "fracture_energy_II = 250.0\nirreversibility = \"y-geo\"",
             "bad.toml:17:19: error: material \"rock\" [material.fracture]: irreversibility = "
             "\"y-geo\" is not implemented; only \"frozen\" is"},
        Case{kLast, "fracture_energy_II = 250.0\nirreversibility = \"frozn\"",
             "bad.toml:17:19: error: material \"rock\" [material.fracture]: irreversibility must "
             "be one of \"frozen\", \"none\", \"y-geo\", got \"frozn\"; did you mean \"frozen\"?"},
        Case{kLast, "fracture_energy_II = 250.0\nresidual_friction = 0.3",
             "bad.toml:17:21: error: material \"rock\" [material.fracture]: residual_friction = "
             "0.3 is not implemented; only 0 (no friction on a softening joint in compression, as "
             "Y, Y-Geo and Solidity; a broken joint's faces get their friction from [contact])"},
        Case{kLast, "fracture_energy_II = 250.0\nresidual_friction = -0.3",
             "bad.toml:17:21: error: material \"rock\" [material.fracture]: residual_friction "
             "must be >= 0, got -0.3"},
        Case{kLast, "fracture_energy_II = 250.0\nsoftening = \"exponential\"",
             "bad.toml:17:13: error: material \"rock\" [material.fracture]: softening must be one "
             "of \"evans-marathe\", \"linear\", got \"exponential\""},
        Case{kLast, "fracture_energy_II = 250.0\nsoftening_length = \"3G/f\"",
             "bad.toml:17:20: error: material \"rock\" [material.fracture]: softening_length must "
             "be one of \"exact\", \"total\", \"y-geo\", \"solidity\", got \"3G/f\""},
        Case{kLast, "fracture_energy_II = 250.0\nmixed_mode = \"coupled\"",
             "bad.toml:17:14: error: material \"rock\" [material.fracture]: mixed_mode must be "
             "one of \"independent\", \"proportional\", got \"coupled\""},
        Case{kLast, "fracture_energy_II = 250.0\nmixed_mode = 1",
             "bad.toml:17:14: error: material \"rock\" [material.fracture]: mixed_mode must be "
             "one of \"independent\", \"proportional\", got a number 1"},
        Case{kLast, "fracture_energy_II = 250.0\nallow_coarse = \"yes\"",
             "bad.toml:17:16: error: material \"rock\" [material.fracture]: allow_coarse must be "
             "true or false, got a string \"yes\""},
        Case{"poisson_ratio = 0.3", "poisson_ratio = 0.3\nfracture = 1.0",
             "bad.toml:23:12: error: material \"steel\": fracture must be a table (write "
             "[material.fracture] on its own line after the material's keys), got a number 1"},
        // joint lengths against the softening rule (theory eqs. 9.12, 9.14); the longest internal
        // edge of the mesh is h = 0.1443 m
        Case{"fracture_energy_I = 50.0", "fracture_energy_I = 5.0",
             "bad.toml:11:1: error: material \"rock\" [material.fracture]: the longest joint (h = "
             "0.1443 m, in body \"blocks\") is longer than h_max = p G_I / (4 I_z f_t^2) = 0.01618 "
             "m (docs/theory.md eq. 9.14: the exact softening branch would be shorter than 2 o_p); "
             "refine the mesh to h <= 0.01618 m, raise penalty or fracture_energy_I, or set "
             "allow_coarse = true"},
        Case{"fracture_energy_I = 50.0", "fracture_energy_I = 5.0\nallow_coarse = true", ""},
        // eq. 9.14 is the well-posedness of "exact"; the other rules take such joints
        Case{"fracture_energy_I = 50.0", "fracture_energy_I = 5.0\nsoftening_length = \"y-geo\"",
             ""},
        Case{"fracture_energy_I = 50.0",
             "fracture_energy_I = 5.0\nsoftening_length = \"total\"\npenalty = 1e10",
             "bad.toml:16:20: error: material \"rock\" [material.fracture]: softening_length = "
             "\"total\" needs fracture_energy_I > (2/3) f_t o_p = (4/3) h f_t^2 / p for every "
             "joint, but the longest joint (h = 0.1443 m, in body \"blocks\") gives 1925 J/m^2 >= "
             "fracture_energy_I = 5 J/m^2 (the pre-peak branch alone dissipates more than G_I); "
             "refine the mesh, raise penalty, or use \"exact\""}),
    case_name);

// [[body]] fracture keys and [fracture]
INSTANTIATE_TEST_SUITE_P(
    BodyAndGlobal, FractureErrors,
    ::testing::Values(
        Case{"material = \"rock\"", "material = \"rock\"\nfracture = \"yes\"",
             "bad.toml:29:12: error: body \"blocks\": fracture must be true or false, got a "
             "string \"yes\""},
        Case{"material = \"rock\"", "material = \"steel\"\nfracture = true",
             "bad.toml:29:12: error: body \"blocks\": fracture = true needs the joint parameters "
             "of material \"steel\", but it has no [material.fracture] table; add one "
             "(tensile_strength, cohesion, friction_angle, fracture_energy_I, "
             "fracture_energy_II) or remove fracture"},
        Case{"material = \"rock\"", "material = \"rock\"\nfixed = true\nfracture = true",
             "bad.toml:30:12: error: body \"blocks\": fracture = true on a fixed body (fixed = "
             "true): a fixed body never deforms, so it cannot crack; remove one of them"},
        Case{"material = \"rock\"", "material = \"rock\"\nelement = \"composite\"",
             "bad.toml:29:11: error: body \"blocks\": fracture (on by default: material \"rock\" "
             "has [material.fracture]) is not available for composite (6-node) elements yet "
             "(spec fracture.md §12.12); set element = \"cst\" (every 6-node triangle split into "
             "4 CSTs) or fracture = false"},
        Case{"material = \"rock\"", "material = \"rock\"\nelement = \"composite\"\nfracture = true",
             "bad.toml:30:12: error: body \"blocks\": fracture = true is not available for "
             "composite (6-node) elements yet"},
        Case{"material = \"rock\"",
             "material = \"rock\"\nelement = \"composite\"\nfracture = false", ""},
        Case{"material = \"rock\"", "material = \"rock\"\nelement = \"cst\"", ""},
        Case{"material = \"rock\"",
             "material = \"rock\"\nfracture = false\nfracture_group = "
             "\"joint\"",
             "bad.toml:30:18: error: body \"blocks\": fracture_group only applies to a body with "
             "fracture, but body \"blocks\" has none (fracture = false); remove fracture_group"},
        Case{"material = \"rock\"", "material = \"steel\"\nprebroken = [\"notch\"]",
             "bad.toml:29:13: error: body \"blocks\": prebroken only applies to a body with "
             "fracture, but body \"blocks\" has none (material \"steel\" has no "
             "[material.fracture]); remove prebroken"},
        Case{"material = \"rock\"", "material = \"rock\"\nfixed = true\nprebroken = [\"notch\"]",
             "bad.toml:30:13: error: body \"blocks\": prebroken only applies to a body with "
             "fracture, but body \"blocks\" has none (it is fixed); remove prebroken"},
        Case{"material = \"rock\"", "material = \"rock\"\nfracture_group = \"jiont\"",
             "bad.toml:29:18: error: body \"blocks\": mesh '*/jointed_blocks.geo' has no physical "
             "group \"jiont\" (did you mean \"joint\"?); available: \"corner\" (point), "
             "\"joint\" (curve), \"notch\" (curve), \"bottom\" (curve), \"top\" (curve), "
             "\"lower\" (surface), \"upper\" (surface)"},
        Case{"material = \"rock\"", "material = \"rock\"\nfracture_group = \"corner\"",
             "bad.toml:29:18: error: body \"blocks\": \"corner\" is a point physical group of "
             "mesh '*/jointed_blocks.geo', but fracture_group needs a surface group (joints on the "
             "internal edges between its triangles) or a curve group (joints on its edges); "
             "available:"},
        Case{"material = \"rock\"", "material = \"rock\"\nfracture_group = \"bottom\"",
             "bad.toml:29:18: error: body \"blocks\": the edge from (0, 0) to (0.125, 0) m of "
             "curve group \"bottom\" is on the boundary of body \"blocks\"; joints exist only on "
             "internal edges (between two triangles of the body)"},
        Case{"material = \"rock\"", "material = \"rock\"\nprebroken = [\"lower\"]",
             "bad.toml:29:14: error: body \"blocks\": \"lower\" is a surface physical group of "
             "mesh '*/jointed_blocks.geo', but prebroken needs curve groups (the edges broken at "
             "t = 0); available:"},
        Case{"material = \"rock\"", "material = \"rock\"\nprebroken = [\"notch\", \"nothc\"]",
             "bad.toml:29:23: error: body \"blocks\": mesh '*/jointed_blocks.geo' has no physical "
             "group \"nothc\" (did you mean \"notch\"?)"},
        Case{"material = \"rock\"", "material = \"rock\"\nprebroken = \"notch\"",
             "bad.toml:29:13: error: body \"blocks\": prebroken must be a non-empty list of curve "
             "group names, e.g. [\"notch\"], got \"notch\""},
        Case{"material = \"rock\"", "material = \"rock\"\nprebroken = []",
             "bad.toml:29:13: error: body \"blocks\": prebroken must be a non-empty list of curve "
             "group names, e.g. [\"notch\"], got []"},
        Case{"material = \"rock\"",
             "material = \"rock\"\nfracture_group = \"joint\"\nprebroken = [\"notch\"]", ""},
        Case{"material = \"rock\"", "material = \"rock\"\nfracture_group = \"upper\"", ""},
        Case{"fix = [\"x\", \"y\"]",
             "fix = [\"x\", \"y\"]\n\n[fracture]\ncrack_contact = \"pairs\"",
             "bad.toml:36:17: error: [fracture]: crack_contact = \"pairs\" (broken joints as "
             "node-pair contacts with a force ramp) is not implemented; only \"self\" is (crack "
             "faces meet by the smooth contact of the body with itself, rule X of "
             "docs/theory.md §9)"},
        Case{"fix = [\"x\", \"y\"]", "fix = [\"x\", \"y\"]\n\n[fracture]\nramp_steps = 10",
             "bad.toml:36:14: error: [fracture]: ramp_steps only applies with crack_contact = "
             "\"pairs\", which is not implemented; remove ramp_steps"},
        Case{"fix = [\"x\", \"y\"]",
             "fix = [\"x\", \"y\"]\n\n[fracture]\ncontact_targets = \"sector\"",
             "bad.toml:36:19: error: [fracture]: contact_targets = \"sector\" (one contact "
             "evaluation per logical vertex) is not implemented; only \"copies\" is (every node "
             "copy is a target with its own mass)"},
        Case{"fix = [\"x\", \"y\"]",
             "fix = [\"x\", \"y\"]\n\n[fracture]\noutput_joints = \"broken\"",
             "bad.toml:36:17: error: [fracture]: output_joints must be one of \"damaged\", "
             "\"all\", \"none\", got \"broken\""},
        Case{"fix = [\"x\", \"y\"]", "fix = [\"x\", \"y\"]\n\n[fracture]\nfragment = \"end\"",
             "bad.toml:36:1: error: [fracture]: unknown key 'fragment'; did you mean "
             "'fragments'?"},
        Case{"fix = [\"x\", \"y\"]", "fix = [\"x\", \"y\"]\n\n[fracture]\nfragments = 1",
             "bad.toml:36:13: error: [fracture]: fragments must be one of \"interval\", \"end\", "
             "got a number 1"},
        Case{"[simulation]", "fracture = 1\n[simulation]",
             "bad.toml:1:12: error: 'fracture' must be a table (write [fracture] on its own "
             "line), got a number 1"}),
    case_name);

TEST(FractureInput, GlobalTableWithoutFractureWarns) {
    const Scenario sc = load(edit("material = \"rock\"", "material = \"steel\"") +
                             "\n[fracture]\noutput_joints = \"all\"\n");
    ASSERT_EQ(sc.warnings.size(), 1u);
    EXPECT_EQ(sc.warnings[0],
              "bad.toml:35:1: warning: [fracture] is given but no body has fracture (no "
              "material with [material.fracture] is used by a body that is not fixed); it has no "
              "effect");
}

}  // namespace
}  // namespace fdem
