// Cohesive joint kernel (docs/performance.md "Fracture joints", theory §9): joint_forces on a
// jointed structured mesh (every triangle its own nodes, a joint per internal edge, ~1.5 joints
// per triangle), intact joints loaded elastically (random separations up to 0.3 o_p).
// items/s = joint-steps/s. Args: {triangles, OpenMP threads}; 2048 triangles keep the whole scene
// in L2 (the rate is about the same as at 16 k: the kernel is not limited by the cache). NoEnergy:
// without E_joint (as the step between outputs); the work W_J is accumulated in both.
#include <random>

#include "bench_common.hpp"
#include "fdem/mesh.hpp"
#include "fracture/joint_mesh.hpp"
#include "fracture/joints.hpp"

namespace fdem {
namespace {

struct JointScene {
    Joints J;
    std::vector<Vec2> x;
};

// x0 moved by seeded random offsets up to 0.15 o_p in each component (o_p the elastic opening
// 2 h f_t / p): every joint loaded, none beyond its elastic range
std::vector<Vec2> perturbed(std::vector<Vec2> x0, Real op) {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> U(-0.15 * op, 0.15 * op);
    for (auto& p : x0)
        p += Vec2{U(rng), U(rng)};
    return x0;
}

const JointScene& cached_scene(int64_t num_tris) {
    static std::map<int64_t, std::unique_ptr<JointScene>> cache;
    auto& slot = cache[num_tris];
    if (!slot) {
        const int n = static_cast<int>(std::lround(std::sqrt(num_tris / 2.0)));
        const MeshData mesh = make_rectangle_mesh(0, 0, 1.0, 1.0, n, n, true);
        const SplitMesh sm = split_mesh(mesh.nodes, mesh.tris);
        slot = std::make_unique<JointScene>();
        JointMaterial jm;
        jm.tensile_strength = 1e7;
        jm.cohesion = 3e7;
        jm.friction_angle = 0.5;
        jm.fracture_energy_I = 50;
        jm.fracture_energy_II = 250;
        jm.penalty = jm.shear_penalty = 5e11;  // 10 E, E = 50 GPa
        slot->J.laws.push_back(make_joint_law(jm));
        add_edge_joints(slot->J, sm.x0, sm.tris, sm.vertex, 0);
        finalize_joints(slot->J, static_cast<int32_t>(sm.x0.size()));
        slot->x = perturbed(sm.x0, 2.0 * (1.0 / n) * jm.tensile_strength / jm.penalty);
    }
    return *slot;
}

// joint_forces of J at positions x, timed; items = joint-steps
void run_kernel(benchmark::State& st, const Joints& J, const std::vector<Vec2>& x, bool energy) {
    omp_set_num_threads(static_cast<int>(st.range(1)));
    JointState s = make_joint_state(J);
    std::vector<Vec2> f(x.size());
    int32_t softening = 0;
    for (auto _ : st) {
        const JointPass p = joint_forces(J, s, x, f, energy);
        softening += p.softening;
        benchmark::DoNotOptimize(p.work);
    }
    if (softening != 0) st.SkipWithError("joints left the elastic range");
    st.SetItemsProcessed(st.iterations() * J.num_joints());
    st.counters["joints"] = static_cast<double>(J.num_joints());
    st.counters["omp_threads"] = static_cast<double>(st.range(1));
}

void joints(benchmark::State& st, bool energy) {
    const JointScene& sc = cached_scene(st.range(0));
    run_kernel(st, sc.J, sc.x, energy);
}

// The joints of the jointed block as a model gets them (scenes::make_block, jointed: finalize_model
// renumbers along the Morton curve and sorts the joints by node 0, Joints::sorted_by_node0, so
// large models prefetch side B; docs/performance.md "Stop 49"), positions perturbed as above.
struct ModelJointScene {
    Model m;
    std::vector<Vec2> x;
};

const ModelJointScene& cached_model_scene(int64_t num_tris) {
    static std::map<int64_t, std::unique_ptr<ModelJointScene>> cache;
    if (!cache.contains(num_tris)) {
        cache.clear();  // one at a time: the 1 M scene holds ~0.5 GB
        auto fresh = std::make_unique<ModelJointScene>();
        scenes::BlockOptions o;
        o.num_tris = num_tris;
        o.jointed = true;
        fresh->m = scenes::make_block(o);
        const JointLaw& L = fresh->m.joints.laws[0];
        const Real h = 1.0 / std::sqrt(num_tris / 2.0);
        fresh->x = perturbed(fresh->m.node_x0, 2.0 * h * L.ft / L.p);
        cache[num_tris] = std::move(fresh);
    }
    return *cache[num_tris];
}

void BM_JointsNoEnergyModel(benchmark::State& st) {
    const ModelJointScene& sc = cached_model_scene(st.range(0));
    run_kernel(st, sc.m.joints, sc.x, false);
    st.counters["sorted_by_node0"] = sc.m.joints.sorted_by_node0 ? 1 : 0;
}

void BM_Joints(benchmark::State& st) {
    joints(st, true);
}
void BM_JointsNoEnergy(benchmark::State& st) {
    joints(st, false);
}

void sizes(benchmark::internal::Benchmark* b) {
    for (int threads : {1, 2})
        for (int64_t n : {1 << 11, 1 << 14, 1 << 17, 1 << 20})
            b->Args({n, threads});
}

BENCHMARK(BM_Joints)->Apply(sizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_JointsNoEnergyModel)->Apply(sizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_JointsNoEnergy)->Apply(sizes)->Unit(benchmark::kMicrosecond);

// The same kernel on each vector path this CPU runs (arg 2: 0 portable, 1 AVX2, 2 AVX-512), one
// thread: which path Auto should pick on this CPU (e.g. AVX-512 executed at half width on Zen 4).
void BM_JointsNoEnergyPath(benchmark::State& st) {
    using detail::JointPath;
    const int which = static_cast<int>(st.range(2));
    if ((which == 1 && !detail::joint_avx2_supported()) ||
        (which == 2 && !detail::joint_avx512_supported())) {
        st.SkipWithError("this CPU or build has no such path");
        return;
    }
    detail::set_joint_path(which == 0   ? JointPath::Portable
                           : which == 1 ? JointPath::Avx2
                                        : JointPath::Avx512);
    joints(st, false);
    st.SetLabel(detail::joint_path_name());
    detail::set_joint_path(JointPath::Auto);
}
BENCHMARK(BM_JointsNoEnergyPath)
    ->ArgsProduct({{1 << 14, 1 << 20}, {1}, {0, 1, 2}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace fdem
