// SIMD CST kernels (element/cst_simd.cpp, AVX-512; the AVX2 loops of element/cst.cpp): the forces,
// the strain energy, the smallest det F and its triangle must be bitwise those of the portable
// kernel (element/cst.cpp), for full groups of 8 triangles, the partial group at the end of a
// range, inverted triangles and whole steps.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "element/cst.hpp"
#include "fdem/scenario.hpp"
#include "fdem/simulate.hpp"
#include "support/hash.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

// Restores the default kernel when a test ends, also on failure.
struct KernelGuard {
    ~KernelGuard() { set_cst_kernel(CstKernel::Auto); }
};

bool simd_available() {
    set_cst_kernel(CstKernel::Auto);
    return std::string(cst_kernel_name()) != "portable";
}

// the SIMD kernels this CPU runs: Auto (AVX-512 or AVX2) and, where it has AVX2, the AVX2 one
std::vector<CstKernel> simd_kernels() {
    std::vector<CstKernel> k;
    if (simd_available()) k.push_back(CstKernel::Auto);
    if (cst_avx2_available()) k.push_back(CstKernel::Avx2);
    return k;
}

using scenes::bits;

struct Pass {
    std::vector<Vec2> f;
    ElementPass p;
};

// serial pass over all triangles with the given kernel (velocities v, zero when empty)
Pass serial_pass(const Model& m, const std::vector<Vec2>& x, CstKernel k,
                 const std::vector<Vec2>& v_in = {}) {
    set_cst_kernel(k);
    Pass r;
    r.f.assign(x.size(), Vec2{});
    const std::vector<Vec2> v = v_in.empty() ? std::vector<Vec2>(x.size()) : v_in;
    r.p = add_internal_forces(m, x.data(), v.data(), r.f.data(), 0, m.num_tris());
    return r;
}

void expect_same_bits(const Pass& a, const Pass& b) {
    ASSERT_EQ(a.f.size(), b.f.size());
    for (size_t i = 0; i < a.f.size(); ++i) {
        ASSERT_EQ(bits(a.f[i].x), bits(b.f[i].x)) << "node " << i;
        ASSERT_EQ(bits(a.f[i].y), bits(b.f[i].y)) << "node " << i;
    }
    EXPECT_EQ(bits(a.p.strain_energy), bits(b.p.strain_energy));
    EXPECT_EQ(bits(a.p.viscous_power), bits(b.p.viscous_power));
    EXPECT_EQ(bits(a.p.min_jacobian), bits(b.p.min_jacobian));
    EXPECT_EQ(a.p.min_jacobian_tri, b.p.min_jacobian_tri);
}

// a block whose nodes are moved by up to `amplitude` cell sizes (seeded): strains of every sign
// and size, and with amplitude ~0.5 some inverted triangles
std::vector<Vec2> perturbed(const Model& m, Real amplitude, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> u(-1.0, 1.0);
    const Real h = 1.0 / std::sqrt(m.num_tris() / 2.0);
    std::vector<Vec2> x = m.node_x0;
    for (Vec2& p : x)
        p += amplitude * h * Vec2{u(rng), u(rng)};
    return x;
}

TEST(CstSimd, ForcesEnergyAndSmallestJMatchThePortableKernel) {
    if (!simd_available())
        GTEST_SKIP() << "no AVX-512 or AVX2 on this CPU: only the portable kernel runs";
    KernelGuard guard;
    // 2 * 37 * 37 = 2738 triangles: not a multiple of 8, so the last group is partial
    scenes::BlockOptions o;
    o.num_tris = 2738;
    const Model m = scenes::make_block(o);
    ASSERT_NE(m.num_tris() % 8, 0);
    for (uint32_t seed : {1u, 2u, 3u}) {
        const std::vector<Vec2> x = perturbed(m, 0.1, seed);
        const Pass a = serial_pass(m, x, CstKernel::Portable);
        for (const CstKernel k : simd_kernels())
            expect_same_bits(a, serial_pass(m, x, k));
        EXPECT_GT(a.p.strain_energy, 0);
        EXPECT_GT(a.p.min_jacobian, 0);  // no inverted triangle at this amplitude
    }
}

