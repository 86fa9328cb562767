// The welded contact topology of bodies with fracture (contact/topology.cpp, docs/theory.md §6.15,
// spec fracture.md §4.2-4.4, test U6) and rule X self-contact in the broad phase: an unbroken
// jointed body is, for contact, the continuous body (same field, same force totals); cracks
// become boundary; a rebuild equals a fresh build bitwise.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <random>

#include "contact/contact.hpp"
#include "contact/validate.hpp"
#include "fdem/simulate.hpp"
#include "fracture/sectors.hpp"
#include "support/jointed.hpp"
#include "support/topology_compare.hpp"

namespace fdem {
namespace {

using testing::add_jointed_body;
using testing::all_edges;
using testing::differing_fields;
using testing::statuses;

// A fixed base under a 3 x 3 block (alternating diagonals), the block either continuous or
// jointed on every internal edge:
//
//   y=3    +--+--+--+          block [0.5, 3.5] x [0, 3]
//          |  |  |  |
//   y=0 +--+--+--+--+--+       base [0, 4] x [-1, 0], fixed
//       |              |
//  y=-1 +--------------+
Model base_and_block(bool jointed, const testing::JointedEdge& edges = all_edges) {
    Model m;
    Material mat;
    mat.name = "rock";
    mat.density = 2000;
    mat.youngs_modulus = 1e9;
    m.materials.push_back(mat);
    m.contact.algorithm = ContactAlgorithm::Smooth;
    BodyOptions base;
    base.name = "base";
    base.fixed = true;
    const MeshData bm = make_rectangle_mesh(0, -1, 4, 1, 4, 1);
    add_bodies(m, bm, std::vector<int32_t>{0, 1, 2, 3, 4, 5, 6, 7}, base);
    const MeshData block = make_rectangle_mesh(0.5, 0, 3, 3, 3, 3, true);
    if (jointed) {
        add_jointed_body(m, block, edges);
        finalize_model(m);
        return m;
    }
    BodyOptions bo;
    bo.name = "block";
    std::vector<int32_t> ids(block.tris.size());
    std::iota(ids.begin(), ids.end(), 0);
    add_bodies(m, block, ids, bo);
    finalize_model(m);
    return m;
}

// the node of c at the reference position of node i of j (a copy's vertex in the continuous mesh)
NodeId vertex_in(const Model& c, const Model& j, NodeId i) {
    for (NodeId n = 0; n < c.num_nodes(); ++n) {
        if (c.node_x0[n] == j.node_x0[i]) return n;
    }
    return kNone;
}

// a state with the sectors of `broken` and the topology built from them
State state_with_sectors(const Model& m, const std::vector<int32_t>& broken = {}) {
    State s = make_state(m, 1e-6);
    compute_node_sectors(m, statuses(m, broken), s.node_sector);
    init_contact_state(m, s);
    return s;
}

TEST(WeldedTopology, NoFractureIgnoresSectors) {
    const Model m = base_and_block(false);
    const ContactTopology plain = build_topology(m);
    std::vector<NodeId> identity(static_cast<size_t>(m.num_nodes()));
    std::iota(identity.begin(), identity.end(), 0);
    ContactTopology t;
    build_topology(m, identity, t);
    EXPECT_EQ(differing_fields(t, plain), "");
    EXPECT_TRUE(t.node_weld.empty());
    EXPECT_THROW(build_topology(m, std::vector<NodeId>{0, 1}, t), std::invalid_argument);
}

// an unbroken jointed block has the continuous block's boundary, distances and total scales
TEST(WeldedTopology, IntactJointedBlockIsTheContinuousBlock) {
    const Model c = base_and_block(false), j = base_and_block(true);
    ASSERT_EQ(j.num_nodes(), 10 + 54);  // base 10 nodes, block 18 triangles x 3
    const ContactTopology tc = build_topology(c);
    std::vector<NodeId> sec;
    compute_node_sectors(j, statuses(j), sec);
    ContactTopology tj;
    build_topology(j, sec, tj);
    const std::vector<std::string> bad = validate_topology(j, tj);
    EXPECT_TRUE(bad.empty()) << bad.front();
    EXPECT_EQ(tj.body_self, (std::vector<uint8_t>{0, 1}));

    // boundary edges: the same vertex pairs, the same orientation
    ASSERT_EQ(tj.boundary_edges.size(), tc.boundary_edges.size());
    std::map<std::array<NodeId, 2>, int> cont;
    for (const auto& e : tc.boundary_edges)
        ++cont[e];
    for (const auto& e : tj.boundary_edges) {
        const std::array<NodeId, 2> v = {vertex_in(c, j, e[0]), vertex_in(c, j, e[1])};
        EXPECT_EQ(cont[v], 1) << e[0] << " " << e[1];
    }
    // boundary nodes: every copy of a boundary vertex; distances equal bitwise; scales add up
    std::map<NodeId, Real> scale_sum;
    for (NodeId i = 0; i < j.num_nodes(); ++i) {
        const NodeId v = vertex_in(c, j, i);
        ASSERT_NE(v, kNone);
        EXPECT_EQ(tj.node_on_boundary[i], tc.node_on_boundary[v]) << i;
        scale_sum[v] += tj.node_scale[i];
    }
    for (const auto& [v, s] : scale_sum)
        EXPECT_NEAR(s, tc.node_scale[v], 1e-14 * tc.node_scale[v]) << v;
    std::vector<uint8_t> in_sub(static_cast<size_t>(j.num_nodes()), 0);
    for (const auto& q : tj.sub_tri) {
        for (NodeId i : q) {
            if (i < j.num_nodes()) in_sub[i] = 1;
        }
    }
    int checked = 0;
    for (NodeId i = 0; i < j.num_nodes(); ++i) {
        if (!in_sub[i] || tj.node_on_boundary[i]) continue;
        EXPECT_EQ(tj.node_dist[i], tc.node_dist[vertex_in(c, j, i)]) << i;
        ++checked;
    }
    EXPECT_GT(checked, 10);  // the inner vertices' copies in boundary elements
    // the same contactor area: the sub-triangles cover the same boundary elements
    EXPECT_EQ(tj.boundary_tris.size(), tc.boundary_tris.size());
}

// pressed into the fixed base, the unbroken jointed block and the continuous block feel the same
// contact force (eq. 19: the copies' masses add up to the vertex's), and the jointed block has no
// self-contact force
TEST(WeldedTopology, IntactJointedBlockSameContactForce) {
    const Model c = base_and_block(false), j = base_and_block(true);
    State sc = make_state(c, 1e-6);
    State sj = state_with_sectors(j);
    const Real delta = 0.05;  // the block sunk by delta into the base
    for (State* s : {&sc, &sj}) {
        const Model& m = s == &sc ? c : j;
        for (NodeId i = m.bodies[1].node_begin; i < m.bodies[1].node_end; ++i)
            s->x[i].y -= delta;
        std::fill(s->f.begin(), s->f.end(), Vec2{});
        std::fill(s->f_contact.begin(), s->f_contact.end(), Vec2{});
        add_contact_forces(m, *s);
    }
    auto total = [](const Model& m, const State& s, BodyId b) {
        Vec2 f;
        for (NodeId i = m.bodies[b].node_begin; i < m.bodies[b].node_end; ++i)
            f += s.f_contact[i];
        return f;
    };
    const Vec2 fc = total(c, sc, 1), fj = total(j, sj, 1);
    ASSERT_GT(fc.y, 0);  // pushed up
    EXPECT_NEAR(fj.y, fc.y, 1e-12 * fc.y);
    EXPECT_NEAR(fj.x, fc.x, 1e-12 * fc.y);
    const Vec2 bc = total(c, sc, 0), bj = total(j, sj, 0);
    EXPECT_NEAR(bj.y, bc.y, 1e-12 * fc.y);
    EXPECT_NEAR(bj.x, bc.x, 1e-12 * fc.y);
    // per vertex: the copies' forces add up to the continuous node's
    std::map<NodeId, Vec2> per_vertex;
    for (NodeId i = j.bodies[1].node_begin; i < j.bodies[1].node_end; ++i)
        per_vertex[vertex_in(c, j, i)] += sj.f_contact[i];
    for (const auto& [v, f] : per_vertex) {
        EXPECT_NEAR(f.x, sc.f_contact[v].x, 1e-12 * fc.y) << v;
        EXPECT_NEAR(f.y, sc.f_contact[v].y, 1e-12 * fc.y) << v;
    }
    // no self pair in contact: every active pair has the base as one side
    int self_pairs = 0;
    for (const ActiveContact& a : sj.contact.active)
        self_pairs += a.body == j.node_body[target_node(sj.topology, a.node)] ? 1 : 0;
    EXPECT_EQ(self_pairs, 0);
    EXPECT_GT(sj.contact.active.size(), sc.contact.active.size());  // more targets: the copies
}

// rule X: the copies of an intact jointed body, each moved on its own by up to 4 % of the element
// size and the whole body sheared, find no contact with their own body
TEST(WeldedTopology, IntactBodyNoSelfContactUnderDeformation) {
    const Model j = base_and_block(true);
    State s = state_with_sectors(j);
    std::mt19937 rng(11);
    std::uniform_real_distribution<Real> u(-0.04, 0.04);
    int64_t candidates = 0;
    for (int trial = 0; trial < 20; ++trial) {
        for (NodeId i = j.bodies[1].node_begin; i < j.bodies[1].node_end; ++i) {
            const Vec2 p = j.node_x0[i];
            s.x[i] = Vec2{p.x + 0.05 * p.y + u(rng), p.y + 1.0 + u(rng)};  // lifted off the base
        }
        s.contact.need_rebuild = true;
        std::fill(s.f_contact.begin(), s.f_contact.end(), Vec2{});
        add_contact_forces(j, s);
        for (NodeId i = 0; i < j.num_nodes(); ++i)
            ASSERT_EQ(s.f_contact[i], Vec2{}) << "trial " << trial << " node " << i;
        EXPECT_EQ(s.contact.active_contacts, 0);
        candidates += static_cast<int64_t>(s.contact.cand.tri.size());
    }
    EXPECT_GT(candidates, 0);  // own sub-triangles were candidates and rule X kept them apart
}

// U6: rebuild_topology after breaking joints == build_topology with the same statuses, bitwise
TEST(WeldedTopology, RebuildAfterBreaksEqualsFreshBuild) {
    const Model j = base_and_block(true);
    // joints on the horizontal line y = 1, then also y = 2 from x = 0.5 to 2.5 (a partial crack)
    auto on_line = [&](Real y, Real xb) {
        std::vector<int32_t> out;
        for (int32_t k = 0; k < j.joints.num_joints(); ++k) {
            const Vec2 a = j.node_x0[j.joints.nodes[k][0]], b = j.node_x0[j.joints.nodes[k][1]];
            if (a.y == y && b.y == y && std::max(a.x, b.x) <= xb) out.push_back(k);
        }
        return out;
    };
    const std::vector<int32_t> first = on_line(1.0, 9), second = on_line(2.0, 2.5);
    ASSERT_EQ(first.size(), 3u);
    ASSERT_EQ(second.size(), 2u);

    std::vector<JointStatus> st = statuses(j);
    std::vector<NodeId> sec;
    compute_node_sectors(j, st, sec);
    ContactTopology t;
    build_topology(j, sec, t);
    const size_t edges0 = t.boundary_edges.size();
    size_t broken = 0;
    for (const std::vector<int32_t>* batch : {&first, &second}) {
        for (const int32_t k : *batch)
            st[static_cast<size_t>(k)] = JointStatus::Broken;
        broken += batch->size();
        update_node_sectors(j, st, *batch, sec);
        const BodyId dirty[1] = {1};
        rebuild_topology(j, dirty, sec, t);
        ContactTopology fresh;
        build_topology(j, sec, fresh);
        EXPECT_EQ(differing_fields(t, fresh), "") << broken << " broken";
        const std::vector<std::string> bad = validate_topology(j, t);
        EXPECT_TRUE(bad.empty()) << bad.front();
        // both faces of every broken joint are boundary edges
        EXPECT_EQ(t.boundary_edges.size(), edges0 + 2 * broken);
    }
    // the fresh build differs from the unbroken one (the test can tell)
    ContactTopology intact;
    std::vector<NodeId> sec0;
    compute_node_sectors(j, statuses(j), sec0);
    build_topology(j, sec0, intact);
    EXPECT_NE(differing_fields(t, intact), "");
}

// validate_topology checks the welded form: a wrong sector, a copy of a boundary sector left off
// the boundary, a self-contact flag that is not Body::fracture
TEST(WeldedTopology, ValidatorCatchesWeldedCorruption) {
    const Model j = base_and_block(true);
    std::vector<NodeId> sec;
    compute_node_sectors(j, statuses(j), sec);
    ContactTopology good;
    build_topology(j, sec, good);
    ASSERT_TRUE(validate_topology(j, good).empty());
    auto first_message = [&](const std::function<void(ContactTopology&)>& corrupt) {
        ContactTopology t = good;
        corrupt(t);
        const std::vector<std::string> bad = validate_topology(j, t);
        return bad.empty() ? std::string() : bad.front();
    };
    // a copy (not its own representative) of an inner vertex, given a larger node as sector
    NodeId copy = kNone;
    for (NodeId i = j.bodies[1].node_begin; i < j.bodies[1].node_end && copy == kNone; ++i) {
        if (sec[i] != i && !good.node_on_boundary[i]) copy = i;
    }
    ASSERT_NE(copy, kNone);
    EXPECT_EQ(first_message([&](ContactTopology& t) {
                  t.node_weld[copy] = copy + 1;
              }).rfind("node_weld: node", 0),
              0u);
    NodeId bcopy = kNone;
    for (NodeId i = j.bodies[1].node_begin; i < j.bodies[1].node_end && bcopy == kNone; ++i) {
        if (sec[i] != i && good.node_on_boundary[i]) bcopy = i;
    }
    ASSERT_NE(bcopy, kNone);
    EXPECT_EQ(first_message([&](ContactTopology& t) {
                  t.node_on_boundary[bcopy] = 0;
              }).rfind("node_on_boundary: node", 0),
              0u);
    EXPECT_EQ(first_message([](ContactTopology& t) { t.body_self[1] = 0; }).rfind("body_self", 0),
              0u);
}

}  // namespace
}  // namespace fdem
