// Jointed bodies in the model build (src/fdem/model/build_model.cpp, BodyOptions::fracture,
// spec fracture.md §1.2, docs/theory.md §9): node copies per fan run, joints on the jointed
// edges, Model::node_vertex, laws and the h_max check of finalize_model(), the renumbering of
// large bodies.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>
#include <set>

#include "element/cst.hpp"
#include "fdem/build.hpp"
#include "fdem/error.hpp"
#include "fracture/joints.hpp"
#include "model/renumber.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

JointMaterial joint_material() {
    JointMaterial jm;
    jm.tensile_strength = 1e6;
    jm.cohesion = 2e6;
    jm.friction_angle = 0.5;
    jm.fracture_energy_I = 100;
    jm.fracture_energy_II = 200;
    jm.penalty = 1e10;
    jm.shear_penalty = 1e10;
    return jm;
}

Model jointed_material() {
    Model m;
    Material mat = scenes::paper_material("rock", 1e9, 0.25, 2700);
    mat.has_fracture = true;
    mat.fracture = joint_material();
    m.materials.push_back(mat);
    return m;
}

std::vector<int32_t> all_tris(const MeshData& mesh) {
    std::vector<int32_t> t(mesh.tris.size());
    std::iota(t.begin(), t.end(), 0);
    return t;
}

BodyOptions fracture_options() {
    BodyOptions opt;
    opt.name = "rock";
    opt.fracture = true;
    return opt;
}

Real total_mass(const Model& m) {
    return std::accumulate(m.node_mass.begin(), m.node_mass.end(), Real(0));
}

// the joint's faces coincide in the reference state: 0 faces 3, 1 faces 2 (theory eq. 9.1),
// and every copy sits where its vertex's representative does
void expect_consistent(const Model& m) {
    ASSERT_EQ(m.node_vertex.size(), static_cast<size_t>(m.num_nodes()));
    for (NodeId n = 0; n < m.num_nodes(); ++n) {
        const NodeId r = m.node_vertex[static_cast<size_t>(n)];
        ASSERT_LE(r, n);
        EXPECT_EQ(m.node_vertex[static_cast<size_t>(r)], r);
        EXPECT_EQ(m.node_x0[static_cast<size_t>(r)].x, m.node_x0[static_cast<size_t>(n)].x);
        EXPECT_EQ(m.node_x0[static_cast<size_t>(r)].y, m.node_x0[static_cast<size_t>(n)].y);
    }
    for (int32_t j = 0; j < m.joints.num_joints(); ++j) {
        const auto& n = m.joints.nodes[static_cast<size_t>(j)];
        const auto X = [&](int k) {
            return m.node_x0[static_cast<size_t>(n[static_cast<size_t>(k)])];
        };
        EXPECT_EQ(X(0).x, X(3).x);
        EXPECT_EQ(X(0).y, X(3).y);
        EXPECT_EQ(X(1).x, X(2).x);
        EXPECT_EQ(X(1).y, X(2).y);
        EXPECT_NEAR(m.joints.length0[static_cast<size_t>(j)], norm(X(1) - X(0)), 1e-15);
        // both sides are copies of the same two vertices, on different triangles' nodes
        EXPECT_EQ(m.node_vertex[static_cast<size_t>(n[0])],
                  m.node_vertex[static_cast<size_t>(n[3])]);
        EXPECT_EQ(m.node_vertex[static_cast<size_t>(n[1])],
                  m.node_vertex[static_cast<size_t>(n[2])]);
    }
}

// Every internal edge jointed: each triangle has its own three nodes, one joint per internal
// edge, the same total mass as the unjointed body.
TEST(FractureBuild, FullyJointedRectangle) {
    const int nx = 4, ny = 3;
    const MeshData mesh = make_rectangle_mesh(0, 0, 1, 0.75, nx, ny);
    Model m = jointed_material();
    add_bodies(m, mesh, all_tris(mesh), fracture_options());
    finalize_model(m);
    EXPECT_EQ(m.num_bodies(), 1);
    EXPECT_TRUE(m.bodies[0].fracture);
    EXPECT_EQ(m.num_nodes(), 3 * m.num_tris());
    const int edges = nx * (ny + 1) + ny * (nx + 1) + nx * ny;
    const int boundary = 2 * (nx + ny);
    EXPECT_EQ(m.joints.num_joints(), edges - boundary);
    expect_consistent(m);
    ASSERT_EQ(m.joints.laws.size(), 1u);
    EXPECT_EQ(m.joints.laws[0].ft, 1e6);
    EXPECT_EQ(m.joints.gather_begin.size(), m.joints.gather_node.size() + 1);

    Model plain = jointed_material();
    add_bodies(plain, mesh, all_tris(mesh), [] {
        BodyOptions o;
        o.name = "rock";
        return o;
    }());
    finalize_model(plain);
    EXPECT_TRUE(plain.node_vertex.empty());
    EXPECT_TRUE(plain.joints.nodes.empty());
    EXPECT_NEAR(total_mass(m), total_mass(plain), 1e-12 * total_mass(plain));
    EXPECT_NEAR(total_mass(m), 2700 * 0.75, 1e-9);
}

