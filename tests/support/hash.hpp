// Bitwise state hash for determinism checks (tests and bench_step), like Box2D's EXPECTED_HASH.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <vector>

#include "fdem/build.hpp"
#include "fdem/simulate.hpp"
#include "fdem/state.hpp"

namespace fdem::scenes {

/// FNV-1a over the n bytes at p, continuing from h (the offset basis to start a hash).
inline uint64_t fnv1a(const unsigned char* p, size_t n, uint64_t h = 1469598103934665603ull) {
    for (size_t i = 0; i < n; ++i) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

/// FNV-1a over the raw bytes of x and v: equal hashes mean bitwise equal positions and velocities.
inline uint64_t state_hash(const State& s) {
    uint64_t h = 1469598103934665603ull;
    for (const std::vector<Vec2>* a : {&s.x, &s.v})
        h = fnv1a(reinterpret_cast<const unsigned char*>(a->data()), a->size() * sizeof(Vec2), h);
    return h;
}

/// The bits of r: EXPECT_EQ(bits(a), bits(b)) compares doubles exactly (also -0 and NaN payloads).
inline uint64_t bits(Real r) {
    return std::bit_cast<uint64_t>(r);
}

/// A state of m away from the reference, for element-pass comparisons: every node moved by up to
/// `amplitude` [m] (deterministic, so every triangle is strained), a velocity of order 1 m/s at
/// every node (viscous stresses) and f zeroed; dt = 1e-6 s.
inline State strained_state(const Model& m, Real amplitude) {
    State s = make_state(m, 1e-6);
    for (size_t i = 0; i < s.x.size(); ++i) {
        s.x[i] += amplitude * Vec2{std::sin(1.7 * i), std::cos(2.3 * i)};
        s.v[i] = Vec2{std::cos(0.9 * i), std::sin(1.1 * i)};
    }
    std::fill(s.f.begin(), s.f.end(), Vec2{});
    return s;
}

/// `steps` steps of m from its initial state with every node moved by up to `strain`
/// (deterministic) so every triangle is strained; the strain energy is evaluated on two steps
/// of three, so both element paths (with and without the energy) run. Used to compare two
/// kernel paths (portable / AVX-512) over whole steps.
inline State run_perturbed(const Model& m, int steps, Real strain) {
    State s = make_state(m, 0.5 * stable_time_step(m));
    for (size_t i = 0; i < s.x.size(); ++i)
        s.x[i] += strain * Vec2{std::sin(1.7 * i), std::cos(2.3 * i)};
    for (int i = 0; i < steps; ++i) {
        s.need_energy = i % 3 != 1;
        step(m, s);
    }
    return s;
}

}  // namespace fdem::scenes