TEST(CstSimd, InvertedTrianglesAndEveryRangeEndMatch) {
    if (!simd_available())
        GTEST_SKIP() << "no AVX-512 or AVX2 on this CPU: only the portable kernel runs";
    KernelGuard guard;
    scenes::BlockOptions o;
    o.num_tris = 800;
    const Model m = scenes::make_block(o);
    // large moves: some triangles inverted (J <= 0), others not; ranges [0, end) of every length
    // from 1 to 40 cover every partial group
    const std::vector<Vec2> x = perturbed(m, 0.6, 11);
    const Pass all = serial_pass(m, x, CstKernel::Portable);
    ASSERT_LT(all.p.min_jacobian, 0);  // the scene does hold inverted triangles
    std::vector<CstKernel> kernels = {CstKernel::Portable};
    for (const CstKernel k : simd_kernels())
        kernels.push_back(k);
    for (TriId end = 1; end <= 40; ++end) {
        for (const CstKernel k : kernels) {
            set_cst_kernel(k);
            std::vector<Vec2> f(x.size());
            const std::vector<Vec2> v(x.size());
            const ElementPass p = add_internal_forces(m, x.data(), v.data(), f.data(), 0, end);
            static std::vector<Vec2> f_ref;
            static ElementPass p_ref;
            if (k == CstKernel::Portable) {
                f_ref = f;
                p_ref = p;
                continue;
            }
            expect_same_bits({f_ref, p_ref}, {f, p});
        }
    }
    for (const CstKernel k : simd_kernels())
        expect_same_bits(all, serial_pass(m, x, k));
}

// The AVX2 kernel (CstKernel::Avx2; Auto on CPUs with AVX2 but not AVX-512) against the portable
// loops on a step without the energy (the chunked pass of a State with need_energy off, whose
// portable path is the blocked elastic_range), inverted triangles included, on blocks whose sizes
// leave partial groups
TEST(CstSimd, Avx2PassWithoutEnergyMatchesThePortableKernel) {
    if (!cst_avx2_available()) GTEST_SKIP() << "no AVX2 on this CPU";
    KernelGuard guard;
    for (const int64_t num_tris : {800, 2738, 20000}) {
        scenes::BlockOptions o;
        o.num_tris = num_tris;
        const Model m = scenes::make_block(o);
        for (const Real amplitude : {0.1, 0.6}) {
            Pass r[2];
            for (int k = 0; k < 2; ++k) {
                set_cst_kernel(k == 0 ? CstKernel::Portable : CstKernel::Avx2);
                EXPECT_STREQ(cst_kernel_name(), k == 0 ? "portable" : "avx2");
                State s = make_state(m, 1e-6);
                s.x = perturbed(m, amplitude, 7);
                s.need_energy = false;
                r[k].p = add_internal_forces(m, s);
                r[k].f = s.f;
            }
            SCOPED_TRACE(testing::Message() << num_tris << " triangles, amplitude " << amplitude);
            expect_same_bits(r[0], r[1]);
            if (amplitude > 0.5) {
                EXPECT_LT(r[0].p.min_jacobian, 0);  // inverted triangles were skipped alike
            }
            Real most = 0;
            for (const Vec2& fi : r[0].f)
                most = std::max(most, std::fabs(fi.x));
            EXPECT_GT(most, 0);  // the pass did compute forces
        }
    }
}

// seeded random nodal velocities up to `amplitude` [m/s] in each component
std::vector<Vec2> random_velocities(size_t n, Real amplitude, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> u(-1.0, 1.0);
    std::vector<Vec2> v(n);
    for (Vec2& p : v)
        p = amplitude * Vec2{u(rng), u(rng)};
    return v;
}

