// A valid scenario builds the expected model: bodies, nodes, materials, BCs, contact, dt.
// Mesh: tests/data/block_on_base.geo (block [0.5, 1] x [0.21, 0.71] above base [0, 2] x [0, 0.2]).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "fdem/build.hpp"
#include "fdem/mesh.hpp"
#include "fdem/scenario.hpp"

namespace fdem {
namespace {

const std::string kData = FDEM_TEST_DATA_DIR;

const char* kGood = R"(# block on a base, both from one .geo
[simulation]
end_time = 0.02              # s
dt = "auto"
dt_fraction = 0.4
gravity = [0.0, -9.81]       # m/s^2

[output]
interval = 0.001
dir = "results"
vtu = false

[[material]]
name = "steel"
density = 7800.0
youngs_modulus = 2.0e11
poisson_ratio = 0.3

[[material]]
name = "rubber"
density = 1100
youngs_modulus = 1e7
poisson_ratio = 0.45
plane = "stress"
viscosity = 10.0

[[body]]
name = "base"
mesh = "block_on_base.geo"
mesh_size = 0.1
group = "base"
material = "steel"
fixed = true

[[body]]
name = "block"
mesh = "block_on_base.geo"
mesh_size = 0.1
group = "block"
material = "rubber"
velocity = [0.5, -1.0]

[[boundary]]
body = "base"
group = "base_bottom"
fix = ["x", "y"]

[[boundary]]
body = "block"
group = "block_top"
velocity = [0.25, 0]
components = ["x"]
start = 0.001
end = 0.005

[[kick]]
body = "block"
time = 0.01
velocity = [0, 0]
components = ["y"]

[damping]
mass_proportional = 5.0
until = 0.002

[contact]
algorithm = "smooth"
penalty = 5e9
friction = 0.3

[[contact.pair]]
materials = ["rubber", "steel"]
friction = 0.8
)";

TEST(LoadScenario, GoodScenarioBuildsTheModel) {
    const Scenario sc = load_scenario_from_string(kGood, "good.toml", kData);
    const Model& m = sc.model;

    // run settings
    EXPECT_EQ(sc.run.end_time, 0.02);
    EXPECT_TRUE(sc.run.dt_auto);
    EXPECT_EQ(sc.run.dt_fraction, 0.4);
    EXPECT_EQ(sc.run.output.interval, 0.001);
    EXPECT_EQ(sc.run.output.dir, "results");
    EXPECT_FALSE(sc.run.output.vtu);
    EXPECT_EQ(m.gravity, (Vec2{0.0, -9.81}));

    // materials and their Lame constants (theory eq. 2.5; 1e-12 relative: a few roundings)
    ASSERT_EQ(m.materials.size(), 2u);
    const Material& steel = m.materials[0];
    const Material& rubber = m.materials[1];
    EXPECT_EQ(steel.name, "steel");
    EXPECT_EQ(steel.plane, PlaneMode::Strain);
    const double E = 2.0e11, nu = 0.3;
    EXPECT_NEAR(steel.mu, E / (2 * (1 + nu)), 1e-12 * E);
    EXPECT_NEAR(steel.lambda, E * nu / ((1 + nu) * (1 - 2 * nu)), 1e-12 * E);
    EXPECT_EQ(rubber.plane, PlaneMode::Stress);
    EXPECT_EQ(rubber.viscosity, 10.0);
    const double Er = 1e7, nur = 0.45;
    EXPECT_NEAR(rubber.mu, Er / (2 * (1 + nur)), 1e-12 * Er);
    EXPECT_NEAR(rubber.lambda, Er * nur / (1 - nur * nur), 1e-12 * Er);  // plane stress

    // bodies: one connected component per entry, in file order
    ASSERT_EQ(m.num_bodies(), 2);
    EXPECT_EQ(m.group_names, (std::vector<std::string>{"base", "block"}));
    EXPECT_EQ(m.bodies[0].name, "base");
    EXPECT_TRUE(m.bodies[0].fixed);
    EXPECT_EQ(m.bodies[0].material, 0);
    EXPECT_EQ(m.bodies[1].group, 1);
    EXPECT_EQ(m.bodies[1].material, 1);
    EXPECT_FALSE(m.bodies[1].fixed);

    // node and triangle counts match the mesh's physical groups
    const MeshData mesh = read_mesh(kData + "/block_on_base.geo", 0.1);
    int32_t tri_total = 0, node_total = 0;
    for (const PhysicalGroup& g : mesh.groups) {
        if (g.dim == 2) {
            tri_total += static_cast<int32_t>(g.elements.size());
            node_total += static_cast<int32_t>(mesh.group_nodes(g).size());
        }
    }
    EXPECT_EQ(m.num_tris(), tri_total);
    EXPECT_EQ(m.num_nodes(), node_total);

    // areas: 2 x 0.2 and 0.5 x 0.5 (1e-12: sums of O(100) rounded products)
    double area[2] = {0, 0};
    for (TriId t = 0; t < m.num_tris(); ++t) {
        area[m.tri_body[t]] += m.tri_area0[t];
        EXPECT_GT(m.tri_area0[t], 0.0);
    }
    EXPECT_NEAR(area[0], 0.4, 1e-12);
    EXPECT_NEAR(area[1], 0.25, 1e-12);

    // initial velocity only on the block
    for (NodeId n = m.bodies[1].node_begin; n < m.bodies[1].node_end; ++n) {
        EXPECT_EQ(m.node_v0[n], (Vec2{0.5, -1.0}));
    }
    for (NodeId n = m.bodies[0].node_begin; n < m.bodies[0].node_end; ++n) {
        EXPECT_EQ(m.node_v0[n], (Vec2{0, 0}));
    }

    // BCs: a side of length L meshed at 0.1 m has L / 0.1 segments, L / 0.1 + 1 nodes
    ASSERT_EQ(m.bcs.size(), 2u);
    EXPECT_EQ(m.bcs[0].nodes.size(), 21u);  // base bottom, 2 m
    EXPECT_TRUE(m.bcs[0].has_x && m.bcs[0].has_y);
    EXPECT_EQ(m.bcs[0].velocity, (Vec2{0, 0}));
    for (NodeId n : m.bcs[0].nodes) {
        EXPECT_EQ(m.node_x0[n].y, 0.0);
        EXPECT_EQ(m.node_body[n], 0);
    }
    EXPECT_EQ(m.bcs[1].nodes.size(), 6u);  // block top, 0.5 m
    EXPECT_TRUE(m.bcs[1].has_x);
    EXPECT_FALSE(m.bcs[1].has_y);
    EXPECT_EQ(m.bcs[1].velocity.x, 0.25);
    EXPECT_EQ(m.bcs[1].start, 0.001);
    EXPECT_EQ(m.bcs[1].end, 0.005);
    for (NodeId n : m.bcs[1].nodes) {
        EXPECT_EQ(m.node_x0[n].y, 0.71);
        EXPECT_EQ(m.node_body[n], 1);
    }

    // kick, damping, contact
    ASSERT_EQ(m.kicks.size(), 1u);
    EXPECT_EQ(m.kicks[0].group, 1);
    EXPECT_FALSE(m.kicks[0].has_x);
    EXPECT_TRUE(m.kicks[0].has_y);
    EXPECT_EQ(m.mass_damping.coefficient, 5.0);
    EXPECT_EQ(m.mass_damping.until, 0.002);
    EXPECT_EQ(m.contact.algorithm, ContactAlgorithm::Smooth);
    EXPECT_EQ(m.contact.params.penalty, 5e9);
    EXPECT_EQ(m.contact.params.friction, 0.3);
    ASSERT_EQ(m.contact.pair_overrides.size(), 2u);             // only the pair set, in both orders
    EXPECT_EQ(pair_parameters(m.contact, 0, 0).friction, 0.3);  // steel-steel: default
    EXPECT_EQ(pair_parameters(m.contact, 0, 1).friction, 0.8);  // symmetric override
    EXPECT_EQ(pair_parameters(m.contact, 1, 0).friction, 0.8);
    EXPECT_EQ(pair_parameters(m.contact, 1, 0).penalty, 5e9);  // inherited

    // dt = "auto": dt_fraction times the model's stable limit, and that limit is below the
    // plane-stress wave transit time over the shortest edge of the moving block (a CST cannot
    // be stable beyond it: its highest mode is faster than the continuum wave)
    EXPECT_EQ(sc.run.stable_dt, stable_time_step(m));
    EXPECT_EQ(sc.run.dt, 0.4 * sc.run.stable_dt);
    double shortest = 1e9;
    for (TriId t = m.bodies[1].tri_begin; t < m.bodies[1].tri_end; ++t) {
        const auto& n = m.tri_nodes[t];
        for (int k = 0; k < 3; ++k) {
            shortest = std::min(shortest, norm(m.node_x0[n[k]] - m.node_x0[n[(k + 1) % 3]]));
        }
    }
    const double c_p = std::sqrt(Er / (1100 * (1 - nur * nur)));
    EXPECT_LT(sc.run.stable_dt, shortest / c_p);
    EXPECT_GT(sc.run.stable_dt, 0.0);
}

TEST(LoadScenario, FromFileResolvesMeshesBesideTheScenario) {
    const std::string dir = ::testing::TempDir() + "/fdem_scenario_dir";
    std::filesystem::create_directories(dir);
    std::filesystem::copy_file(kData + "/square_41_bin.msh", dir + "/square.msh",
                               std::filesystem::copy_options::overwrite_existing);
    std::ofstream(dir + "/s.toml") << R"(
[simulation]
end_time = 1e-3
dt = 1e-7
[[material]]
name = "m"
density = 1000
youngs_modulus = 1e6
poisson_ratio = 0
[[body]]
name = "sq"
mesh = "square.msh"
material = "m"
)";
    const Scenario sc = load_scenario(dir + "/s.toml");
    EXPECT_EQ(sc.path, dir + "/s.toml");
    EXPECT_EQ(sc.model.num_bodies(), 1);
    EXPECT_EQ(sc.run.dt, 1e-7);
    EXPECT_FALSE(sc.run.dt_auto);
    EXPECT_EQ(sc.model.contact.algorithm, ContactAlgorithm::None);
    double area = 0;
    for (const Real a : sc.model.tri_area0) {
        area += a;
    }
    EXPECT_NEAR(area, 1.0, 1e-12);        // unit square; 1e-12: sum of O(10) rounded products
    EXPECT_EQ(sc.run.output.dir, "out");  // documented default
}

