// Helpers shared by the benchmarks: cached scenes (building a 4M-triangle model takes seconds) and
// the OpenMP thread count taken from a benchmark argument.
#pragma once

#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <tuple>

#include "support/scenes.hpp"

namespace fdem::bench {

/// The block scene for (triangles, gravity+clamp, shuffled), built once per process.
inline const Model& cached_block(int64_t num_tris, bool loaded, bool shuffled) {
    static std::map<std::tuple<int64_t, bool, bool>, std::unique_ptr<Model>> cache;
    auto& slot = cache[{num_tris, loaded, shuffled}];
    if (!slot) {
        scenes::BlockOptions o;
        o.num_tris = num_tris;
        o.gravity = o.clamp = loaded;
        o.shuffled = shuffled;
        // keep at most one big model alive: the 4M case alone is ~0.5 GB
        if (num_tris >= (1 << 20)) cache.clear();
        auto& fresh = cache[{num_tris, loaded, shuffled}];
        fresh = std::make_unique<Model>(scenes::make_block(o));
        return *fresh;
    }
    return *slot;
}

/// The contact-heavy pack (scenes::make_contact_pack) with about num_tris triangles (two per
/// block, square raster), built once per process; the last big one is kept.
/// The contact-saturated pack of issue #16: a brick-bond pack of two-triangle blocks converging
/// on its centre (PackOptions::converge), neighbours closing at closing_speed [m/s]; every gap
/// closes after about gap / closing_speed (gap 0: the blocks start touching).
inline const Model& cached_saturated_pack(int64_t num_tris, Real closing_speed, Real gap) {
    static std::map<std::pair<int64_t, Real>, std::unique_ptr<Model>> cache;
    auto& slot = cache[{num_tris, gap}];
    if (!slot) {
        scenes::PackOptions o;
        o.blocks_x = std::max(1, static_cast<int>(std::lround(std::sqrt(num_tris / 2.0))));
        o.blocks_y = o.blocks_x;
        o.brick_bond = true;
        o.converge = true;
        o.gap = gap;
        // edge speed so that neighbours close at closing_speed: speed x pitch / half width
        o.speed = closing_speed * 0.5 * (o.blocks_x + 0.5);
        slot = std::make_unique<Model>(scenes::make_contact_pack(o));
    }
    return *slot;
}

inline const Model& cached_pack(int64_t num_tris, bool shuffled) {
    static std::map<std::pair<int64_t, bool>, std::unique_ptr<Model>> cache;
    auto& slot = cache[{num_tris, shuffled}];
    if (!slot) {
        scenes::PackOptions o;
        o.blocks_x = std::max(1, static_cast<int>(std::lround(std::sqrt(num_tris / 2.0))));
        o.blocks_y = o.blocks_x;
        o.shuffled = shuffled;
        if (num_tris >= (1 << 20)) cache.clear();
        auto& fresh = cache[{num_tris, shuffled}];
        fresh = std::make_unique<Model>(scenes::make_contact_pack(o));
        return *fresh;
    }
    return *slot;
}

/// The particle box (scenes::make_particle_box) with n x n particles, built once per process.
inline const Model& cached_particles(int n) {
    static std::map<int, std::unique_ptr<Model>> cache;
    auto& slot = cache[n];
    if (!slot) {
        scenes::ParticleOptions o;
        o.nx = o.ny = n;
        slot = std::make_unique<Model>(scenes::make_particle_box(o));
    }
    return *slot;
}

/// Triangle counts 1k ... 4M (x4).
inline void tri_sizes(benchmark::internal::Benchmark* b, int threads) {
    for (int64_t n = 1 << 10; n <= (1 << 22); n *= 4)
        b->Args({n, threads});
}

}  // namespace fdem::bench