// a block of a viscous material (viscosity > 0, so every chunk takes the viscous path) whose
// tri_eta is 0 in some triangles (theory eq. 2.4 applies only where eta > 0): mixed groups, a
// run of 16 (two whole groups) without viscosity, and one with eta > 0 everywhere
Model viscous_block(int64_t num_tris) {
    scenes::BlockOptions o;
    o.num_tris = num_tris;
    o.viscosity = 500.0;
    Model m = scenes::make_block(o);
    for (TriId t = 0; t < m.num_tris(); ++t) {
        if (t % 5 == 0 || t % 7 == 3 || (t >= 96 && t < 112)) m.tri_eta[t] = 0;
        if (t % 11 == 4) m.tri_eta[t] = 1e-3 * (1 + t % 3);  // small but > 0
    }
    return m;
}

TEST(CstSimd, ViscousForcesEnergyPowerAndSmallestJMatchThePortableKernel) {
    if (!simd_available())
        GTEST_SKIP() << "no AVX-512 or AVX2 on this CPU: only the portable kernel runs";
    KernelGuard guard;
    const Model m = viscous_block(2738);  // last group partial
    ASSERT_NE(m.num_tris() % 8, 0);
    for (uint32_t seed : {1u, 2u, 3u}) {
        const std::vector<Vec2> x = perturbed(m, 0.1, seed);
        const std::vector<Vec2> v = random_velocities(x.size(), 0.5, seed + 100);
        const Pass a = serial_pass(m, x, CstKernel::Portable, v);
        for (const CstKernel k : simd_kernels())
            expect_same_bits(a, serial_pass(m, x, k, v));
        EXPECT_GT(a.p.viscous_power, 0);
        EXPECT_GT(a.p.min_jacobian, 0);
        // the viscous stress does change the forces (else the comparison would prove little)
        const Pass e = serial_pass(m, x, CstKernel::Portable);
        EXPECT_NE(bits(a.f[m.tri_nodes[1][0]].x), bits(e.f[m.tri_nodes[1][0]].x));
    }
}

TEST(CstSimd, ViscousInvertedTrianglesAndEveryRangeEndMatch) {
    if (!simd_available())
        GTEST_SKIP() << "no AVX-512 or AVX2 on this CPU: only the portable kernel runs";
    KernelGuard guard;
    const Model m = viscous_block(800);
    const std::vector<Vec2> x = perturbed(m, 0.6, 11);
    const std::vector<Vec2> v = random_velocities(x.size(), 0.5, 12);
    const Pass all = serial_pass(m, x, CstKernel::Portable, v);
    ASSERT_LT(all.p.min_jacobian, 0);  // the scene does hold inverted triangles
    ASSERT_GT(all.p.viscous_power, 0);
    std::vector<CstKernel> kernels = {CstKernel::Portable};
    for (const CstKernel k : simd_kernels())
        kernels.push_back(k);
    for (TriId begin : {0, 5, 93}) {
        for (TriId end = begin + 1; end <= begin + 40; ++end) {
            std::vector<Pass> r;
            for (const CstKernel k : kernels) {
                set_cst_kernel(k);
                Pass p;
                p.f.assign(x.size(), Vec2{});
                p.p = add_internal_forces(m, x.data(), v.data(), p.f.data(), begin, end);
                r.push_back(std::move(p));
            }
            for (size_t k = 1; k < r.size(); ++k)
                expect_same_bits(r[0], r[k]);
        }
    }
    for (const CstKernel k : simd_kernels())
        expect_same_bits(all, serial_pass(m, x, k, v));
}

// whole steps (parallel chunked pass, node update) give the same state hash and energies;
// `strain` > 0 moves every node by up to that much (deterministic) so every triangle is strained
void expect_same_run(const Model& m, int steps, int threads, Real strain = 0) {
    KernelGuard guard;
    omp_set_num_threads(threads);
    // Auto (AVX-512 or AVX2 by the CPU) and, where the CPU has it, the AVX2 choice
    std::vector<CstKernel> kernels = {CstKernel::Portable, CstKernel::Auto};
    if (cst_avx2_available()) kernels.push_back(CstKernel::Avx2);
    std::vector<uint64_t> hash;
    std::vector<Energy> e;
    for (const CstKernel k : kernels) {
        set_cst_kernel(k);
        const State s = scenes::run_perturbed(m, steps, strain);
        hash.push_back(scenes::state_hash(s));
        e.push_back(s.energy);
    }
    for (size_t k = 1; k < kernels.size(); ++k) {
        SCOPED_TRACE(testing::Message() << "kernel " << static_cast<int>(kernels[k]));
        EXPECT_EQ(hash[0], hash[k]);
        EXPECT_EQ(bits(e[0].strain), bits(e[k].strain));
        EXPECT_EQ(bits(e[0].kinetic), bits(e[k].kinetic));
        EXPECT_EQ(bits(e[0].dissipated_viscous), bits(e[k].dissipated_viscous));
    }
    EXPECT_GT(e[0].strain, 0);
}