TEST(LoadScenario, SameMeshFileIsSplitIntoComponents) {
    // no group: every triangle of the .geo, two connected components -> with pieces =
    // "separate" two bodies, one entry (without it: an input error, tests/input/io/pieces_test)
    const Scenario sc = load_scenario_from_string(R"(
[simulation]
end_time = 1e-3
dt = "auto"
[[material]]
name = "m"
density = 1000
youngs_modulus = 1e6
poisson_ratio = 0.2
[[body]]
name = "both"
mesh = "block_on_base.geo"
mesh_size = 0.1
material = "m"
pieces = "separate"
[[boundary]]
body = "both"
group = "block_corner"
fix = ["y"]
)",
                                                  "inline.toml", kData);
    ASSERT_EQ(sc.model.num_bodies(), 2);
    EXPECT_EQ(sc.model.bodies[0].group, 0);
    EXPECT_EQ(sc.model.bodies[1].group, 0);
    EXPECT_EQ(sc.model.group_names.size(), 1u);
    ASSERT_EQ(sc.model.bcs.size(), 1u);
    ASSERT_EQ(sc.model.bcs[0].nodes.size(), 1u);
    EXPECT_EQ(sc.model.node_x0[sc.model.bcs[0].nodes[0]], (Vec2{0.5, 0.21}));
}

