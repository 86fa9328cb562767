// State::need_energy (docs/performance.md "Cheaper energy"): skipping the strain energy must not
// change a single bit of x and v, and the steps that do evaluate it must report the same
// energies as a run that evaluates it every step.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>

#include "fdem/simulate.hpp"
#include "support/hash.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

struct EnergyRun {
    uint64_t hash = 0;
    std::vector<Energy> sampled;  ///< energies after every 7th step
};

// every_k = 1: energy every step; otherwise only on the steps before a sample (k % 7 == 6)
EnergyRun run(const Model& m, int steps, bool every_step) {
    State s = make_state(m, 0.5 * stable_time_step(m));
    EnergyRun r;
    for (int k = 0; k < steps; ++k) {
        s.need_energy = every_step || k % 7 == 6;
        step(m, s);
        if (k % 7 == 6) r.sampled.push_back(s.energy);
    }
    r.hash = scenes::state_hash(s);
    return r;
}

void expect_same(const EnergyRun& a, const EnergyRun& b) {
    EXPECT_EQ(a.hash, b.hash);  // bitwise: the forces never depend on the energy
    ASSERT_EQ(a.sampled.size(), b.sampled.size());
    for (size_t i = 0; i < a.sampled.size(); ++i) {
        EXPECT_EQ(a.sampled[i].strain, b.sampled[i].strain) << "sample " << i;
        EXPECT_EQ(a.sampled[i].kinetic, b.sampled[i].kinetic) << "sample " << i;
        EXPECT_EQ(a.sampled[i].contact, b.sampled[i].contact) << "sample " << i;
        EXPECT_EQ(a.sampled[i].dissipated_viscous, b.sampled[i].dissipated_viscous);
        EXPECT_EQ(a.sampled[i].dissipated_contact, b.sampled[i].dissipated_contact);
    }
}

// viscous block with gravity and a clamped base, 20k triangles (parallel chunked pass)
TEST(NeedEnergy, BlockStateIsBitwiseTheSame) {
    omp_set_num_threads(2);
    scenes::BlockOptions o;
    o.num_tris = 20000;
    o.gravity = o.clamp = true;
    o.viscosity = 2e3;
    const Model m = scenes::make_block(o);
    const EnergyRun a = run(m, 50, true), b = run(m, 50, false);
    expect_same(a, b);
    EXPECT_GT(a.sampled.back().strain, 0);  // the block deformed: the comparison means something
}

// a small particle box: contact forces, many bodies (the grains touch from about step 300 on)
TEST(NeedEnergy, ParticleBoxStateIsBitwiseTheSame) {
    omp_set_num_threads(2);
    scenes::ParticleOptions o;
    o.nx = o.ny = 12;
    const Model m = scenes::make_particle_box(o);
    const EnergyRun a = run(m, 1000, true), b = run(m, 1000, false);
    expect_same(a, b);
    // pairs in contact at some sample: the stored contact energy compared above means something
    Real most = 0;
    for (const Energy& e : a.sampled)
        most = std::max(most, e.contact);
    EXPECT_GT(most, 0);
}

// Without the flag the strain energy is left at the value of the last evaluating step.
TEST(NeedEnergy, SkippedStepKeepsTheLastStrainEnergy) {
    scenes::BlockOptions o;
    o.num_tris = 2000;
    const Model m = scenes::make_block(o);
    State s = make_state(m, 0.5 * stable_time_step(m));
    for (int k = 0; k < 20; ++k)
        step(m, s);
    const Real strain = s.energy.strain;
    ASSERT_GT(strain, 0);
    s.need_energy = false;
    step(m, s);
    EXPECT_EQ(s.energy.strain, strain);
    s.need_energy = true;
    step(m, s);
    EXPECT_NE(s.energy.strain, strain);
}

// The kinetic energy and the gravity work too (their ordered node sums are skipped); the
// dissipated energy is integrated every step, so it keeps growing.
TEST(NeedEnergy, SkippedStepKeepsTheLastKineticEnergyAndGravityWork) {
    scenes::BlockOptions o;
    o.num_tris = 2000;
    o.gravity = true;
    o.viscosity = 2e3;
    const Model m = scenes::make_block(o);
    State s = make_state(m, 0.5 * stable_time_step(m));
    for (int k = 0; k < 20; ++k)
        step(m, s);
    const Energy e = s.energy;
    ASSERT_GT(e.kinetic, 0);
    ASSERT_NE(e.work_gravity, 0);
    s.need_energy = false;
    step(m, s);
    EXPECT_EQ(s.energy.kinetic, e.kinetic);
    EXPECT_EQ(s.energy.work_gravity, e.work_gravity);
    EXPECT_GT(s.energy.dissipated_viscous, e.dissipated_viscous);
    s.need_energy = true;
    step(m, s);
    EXPECT_NE(s.energy.kinetic, e.kinetic);
    EXPECT_NE(s.energy.work_gravity, e.work_gravity);
}

// The stored contact energy too (an exact sum over the pairs in contact, skipped without the
// flag); each pair's own stored energy is kept by the law every step, so the next evaluating
// step reports the same value as a run that sums it every step (ParticleBoxStateIsBitwiseTheSame).
TEST(NeedEnergy, SkippedStepKeepsTheLastContactEnergy) {
    scenes::ParticleOptions o;
    o.nx = o.ny = 12;
    const Model m = scenes::make_particle_box(o);
    State s = make_state(m, 0.5 * stable_time_step(m));
    int k = 0;
    for (; k < 2000 && !(s.energy.contact > 0); ++k)
        step(m, s);
    ASSERT_GT(s.energy.contact, 0) << "no pair in contact after " << k << " steps";
    const Real contact = s.energy.contact;
    s.need_energy = false;
    step(m, s);
    EXPECT_EQ(s.energy.contact, contact);
    s.need_energy = true;
    step(m, s);
    EXPECT_NE(s.energy.contact, contact);
}

}  // namespace
}  // namespace fdem