// fracture_tris: only the edges between two triangles of the region are jointed; vertices
// outside it keep one node.
TEST(FractureBuild, RegionOnly) {
    const int nx = 6, ny = 2;
    const MeshData mesh = make_rectangle_mesh(0, 0, 1.2, 0.4, nx, ny);
    BodyOptions opt = fracture_options();
    std::set<int32_t> region;
    for (int32_t t = 0; t < static_cast<int32_t>(mesh.tris.size()); ++t) {
        const auto& n = mesh.tris[static_cast<size_t>(t)];
        const Real cx = (mesh.nodes[n[0]].x + mesh.nodes[n[1]].x + mesh.nodes[n[2]].x) / 3;
        if (cx < 0.4) region.insert(t);  // the two left columns of cells
    }
    opt.fracture_tris.assign(region.begin(), region.end());
    Model m = jointed_material();
    add_bodies(m, mesh, all_tris(mesh), opt);
    finalize_model(m);
    expect_consistent(m);
    // internal edges of the 2 x 2 cell block: 2 * 3 horizontal... counted directly
    std::set<std::pair<int32_t, int32_t>> seen, shared;
    for (int32_t t : region) {
        const auto& n = mesh.tris[static_cast<size_t>(t)];
        for (int k = 0; k < 3; ++k) {
            const auto e = std::minmax(n[k], n[(k + 1) % 3]);
            if (!seen.insert(e).second) shared.insert(e);
        }
    }
    EXPECT_EQ(m.joints.num_joints(), static_cast<int32_t>(shared.size()));
    for (int32_t j = 0; j < m.joints.num_joints(); ++j) {
        for (NodeId n : m.joints.nodes[static_cast<size_t>(j)])
            EXPECT_LE(m.node_x0[static_cast<size_t>(n)].x, 0.4 + 1e-12);
    }
    // vertices right of the region are not split
    for (NodeId n = 0; n < m.num_nodes(); ++n) {
        if (m.node_x0[static_cast<size_t>(n)].x > 0.45) {
            EXPECT_EQ(m.node_vertex[static_cast<size_t>(n)], n);
        }
    }
}

// joint_edges on a straight line across the body: one joint per edge of the line, every vertex
// of the line split in two, nothing else.
TEST(FractureBuild, JointEdgesOnALine) {
    const int nx = 5, ny = 4;
    const MeshData mesh = make_rectangle_mesh(0, 0, 1, 0.8, nx, ny, true);
    BodyOptions opt = fracture_options();
    for (int i = 0; i < nx; ++i)  // the line y = 0.4 (row j = 2 of nodes)
        opt.joint_edges.push_back({2 * (nx + 1) + i, 2 * (nx + 1) + i + 1});
    Model m = jointed_material();
    add_bodies(m, mesh, all_tris(mesh), opt);
    finalize_model(m);
    expect_consistent(m);
    EXPECT_EQ(m.joints.num_joints(), nx);
    EXPECT_EQ(m.num_nodes(), (nx + 1) * (ny + 1) + (nx + 1));
    for (int32_t j = 0; j < nx; ++j) {
        for (NodeId n : m.joints.nodes[static_cast<size_t>(j)])
            EXPECT_NEAR(m.node_x0[static_cast<size_t>(n)].y, 0.4, 1e-12);
        // A below or above, B the other side: all four nodes distinct
        const auto& n = m.joints.nodes[static_cast<size_t>(j)];
        EXPECT_EQ(std::set<NodeId>(n.begin(), n.end()).size(), 4u);
    }
    EXPECT_TRUE(m.prebroken_joints.empty());
}