// Meshes given in memory (the Python ModelBuilder's path, docs/python.md): a [[body]] whose mesh
// names one takes it instead of a file, and the model equals the one built from the same mesh
// by add_bodies directly.
const char* kMemory = R"(
[simulation]
end_time = 0.1
dt = "auto"
[[material]]
name = "m"
density = 1000
youngs_modulus = 1e6
poisson_ratio = 0.2
[[body]]
name = "bar"
mesh = "<bar>"
material = "m"
[[boundary]]
body = "bar"
group = "left"
fix = ["x", "y"]
)";

TEST(LoadScenario, MeshGivenInMemory) {
    MeshStore meshes;
    meshes["<bar>"] = make_rectangle_mesh(0, 0, 1, 0.2, 5, 2);
    const Scenario sc = load_scenario_from_string(kMemory, "memory.toml", kData, &meshes);
    ASSERT_EQ(sc.model.num_bodies(), 1);
    EXPECT_EQ(sc.model.num_tris(), 20);
    EXPECT_EQ(sc.model.num_nodes(), 18);
    ASSERT_EQ(sc.model.bcs.size(), 1u);
    EXPECT_EQ(sc.model.bcs[0].nodes.size(), 3u);  // the left edge: 3 nodes
    for (NodeId i : sc.model.bcs[0].nodes)
        EXPECT_EQ(sc.model.node_x0[i].x, 0.0);
}

