// `fdem decompose` (parallel/decompose.hpp, issue #15 M5): the counts of every part, checked
// against their definitions computed here from the model and the candidate pairs directly
// (the equality with what real processes exchange is the MPI test mpi.decompose_matches_run.*).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "contact/contact.hpp"
#include "fdem/build.hpp"
#include "fdem/simulate.hpp"
#include "integrate/node_update.hpp"
#include "parallel/decompose.hpp"
#include "parallel/distributed.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

// a particle box stepped until the broad phase has candidate pairs and some are in contact
struct Scene {
    Model m;
    State s;
};

Scene particle_scene() {
    scenes::ParticleOptions o;
    o.nx = 12;
    o.ny = 10;
    Scene sc{scenes::make_particle_box(o), {}};
    sc.s = make_state(sc.m, 0.5 * stable_time_step(sc.m));
    for (int k = 0; k < 5000 && sc.s.contact.active.empty(); ++k)
        step(sc.m, sc.s);
    return sc;
}

// the ghosts of part r by the definition of spec D6 (distributed.hpp GhostExchange): the nodes
// of every triangle with an owned node and of every chunk the part counts, of the loads, the second
// node of an owned edge target, and the contact nodes of the contactor body (unless fixed) of a
// pair of an owned target (its sub-triangles' real vertices and its virtual nodes' parents; this
// scene has no welds); minus the owned nodes
std::set<NodeId> ghosts_by_definition(const Model& m, const State& s,
                                      const std::vector<int32_t>& node_owner, int32_t r) {
    std::set<NodeId> need;
    for (const auto& [b, e] : m.element_schedule.chunk_tris) {
        // a chunk the part counts (its first triangle's first node is owned): every triangle
        // (energy steps); any other: the triangles with an owned node
        const bool counted = node_owner[static_cast<size_t>(m.tri_nodes[b][0])] == r;
        for (TriId t = b; t < e; ++t) {
            bool mine = counted;
            for (const NodeId n : m.tri_nodes[static_cast<size_t>(t)])
                mine = mine || node_owner[static_cast<size_t>(n)] == r;
            if (!mine) continue;
            for (const NodeId n : m.tri_nodes[static_cast<size_t>(t)])
                need.insert(n);
        }
    }
    const ContactTopology& ct = s.topology;
    for (size_t pr = 0; pr < s.contact.cand.node.size(); ++pr) {
        const NodeId j = s.contact.cand.node[pr];
        const bool edge = j >= ct.num_real_nodes;
        const auto& e = edge ? ct.boundary_edges[static_cast<size_t>(j - ct.edge_target_base)]
                             : std::array<NodeId, 2>{j, j};
        if (node_owner[static_cast<size_t>(e[0])] != r) continue;
        need.insert(e[1]);
        const BodyId cb = s.contact.cand.body[pr];
        if (m.bodies[static_cast<size_t>(cb)].fixed) continue;  // never moves: every process has it
        for (int32_t t = ct.body_sub_begin[static_cast<size_t>(cb)];
             t < ct.body_sub_begin[static_cast<size_t>(cb) + 1]; ++t) {
            for (const NodeId n : ct.sub_tri[static_cast<size_t>(t)]) {
                if (n < ct.num_real_nodes) {
                    need.insert(n);
                } else {
                    for (const NodeId q :
                         ct.virt_parent[static_cast<size_t>(n - ct.num_real_nodes)])
                        need.insert(q);
                }
            }
        }
    }
    std::set<NodeId> out;
    for (const NodeId n : need) {
        if (node_owner[static_cast<size_t>(n)] != r) out.insert(n);
    }
    return out;
}

