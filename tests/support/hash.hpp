// Bitwise state hash for determinism checks (tests and bench_step), like Box2D's EXPECTED_HASH.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

#include "fdem/state.hpp"

namespace fdem::scenes {

/// FNV-1a over the raw bytes of x and v: equal hashes mean bitwise equal positions and velocities.
inline uint64_t state_hash(const State& s) {
    uint64_t h = 1469598103934665603ull;
    auto mix = [&h](const std::vector<Vec2>& a) {
        const auto* p = reinterpret_cast<const unsigned char*>(a.data());
        for (size_t i = 0; i < a.size() * sizeof(Vec2); ++i) {
            h ^= p[i];
            h *= 1099511628211ull;
        }
    };
    mix(s.x);
    mix(s.v);
    return h;
}

}  // namespace fdem::scenes
