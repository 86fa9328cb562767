// `fdem decompose` (parallel/decompose.hpp, issue #15 M5): the counts of every part, checked
// against their definitions computed here from the model and the candidate pairs directly
// (the equality with what real processes exchange is the MPI test mpi.decompose_matches_run.*).
#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "fdem/build.hpp"
#include "fdem/simulate.hpp"
#include "integrate/node_update.hpp"
#include "parallel/decompose.hpp"
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
// node of an owned edge target, and every node of the contactor body (unless fixed) of a pair of an
// owned target; minus the owned nodes
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
        const Body& b = m.bodies[static_cast<size_t>(s.contact.cand.body[pr])];
        if (b.fixed) continue;  // its nodes never move: every process has them
        for (NodeId n = b.node_begin; n < b.node_end; ++n)
            need.insert(n);
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

TEST(Decompose, CsvHasAHeaderAndARowPerPart) {
    std::vector<PartCounts> parts(2);
    parts[1].part = 1;
    parts[1].ghost_nodes = 3;
    parts[1].contact_records = 2;
    const std::string csv = partition_csv(parts);
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "parts,part,nodes,tris_counted,tris_run,chunks_run,ghost_nodes,send_nodes,recv_from,"
              "send_to,candidate_pairs,contact_records,support_slots,ghost_bytes_in,"
              "ghost_bytes_out,gathered_bytes");
    EXPECT_NE(csv.find("\n2,1,0,0,0,0,3,0,0,0,0,2,0,96,0,"), std::string::npos) << csv;
}

}  // namespace
}  // namespace fdem
