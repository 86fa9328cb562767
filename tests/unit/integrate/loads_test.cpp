// Load kernels (integrate/loads.cpp, docs/theory.md eqs. 4.5-4.8): time functions, the nodal
// forces of traction, follower pressure and point forces, and their power.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "fdem/scenario.hpp"
#include "fdem/simulate.hpp"
#include "integrate/loads.hpp"

namespace fdem {
namespace {

TEST(TimeFunction, ConstantRampAndTable) {
    TimeFunction c;
    EXPECT_EQ(c.at(-1.0), 1.0);
    EXPECT_EQ(c.at(7.0), 1.0);

    TimeFunction r;
    r.kind = TimeFunction::Kind::Ramp;
    r.ramp_time = 0.5;
    EXPECT_EQ(r.at(0.0), 0.0);
    EXPECT_EQ(r.at(-0.1), 0.0);
    EXPECT_DOUBLE_EQ(r.at(0.125), 0.25);
    EXPECT_EQ(r.at(0.5), 1.0);
    EXPECT_EQ(r.at(3.0), 1.0);

    TimeFunction t;
    t.kind = TimeFunction::Kind::Table;
    t.table = {{0.1, 2.0}, {0.2, -1.0}, {0.4, 0.0}};
    EXPECT_EQ(t.at(0.0), 2.0);  // held before the first point
    EXPECT_EQ(t.at(0.1), 2.0);
    EXPECT_DOUBLE_EQ(t.at(0.15), 0.5);
    EXPECT_EQ(t.at(0.2), -1.0);
    EXPECT_DOUBLE_EQ(t.at(0.3), -0.5);
    EXPECT_EQ(t.at(0.4), 0.0);
    EXPECT_EQ(t.at(9.0), 0.0);  // held after the last

    TimeFunction one;
    one.kind = TimeFunction::Kind::Table;
    one.table = {{0.3, 4.0}};
    EXPECT_EQ(one.at(0.0), 4.0);
    EXPECT_EQ(one.at(1.0), 4.0);
}

// The unit square of tests/data/square_41_ascii.msh with one load on `group`.
Scenario square_with(const std::string& load, const std::string& mesh = "square_41_ascii.msh") {
    return load_scenario_from_string(R"([simulation]
end_time = 0.01
dt = 1e-6
[[material]]
name = "m"
density = 1000.0
youngs_modulus = 1e9
poisson_ratio = 0.25
[[body]]
name = "sq"
mesh = ")" + mesh + R"("
material = "m"
[[load]]
body = "sq"
)" + load + "\n",
                                     "loads.toml", FDEM_TEST_DATA_DIR);
}

std::vector<Vec2> load_forces(const Model& m, const std::vector<Vec2>& x, Real t) {
    size_t slots = 0;
    for (const Load& ld : m.loads)
        slots += static_cast<size_t>(ld.num_slots());
    std::vector<Vec2> slot_f(slots), f(static_cast<size_t>(m.num_nodes()));
    evaluate_loads(m, t, x.data(), slot_f.data());
    add_load_forces(m, slot_f.data(), f.data());
    return f;
}

// A positive pressure on both sides of the square pushes each side inward with p times its
// length, half of an edge's share on each of its nodes; the corners get half an edge.
TEST(LoadKernels, PressurePushesInwardWithItsEdgeLength) {
    const Scenario sc = square_with("group = \"sides\"\npressure = 3.0");
    const Model& m = sc.model;
    const std::vector<Vec2> f = load_forces(m, m.node_x0, 0.0);
    Vec2 left{0, 0}, right{0, 0};
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        const Vec2 p = m.node_x0[i];
        if (p.x < 1e-12)
            left += f[i];
        else if (p.x > 1 - 1e-12)
            right += f[i];
        else
            EXPECT_EQ(norm(f[i]), 0.0) << "interior node " << i;
    }
    EXPECT_NEAR(left.x, 3.0, 1e-12);
    EXPECT_NEAR(right.x, -3.0, 1e-12);
    EXPECT_NEAR(left.y, 0.0, 1e-12);
    EXPECT_NEAR(right.y, 0.0, 1e-12);
}

