// Probes (src/fdem/measure/probes.cpp) under a homogeneous deformation x = F X + c with a
// uniform velocity w: position, velocity and the Cauchy stress of theory eq. 2.2 computed here
// from F (B = F F^T, J = det F), for a node, a curve group and a whole body.
#include <gtest/gtest.h>

#include <cmath>

#include "fdem/build.hpp"
#include "fdem/measure.hpp"
#include "fdem/simulate.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

constexpr Real kE = 1e9, kNu = 0.25;

// plane-strain Cauchy stress of theory eq. 2.2, sigma = (mu/J)(B - I) + (lambda/2)(J - 1/J) I
Mat2 analytic_stress(const Mat2& F) {
    const Real lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu)), mu = kE / (2 * (1 + kNu));
    const Real J = F.xx * F.yy - F.xy * F.yx;
    const Real bxx = F.xx * F.xx + F.xy * F.xy, byy = F.yx * F.yx + F.yy * F.yy;
    const Real bxy = F.xx * F.yx + F.xy * F.yy;
    const Real p = 0.5 * lambda * (J - 1 / J);
    return {mu / J * (bxx - 1) + p, mu / J * bxy, mu / J * bxy, mu / J * (byy - 1) + p};
}

struct Deformed {
    Model m;
    State s;
    Mat2 F{1.01, 0.02, -0.005, 0.99};
    Vec2 c{0.3, -0.1}, w{1.5, -2.0};
    Deformed() {
        m.materials.push_back(scenes::paper_material("m", kE, kNu));
        scenes::add_rectangle(m, 0, 0, 1, 0.5, 4, 2, 0);
        finalize_model(m);
        s = make_state(m, 1e-6);
        for (NodeId i = 0; i < m.num_nodes(); ++i) {
            s.x[i] = F * m.node_x0[i] + c;
            s.v[i] = w;
        }
    }
};

void expect_stress(const Mat2& got, const Mat2& want) {
    const Real tol = 1e-9 * kE * 0.02;
    EXPECT_NEAR(got.xx, want.xx, tol);
    EXPECT_NEAR(got.yy, want.yy, tol);
    EXPECT_NEAR(got.xy, want.xy, tol);
}

TEST(Probes, NodeProbeFollowsTheNearestNodeAndItsTriangle) {
    Deformed d;
    ProbeSpec p;
    p.position = {0.3, 0.2};
    NodeId node = kNone;
    TriId tri = kNone;
    locate_probe(d.m, p.position, -1, node, tri);
    ASSERT_NE(node, kNone);
    ASSERT_NE(tri, kNone);
    // grid spacing 0.25: the nearest node is (0.25, 0.25)
    EXPECT_EQ(d.m.node_x0[node].x, 0.25);
    EXPECT_EQ(d.m.node_x0[node].y, 0.25);
    // the triangle contains the point (barycentric coordinates >= 0)
    const auto& n = d.m.tri_nodes[tri];
    const Vec2 a = d.m.node_x0[n[0]], b = d.m.node_x0[n[1]], e = d.m.node_x0[n[2]];
    EXPECT_GE(cross(b - a, p.position - a), 0);
    EXPECT_GE(cross(e - b, p.position - b), 0);
    EXPECT_GE(cross(a - e, p.position - e), 0);
    p.nodes = {node};
    p.tris = {tri};
    const ProbeValues v = evaluate_probe(d.m, d.s, p);
    const Vec2 x = d.F * Vec2{0.25, 0.25} + d.c;
    EXPECT_NEAR(v.x.x, x.x, 1e-15);
    EXPECT_NEAR(v.x.y, x.y, 1e-15);
    EXPECT_EQ(v.v.x, d.w.x);
    EXPECT_EQ(v.v.y, d.w.y);
    expect_stress(v.stress, analytic_stress(d.F));
}

TEST(Probes, PointOutsideTakesTheNearestNodesTriangle) {
    Deformed d;
    NodeId node = kNone;
    TriId tri = kNone;
    locate_probe(d.m, {1.2, 0.6}, -1, node, tri);
    EXPECT_EQ(d.m.node_x0[node].x, 1.0);
    EXPECT_EQ(d.m.node_x0[node].y, 0.5);
    ASSERT_NE(tri, kNone);
    const auto& n = d.m.tri_nodes[tri];
    EXPECT_TRUE(n[0] == node || n[1] == node || n[2] == node);
}

TEST(Probes, GroupAndBodyProbesAverage) {
    Deformed d;
    ProbeSpec bottom;  // a curve group: the nodes at y = 0
    bottom.kind = ProbeSpec::Kind::Group;
    for (NodeId i = 0; i < d.m.num_nodes(); ++i)
        if (d.m.node_x0[i].y == 0) bottom.nodes.push_back(i);
    ASSERT_EQ(bottom.nodes.size(), 5u);
    bottom.tris = probe_triangles(d.m, bottom.nodes);
    EXPECT_EQ(bottom.tris.size(), 8u);  // no triangle lies on a line: the 8 touching it
    const ProbeValues g = evaluate_probe(d.m, d.s, bottom);
    // the mass-weighted mean of a homogeneous deformation is F Xbar + c, Xbar the lumped-mass
    // mean of the reference positions (end nodes carry less mass than inner ones)
    Vec2 xbar{};
    Real mass = 0;
    for (NodeId i : bottom.nodes) {
        xbar += d.m.node_mass[i] * d.m.node_x0[i];
        mass += d.m.node_mass[i];
    }
    const Vec2 xg = d.F * (xbar / mass) + d.c;
    EXPECT_NEAR(g.x.x, xg.x, 1e-14);
    EXPECT_NEAR(g.x.y, xg.y, 1e-14);
    expect_stress(g.stress, analytic_stress(d.F));

    ProbeSpec all;
    all.kind = ProbeSpec::Kind::Body;
    for (NodeId i = 0; i < d.m.num_nodes(); ++i)
        all.nodes.push_back(i);
    for (TriId t = 0; t < d.m.num_tris(); ++t)
        all.tris.push_back(t);
    const ProbeValues b = evaluate_probe(d.m, d.s, all);
    const Vec2 xb = d.F * Vec2{0.5, 0.25} + d.c;  // centre of mass
    EXPECT_NEAR(b.x.x, xb.x, 1e-14);
    EXPECT_NEAR(b.x.y, xb.y, 1e-14);
    EXPECT_NEAR(b.v.x, d.w.x, 1e-14);
    EXPECT_NEAR(b.v.y, d.w.y, 1e-14);
    expect_stress(b.stress, analytic_stress(d.F));
}

}  // namespace
}  // namespace fdem