// prebroken_edges are jointed and listed in Model::prebroken_joints
TEST(FractureBuild, PrebrokenEdges) {
    const int nx = 4, ny = 2;
    const MeshData mesh = make_rectangle_mesh(0, 0, 0.8, 0.4, nx, ny);
    BodyOptions opt = fracture_options();
    opt.joint_edges = {{0 + (nx + 1), 1 + (nx + 1)}, {1 + (nx + 1), 2 + (nx + 1)}};
    opt.prebroken_edges = {{2 + (nx + 1), 3 + (nx + 1)}};
    Model m = jointed_material();
    add_bodies(m, mesh, all_tris(mesh), opt);
    finalize_model(m);
    expect_consistent(m);
    ASSERT_EQ(m.joints.num_joints(), 3);
    ASSERT_EQ(m.prebroken_joints.size(), 1u);
    const auto& n = m.joints.nodes[static_cast<size_t>(m.prebroken_joints[0])];
    const Real xa = m.node_x0[static_cast<size_t>(n[0])].x,
               xb = m.node_x0[static_cast<size_t>(n[1])].x;
    EXPECT_NEAR(std::min(xa, xb), 0.4, 1e-12);
    EXPECT_NEAR(std::max(xa, xb), 0.6, 1e-12);
}

// A jointed body moved rigidly (rotation + translation) carries no joint forces.
TEST(FractureBuild, RigidMotionGivesNoJointForce) {
    const MeshData mesh = make_rectangle_mesh(0, 0, 1, 0.5, 6, 3, true);
    Model m = jointed_material();
    add_bodies(m, mesh, all_tris(mesh), fracture_options());
    finalize_model(m);
    JointState js = make_joint_state(m.joints);
    const Real c = std::cos(0.7), s = std::sin(0.7);
    std::vector<Vec2> x(static_cast<size_t>(m.num_nodes())), f(x.size());
    for (size_t i = 0; i < x.size(); ++i) {
        const Vec2 p = m.node_x0[i];
        x[i] = Vec2{c * p.x - s * p.y + 3.0, s * p.x + c * p.y - 2.0};
    }
    const JointPass pass = joint_forces(m.joints, js, x, f, true);
    Real fmax = 0;
    for (const Vec2& v : f)
        fmax = std::max(fmax, norm(v));
    // scale: the force of a joint opened to its peak, f_t h; rounding of x gives ~1e-16 of it
    EXPECT_LT(fmax, 1e-8 * 1e6 * 0.1);
    EXPECT_LT(std::abs(pass.elastic_energy), 1e-12);
    EXPECT_EQ(pass.newly_broken, 0);
}

// finalize_model: joints longer than h_max (theory eq. 9.14) are refused unless allowed, bad
// joint parameters name the material; composite bodies and materials without joint parameters
// are refused by add_bodies.
TEST(FractureBuild, Errors) {
    const MeshData coarse = make_rectangle_mesh(0, 0, 4, 2, 2, 1);  // joints up to 2.8 m
    {
        Model m = jointed_material();
        add_bodies(m, coarse, all_tris(coarse), fracture_options());
        try {
            finalize_model(m);
            FAIL() << "no error";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("h_max"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("rock"), std::string::npos) << e.what();
        }
    }
    {
        Model m = jointed_material();  // y-geo sets its own softening length: no h_max
        m.materials[0].fracture.softening_length = SofteningLength::YGeo;
        add_bodies(m, coarse, all_tris(coarse), fracture_options());
        EXPECT_NO_THROW(finalize_model(m));
    }
    {
        Model m = jointed_material();
        m.materials[0].fracture.allow_coarse = true;
        add_bodies(m, coarse, all_tris(coarse), fracture_options());
        EXPECT_NO_THROW(finalize_model(m));
    }
    {
        Model m = jointed_material();
        m.materials[0].fracture.tensile_strength = -1;
        const MeshData mesh = make_rectangle_mesh(0, 0, 1, 1, 2, 2);
        add_bodies(m, mesh, all_tris(mesh), fracture_options());
        try {
            finalize_model(m);
            FAIL() << "no error";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("rock"), std::string::npos) << e.what();
        }
    }
    {
        Model m = jointed_material();
        m.materials[0].has_fracture = false;
        const MeshData mesh = make_rectangle_mesh(0, 0, 1, 1, 2, 2);
        EXPECT_THROW(add_bodies(m, mesh, all_tris(mesh), fracture_options()), InputError);
    }
    {
        Model m = jointed_material();
        const MeshData mesh = make_rectangle_mesh_order2(0, 0, 1, 1, 2, 2);
        EXPECT_THROW(add_bodies(m, mesh, all_tris(mesh), fracture_options()), InputError);
        BodyOptions cst = fracture_options();
        // four plain CSTs per 6-node triangle: allowed, joints between the 6-node triangles
        cst.element = ElementKind::Cst;
        Model m2 = jointed_material();
        add_bodies(m2, mesh, all_tris(mesh), cst);
        finalize_model(m2);
        expect_consistent(m2);
        EXPECT_EQ(m2.num_nodes(), 6 * static_cast<int32_t>(mesh.tris.size()));
        EXPECT_EQ(m2.joints.num_joints(), 2 * 8);  // 8 internal edges of 2 half-edges each
    }
}

