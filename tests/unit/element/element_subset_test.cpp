// "Owner computes" for the element pass (issue #15, spec parallel-and-python.md D7.1; element/
// cst.hpp ElementSubset): P simulated processes, each running only the chunks that touch its
// nodes, give every owned node the serial force bit for bit, and their exact energy sums add up
// to the serial pass's bits, for any assignment of nodes to processes.
#include <gtest/gtest.h>
#include <omp.h>

#include <bit>
#include <cmath>
#include <random>
#include <vector>

#include "element/cst.hpp"
#include "fdem/build.hpp"
#include "fdem/simulate.hpp"
#include "support/hash.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

uint64_t bits(double x) {
    return std::bit_cast<uint64_t>(x);
}

// a state away from the reference: displaced nodes (every triangle strained) and velocities
// (viscous stresses)
State strained_state(const Model& m) {
    return scenes::strained_state(m, 1e-3);
}

// sums = false: a step without energies (need_energy false, no viscous power read): the chunks
// run only their triangles of owned nodes; the owned forces and the smallest det F must still
// be the serial ones
void check_partition(const Model& m, const std::vector<int32_t>& owner, int procs,
                     bool sums = true) {
    State serial = strained_state(m);
    const ElementPass ref = add_internal_forces(m, serial);
    ASSERT_GT(ref.strain_energy, 0);

    std::vector<int> counted(static_cast<size_t>(m.element_schedule.num_chunks()), 0);
    ExactSum strain, viscous;
    Real min_j = std::numeric_limits<Real>::infinity();
    int32_t min_chunk = -1;
    TriId min_tri = kNone;
    for (int32_t r = 0; r < procs; ++r) {
        const ElementSubset sub = element_subset(m, owner, r);
        State s = strained_state(m);
        s.need_energy = sums;
        const ElementSubsetPass p = add_internal_forces(m, s, sub, sums);
        for (size_t n = 0; n < s.f.size(); ++n) {
            if (owner[n] != r) continue;
            ASSERT_EQ(bits(s.f[n].x), bits(serial.f[n].x)) << "node " << n << " process " << r;
            ASSERT_EQ(bits(s.f[n].y), bits(serial.f[n].y)) << "node " << n << " process " << r;
        }
        for (size_t i = 0; i < sub.chunks.size(); ++i)
            counted[static_cast<size_t>(sub.chunks[i])] += sub.counts_energy[i];
        strain.add(p.strain_energy);
        viscous.add(p.viscous_power);
        // the minimum over processes, ties to the smallest chunk: the serial pass's
        // (and to the smallest triangle of that chunk: step.cpp's reduction)
        if (p.min_jacobian < min_j ||
            (p.min_jacobian == min_j &&
             (p.min_jacobian_chunk < min_chunk ||
              (p.min_jacobian_chunk == min_chunk && p.min_jacobian_tri < min_tri)))) {
            min_j = p.min_jacobian;
            min_chunk = p.min_jacobian_chunk;
            min_tri = p.min_jacobian_tri;
        }
    }
    for (size_t k = 0; k < counted.size(); ++k)
        ASSERT_EQ(counted[k], 1) << "chunk " << k << " counted by " << counted[k] << " processes";
    if (sums) {
        EXPECT_EQ(bits(strain.value()), bits(ref.strain_energy));
        EXPECT_EQ(bits(viscous.value()), bits(ref.viscous_power));
    }
    EXPECT_EQ(bits(min_j), bits(ref.min_jacobian));
    EXPECT_EQ(min_tri, ref.min_jacobian_tri);
}

Model viscous_block() {
    scenes::BlockOptions o;
    o.num_tris = 20000;
    o.shuffled = true;  // node and triangle ids with no spatial order
    o.viscosity = 50.0;
    return scenes::make_block(o);
}

TEST(ElementSubset, OwnedForcesAndEnergiesAreSerialForAnyPartition) {
    const Model m = viscous_block();
    ASSERT_GE(m.element_schedule.num_chunks(), 32);  // the subset passes run in parallel too
    const size_t nn = static_cast<size_t>(m.num_nodes());
    for (int procs : {1, 2, 3, 4}) {
        // spatial strips (what RCB gives) and a random assignment (the worst case)
        std::vector<int32_t> strips(nn), random(nn);
        std::mt19937 rng(static_cast<unsigned>(procs));
        for (size_t n = 0; n < nn; ++n) {
            strips[n] = std::min(procs - 1, static_cast<int>(m.node_x0[n].x * procs));
            random[n] = static_cast<int32_t>(rng() % static_cast<unsigned>(procs));
        }
        for (const bool sums : {true, false}) {
            check_partition(m, strips, procs, sums);
            check_partition(m, random, procs, sums);
        }
    }
    // one process owning a few scattered nodes: its subset is a few chunks, each needed only
    // through one triangle corner
    std::vector<int32_t> sparse(nn, 0);
    std::mt19937 rng(99);
    for (int k = 0; k < 40; ++k)
        sparse[rng() % nn] = 1;
    check_partition(m, sparse, 2);
}

TEST(ElementSubset, CompositeAndSmallBodies) {
    const Model m = scenes::make_mixed_element_model();
    std::vector<int32_t> owner(static_cast<size_t>(m.num_nodes()));
    std::mt19937 rng(11);
    for (int32_t& o : owner)
        o = static_cast<int32_t>(rng() % 3);
    check_partition(m, owner, 3);
    check_partition(m, owner, 3, false);
}

// A model whose element schedule groups several chunks per unit (262 144 triangles: units of
// 4 chunks): each subset keeps the schedule's units, so owned forces stay the serial bits.
TEST(ElementSubset, UnitsOfSeveralChunks) {
    scenes::BlockOptions o;
    o.num_tris = 1 << 18;
    o.viscosity = 50.0;
    const Model m = scenes::make_block(o);
    ASSERT_GT(element_unit_chunks(m.element_schedule.num_chunks()), 1);
    const size_t nn = static_cast<size_t>(m.num_nodes());
    for (int procs : {2, 3}) {
        std::vector<int32_t> strips(nn), random(nn);
        std::mt19937 rng(static_cast<unsigned>(procs) + 17);
        for (size_t n = 0; n < nn; ++n) {
            strips[n] = std::min(procs - 1, static_cast<int>(m.node_x0[n].x * procs));
            random[n] = static_cast<int32_t>(rng() % static_cast<unsigned>(procs));
        }
        check_partition(m, strips, procs);
        check_partition(m, random, procs, false);
    }
}

// A subset pass gives the same bits on 1 and 2 threads (its own OpenMP schedule).
TEST(ElementSubset, SameBitsForOneAndTwoThreads) {
    const Model m = viscous_block();
    std::vector<int32_t> owner(static_cast<size_t>(m.num_nodes()));
    for (size_t n = 0; n < owner.size(); ++n)
        owner[n] = m.node_x0[n].y < 0.5 ? 0 : 1;
    const ElementSubset sub = element_subset(m, owner, 1);
    auto run = [&](int threads) {
        omp_set_num_threads(threads);
        State s = strained_state(m);
        const ElementSubsetPass p = add_internal_forces(m, s, sub);
        return std::make_pair(s.f, p.strain_energy.value());
    };
    const auto a = run(1);
    const auto b = run(2);
    omp_set_num_threads(2);
    EXPECT_EQ(bits(a.second), bits(b.second));
    for (size_t n = 0; n < a.first.size(); ++n) {
        ASSERT_EQ(bits(a.first[n].x), bits(b.first[n].x));
        ASSERT_EQ(bits(a.first[n].y), bits(b.first[n].y));
    }
}

}  // namespace
}  // namespace fdem