TEST(Decompose, CountsAreTheirDefinitions) {
    const Scene sc = particle_scene();
    const Model& m = sc.m;
    ASSERT_TRUE(m.loads.empty());
    ASSERT_FALSE(sc.s.contact.cand.node.empty());
    ASSERT_FALSE(sc.s.contact.active.empty());
    int64_t tris = 0;  // of the chunks (non-fixed bodies)
    for (const auto& [b, e] : m.element_schedule.chunk_tris)
        tris += e - b;
    for (const char* rule : {"ids", "random"}) {
        for (const int32_t P : {1, 2, 3, 5}) {
            SCOPED_TRACE(std::string(rule) + " P=" + std::to_string(P));
            const std::vector<int32_t> groups = group_owners(m, rule, P);
            const std::vector<PartCounts> parts = decompose(m, sc.s, groups, P);
            ASSERT_EQ(parts.size(), static_cast<size_t>(P));
            std::vector<int32_t> node_owner(static_cast<size_t>(m.num_nodes()));
            for (size_t i = 0; i < node_owner.size(); ++i)
                node_owner[i] = groups[i / kNodeGroup];
            int64_t nodes = 0, counted = 0, ghosts = 0, sends = 0, records = 0, pairs = 0;
            int64_t msgs_in = 0, msgs_out = 0;
            for (int32_t r = 0; r < P; ++r) {
                const PartCounts& c = parts[static_cast<size_t>(r)];
                EXPECT_EQ(c.part, r);
                int64_t own = 0;
                for (const int32_t o : node_owner)
                    own += o == r;
                EXPECT_EQ(c.nodes, own);
                const std::set<NodeId> g = ghosts_by_definition(m, sc.s, node_owner, r);
                EXPECT_EQ(c.ghost_nodes, static_cast<int64_t>(g.size()));
                std::set<int32_t> from;
                for (const NodeId n : g)
                    from.insert(node_owner[static_cast<size_t>(n)]);
                EXPECT_EQ(c.recv_from, static_cast<int32_t>(from.size()));
                // a step without energies runs the triangles with an owned node (no viscosity)
                int64_t mine = 0;
                for (const auto& [b, e] : m.element_schedule.chunk_tris) {
                    for (TriId t = b; t < e; ++t) {
                        bool any = false;
                        for (const NodeId n : m.tri_nodes[static_cast<size_t>(t)])
                            any = any || node_owner[static_cast<size_t>(n)] == r;
                        mine += any;
                    }
                }
                EXPECT_EQ(c.tris_run, mine);
                nodes += c.nodes;
                counted += c.tris_counted;
                ghosts += c.ghost_nodes;
                sends += c.send_nodes;
                msgs_in += c.recv_from;
                msgs_out += c.send_to;
                records += c.contact_records;
                pairs += c.candidate_pairs;
                EXPECT_EQ(ghost_bytes_in(c), 32 * c.ghost_nodes);
            }
            EXPECT_EQ(nodes, m.num_nodes());
            EXPECT_EQ(counted, tris);  // every chunk's energy counted by exactly one part
            EXPECT_EQ(sends, ghosts);  // every ghost sent by its owner
            EXPECT_EQ(msgs_in, msgs_out);
            EXPECT_EQ(records, static_cast<int64_t>(sc.s.contact.active.size()));
            EXPECT_EQ(pairs, static_cast<int64_t>(sc.s.contact.cand.node.size()));
            if (P == 1) {
                EXPECT_EQ(ghosts, 0);
            } else {
                EXPECT_GT(ghosts, 0);
            }
        }
    }
}

TEST(Decompose, GroupOwnerRules) {
    const Scene sc = particle_scene();
    const int32_t groups = (sc.m.num_nodes() + kNodeGroup - 1) / kNodeGroup;
    const std::vector<int32_t> ids = group_owners(sc.m, "ids", 4);
    ASSERT_EQ(ids.size(), static_cast<size_t>(groups));
    EXPECT_EQ(ids.front(), 0);
    EXPECT_EQ(ids.back(), 3);
    for (size_t g = 1; g < ids.size(); ++g)
        EXPECT_LE(ids[g - 1], ids[g]);  // contiguous ranges
    const std::vector<int32_t> rnd = group_owners(sc.m, "random", 4);
    std::set<int32_t> used(rnd.begin(), rnd.end());
    EXPECT_EQ(used, (std::set<int32_t>{0, 1, 2, 3}));
    EXPECT_THROW(group_owners(sc.m, "metis", 4), std::invalid_argument);
    EXPECT_THROW(decompose(sc.m, sc.s, std::vector<int32_t>(ids.size(), 4), 4),
                 std::invalid_argument);  // an owner out of range
}

