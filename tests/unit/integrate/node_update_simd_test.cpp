// AVX-512 and AVX2 node updates (integrate/node_update_simd.cpp): x, v and every energy must be
// bitwise those of the portable loop (integrate/step.cpp), with gravity, supports, mass damping,
// fixed bodies (nodes with 1/m = 0), node counts that are not a multiple of 8, the first (half)
// step, and 1 or 2 threads.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "fdem/simulate.hpp"
#include "integrate/node_update.hpp"
#include "support/hash.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

struct KernelGuard {
    ~KernelGuard() { set_node_kernel(NodeKernel::Auto); }
};

using scenes::bits;

bool simd_available() {
    set_node_kernel(NodeKernel::Auto);
    return node_update_uses_avx512() || node_update_uses_avx2();
}

// `steps` steps with the portable node update, the CPU's choice (AVX-512 or AVX2) and, where the
// CPU has it, the AVX2 one: same hash and energies
void expect_same_run(const Model& m, int steps, int threads, Real strain = 0) {
    KernelGuard guard;
    omp_set_num_threads(threads);
    std::vector<NodeKernel> kernels = {NodeKernel::Portable, NodeKernel::Auto};
    if (node_update_avx2_available()) kernels.push_back(NodeKernel::Avx2);
    std::vector<uint64_t> hash;
    std::vector<Energy> e;
    for (const NodeKernel k : kernels) {
        set_node_kernel(k);
        if (k == NodeKernel::Portable) {
            ASSERT_FALSE(node_update_uses_avx512() || node_update_uses_avx2());
        } else {
            ASSERT_TRUE(node_update_uses_avx512() || node_update_uses_avx2());
        }
        if (k == NodeKernel::Avx2) {
            ASSERT_TRUE(node_update_uses_avx2());
        }
        const State s = scenes::run_perturbed(m, steps, strain);
        hash.push_back(scenes::state_hash(s));
        e.push_back(s.energy);
    }
    for (size_t k = 1; k < kernels.size(); ++k) {
        SCOPED_TRACE(testing::Message() << "kernel " << static_cast<int>(kernels[k]));
        EXPECT_EQ(hash[0], hash[k]);
        EXPECT_EQ(bits(e[0].kinetic), bits(e[k].kinetic));
        EXPECT_EQ(bits(e[0].work_gravity), bits(e[k].work_gravity));
        EXPECT_EQ(bits(e[0].dissipated_viscous), bits(e[k].dissipated_viscous));
        EXPECT_EQ(bits(e[0].work_external), bits(e[k].work_external));
    }
    EXPECT_GT(e[0].kinetic, 0);
}

TEST(NodeUpdateSimd, BlockWithGravityAndSupportIsBitwiseTheSame) {
    if (!simd_available())
        GTEST_SKIP() << "no AVX-512 or AVX2 on this CPU: only the portable loop runs";
    scenes::BlockOptions o;
    o.num_tris = 20000;  // 101 x 101 = 10201 nodes: several node blocks, a partial last group
    o.gravity = o.clamp = true;
    const Model m = scenes::make_block(o);
    ASSERT_NE(m.num_nodes() % 8, 0);
    expect_same_run(m, 30, 1);
    expect_same_run(m, 30, 2);
}

TEST(NodeUpdateSimd, MassDampedViscousBlockIsBitwiseTheSame) {
    if (!simd_available())
        GTEST_SKIP() << "no AVX-512 or AVX2 on this CPU: only the portable loop runs";
    scenes::BlockOptions o;
    o.num_tris = 3000;
    o.gravity = true;
    o.viscosity = 2e3;
    Model m = scenes::make_block(o);
    m.mass_damping = {50.0, 1.0};  // on for every step of the run
    expect_same_run(m, 40, 1);
    // without gravity: the damped-only kernel
    m.gravity = {0, 0};
    expect_same_run(m, 40, 1);
}

TEST(NodeUpdateSimd, ParticleBoxWithFixedWallsIsBitwiseTheSame) {
    if (!simd_available())
        GTEST_SKIP() << "no AVX-512 or AVX2 on this CPU: only the portable loop runs";
    scenes::ParticleOptions o;
    o.nx = o.ny = 20;  // fixed walls: nodes with 1/m = 0 mixed with particle nodes; contact
    const Model m = scenes::make_particle_box(o);
    expect_same_run(m, 200, 2, 1e-5);
}

}  // namespace
}  // namespace fdem