TEST(CstSimd, BlockStepsAreBitwiseTheSame) {
    if (!simd_available())
        GTEST_SKIP() << "no AVX-512 or AVX2 on this CPU: only the portable kernel runs";
    scenes::BlockOptions o;
    o.num_tris = 20000;  // parallel pass (> 32 chunks)
    o.gravity = o.clamp = true;
    const Model m = scenes::make_block(o);
    expect_same_run(m, 30, 1);
    expect_same_run(m, 30, 2);
}

TEST(CstSimd, ViscousBlockStepsAreBitwiseTheSame) {
    if (!simd_available())
        GTEST_SKIP() << "no AVX-512 or AVX2 on this CPU: only the portable kernel runs";
    scenes::BlockOptions o;
    o.num_tris = 20000;  // parallel pass (> 32 chunks)
    o.gravity = o.clamp = true;
    o.viscosity = 2000.0;
    const Model m = scenes::make_block(o);
    expect_same_run(m, 30, 1);
    expect_same_run(m, 30, 2);
}

TEST(CstSimd, ParticleBoxStepsAreBitwiseTheSame) {
    if (!simd_available())
        GTEST_SKIP() << "no AVX-512 or AVX2 on this CPU: only the portable kernel runs";
    scenes::ParticleOptions o;
    o.nx = o.ny = 20;  // chunks of many 5-8 triangle bodies: partial groups everywhere; contact
    const Model m = scenes::make_particle_box(o);
    expect_same_run(m, 200, 2, 1e-5);
}

// first_internal_forces (the serial step's element pass, docs/performance.md "Stop 49"): the
// chunks of a jointed block (every triangle its own nodes) store their nodes' forces, so f there
// may hold anything before the pass; the forces, energies and smallest det F must be the bits of
// zeroing f and adding (add_internal_forces), for every kernel, with and without the energy,
// elastic and viscous, inverted triangles included (their nodes get the cleared zeros), on 1 and
// 2 threads. Without fracture no chunk is a first writer and every node is cleared.
TEST(CstSimd, FirstWriterChunksStoreTheBitsOfClearAndAdd) {
    KernelGuard guard;
    std::vector<CstKernel> kernels{CstKernel::Portable};
    for (const CstKernel k : simd_kernels())
        kernels.push_back(k);
    for (const Real viscosity : {0.0, 2000.0}) {
        scenes::BlockOptions o;
        o.num_tris = 20000;  // parallel pass (> 32 chunks), a partial group per chunk end
        o.jointed = true;
        o.viscosity = viscosity;
        const Model m = scenes::make_block(o);
        const ElementSchedule& sc = m.element_schedule;
        ASSERT_EQ(sc.chunk_first.size(), static_cast<size_t>(sc.num_chunks()));
        EXPECT_TRUE(std::all_of(sc.chunk_first.begin(), sc.chunk_first.end(),
                                [](uint8_t c) { return c == 1; }));
        EXPECT_TRUE(sc.clear_runs.empty());  // every node is a triangle's own
        for (const Real amplitude : {0.1, 0.6}) {
            const std::vector<Vec2> x = perturbed(m, amplitude, 5);
            const std::vector<Vec2> v = random_velocities(x.size(), 0.3, 9);
            for (const CstKernel k : kernels) {
                for (const bool energy : {false, true}) {
                    for (const int threads : {1, 2}) {
                        SCOPED_TRACE(testing::Message()
                                     << "eta " << viscosity << ", amplitude " << amplitude
                                     << ", kernel " << static_cast<int>(k) << ", energy " << energy
                                     << ", threads " << threads);
                        set_cst_kernel(k);
                        omp_set_num_threads(threads);
                        Pass r[2];
                        for (int first = 0; first < 2; ++first) {
                            State s = make_state(m, 1e-6);
                            s.x = x;
                            s.v = v;
                            s.need_energy = energy;
                            if (first) {
                                // what a step leaves: last step's forces; here NaN everywhere
                                std::fill(s.f.begin(), s.f.end(), Vec2{NAN, NAN});
                                r[first].p = first_internal_forces(m, s);
                            } else {
                                std::fill(s.f.begin(), s.f.end(), Vec2{});
                                r[first].p = add_internal_forces(m, s);
                            }
                            r[first].f = s.f;
                        }
                        expect_same_bits(r[0], r[1]);
                        if (amplitude > 0.5) EXPECT_LT(r[0].p.min_jacobian, 0);
                    }
                }
            }
        }
    }
    omp_set_num_threads(omp_get_num_procs());
    // a continuum (shared nodes): no first writer, one clear run of every node
    scenes::BlockOptions o;
    o.num_tris = 2000;
    const Model m = scenes::make_block(o);
    EXPECT_TRUE(std::none_of(m.element_schedule.chunk_first.begin(),
                             m.element_schedule.chunk_first.end(), [](uint8_t c) { return c; }));
    ASSERT_EQ(m.element_schedule.clear_runs.size(), 1u);
    EXPECT_EQ(m.element_schedule.clear_runs[0][0], 0);
    EXPECT_EQ(m.element_schedule.clear_runs[0][1], m.num_nodes());
}