// A plain body added after a jointed one gets identity node_vertex entries; one before it too.
TEST(FractureBuild, MixedBodies) {
    const MeshData mesh = make_rectangle_mesh(0, 0, 1, 1, 3, 3);
    Model m = jointed_material();
    BodyOptions plain;
    plain.name = "plain";
    add_bodies(m, mesh, all_tris(mesh), plain);
    const NodeId n_plain = m.num_nodes();
    add_bodies(m, mesh, all_tris(mesh), fracture_options());
    add_bodies(m, mesh, all_tris(mesh), plain);
    finalize_model(m);
    expect_consistent(m);
    EXPECT_FALSE(m.bodies[0].fracture);
    EXPECT_TRUE(m.bodies[1].fracture);
    for (NodeId n = 0; n < n_plain; ++n)
        EXPECT_EQ(m.node_vertex[static_cast<size_t>(n)], n);
    for (NodeId n = m.bodies[2].node_begin; n < m.bodies[2].node_end; ++n)
        EXPECT_EQ(m.node_vertex[static_cast<size_t>(n)], n);
}

// Bodies of >= kRenumberMinTris triangles are renumbered along a Morton curve: the joints' node
// ids and node_vertex follow (faces still coincide, representatives are the smallest copies).
TEST(FractureBuild, RenumberedBodyKeepsJoints) {
    const int nx = 50, ny = 42;  // 4200 triangles
    ASSERT_GE(2 * nx * ny, kRenumberMinTris);
    const MeshData mesh = make_rectangle_mesh(0, 0, 1, 0.84, nx, ny);
    BodyOptions opt = fracture_options();
    opt.joint_edges.push_back({10 * (nx + 1) + 3, 10 * (nx + 1) + 4});
    for (int32_t t = 0; t < 600; ++t)
        opt.fracture_tris.push_back(t);
    Model m = jointed_material();
    add_bodies(m, mesh, all_tris(mesh), opt);
    const int32_t joints_before = m.joints.num_joints();
    std::vector<int32_t> node_new;
    finalize_model(m, node_new);
    bool moved = false;
    for (size_t i = 0; i < node_new.size(); ++i)
        moved = moved || node_new[i] != static_cast<int32_t>(i);
    EXPECT_TRUE(moved);
    EXPECT_EQ(m.joints.num_joints(), joints_before);
    expect_consistent(m);
    for (NodeId n = 0; n < m.num_nodes(); ++n) {  // smallest copy
        const NodeId r = m.node_vertex[static_cast<size_t>(n)];
        for (NodeId k = 0; k < r; ++k)
            ASSERT_NE(m.node_vertex[static_cast<size_t>(k)], r);
        if (n > 300) break;
    }
}

