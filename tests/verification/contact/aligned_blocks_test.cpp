// Aligned square blocks (issue #12 item 5, docs/theory.md §6.12): two-triangle blocks in exactly
// aligned rows, converging. Every corner node then slides along the neighbour's boundary edge
// line, where the nodal distance field is zero, so nodal targets alone never feel a force and
// the blocks pass through each other. The edge-midpoint targets of §6.12 must stop them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "contact/contact.hpp"
#include "fdem/build.hpp"
#include "fdem/mesh.hpp"
#include "fdem/simulate.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

struct AlignedPack {
    int nx = 2, ny = 1;  ///< blocks per row, rows
    Real size = 0.01;    ///< block edge [m]
    Real gap = 0.0005;   ///< gap between neighbours [m]
    Real speed = 20;     ///< the left half moves at +speed, the right half at -speed [m/s]
    bool edge_targets = true;
};

// nx x ny two-triangle square blocks on an exact raster (no jitter: rows and columns aligned)
Model make_aligned_pack(const AlignedPack& o) {
    Model m;
    m.materials.push_back(scenes::paper_material("block", 1e9, 0.25, 1000.0));
    MeshData mesh;
    std::vector<Vec2> body_v;
    const Real pitch = o.size + o.gap;
    for (int j = 0; j < o.ny; ++j) {
        for (int i = 0; i < o.nx; ++i) {
            const Real x0 = i * pitch, y0 = j * pitch;
            const int32_t b = static_cast<int32_t>(mesh.nodes.size());
            mesh.nodes.push_back({x0, y0});
            mesh.nodes.push_back({x0 + o.size, y0});
            mesh.nodes.push_back({x0 + o.size, y0 + o.size});
            mesh.nodes.push_back({x0, y0 + o.size});
            mesh.tris.push_back({b, b + 1, b + 2});
            mesh.tris.push_back({b, b + 2, b + 3});
            body_v.push_back({2 * i < o.nx ? o.speed : -o.speed, 0});
        }
    }
    mesh.tri_tag.assign(mesh.tris.size(), 1);
    std::vector<int32_t> all(mesh.tris.size());
    std::iota(all.begin(), all.end(), 0);
    BodyOptions opt;
    opt.name = "blocks";
    add_bodies(m, mesh, all, opt);
    for (BodyId b = 0; b < m.num_bodies(); ++b) {
        for (NodeId i = m.bodies[b].node_begin; i < m.bodies[b].node_end; ++i)
            m.node_v0[i] = body_v[static_cast<size_t>(b)];
    }
    m.contact.algorithm = ContactAlgorithm::Smooth;
    m.contact.edge_targets = o.edge_targets;
    finalize_model(m);
    return m;
}

// mean x velocity of the bodies of the left half of every row
Real left_half_vx(const Model& m, const State& s, int nx) {
    Real p = 0, mass = 0;
    for (BodyId b = 0; b < m.num_bodies(); ++b) {
        if (2 * (b % nx) >= nx) continue;
        for (NodeId i = m.bodies[b].node_begin; i < m.bodies[b].node_end; ++i) {
            p += m.node_mass[i] * s.v[i].x;
            mass += m.node_mass[i];
        }
    }
    return p / mass;
}

struct Outcome {
    Real ke0 = 0, ke_min = 0, ke_end = 0;
    Real vx_end = 0;        ///< mean x velocity of the left half at the end [m/s]
    Real overlap = 0;       ///< largest overlap of the two middle columns of row 0 [m]
    Real energy_error = 0;  ///< max |E_total - E_0| / KE_0
    int64_t lost = 0, deep = 0;
};

Outcome run(const Model& m, int nx, int steps, Real dt_fraction) {
    const Real dt = dt_fraction * stable_time_step(m);
    State s = make_state(m, dt);
    Outcome o;
    // nodes of row 0: right face of the last left block, left face of the first right block
    const BodyId a = nx / 2 - 1, b = nx / 2;
    const NodeId a_right = m.bodies[a].node_begin + 1, b_left = m.bodies[b].node_begin;
    Real e0 = 0;
    for (int n = 0; n < steps; ++n) {
        step(m, s);
        if (n == 0) {
            o.ke0 = s.energy.kinetic;
            o.ke_min = o.ke0;
            e0 = s.energy.total();
        }
        o.ke_min = std::min(o.ke_min, s.energy.kinetic);
        o.overlap = std::max(o.overlap, s.x[a_right].x - s.x[b_left].x);
        o.energy_error = std::max(o.energy_error, std::abs(s.energy.total() - e0));
    }
    o.energy_error /= o.ke0;
    o.ke_end = s.energy.kinetic;
    o.vx_end = left_half_vx(m, s, nx);
    o.lost = s.contact.total_lost_inside;
    o.deep = s.contact.total_deep_penetrations;
    return o;
}

void print(const char* what, const Outcome& o) {
    std::printf(
        "[ info ] %s: KE min/KE0 = %.4f, KE end/KE0 = %.4f, left-half vx end = %.3f m/s, overlap "
        "= %.3g m, energy error = %.2e KE0, lost inside = %lld, deep = %lld\n",
        what, o.ke_min / o.ke0, o.ke_end / o.ke0, o.vx_end, o.overlap, o.energy_error,
        static_cast<long long>(o.lost), static_cast<long long>(o.deep));
}

// The energy balance is checked at dt = 0.1 (pack: 0.05) of the stable limit: at the default
// fraction 0.5 the error is 6 % of KE0 here, and it is 8.6 % for the same two blocks offset by
// half a block without edge targets (contact near its stability limit, issue #12 item 3, not
// this remedy); it falls with dt (0.5: 6.2e-2, 0.25: 1.7e-2, 0.125: 2.6e-3, 0.0625: 1.1e-3) to
// the ~0.1 % floor of the non-variational contactor share (docs/theory.md §6.7).

// Two blocks converging at 40 m/s (20 m/s each): they must stop (KE through a deep minimum),
// rebound (velocities reversed, the elastic law returns the KE, part of it as vibration) with the
// energy balance closed and without any node leaving the contact layer. Without edge targets
// they pass through each other with KE unchanged and no penetration warning.
TEST(AlignedBlocks, TwoBlocksStopAndRebound) {
    AlignedPack p;
    const Model m = make_aligned_pack(p);
    const Outcome o = run(m, p.nx, 3000, 0.1);
    print("two blocks, 40 m/s", o);
    EXPECT_LT(o.ke_min, 0.2 * o.ke0);
    EXPECT_LT(o.vx_end, -0.6 * p.speed);
    EXPECT_GT(o.ke_end, 0.6 * o.ke0);
    EXPECT_LT(o.overlap, 0.1 * p.size);
    EXPECT_LT(o.energy_error, 5e-3);
    EXPECT_EQ(o.lost, 0);
}

// A 4 x 3 pack in aligned rows: the two middle columns collide; the left half must stop and
// come back.
TEST(AlignedBlocks, PackStopsAndRebounds) {
    AlignedPack p;
    p.nx = 4;
    p.ny = 3;
    const Model m = make_aligned_pack(p);
    const Outcome o = run(m, p.nx, 3000, 0.05);
    print("4 x 3 aligned pack", o);
    EXPECT_LT(o.ke_min, 0.5 * o.ke0);
    EXPECT_LT(o.vx_end, -0.3 * p.speed);
    EXPECT_LT(o.overlap, 0.1 * p.size);
    EXPECT_LT(o.energy_error, 5e-3);
    EXPECT_EQ(o.lost, 0);
}

}  // namespace
}  // namespace fdem