// A scenario with a jointed specimen between continuum platens (example 09, UCS): the
// specimen's chunks are first writers, the platens' nodes (and only theirs) are cleared.
TEST(CstSimd, FirstWriterScheduleOfTheUcsExample) {
    const Scenario sc = load_scenario(FDEM_SOURCE_DIR "/examples/09_ucs/scenario.toml");
    const Model& m = sc.model;
    const ElementSchedule& es = m.element_schedule;
    std::vector<int> uses(static_cast<size_t>(m.num_nodes()), 0);
    for (const auto& q : m.tri_nodes) {
        for (NodeId n : q)
            ++uses[static_cast<size_t>(n)];
    }
    std::vector<uint8_t> cleared(static_cast<size_t>(m.num_nodes()), 0);
    for (const auto& [b, e] : es.clear_runs) {
        ASSERT_LT(b, e);
        for (NodeId n = b; n < e; ++n)
            cleared[static_cast<size_t>(n)] = 1;
    }
    int first_chunks = 0;
    std::vector<uint8_t> stored(static_cast<size_t>(m.num_nodes()), 0);
    for (int32_t k = 0; k < es.num_chunks(); ++k) {
        const auto [b, e] = es.chunk_tris[static_cast<size_t>(k)];
        bool own = true;
        for (TriId t = b; t < e; ++t) {
            for (NodeId n : m.tri_nodes[t])
                own = own && uses[static_cast<size_t>(n)] == 1;
        }
        EXPECT_EQ(es.chunk_first[static_cast<size_t>(k)] != 0, own) << "chunk " << k;
        if (!es.chunk_first[static_cast<size_t>(k)]) continue;
        ++first_chunks;
        for (TriId t = b; t < e; ++t) {
            for (NodeId n : m.tri_nodes[t])
                stored[static_cast<size_t>(n)] = 1;
        }
    }
    EXPECT_GT(first_chunks, 0);
    EXPECT_LT(first_chunks, es.num_chunks());   // the platens share nodes
    for (NodeId n = 0; n < m.num_nodes(); ++n)  // each node is stored or cleared, never both
        ASSERT_NE(stored[static_cast<size_t>(n)], cleared[static_cast<size_t>(n)]) << "node " << n;
}

}  // namespace
}  // namespace fdem
