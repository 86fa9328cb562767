// Spec §5.2, T15 (paper §5, Figs. 25-26): two elastic disks (R = 1 m, E = 1 GPa, nu = 0,
// rho = 1000), the left one at 10 m/s, the right one at rest, with the loading/unloading law
// (alpha, beta) = (1,1), (1,2), (1,3), (1,4) (continuous unloading, spec §4.5-4).
// Momentum is conserved exactly by the pair forces (spec §4.6); alpha = beta stores and returns
// the contact energy; beta > alpha returns (alpha+1)/(beta+1) of it per node cycle (spec §6.2).
#pragma once

#include <string>
#include <vector>

#include "fdem/build.hpp"
#include "fdem/mesh.hpp"
#include "support/scenes.hpp"
#include "validation/cases/common.hpp"

namespace fdem::validation {

struct DiskImpactOptions {
    double h = 0.05;           ///< mesh size [m] (spec §5.2: ~2900 triangles per disk)
    double dt_fraction = 0.2;  ///< of the stable limit (spec §3.4)
    double t_end = 16e-3;      ///< [s]: contact lasts from 1 ms to ~10 ms at 10 m/s
    std::vector<double> betas{1, 2, 3, 4};
    static DiskImpactOptions quick() {
        DiskImpactOptions o;
        o.h = 0.1;
        return o;
    }
};

struct DiskImpactResult {
    Table series{{"time", "kinetic", "energy_error", "v_left", "v_right"}};
    double alpha = 1, beta = 1;
    double ke0 = 0, ke_after = 0, p0 = 0;
    double max_momentum_error = 0;  ///< max |P - P0| / |P0| (both components)
    double max_energy_error = 0;    ///< max |E_tot - E_tot(0)| [J/m] (incl. dissipation)
    double t_separation = NAN;      ///< last step with an active contact [s]
    int32_t tris = 0;
};

inline Model make_disk_impact(const DiskImpactOptions& o, double alpha, double beta) {
    const MeshData mesh =
        read_mesh(std::string(FDEM_SOURCE_DIR) + "/tests/validation/data/disks.geo", o.h);
    Model m;
    m.materials.push_back(scenes::paper_material("paper"));
    for (const char* name : {"left", "right"}) {
        const auto& pg = mesh.physical.at(name);
        std::vector<int32_t> tris;
        for (const PhysicalGroup& g : mesh.groups)
            if (g.dim == 2 && g.tag == pg.second) tris = g.elements;
        BodyOptions opt;
        opt.name = name;
        opt.material = 0;
        opt.velocity = std::string(name) == "left" ? Vec2{10, 0} : Vec2{};
        add_bodies(m, mesh, tris, opt);
    }
    m.contact.algorithm = ContactAlgorithm::Smooth;
    m.contact.params.penalty = 5e9;  // spec §5: k_n = 5 E
    m.contact.params.alpha = alpha;
    m.contact.params.beta = beta;
    finalize_model(m);
    return m;
}

inline DiskImpactResult run_disk_impact(const DiskImpactOptions& o, double alpha, double beta) {
    const Model m = make_disk_impact(o, alpha, beta);
    DiskImpactResult r;
    r.alpha = alpha;
    r.beta = beta;
    r.tris = m.num_tris();
    const double dt = o.dt_fraction * stable_time_step(m);
    State s = make_state(m, dt);
    const int64_t n = static_cast<int64_t>(std::ceil(o.t_end / dt));
    const int64_t every = std::max<int64_t>(1, n / 400);
    double e0 = 0;
    Vec2 p0;
    for (BodyId b = 0; b < m.num_bodies(); ++b)
        p0 += body_sums(m, s, b).momentum;
    r.p0 = norm(p0);
    for (int64_t k = 0; k < n; ++k) {
        step(m, s);
        if (k == 0) {
            e0 = s.energy.total();
            r.ke0 = s.energy.kinetic;
        }
        Vec2 p;
        for (BodyId b = 0; b < m.num_bodies(); ++b)
            p += body_sums(m, s, b).momentum;
        r.max_momentum_error = std::max(r.max_momentum_error, norm(p - p0) / r.p0);
        r.max_energy_error = std::max(r.max_energy_error, std::abs(s.energy.total() - e0));
        if (s.contact.active_contacts > 0) r.t_separation = s.energy.time;
        if (k % every == 0 || k == n - 1) {
            const BodySums a = body_sums(m, s, 0), b = body_sums(m, s, 1);
            r.series.row({s.energy.time, s.energy.kinetic, s.energy.total() - e0,
                          a.momentum.x / a.mass, b.momentum.x / b.mass});
        }
    }
    r.ke_after = s.energy.kinetic;
    return r;
}

inline std::vector<Check> disk_impact_suite(const DiskImpactOptions& o, const std::string& out_dir,
                                            std::vector<DiskImpactResult>* results = nullptr) {
    std::vector<Check> c;
    std::vector<DiskImpactResult> runs;
    for (double beta : o.betas) {
        runs.push_back(run_disk_impact(o, 1.0, beta));
        const DiskImpactResult& r = runs.back();
        if (!out_dir.empty())
            r.series.write(out_dir + "/disk_impact_beta" + std::to_string(static_cast<int>(beta)) +
                           ".csv");
        char tag[48];
        std::snprintf(tag, sizeof tag, "(alpha, beta) = (1, %g)", beta);
        c.push_back(check("T15", std::string("momentum error ") + tag, r.max_momentum_error,
                          Rel::AtMost, 1e-10, 0, "",
                          "pair forces sum to zero (spec §4.6); spec T15: 1e-10 relative"));
        c.push_back(check("T15", std::string("contact separated before the end ") + tag,
                          r.t_separation * 1e3, Rel::AtMost, o.t_end * 1e3 * 0.9, 0, "ms",
                          "KE after is measured after separation"));
        c.push_back(check("T15", std::string("KE after / KE0 ") + tag, r.ke_after / r.ke0,
                          Rel::AtLeast, beta == 1 ? 0.90 : 2.0 / (beta + 1) - 0.05, 0, "",
                          beta == 1 ? "spec T15: >= 0.90 for alpha = beta"
                                    : "spec T15: >= (alpha+1)/(beta+1) - 0.05 (spec §6.2)"));
        c.push_back(check("T15", std::string("energy balance error / KE0 ") + tag,
                          r.max_energy_error / r.ke0, Rel::AtMost, 0.01, 0, "",
                          "spec T15: E_tot (+ W_dissipated) within 1 %"));
    }
    for (size_t i = 1; i < runs.size(); ++i) {
        char name[80];
        std::snprintf(name, sizeof name, "KE after / KE0: beta = %g minus beta = %g", runs[i].beta,
                      runs[i - 1].beta);
        c.push_back(check("T15", name, (runs[i].ke_after - runs[i - 1].ke_after) / runs[i].ke0,
                          Rel::AtMost, 0, 0, "", "spec T15: KE after decreasing with beta"));
    }
    if (results) *results = std::move(runs);
    return c;
}

}  // namespace fdem::validation