// On a mesh of 6-node triangles (composite elements) a 3-node line is loaded as its two halves,
// the boundary edges of the sub-triangles: the side still gets p times its length, and its
// mid-edge nodes carry a share.
TEST(LoadKernels, PressureOnSecondOrderLinesLoadsTheHalfEdges) {
    const Scenario sc = square_with("group = \"right\"\npressure = 3.0", "square_order2_41.msh");
    const Model& m = sc.model;
    ASSERT_EQ(m.bodies[0].element, ElementKind::Composite6);
    const std::vector<Vec2> f = load_forces(m, m.node_x0, 0.0);
    Vec2 right{0, 0};
    int loaded = 0;
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        if (m.node_x0[i].x > 1 - 1e-12) {
            right += f[i];
            loaded += f[i].x < 0;
        }
    }
    EXPECT_NEAR(right.x, -3.0, 1e-12);
    EXPECT_NEAR(right.y, 0.0, 1e-12);
    EXPECT_EQ(static_cast<size_t>(loaded), m.loads[0].edges.size() + 1);
}

// A body of more than kRenumberMinTris triangles is renumbered in space (model/renumber.cpp)
// after the loads are read: their edges must follow. Every loaded node of the ring's outer rim
// gets an inward radial force, and the forces add up to p times the rim's length.
TEST(LoadKernels, EdgesFollowTheSpatialRenumbering) {
    const Scenario sc = load_scenario_from_string(R"([simulation]
end_time = 0.01
dt = 1e-6
[[material]]
name = "m"
density = 1000.0
youngs_modulus = 1e9
poisson_ratio = 0.25
[[body]]
name = "ring"
mesh = "ring.geo"
mesh_size = 0.03
material = "m"
[[load]]
body = "ring"
group = "outer"
pressure = 2.0
)",
                                                  "ring.toml", FDEM_TEST_DATA_DIR);
    const Model& m = sc.model;
    ASSERT_GE(m.num_tris(), 4096);  // renumbered (model/renumber.hpp kRenumberMinTris)
    const std::vector<Vec2> f = load_forces(m, m.node_x0, 0.0);
    Real sum = 0, length = 0;
    for (Real l : m.loads[0].edge_length0)
        length += l;
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        const Real r = norm(m.node_x0[i]);
        if (norm(f[i]) == 0) continue;
        EXPECT_NEAR(r, 1.0, 1e-9) << "node " << i;
        EXPECT_LT(dot(f[i], m.node_x0[i]) / r, -0.999 * norm(f[i])) << "node " << i;
        sum += norm(f[i]);
    }
    EXPECT_NEAR(sum, 2.0 * length, 1e-3 * length);
    EXPECT_NEAR(length, 2 * M_PI, 0.01);
}

// Follower: the pressure turns with the edge. Rotating the square by 90 degrees turns the force
// on the (former) right side from -x to -y; the dead traction does not turn.
TEST(LoadKernels, PressureFollowsTheCurrentEdgeTractionDoesNot) {
    for (const bool follower : {true, false}) {
        const Scenario sc = square_with(follower ? "group = \"right\"\npressure = 2.0"
                                                 : "group = \"right\"\ntraction = [-2.0, 0.0]");
        const Model& m = sc.model;
        std::vector<Vec2> x = m.node_x0;
        for (Vec2& p : x)
            p = perp(p);  // +90 degrees about the origin
        const std::vector<Vec2> f = load_forces(m, x, 0.0);
        Vec2 sum{0, 0};
        for (const Vec2& fi : f)
            sum += fi;
        EXPECT_NEAR(sum.x, follower ? 0.0 : -2.0, 1e-12);
        EXPECT_NEAR(sum.y, follower ? -2.0 : 0.0, 1e-12);
    }
}

// A point force is split equally over the nodes of its group and scaled by its time function;
// its power is F . v.
TEST(LoadKernels, PointForceSharesAndPower) {
    const Scenario sc = square_with(
        "group = \"origin\"\nforce = [4.0, -2.0]\ntime_function = \"table\"\n"
        "table = [[0, 0], [1, 1]]");
    const Model& m = sc.model;
    ASSERT_EQ(m.loads[0].nodes.size(), 1u);
    const NodeId n = m.loads[0].nodes[0];
    EXPECT_EQ(m.node_x0[n].x, 0.0);
    EXPECT_EQ(m.node_x0[n].y, 0.0);
    const std::vector<Vec2> f = load_forces(m, m.node_x0, 0.25);
    EXPECT_DOUBLE_EQ(f[n].x, 1.0);
    EXPECT_DOUBLE_EQ(f[n].y, -0.5);
    std::vector<Vec2> slot_f(1), v(static_cast<size_t>(m.num_nodes()), Vec2{1.0, 3.0});
    evaluate_loads(m, 0.25, m.node_x0.data(), slot_f.data());
    EXPECT_DOUBLE_EQ(load_power(m, slot_f.data(), v.data()), 1.0 - 1.5);
}

