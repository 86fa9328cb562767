// Resultants (src/fdem/measure/resultants.cpp, theory §8): the accumulation of a subset of the
// sets, as a distributed run shares them between its processes (run/simulation.cpp
// share_resultants()), gives every set's impulse bit for bit as the accumulation of all sets.
#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <string>
#include <vector>

#include "fdem/measure.hpp"
#include "fdem/simulation.hpp"

namespace fdem {
namespace {

const std::string kDemo = FDEM_SOURCE_DIR "/examples/03_contact_slide/scenario.toml";
// fixed walls around 2 500 particles
const std::string kParticles = FDEM_SOURCE_DIR "/examples/04_particles/scenario.toml";

TEST(Resultants, SharedSetsSumTheSameBits) {
    Simulation sim = Simulation::from_file(kDemo);
    const Model& m = sim.model();
    const State& s = sim.state();
    const Resultants r(m, s.topology);
    ASSERT_GE(r.num_sets(), 2);
    IntervalImpulses all = r.make_impulses(), a = r.make_impulses(), b = r.make_impulses();
    std::vector<uint8_t> mine_a(static_cast<size_t>(r.num_sets()), 0), mine_b;
    for (size_t k = 0; k < mine_a.size(); k += 2)
        mine_a[k] = 1;
    for (const uint8_t f : mine_a)
        mine_b.push_back(f ? 0 : 1);
    while (sim.contact_counts().in_contact == 0 && s.time < 0.05)
        sim.run(s.time + s.dt);  // until the bodies touch
    for (int k = 0; k < 200; ++k) {
        sim.run(s.time + s.dt);
        r.accumulate(m, s, all);
        r.accumulate(m, s, a, mine_a);
        r.accumulate(m, s, b, mine_b);
    }
    bool some_contact = false;
    for (int32_t k = 0; k < r.num_sets(); ++k) {
        const IntervalImpulses& mine = mine_a[static_cast<size_t>(k)] ? a : b;
        const IntervalImpulses& other = mine_a[static_cast<size_t>(k)] ? b : a;
        const size_t i = static_cast<size_t>(k);
        EXPECT_EQ(mine.contact[i].x, all.contact[i].x) << r.name(k);
        EXPECT_EQ(mine.contact[i].y, all.contact[i].y) << r.name(k);
        EXPECT_EQ(mine.reaction[i].x, all.reaction[i].x) << r.name(k);
        EXPECT_EQ(mine.reaction[i].y, all.reaction[i].y) << r.name(k);
        EXPECT_EQ(other.contact[i].x, 0.0);  // not summed there
        EXPECT_EQ(other.reaction[i].y, 0.0);
        some_contact = some_contact || all.contact[i].x != 0.0 || all.contact[i].y != 0.0;
        EXPECT_GE(r.set_cost(k), 1);
    }
    EXPECT_GT(sim.contact_counts().in_contact, 0);
    EXPECT_TRUE(some_contact);  // the block presses on the ground: the sums are not all zero
    EXPECT_EQ(a.time, all.time);
    EXPECT_EQ(b.time, all.time);
}

// A distributed run clears and adds to f only where a set reads f (a fixed body's reaction,
// eq. 8.2) and to f_contact where it reads the contact force (contact/contact.cpp
// set_force_readers()): the two lists are ascending, make up read_nodes(), and f is read only at
// fixed bodies' nodes.
TEST(Resultants, ReadNodesAreTheContactReadsAndTheForceReads) {
    Simulation sim = Simulation::from_file(kParticles);
    const Model& m = sim.model();
    const Resultants r(m, sim.state().topology);
    bool fixed_reads = false, contact_reads = false;
    for (int32_t k = 0; k < r.num_sets(); ++k) {
        const std::vector<NodeId>& c = r.contact_read_nodes(k);
        const std::vector<NodeId>& f = r.force_read_nodes(k);
        EXPECT_TRUE(std::is_sorted(c.begin(), c.end())) << r.name(k);
        EXPECT_TRUE(std::is_sorted(f.begin(), f.end())) << r.name(k);
        std::vector<NodeId> both;
        std::set_union(c.begin(), c.end(), f.begin(), f.end(), std::back_inserter(both));
        EXPECT_EQ(both, r.read_nodes(k)) << r.name(k);
        for (const NodeId i : f) {
            const Body& b = m.bodies[static_cast<size_t>(m.node_body[static_cast<size_t>(i)])];
            EXPECT_TRUE(b.fixed) << r.name(k) << " node " << i;
        }
        fixed_reads = fixed_reads || !f.empty();
        contact_reads = contact_reads || !c.empty();
    }
    EXPECT_TRUE(fixed_reads);  // the walls are fixed: their reaction reads f
    EXPECT_TRUE(contact_reads);
}

// Each set is summed by the process that owns most of the nodes it reads (so that few contact
// forces travel to a process that does not own their node); a set whose read nodes are split
// evenly goes to the less loaded of those processes; none is lost or duplicated.
TEST(Resultants, SetsGoToTheOwnerOfMostOfTheirNodes) {
    Simulation sim = Simulation::from_file(kDemo);
    const Model& m = sim.model();
    const Resultants r(m, sim.state().topology);
    std::vector<int32_t> reading;  // the sets with read nodes
    for (int32_t k = 0; k < r.num_sets(); ++k) {
        if (!r.read_nodes(k).empty()) reading.push_back(k);
    }
    ASSERT_GE(reading.size(), 2U);
    // every node to process 1: every set with read nodes goes there, whatever the load
    std::vector<int32_t> owner(static_cast<size_t>(m.num_nodes()), 1);
    std::vector<int32_t> rank = r.set_ranks(3, owner);
    ASSERT_EQ(rank.size(), static_cast<size_t>(r.num_sets()));
    for (const int32_t k : reading)
        EXPECT_EQ(rank[static_cast<size_t>(k)], 1) << r.name(k);
    // set k's read nodes to process k % 2, except one node of the first set to the other: the
    // majority still decides
    std::fill(owner.begin(), owner.end(), 0);
    for (const int32_t k : reading) {
        for (const NodeId i : r.read_nodes(k))
            owner[static_cast<size_t>(i)] = k % 2;
    }
    const std::vector<NodeId> first = r.read_nodes(reading[0]);
    if (first.size() >= 3) owner[static_cast<size_t>(first[0])] = 1 - reading[0] % 2;
    rank = r.set_ranks(2, owner);
    for (const int32_t k : reading)
        EXPECT_EQ(rank[static_cast<size_t>(k)], k % 2) << r.name(k);
    // the first set's read nodes split between processes 0 and 1 (the first half to 0), the
    // others' on 2: an odd count has its majority on 1; an even split is a tie, which goes to
    // one of the two owners, never to process 2 that owns none of its nodes
    ASSERT_GE(first.size(), 2U);
    std::fill(owner.begin(), owner.end(), 2);
    for (size_t n = 0; n < first.size(); ++n)
        owner[static_cast<size_t>(first[n])] = n < first.size() / 2 ? 0 : 1;
    rank = r.set_ranks(3, owner);
    const int32_t got = rank[static_cast<size_t>(reading[0])];
    if (first.size() % 2 == 1) {
        EXPECT_EQ(got, 1);
    } else {
        EXPECT_TRUE(got == 0 || got == 1) << got;
    }
}

}  // namespace
}  // namespace fdem
