// Per-phase timing of the step on a contact scene (docs/performance.md): the phase functions of
// step() called one by one on a copy of a warmed-up state, so step() itself is not instrumented.
// Times are process CPU seconds (CLOCK_PROCESS_CPUTIME_ID), like Google Benchmark's CPU time:
// on the shared development machine wall time is inflated several-fold by other processes. With
// one thread this is the phase's time on an idle core; with two it is the sum over both.
#pragma once

#include <algorithm>
#include <cmath>
#include <ctime>

#include "contact/contact.hpp"
#include "detect/broad_phase.hpp"
#include "element/cst.hpp"
#include "fdem/simulate.hpp"

namespace fdem::bench {

/// CPU seconds per call of each phase, measured on a copy of s (s is not changed).
struct PhaseTimes {
    double element = 0;     ///< add_internal_forces (F, stress, energy, nodal forces)
    double broad = 0;       ///< update_virtual_nodes + find_candidates (one detection)
    double narrow = 0;      ///< add_contact_forces without rebuild: locate, field, law, scatter
    int64_t pairs = 0;      ///< candidate (node, body) pairs evaluated by one narrow phase
    int64_t cand_tris = 0;  ///< candidate sub-triangles (locate tests) of one narrow phase
};

inline PhaseTimes time_phases(const Model& m, const State& s, int reps) {
    State c = s;  // copy: the phases below must not change the benchmarked trajectory
    struct clock {
        static double now() {
            timespec ts{};
            clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
            return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
        }
    };
    auto secs = [](double a, double b) { return b - a; };
    PhaseTimes p;
    double best_e = 1e30, best_b = 1e30, best_n = 1e30;
    for (int r = 0; r < reps; ++r) {
        std::fill(c.f.begin(), c.f.end(), Vec2{});
        auto t0 = clock::now();
        add_internal_forces(m, c);
        auto t1 = clock::now();
        best_e = std::min(best_e, secs(t0, t1));
        if (m.contact.algorithm == ContactAlgorithm::None) continue;
        t0 = clock::now();
        update_virtual_nodes(m, c);
        find_candidates(m, c.topology, c.x.data(), c.contact.xv.data(), c.contact.cand,
                        c.contact.broad);
        t1 = clock::now();
        best_b = std::min(best_b, secs(t0, t1));
        c.contact.need_rebuild = false;
        c.contact.skin_used = 0;
        t0 = clock::now();
        add_contact_forces(m, c);
        t1 = clock::now();
        best_n = std::min(best_n, secs(t0, t1));
    }
    // fastest of reps: the machine is shared, the minimum is the least disturbed run
    p.element = best_e;
    p.broad = m.contact.algorithm == ContactAlgorithm::None ? 0 : best_b;
    p.narrow = m.contact.algorithm == ContactAlgorithm::None ? 0 : best_n;
    p.pairs = static_cast<int64_t>(c.contact.cand.node.size());
    p.cand_tris = static_cast<int64_t>(c.contact.cand.tri.size());
    return p;
}

}  // namespace fdem::bench