// Rebalancing (spec D10): the rules from weights. "ids": contiguous ranges whose sums differ from
// the mean by at most one group's weight; "random": in range, and another draw per round.
TEST(Decompose, WeightedGroupOwnerRules) {
    std::vector<double> w(200);
    for (size_t g = 0; g < w.size(); ++g)
        w[g] = 1.0 + static_cast<double>((g * 37) % 11) + (g >= 150 ? 40.0 : 0.0);
    double total = 0, biggest = 0;
    for (const double x : w) {
        total += x;
        biggest = std::max(biggest, x);
    }
    for (const int32_t P : {1, 2, 3, 7}) {
        SCOPED_TRACE(P);
        const std::vector<int32_t> ids = group_owners(w, "ids", P, 5);
        ASSERT_EQ(ids.size(), w.size());
        EXPECT_EQ(ids.front(), 0);
        EXPECT_EQ(ids.back(), P - 1);
        std::vector<double> sum(static_cast<size_t>(P), 0.0);
        for (size_t g = 0; g < w.size(); ++g) {
            if (g > 0) {
                EXPECT_LE(ids[g - 1], ids[g]);  // contiguous ranges
            }
            sum[static_cast<size_t>(ids[g])] += w[g];
        }
        for (const double s : sum)
            EXPECT_LE(std::abs(s - total / P), biggest) << s;
        // equal weights: the groups split as evenly as whole groups allow
        const std::vector<int32_t> even = group_owners(std::vector<double>(10, 2.0), "ids", P, 0);
        std::vector<int32_t> n(static_cast<size_t>(P), 0);
        for (const int32_t o : even)
            ++n[static_cast<size_t>(o)];
        for (const int32_t k : n)
            EXPECT_LE(std::abs(k - 10.0 / P), 1.0);
    }
    const std::vector<int32_t> r1 = group_owners(w, "random", 4, 1);
    const std::vector<int32_t> r2 = group_owners(w, "random", 4, 2);
    EXPECT_EQ(r1, group_owners(w, "random", 4, 1));  // a function of the round
    EXPECT_NE(r1, r2);
    EXPECT_EQ(std::set<int32_t>(r1.begin(), r1.end()), (std::set<int32_t>{0, 1, 2, 3}));
    EXPECT_THROW(group_owners(w, "metis", 4, 0), std::invalid_argument);
    EXPECT_THROW(group_owners(w, "ids", 0, 0), std::invalid_argument);
}

TEST(Decompose, EstimatedWorkWeighsTrianglesPairsAndContacts) {
    PartCounts c;
    c.tris_run = 1000;
    c.candidate_pairs = 300;
    c.contact_records = 20;
    c.ghost_nodes = 999;  // (communication is not in the estimate)
    EXPECT_DOUBLE_EQ(estimated_work(c),
                     1000 * kWorkPerTriangle + 300 * kWorkPerCandidate + 20 * kWorkPerContact);
    // a pair in contact costs more than a rejected candidate, which costs less than a triangle
    EXPECT_GT(kWorkPerContact, kWorkPerTriangle);
    EXPECT_LT(kWorkPerCandidate, kWorkPerTriangle);
}

// The input of a rebalance: the groups' centres at the current positions and their weights,
// 1 + the estimated work of the movable triangles, candidate pairs and pairs in contact whose
// node (an edge target: its first node) lies in the group
TEST(Decompose, NodeGroupWorkAtTheCurrentPositions) {
    Scene sc = particle_scene();
    const Model& m = sc.m;
    std::vector<Vec2> c0, c1;
    std::vector<double> w0, w1;
    node_group_work(m, sc.s, c0, w0);
    const size_t groups = static_cast<size_t>((m.num_nodes() + kNodeGroup - 1) / kNodeGroup);
    // the units of the centres: 1 / the groups' mean bounding-box width and height
    Real wx = 0, wy = 0;
    for (size_t g = 0; g < groups; ++g) {
        const NodeId b = static_cast<NodeId>(g) * kNodeGroup,
                     e = std::min(m.num_nodes(), b + kNodeGroup);
        Real lx = 1e300, hx = -1e300, ly = 1e300, hy = -1e300;
        for (NodeId i = b; i < e; ++i) {
            lx = std::min(lx, sc.s.x[i].x);
            hx = std::max(hx, sc.s.x[i].x);
            ly = std::min(ly, sc.s.x[i].y);
            hy = std::max(hy, sc.s.x[i].y);
        }
        wx += hx - lx;
        wy += hy - ly;
    }
    ASSERT_GT(wx, 0);
    ASSERT_GT(wy, 0);
    const Real sx = static_cast<Real>(groups) / wx, sy = static_cast<Real>(groups) / wy;
    EXPECT_GT(std::max(sx / sy, sy / sx), 1.01);  // (the scene's groups are not square)
    for (Vec2& x : sc.s.x)
        x += Vec2{0.25, -1.0};  // the centres follow the nodes (the extents stay); the weights stay
    std::vector<Vec2> centre;
    std::vector<double> weight;
    node_group_work(m, sc.s, centre, weight);
    ASSERT_EQ(centre.size(), groups);
    ASSERT_EQ(weight.size(), groups);
    EXPECT_EQ(weight, w0);
    for (size_t g = 0; g < groups; ++g) {
        EXPECT_NEAR(centre[g].x, c0[g].x + 0.25 * sx, 1e-9);
        EXPECT_NEAR(centre[g].y, c0[g].y - 1.0 * sy, 1e-9);
    }
    for (const size_t g : {size_t{0}, groups - 1}) {  // the mean of the group's positions
        const NodeId b = static_cast<NodeId>(g) * kNodeGroup,
                     e = std::min(m.num_nodes(), b + kNodeGroup);
        Vec2 sum;
        for (NodeId i = b; i < e; ++i)
            sum += sc.s.x[i];
        EXPECT_NEAR(centre[g].x, sum.x / (e - b) * sx, 1e-9);
        EXPECT_NEAR(centre[g].y, sum.y / (e - b) * sy, 1e-9);
    }
    node_group_points(m, c1, w1);  // (the reference positions: not where the nodes are now)
    EXPECT_NE(c1[0].x, c0[0].x);
    std::vector<double> expect(groups, 1.0);
    int64_t movable = 0;
    for (const Body& b : m.bodies) {
        if (b.fixed) continue;
        for (TriId t = b.tri_begin; t < b.tri_end; ++t, ++movable)
            expect[static_cast<size_t>(m.tri_nodes[t][0] / kNodeGroup)] += kWorkPerTriangle;
    }
    ASSERT_LT(movable, m.num_tris());  // the walls are fixed and cost nothing
    const ContactTopology& ct = sc.s.topology;
    for (const NodeId j : sc.s.contact.cand.node)
        expect[static_cast<size_t>(target_node(ct, j) / kNodeGroup)] += kWorkPerCandidate;
    for (const ActiveContact& a : sc.s.contact.active)
        expect[static_cast<size_t>(target_node(ct, a.node) / kNodeGroup)] += kWorkPerContact;
    for (size_t g = 0; g < groups; ++g)
        EXPECT_DOUBLE_EQ(weight[g], expect[g]) << g;
}

