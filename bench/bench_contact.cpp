// Narrow phase of the smooth contact on the contact-heavy pack (docs/performance.md): one
// add_contact_forces() without broad-phase rebuild = virtual-node update, skin check, history
// merge, locate + field + law of every candidate (node, body) pair, serial scatter.
// items/s = candidate pairs/s; box_pass = fraction of the pairs not rejected by the body box;
// in_contact = pairs in contact (with a force); BM_NarrowPhaseSplit separates the cost of those
// from that of the rejected candidates. Args: {triangles, shuffled numbering (0/1), threads}.
// Shuffled: the blocks are numbered in random order, so the contactor data of neighbouring
// pairs lie far apart in memory.
#include <chrono>

#include "bench_common.hpp"
#include "bench_phases.hpp"
#include "contact/contact.hpp"
#include "fdem/simulate.hpp"

namespace fdem {
namespace {

// warm-up: 100 steps, so that the pack's middle has collided and the pair histories are live
State warm_pack(const Model& m) {
    State s = make_state(m, 0.5 * stable_time_step(m));
    for (int k = 0; k < 100; ++k)
        step(m, s);
    return s;
}

void BM_NarrowPhase(benchmark::State& st) {
    omp_set_num_threads(static_cast<int>(st.range(2)));
    const Model& m = bench::cached_pack(st.range(0), st.range(1) != 0);
    State s = warm_pack(m);
    s.contact.need_rebuild = true;  // candidates from the current positions
    add_contact_forces(m, s);
    for (auto _ : st) {
        s.contact.need_rebuild = false;
        s.contact.skin_used = 0;
        add_contact_forces(m, s);
    }
    const double pairs = static_cast<double>(s.contact.cand.node.size());
    st.SetItemsProcessed(st.iterations() * static_cast<int64_t>(pairs));
    st.counters["omp_threads"] = static_cast<double>(st.range(2));
    st.counters["pairs"] = pairs;
    st.counters["tris_per_pair"] = static_cast<double>(s.contact.cand.tri.size()) / pairs;
    st.counters["in_contact"] = s.contact.active_contacts;
    // pairs that pass the body-box reject (contact.cpp body_boxes()) and run the locate test
    int64_t survivors = 0;
    for (size_t p = 0; p < s.contact.cand.node.size(); ++p) {
        survivors += !box_rejects(s.contact.body_box[s.contact.cand.body[p]],
                                  target_point(s.topology, s.x.data(), s.contact.cand.node[p]));
    }
    st.counters["box_pass"] = static_cast<double>(survivors) / pairs;
    st.counters["sub_tris"] = s.topology.num_sub_tris();
    st.counters["virtual"] = s.topology.num_virtual();
    st.counters["bodies"] = m.num_bodies();
}

BENCHMARK(BM_NarrowPhase)
    ->ArgsProduct({{20000, 200000}, {0, 1}, {1, 2}})
    ->Unit(benchmark::kMicrosecond);

/// The candidates of c whose (node, body) is in `active` (both sorted by (node, body)), in the
/// same order with the same candidate sub-triangles.
Candidates in_contact_candidates(const Candidates& c, const std::vector<ActiveContact>& active) {
    Candidates kept;
    kept.begin.push_back(0);
    size_t ia = 0;
    for (size_t p = 0; p < c.node.size(); ++p) {
        while (ia < active.size() &&
               (active[ia].node < c.node[p] ||
                (active[ia].node == c.node[p] && active[ia].body < c.body[p])))
            ++ia;
        if (ia == active.size() || active[ia].node != c.node[p] || active[ia].body != c.body[p])
            continue;
        kept.node.push_back(c.node[p]);
        kept.body.push_back(c.body[p]);
        kept.tri.insert(kept.tri.end(), c.tri.begin() + c.begin[p], c.tri.begin() + c.begin[p + 1]);
        kept.begin.push_back(static_cast<int32_t>(kept.tri.size()));
    }
    return kept;
}

// BM_NarrowPhase split into its parts (issue #16 item 1). Every iteration times (wall clock)
// the same add_contact_forces() three times (the counters use the fastest of each): on all
// candidates (T_all, the benchmark's time), on the in-contact candidates only (T_in: the list cut
// down to the pairs in contact after the warm-up, same order and sub-triangles) and on no
// candidates (T_0: virtual nodes, skin check, body boxes). Counters: ns_per_in_contact = (T_in -
// T_0) / in-contact pairs, in_contact_per_s its inverse (pairs located, evaluated through the law
// and scattered), ns_per_rejected = (T_all - T_in) / (candidates not in contact), fixed_us = T_0.
void BM_NarrowPhaseSplit(benchmark::State& st) {
    using clock = std::chrono::steady_clock;
    omp_set_num_threads(static_cast<int>(st.range(2)));
    const Model& m = bench::cached_pack(st.range(0), st.range(1) != 0);
    State all = warm_pack(m);
    all.contact.need_rebuild = true;
    add_contact_forces(m, all);
    State in = all, none = all;
    in.contact.cand = in_contact_candidates(all.contact.cand, all.contact.active);
    none.contact.cand = Candidates{};
    none.contact.cand.begin.push_back(0);
    const auto n_all = static_cast<int64_t>(all.contact.cand.node.size());
    const auto n_in = static_cast<int64_t>(in.contact.cand.node.size());
    auto once = [&m](State& s) {
        s.contact.need_rebuild = false;
        s.contact.skin_used = 0;
        const auto t0 = clock::now();
        add_contact_forces(m, s);
        return std::chrono::duration<double>(clock::now() - t0).count();
    };
    once(in);
    once(none);  // releases the warm-up's pairs once, outside the timing
    // the fastest of the iterations for each list: preemption on a shared machine only adds
    double t_all = 1e30, t_in = 1e30, t_0 = 1e30;
    for (auto _ : st) {
        const double a = once(all);
        t_all = std::min(t_all, a);
        t_in = std::min(t_in, once(in));
        t_0 = std::min(t_0, once(none));
        st.SetIterationTime(a);
    }
    if (in.contact.active_contacts != n_in || all.contact.active_contacts != n_in) {
        st.SkipWithError("the pairs in contact changed while timed");
        return;
    }
    st.counters["omp_threads"] = static_cast<double>(st.range(2));
    st.counters["pairs"] = static_cast<double>(n_all);
    st.counters["in_contact"] = static_cast<double>(n_in);
    st.counters["ns_per_in_contact"] = 1e9 * (t_in - t_0) / static_cast<double>(n_in);
    st.counters["in_contact_per_s"] = static_cast<double>(n_in) / (t_in - t_0);
    st.counters["ns_per_rejected"] = 1e9 * (t_all - t_in) / static_cast<double>(n_all - n_in);
    st.counters["fixed_us"] = 1e6 * t_0;
}

BENCHMARK(BM_NarrowPhaseSplit)
    ->ArgsProduct({{20000, 200000}, {0, 1}, {1, 2}})
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

// The per-step body boxes alone (contact.cpp body_boxes(), 1 thread): items/s = bodies/s.
// Arg 2: 0 = body_boxes() (each body's distinct contact nodes), 1 = body_boxes_reference()
// (every sub-triangle's vertices in turn, the specification; the pre-round-5 code).
void BM_BodyBoxes(benchmark::State& st) {
    omp_set_num_threads(1);
    const Model& m = bench::cached_pack(st.range(0), st.range(1) != 0);
    State s = warm_pack(m);
    update_virtual_nodes(m, s);
    std::vector<BodyBox> box(static_cast<size_t>(m.num_bodies()));
    const bool ref = st.range(2) != 0;
    for (auto _ : st) {
        if (ref) {
            body_boxes_reference(s.topology, s.x.data(), s.contact.xv.data(), box.data(),
                                 m.num_bodies());
        } else {
            body_boxes(s.topology, s.x.data(), s.contact.xv.data(), box.data(), m.num_bodies());
        }
        benchmark::DoNotOptimize(box.data());
        benchmark::ClobberMemory();
    }
    st.SetItemsProcessed(st.iterations() * m.num_bodies());
}

BENCHMARK(BM_BodyBoxes)
    ->ArgsProduct({{20000, 200000}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace fdem