// After the spatial renumbering the joints follow it (ordered by node 0, whose ids follow the
// Morton curve: each chunk of kJointChunk joints lies in one region, docs/parallel.md "Joints";
// in the mesh's triangle order they are not sorted by the new ids), and a pre-broken joint is
// still the one on its edge.
TEST(FractureBuild, RenumberedJointsFollowTheMortonOrder) {
    const int nx = 50, ny = 42;  // 4200 triangles
    const MeshData mesh = make_rectangle_mesh(0, 0, 1, 0.84, nx, ny);
    BodyOptions opt = fracture_options();
    // a pre-broken edge at y = 0.4, x in [0.4, 0.42]
    opt.prebroken_edges = {{20 * (nx + 1) + 20, 20 * (nx + 1) + 21}};
    Model m = jointed_material();
    add_bodies(m, mesh, all_tris(mesh), opt);
    const int32_t joints_before = m.joints.num_joints();
    finalize_model(m);
    expect_consistent(m);
    ASSERT_EQ(m.joints.num_joints(), joints_before);
    bool sorted = true;
    for (size_t j = 1; j < m.joints.nodes.size(); ++j)
        sorted = sorted && m.joints.nodes[j - 1][0] < m.joints.nodes[j][0];
    EXPECT_TRUE(sorted);
    EXPECT_TRUE(m.joints.sorted_by_node0);  // (joint_forces prefetches side B of large models)
    ASSERT_EQ(m.prebroken_joints.size(), 1u);
    const auto& n = m.joints.nodes[static_cast<size_t>(m.prebroken_joints[0])];
    const Vec2 a = m.node_x0[static_cast<size_t>(n[0])], b = m.node_x0[static_cast<size_t>(n[1])];
    EXPECT_NEAR(std::min(a.x, b.x), 0.4, 1e-12);
    EXPECT_NEAR(std::max(a.x, b.x), 0.42, 1e-12);
    EXPECT_NEAR(a.y, 0.4, 1e-12);
    EXPECT_NEAR(b.y, 0.4, 1e-12);
    // a body below kRenumberMinTris keeps its mesh order, and its joints theirs
    Model small = jointed_material();
    const MeshData mesh_small = make_rectangle_mesh(0, 0, 1, 1, 10, 10);
    add_bodies(small, mesh_small, all_tris(mesh_small), fracture_options());
    finalize_model(small);
    ASSERT_GT(small.joints.num_joints(), 0);
    EXPECT_FALSE(small.joints.sorted_by_node0);
}

// stable_time_step of a jointed body (theory eq. 9.21): the largest omega^2 of M^-1 (K_e + K_j),
// by power iteration with the element and joint kernels' own forces about the reference state,
// stays below (2/dt)^2; the minimum of the element and joint bounds would not bound it.
TEST(FractureBuild, StableTimeStepBoundsElementsAndJoints) {
    const MeshData mesh = make_rectangle_mesh(0, 0, 0.06, 0.06, 6, 6, true);
    Model m = jointed_material();
    const Real p = 8e8;                   // the joint bound equals the element bound
    m.materials[0].fracture.penalty = p;  // joints and elements of similar frequency
    m.materials[0].fracture.shear_penalty = p;
    m.materials[0].fracture.fracture_energy_I = 1000;  // h_max
    add_bodies(m, mesh, all_tris(mesh), fracture_options());
    finalize_model(m);
    const Real dt = stable_time_step(m);
    const Real dte = element_stable_time_step(m);
    const Real dtj = joint_critical_dt(m.joints, m.node_mass);
    const size_t nn = static_cast<size_t>(m.num_nodes());
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> U(-1, 1);
    std::vector<Vec2> u(nn), x(nn), fp(nn), fm(nn), v0(nn);
    for (auto& w : u)
        w = {U(rng), U(rng)};
    const double eps = 1e-9;
    double lambda = 0;
    for (int it = 0; it < 600; ++it) {
        double un = 0;
        for (auto& w : u)
            un = std::max(un, norm(w));
        for (auto& w : u)
            w = w / un;
        for (int sgn : {1, -1}) {
            JointState js = make_joint_state(m.joints);
            for (size_t i = 0; i < nn; ++i)
                x[i] = m.node_x0[i] + (sgn * eps) * u[i];
            auto& ff = sgn > 0 ? fp : fm;
            ff.assign(nn, Vec2{0, 0});
            add_internal_forces(m, x.data(), v0.data(), ff.data(), 0, m.num_tris());
            joint_forces(m.joints, js, x, ff, false);
        }
        double num = 0, den = 0;
        for (size_t i = 0; i < nn; ++i) {
            const Vec2 ku = (-1.0 / (2 * eps)) * (fp[i] - fm[i]);
            num += dot(u[i], ku);
            den += m.node_mass[i] * dot(u[i], u[i]);
            u[i] = ku / m.node_mass[i];
        }
        lambda = num / den;
    }
    const double bound = 4.0 / (dt * dt);
    const double min_bound = 4.0 / std::pow(std::min(dte, dtj), 2);
    std::printf(
        "[ dt ] dt_e %.4g s, dt_joint %.4g s, dt %.4g s; omega^2 / (2/dt)^2 = %.4f, "
        "omega^2 / (2/min(dt_e, dt_joint))^2 = %.4f\n",
        dte, dtj, dt, lambda / bound, lambda / min_bound);
    EXPECT_LE(lambda, bound);
    EXPECT_GT(lambda, min_bound);  // the minimum alone would be unstable here
}

}  // namespace
}  // namespace fdem