// joints_run: the joints of a part's JointSubset that are not broken: every joint of the chunks
// whose first joint's node 0 it owns, and every other joint with a node it owns (docs/parallel.md
// "Joints"); one part runs them all
TEST(Decompose, JointsRunAreThoseOfThePartsSubset) {
    scenes::BlockOptions o;
    o.num_tris = 1 << 13;  // 4 joint chunks
    o.jointed = true;
    const Model m = scenes::make_block(o);
    State s = make_state(m, 0.5 * stable_time_step(m));
    const int32_t nj = m.joints.num_joints();
    ASSERT_GT(nj, 2 * kJointChunk);
    s.joints.status[7] = JointStatus::Broken;  // a broken joint is not counted
    for (const int32_t P : {1, 2, 3}) {
        SCOPED_TRACE(P);
        const std::vector<int32_t> groups = group_owners(m, "random", P);
        const std::vector<PartCounts> parts = decompose(m, s, groups, P);
        int64_t sum = 0;
        for (int32_t r = 0; r < P; ++r) {
            int64_t expect = 0;
            for (int32_t j = 0; j < nj; ++j) {
                const int32_t first = j / kJointChunk * kJointChunk;
                bool runs = groups[static_cast<size_t>(m.joints.nodes[first][0] / kNodeGroup)] == r;
                for (const NodeId n : m.joints.nodes[static_cast<size_t>(j)])
                    runs = runs || groups[static_cast<size_t>(n / kNodeGroup)] == r;
                expect += runs && j != 7;
            }
            EXPECT_EQ(parts[static_cast<size_t>(r)].joints_run, expect) << r;
            sum += parts[static_cast<size_t>(r)].joints_run;
        }
        if (P == 1) {
            EXPECT_EQ(sum, nj - 1);
        } else {
            EXPECT_GT(sum, nj - 1);  // the joints at the cuts run by each side
        }
    }
}

TEST(Decompose, CsvHasAHeaderAndARowPerPart) {
    std::vector<PartCounts> parts(2);
    parts[1].part = 1;
    parts[1].ghost_nodes = 3;
    parts[1].contact_records = 2;
    parts[1].support_slots = 1;
    parts[1].contact_neighbours = 1;
    parts[1].contact_sent = 3;
    parts[1].contact_received = 1;
    const std::string csv = partition_csv(parts);
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "parts,part,nodes,tris_counted,tris_run,chunks_run,ghost_nodes,send_nodes,recv_from,"
              "send_to,candidate_pairs,contact_records,support_slots,ghost_bytes_in,"
              "ghost_bytes_out,gathered_bytes,contact_neighbours,contact_sent,contact_received,"
              "contact_bytes_in,contact_bytes_out,joints_run");
    // ghosts 32 B per node; the supports' all-gather 16 B per slot; records point to point
    const int64_t rec = static_cast<int64_t>(kContactRecordBytes);
    EXPECT_NE(
        csv.find(fmt::format("\n2,1,0,0,0,0,3,0,0,0,0,2,1,96,0,16,1,3,1,{},{},0\n", rec, 3 * rec)),
        std::string::npos)
        << csv;
}

}  // namespace
}  // namespace fdem
