// Narrow phase of the smooth contact on the contact-heavy pack (docs/performance.md): one
// add_contact_forces() without broad-phase rebuild = virtual-node update, skin check, history
// merge, locate + field + law of every candidate (node, body) pair, serial scatter.
// items/s = candidate pairs/s; box_pass = fraction of the pairs not rejected by the body box. Args:
// {triangles, shuffled numbering (0/1), threads}. Shuffled: the blocks are numbered in random
// order, so the contactor data of neighbouring pairs lie far apart in memory.
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
    st.counters["active"] = s.contact.active_contacts;
    // pairs that pass the body-box reject (contact.cpp body_boxes()) and run the locate test
    int64_t survivors = 0;
    for (size_t p = 0; p < s.contact.cand.node.size(); ++p) {
        survivors += !box_rejects(s.contact.body_box[s.contact.cand.body[p]],
                                  target_point(m.contact, s.x.data(), s.contact.cand.node[p]));
    }
    st.counters["box_pass"] = static_cast<double>(survivors) / pairs;
    st.counters["sub_tris"] = m.contact.num_sub_tris();
    st.counters["virtual"] = m.contact.num_virtual();
    st.counters["bodies"] = m.num_bodies();
}

BENCHMARK(BM_NarrowPhase)
    ->ArgsProduct({{20000, 200000}, {0, 1}, {1, 2}})
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
            body_boxes_reference(m.contact, s.x.data(), s.contact.xv.data(), box.data(),
                                 m.num_bodies());
        } else {
            body_boxes(m.contact, s.x.data(), s.contact.xv.data(), box.data(), m.num_bodies());
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
