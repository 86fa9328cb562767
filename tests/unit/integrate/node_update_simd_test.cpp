// AVX-512 node update (integrate/node_update_simd.cpp): x, v and every energy must be bitwise
// those of the portable loop (integrate/step.cpp), with gravity, supports, mass damping, fixed
// bodies (nodes with 1/m = 0), node counts that are not a multiple of 8, the first (half) step,
// and 1 or 2 threads.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>

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
    return node_update_uses_avx512();
}

// `steps` steps with the portable and with the AVX-512 node update: same hash and energies
void expect_same_run(const Model& m, int steps, int threads, Real strain = 0) {
    KernelGuard guard;
    omp_set_num_threads(threads);
    uint64_t hash[2];
    Energy e[2];
    for (int k = 0; k < 2; ++k) {
        set_node_kernel(k == 0 ? NodeKernel::Portable : NodeKernel::Auto);
        ASSERT_EQ(node_update_uses_avx512(), k == 1);
        const State s = scenes::run_perturbed(m, steps, strain);
        hash[k] = scenes::state_hash(s);
        e[k] = s.energy;
    }
    EXPECT_EQ(hash[0], hash[1]);
    EXPECT_EQ(bits(e[0].kinetic), bits(e[1].kinetic));
    EXPECT_EQ(bits(e[0].work_gravity), bits(e[1].work_gravity));
    EXPECT_EQ(bits(e[0].dissipated_viscous), bits(e[1].dissipated_viscous));
    EXPECT_EQ(bits(e[0].work_external), bits(e[1].work_external));
    EXPECT_GT(e[0].kinetic, 0);
}

TEST(NodeUpdateSimd, BlockWithGravityAndSupportIsBitwiseTheSame) {
    if (!simd_available()) GTEST_SKIP() << "no AVX-512 on this CPU: only the portable loop runs";
    scenes::BlockOptions o;
    o.num_tris = 20000;  // 101 x 101 = 10201 nodes: several node blocks, a partial last group
    o.gravity = o.clamp = true;
    const Model m = scenes::make_block(o);
    ASSERT_NE(m.num_nodes() % 8, 0);
    expect_same_run(m, 30, 1);
    expect_same_run(m, 30, 2);
}

TEST(NodeUpdateSimd, MassDampedViscousBlockIsBitwiseTheSame) {
    if (!simd_available()) GTEST_SKIP() << "no AVX-512 on this CPU: only the portable loop runs";
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
    if (!simd_available()) GTEST_SKIP() << "no AVX-512 on this CPU: only the portable loop runs";
    scenes::ParticleOptions o;
    o.nx = o.ny = 20;  // fixed walls: nodes with 1/m = 0 mixed with particle nodes; contact
    const Model m = scenes::make_particle_box(o);
    expect_same_run(m, 200, 2, 1e-5);
}

}  // namespace
}  // namespace fdem