// On a fully jointed body a mesh vertex has one node copy per triangle around it. A point force
// acts on the vertex as a whole: F / (number of vertices) per vertex, split over its copies by
// mass (theory eq. 4.11), so all copies of a vertex get the same acceleration. (Before, the
// force went to one copy per vertex only and the others got nothing.)
TEST(LoadKernels, PointForceOnJointedVerticesActsOnEveryCopy) {
    const Scenario sc = load_scenario_from_string(R"([simulation]
end_time = 0.01
dt = 1e-7
[[material]]
name = "m"
density = 1000.0
youngs_modulus = 1e9
poisson_ratio = 0.25
[material.fracture]
tensile_strength = 1e6
cohesion = 2e6
friction_angle = 30.0
fracture_energy_I = 1000.0
fracture_energy_II = 2000.0
penalty = 1e10
[[body]]
name = "sq"
mesh = "square_41_ascii.msh"
material = "m"
[[load]]
body = "sq"
group = "bottom"
force = [4.0, -2.0]
)",
                                                  "loads.toml", FDEM_TEST_DATA_DIR);
    const Model& m = sc.model;
    ASSERT_EQ(m.node_vertex.size(), static_cast<size_t>(m.num_nodes()));
    const Load& ld = m.loads[0];
    // the vertices of the bottom edge (y = 0) and all their copies
    std::map<NodeId, std::vector<NodeId>> copies;
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        if (m.node_x0[i].y == 0.0) copies[m.node_vertex[static_cast<size_t>(i)]].push_back(i);
    }
    size_t n_copies = 0, shared = 0;
    for (const auto& [v, c] : copies) {
        n_copies += c.size();
        shared += c.size() > 1 ? 1 : 0;
    }
    ASSERT_GT(shared, 0u);  // some bottom vertices have several copies
    EXPECT_EQ(ld.nodes.size(), n_copies);
    const std::vector<Vec2> f = load_forces(m, m.node_x0, 0.0);
    const Real nv = static_cast<Real>(copies.size());
    Vec2 total{0, 0};
    for (const auto& [v, c] : copies) {
        Vec2 fv{0, 0};
        for (const NodeId i : c) {
            fv += f[i];
            // the same acceleration F / (N_v M_v) for every copy of the vertex
            Real mv = 0;
            for (const NodeId j : c)
                mv += m.node_mass[j];
            EXPECT_NEAR(f[i].x / m.node_mass[i], 4.0 / (nv * mv), 1e-12 * 4.0 / (nv * mv));
            EXPECT_NEAR(f[i].y / m.node_mass[i], -2.0 / (nv * mv), 1e-12 * 2.0 / (nv * mv));
        }
        EXPECT_NEAR(fv.x, 4.0 / nv, 1e-14);
        EXPECT_NEAR(fv.y, -2.0 / nv, 1e-14);
        total += fv;
    }
    EXPECT_NEAR(total.x, 4.0, 1e-13);
    EXPECT_NEAR(total.y, -2.0, 1e-13);
    // its power is F_i . v_i summed over the copies
    std::vector<Vec2> slot_f(static_cast<size_t>(ld.num_slots()));
    std::vector<Vec2> v(static_cast<size_t>(m.num_nodes()), Vec2{1.0, 3.0});
    evaluate_loads(m, 0.0, m.node_x0.data(), slot_f.data());
    EXPECT_NEAR(load_power(m, slot_f.data(), v.data()), 4.0 - 6.0, 1e-13);
}

// A run without [[load]] is untouched; with loads the step is deterministic and allocates no
// load scratch after make_state (the same buffer is reused).
TEST(LoadKernels, StepReusesTheLoadScratch) {
    const Scenario sc = square_with("group = \"top\"\ntraction = [0.0, -1e5]");
    const Model& m = sc.model;
    State s = make_state(m, 1e-6);
    const Vec2* buf = s.scratch_load.data();
    ASSERT_EQ(s.scratch_load.size(), m.loads[0].edges.size());
    for (int k = 0; k < 10; ++k)
        step(m, s);
    EXPECT_EQ(s.scratch_load.data(), buf);
    Vec2 p{0, 0};
    for (NodeId i = 0; i < m.num_nodes(); ++i)
        p += m.node_mass[i] * s.v[i];
    // impulse of the resultant -1e5 N/m over 9.5 steps (the first is a half step)
    EXPECT_NEAR(p.y, -1e5 * 9.5e-6, 1e-9);
}

}  // namespace
}  // namespace fdem