TEST(LoadScenario, MeshInMemoryRefusesGeoKeys) {
    MeshStore meshes;
    meshes["<bar>"] = make_rectangle_mesh(0, 0, 1, 0.2, 5, 2);
    std::string text = kMemory;
    text.replace(text.find("material = \"m\"\n[[boundary]]"), 0, "mesh_size = 0.1\n");
    try {
        (void)load_scenario_from_string(text, "memory.toml", kData, &meshes);
        FAIL() << "expected an InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(e.location().line, 13);  // the mesh_size line
        EXPECT_NE(std::string(e.what()).find("mesh_size only applies to .geo files (mesh "
                                             "\"<bar>\" is given in memory, already meshed)"),
                  std::string::npos)
            << e.what();
    }
}

TEST(LoadScenario, NameNotInMemoryIsAFilePath) {
    MeshStore meshes;
    meshes["<other>"] = make_rectangle_mesh(0, 0, 1, 0.2, 5, 2);
    try {
        (void)load_scenario_from_string(kMemory, "memory.toml", kData, &meshes);
        FAIL() << "expected an InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(e.key(), "body[0].mesh") << e.what();
        EXPECT_NE(std::string(e.what()).find("mesh must be a Gmsh .msh or .geo file"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace fdem

namespace fdem {
namespace {

TEST(LoadScenario, DocumentedExampleIsValid) {
    // the annotated example of docs/scenario.md (first ```toml block) must load as documented;
    // its mesh block_on_base.geo lives in tests/data
    std::ifstream in(std::string(FDEM_SOURCE_DIR) + "/docs/scenario.md");
    const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t begin = doc.find("```toml\n");
    ASSERT_NE(begin, std::string::npos);
    const size_t end = doc.find("```", begin + 8);
    const std::string text = doc.substr(begin + 8, end - begin - 8);
    const Scenario sc = load_scenario_from_string(text, "docs/scenario.md", kData);
    EXPECT_EQ(sc.model.num_bodies(), 2);
    EXPECT_EQ(sc.model.materials.size(), 2u);
    EXPECT_EQ(sc.model.bcs.size(), 1u);
    EXPECT_EQ(sc.model.kicks.size(), 1u);
    EXPECT_EQ(sc.model.contact.algorithm, ContactAlgorithm::Smooth);
    EXPECT_EQ(sc.run.output.dir, "out/block_on_base");
    EXPECT_TRUE(sc.run.dt_auto);
}

}  // namespace
}  // namespace fdem

namespace fdem {
namespace {

// A [[probe]] group is looked up after finalize_model(), which renumbers the nodes of a body of
// >= 4096 triangles (kRenumberMinTris): the probe must still get the group's nodes (before the
// fix the "tip" probe of this 9326-triangle bar sat at (0.0225, 0.078) instead of (1, 0.05)).
TEST(LoadScenario, ProbeGroupOnARenumberedBody) {
    const std::string text = R"(
[simulation]
end_time = 2e-4
dt = "auto"
[[material]]
name = "m"
density = 1000
youngs_modulus = 1e6
poisson_ratio = 0.2
[[body]]
name = "bar"
mesh = "loaded_bar.geo"
mesh_size = 0.005
material = "m"
[[probe]]
name = "tip"
body = "bar"
group = "tip"
[[probe]]
name = "left"
body = "bar"
group = "left"
)";
    const Scenario sc = load_scenario_from_string(text, "probe.toml", kData);
    ASSERT_GE(sc.model.num_tris(), 4096);  // renumbered
    ASSERT_EQ(sc.run.output.probes.size(), 2u);
    const ProbeSpec& tip = sc.run.output.probes[0];
    ASSERT_EQ(tip.nodes.size(), 1u);
    EXPECT_EQ(sc.model.node_x0[static_cast<size_t>(tip.nodes[0])].x, 1.0);
    EXPECT_EQ(sc.model.node_x0[static_cast<size_t>(tip.nodes[0])].y, 0.05);
    const ProbeSpec& left = sc.run.output.probes[1];
    ASSERT_GE(left.nodes.size(), 20u);  // 0.1 m at mesh_size 0.005
    for (const NodeId n : left.nodes)
        EXPECT_EQ(sc.model.node_x0[static_cast<size_t>(n)].x, 0.0) << n;
}

}  // namespace
}  // namespace fdem
