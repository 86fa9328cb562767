// ContactState::fc_nodes (contact/contact.cpp note_contact_force_nodes(), integrate/step.cpp
// step 2, measure/resultants.cpp): with few pairs in contact a step clears f_contact, and
// bodies.csv sums it, only at the nodes the last applies reached. Every bit must be that of the
// full clear and the full sum, and the list must hold every node whose f_contact is non-zero.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <vector>

#include "fdem/measure.hpp"
#include "fdem/simulate.hpp"
#include "support/scenes.hpp"
#include "support/topology_compare.hpp"

namespace fdem {
namespace {

using fdem::testing::same_bits;

// fc_sparse: every node with a non-zero f_contact is listed (the list is ascending, unique)
::testing::AssertionResult list_holds_every_force(const State& s) {
    const ContactState& cs = s.contact;
    if (!cs.fc_sparse) return ::testing::AssertionSuccess();
    if (!std::is_sorted(cs.fc_nodes.begin(), cs.fc_nodes.end()) ||
        std::adjacent_find(cs.fc_nodes.begin(), cs.fc_nodes.end()) != cs.fc_nodes.end())
        return ::testing::AssertionFailure() << "fc_nodes not ascending without repeats";
    for (size_t i = 0; i < s.f_contact.size(); ++i) {
        const Vec2 fc = s.f_contact[i];
        if ((fc.x != 0 || fc.y != 0) &&
            !std::binary_search(cs.fc_nodes.begin(), cs.fc_nodes.end(), static_cast<NodeId>(i)))
            return ::testing::AssertionFailure() << "node " << i << " has a contact force";
    }
    return ::testing::AssertionSuccess();
}

// The particle box (a few dozen pairs in contact among ~1 000 nodes) stepped with the list, and
// with the list dropped before every step (every step then clears every node): the same x, v,
// f, f_contact and bodies.csv resultants, bit for bit, at every step.
TEST(ContactForceList, ListedClearAndSumGiveTheBitsOfTheFullOnes) {
    omp_set_num_threads(2);
    scenes::ParticleOptions o;
    o.nx = o.ny = 12;
    const Model m = scenes::make_particle_box(o);
    const Real dt = 0.5 * stable_time_step(m);
    State a = make_state(m, dt), b = make_state(m, dt);
    const Resultants r(m, a.topology);
    ASSERT_GE(r.num_sets(), 2);
    int listed_steps = 0, contact_steps = 0;
    for (int k = 0; k < 1200; ++k) {
        listed_steps += a.contact.fc_sparse ? 1 : 0;
        b.contact.fc_sparse = false;
        step(m, a);
        step(m, b);
        contact_steps += a.contact.active_contacts > 0 ? 1 : 0;
        ASSERT_TRUE(same_bits(a.x, b.x)) << "step " << k;
        ASSERT_TRUE(same_bits(a.v, b.v)) << "step " << k;
        ASSERT_TRUE(same_bits(a.f, b.f)) << "step " << k;
        ASSERT_TRUE(same_bits(a.f_contact, b.f_contact)) << "step " << k;
        ASSERT_TRUE(list_holds_every_force(a)) << "step " << k;
        // the resultants: the listed sum (a) against the sum over every node (b has no list)
        for (int32_t set = 0; set < r.num_sets(); ++set) {
            Vec2 ca, ra, cb, rb;
            r.forces(m, a, set, ca, ra);
            r.forces(m, b, set, cb, rb);
            ASSERT_TRUE(same_bits(ca, cb)) << "step " << k << ", set " << set;
            ASSERT_TRUE(same_bits(ra, rb)) << "step " << k << ", set " << set;
        }
    }
    // the comparison means something: the grains touched, and the listed path ran
    EXPECT_GT(contact_steps, 100);
    EXPECT_GT(listed_steps, 1000);
    EXPECT_TRUE(a.contact.fc_sparse);
}

// A saturated pack has more pairs than the list may hold: the apply drops the list and the next
// step clears every node; the bits are those of a run that never lists.
TEST(ContactForceList, TooManyPairsFallBackToTheFullClear) {
    omp_set_num_threads(1);
    scenes::PackOptions o;
    o.blocks_x = o.blocks_y = 12;
    o.gap = 0;
    o.converge = true;
    const Model m = scenes::make_contact_pack(o);
    const Real dt = 0.5 * stable_time_step(m);
    State a = make_state(m, dt), b = make_state(m, dt);
    int dropped = 0;
    for (int k = 0; k < 60; ++k) {
        b.contact.fc_sparse = false;
        step(m, a);
        step(m, b);
        dropped += a.contact.fc_sparse ? 0 : 1;
        ASSERT_TRUE(list_holds_every_force(a)) << "step " << k;
    }
    EXPECT_GT(dropped, 50);  // (every step but the first few)
    EXPECT_GT(a.contact.active_contacts, m.num_nodes() / 16);
    EXPECT_TRUE(same_bits(a.x, b.x));
    EXPECT_TRUE(same_bits(a.v, b.v));
    EXPECT_TRUE(same_bits(a.f_contact, b.f_contact));
}

}  // namespace
}  // namespace fdem
