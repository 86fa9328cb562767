// fdem command-line program: run or check a scenario.
//   fdem run SCENARIO [--out DIR] [--end-time T] [--threads N] [--quiet]
//                     [--checkpoint-every T] [--restart FILE] [--print-hash]
//                     [--progress-every S] [--partition rcb|ids|random]
//   fdem check SCENARIO
//   fdem decompose SCENARIO --parts P[,P...] [--partition rcb|ids|random] [--end-time T]
//                           [--csv FILE]
// Exit codes: 0 success, 1 simulation failure, 2 usage or input error (including a checkpoint
// that does not belong to the scenario), 130 / 143 stopped by SIGINT / SIGTERM after writing a
// checkpoint (128 + signal number, the shell convention).
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#ifdef FDEM_HAVE_MPI
#include "parallel/mpi/mpi_comm.hpp"
#include "parallel/mpi/rcb.hpp"
#endif
#include <cstring>
#include <memory>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <span>
#include <string>

#include <fmt/format.h>
#include <omp.h>
#include <CLI/CLI.hpp>

#include "contact/contact.hpp"
#include "core/huge_pages.hpp"
#include "detect/broad_phase.hpp"
#include "element/cst.hpp"
#include "fdem/fdem.hpp"
#include "fracture/joints.hpp"
#include "integrate/node_update.hpp"
#include "parallel/decompose.hpp"
#include "parallel/mesh_broadcast.hpp"

namespace {

constexpr int kExitSimulation = 1;
constexpr int kExitInput = 2;

/// Signal number of a pending SIGINT / SIGTERM (0: none). The handler asks the running
/// Simulation to stop (async-signal-safe); it finishes its step, writes a checkpoint, and the
/// program exits with 128 + signal.
volatile std::sig_atomic_t g_stop_signal = 0;
fdem::Simulation* g_sim = nullptr;

extern "C" void on_stop_signal(int sig) {
    g_stop_signal = sig;
    if (g_sim != nullptr) g_sim->request_stop();
}

void install_signal_handlers() {
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

struct RunOptions {
    std::string scenario;
    std::string out;
    bool out_given = false;
    double end_time = -1;
    bool end_time_given = false;
    int threads = 0;
    bool quiet = false;
    double checkpoint_every = 0;  ///< simulated seconds between checkpoints; 0 = none
    std::string restart;          ///< checkpoint to continue from
    bool print_hash = false;
    double progress_every = 30;     ///< wall seconds between progress lines when stderr is no tty
    std::string partition = "rcb";  ///< distributed runs: rcb, ids or random node groups
    int rebalance_every = 10;       ///< distributed runs: broad-phase searches between checks
    double imbalance = 1.1;         ///< distributed runs: max / mean work that rebalances
    bool no_huge_pages = false;     ///< leave the arrays on 4 KiB pages (core/huge_pages.hpp)
};

// Rough resident size of the model and state [bytes], for `fdem check`; with fracture the
// joint arrays (Model::joints, node_vertex; State::joints, tri_fragment, node_sector) too.
size_t memory_estimate(const fdem::Model& m) {
    const size_t nn = static_cast<size_t>(m.num_nodes()), nt = static_cast<size_t>(m.num_tris());
    const size_t model =
        nn * (2 * sizeof(fdem::Vec2) + 2 * sizeof(double) + sizeof(int32_t)) +
        nt * (3 * sizeof(int32_t) + 2 * sizeof(int32_t) + sizeof(fdem::Mat2) + 2 * sizeof(double));
    const size_t state = nn * 4 * sizeof(fdem::Vec2);
    const size_t nj = static_cast<size_t>(m.joints.num_joints());
    if (nj == 0) return model + state;
    const size_t joint_model = nj * (sizeof(std::array<fdem::NodeId, 4>) + sizeof(double) +
                                     sizeof(int32_t) + 4 * 2 * sizeof(int32_t)) +  // + gather
                               nn * sizeof(fdem::NodeId);                          // node_vertex
    const size_t joint_state = nj * (3 * sizeof(double) + 3 + sizeof(int64_t) + sizeof(double) +
                                     8 * sizeof(double) + 2 * sizeof(fdem::Vec2)) +
                               nt * sizeof(int32_t) +
                               nn * sizeof(int32_t);  // tri_fragment, node_sector
    return model + state + joint_model + joint_state;
}

// Per fracture material: joint count and lengths, the law's lengths at the mean joint length,
// l_ch, E_eff; then the time-step limits of elements, joints and contact (docs/theory.md §9).
void print_fracture(const fdem::Scenario& sc) {
    const fdem::Model& m = sc.model;
    const fdem::Joints& J = m.joints;
    if (J.num_joints() == 0) return;
    for (size_t mi = 0; mi < m.materials.size(); ++mi) {
        const fdem::Material& mat = m.materials[mi];
        if (!mat.has_fracture) continue;
        size_t count = 0;
        double h_min = std::numeric_limits<double>::infinity(), h_max = 0, h_sum = 0;
        for (int32_t j = 0; j < J.num_joints(); ++j) {
            const fdem::NodeId n0 = J.nodes[static_cast<size_t>(j)][0];
            const fdem::BodyId b = m.node_body[static_cast<size_t>(n0)];
            if (m.bodies[static_cast<size_t>(b)].material != static_cast<int32_t>(mi)) continue;
            const double h = J.length0[static_cast<size_t>(j)];
            ++count;
            h_min = std::min(h_min, h);
            h_max = std::max(h_max, h);
            h_sum += h;
        }
        if (count == 0) continue;
        const fdem::JointMaterial& jm = mat.fracture;
        const double h = h_sum / static_cast<double>(count);
        const double ft = jm.tensile_strength, p = jm.penalty;
        const double o_p = 2 * h * ft / p;                          // eq. 9.4
        const double s_p = 2 * h * jm.cohesion / jm.shear_penalty;  // eq. 9.4, f_s = c
        const double iz = fdem::softening_integral(jm.softening);   // eq. 9.11
        const double GI = jm.fracture_energy_I;
        double soft = GI / (iz * ft);  // eq. 9.12, "exact"
        const char* rule = "exact";
        switch (jm.softening_length) {
            case fdem::SofteningLength::Exact:
                break;
            case fdem::SofteningLength::Total:
                soft = (GI - 2.0 / 3.0 * ft * o_p) / (iz * ft);
                rule = "total";
                break;
            case fdem::SofteningLength::YGeo:
                soft = 3 * GI / ft;
                rule = "y-geo";
                break;
            case fdem::SofteningLength::Solidity:
                soft = std::max(2 * o_p, 3 * GI / ft);
                rule = "solidity";
                break;
        }
        const double E = mat.youngs_modulus;
        // eq. 9.6 with c_m = 3/2 + p/(2 p_s) (theory §9.2: a vertical and a diagonal joint per
        // cell width of the structured mesh; 2 for p_s = p)
        const double c_m = 1.5 + 0.5 * p / jm.shear_penalty;
        const double e_eff = fdem::joint_effective_modulus(E, p, c_m);
        fmt::print(
            "fracture   material \"{}\": {} joints, h {:.4g} .. {:.4g} m (mean {:.4g} m), "
            "h_max {:.4g} m (eq. 9.14){}\n",
            mat.name, count, h_min, h_max, h, fdem::joint_max_length(jm),
            jm.allow_coarse ? ", allow_coarse" : "");
        fmt::print(
            "           at the mean h: o_p {:.4g} m, s_p {:.4g} m (eq. 9.4), o_r - o_p "
            "{:.4g} m (\"{}\", eq. 9.12); penalty {:.4g} Pa, shear {:.4g} Pa\n"
            "           mixed mode \"{}\" ({})\n",
            o_p, s_p, soft, rule, p, jm.shear_penalty,
            jm.mixed_mode == fdem::MixedMode::Proportional ? "proportional" : "independent",
            jm.mixed_mode == fdem::MixedMode::Proportional
                ? fmt::format("eq. 9.30: each softened traction scaled by its mode's share of the "
                              "damage, blended in over K_w = {:g}",
                              fdem::kMixOnset)
                : std::string("eqs. 9.5, 9.8: each traction capped at its own strength times z"));
        fmt::print(
            "           l_ch = E G_I/f_t^2 = {:.4g} m; E_eff = E/(1 + c_m E/p) = {:.4g} Pa = "
            "{:.3f} E, c_m = 3/2 + p/(2 p_s) = {:.4g} (eq. 9.6, structured mesh)\n",
            E * GI / (ft * ft), e_eff, e_eff / E, c_m);
    }
    const double dt_e = fdem::element_stable_time_step(m);
    const double dt_j = fdem::joint_critical_dt(J, m.node_mass);  // eq. 9.16
    const fdem::ContactTopology topo = fdem::build_topology(m);
    const double dt_c = fdem::contact_stable_dt(m, topo);
    fmt::print("dt limits  elements {:.4g} s, joints {:.4g} s (eq. 9.16), contact {}\n", dt_e, dt_j,
               std::isfinite(dt_c) ? fmt::format("{:.4g} s", dt_c) : std::string("none"));
}

// The `timing` table of `fdem run`: wall seconds per phase of the steps (fdem::StepTiming), the
// rest of the run's wall time after the load ("other": output, checks, checkpoints,
// rebalancing) and that wall time, one row per process (timing.csv); the table prints min /
// mean / max over the rows (one process: all three the same).
struct TimingTable {
    static constexpr int kCols = fdem::kStepPhases + 2;  ///< the phases, other, wall
    static constexpr int kOther = fdem::kStepPhases, kWall = fdem::kStepPhases + 1;
    int procs = 0;  ///< 0: not timed (--quiet)
    int64_t steps = 0;
    std::vector<double> rows;  ///< process r's kCols seconds at r * kCols
    double at(int r, int k) const {
        return rows[static_cast<size_t>(r) * kCols + static_cast<size_t>(k)];
    }
};

// every process's row, on every process (collective in a distributed run)
TimingTable timing_table(const fdem::StepTiming& st, double wall, const fdem::Comm* comm) {
    constexpr int kCols = TimingTable::kCols;
    TimingTable tt;
    tt.steps = st.steps;
    tt.procs = comm != nullptr ? comm->size() : 1;
    const int rank = comm != nullptr ? comm->rank() : 0;
    tt.rows.assign(static_cast<size_t>(tt.procs) * kCols, 0.0);
    double* mine = tt.rows.data() + static_cast<size_t>(rank) * kCols;
    double phases = 0;
    for (int k = 0; k < fdem::kStepPhases; ++k) {
        mine[k] = st.seconds[k];
        phases += st.seconds[k];
    }
    mine[TimingTable::kOther] = std::max(0.0, wall - phases);
    mine[TimingTable::kWall] = wall;
    if (comm != nullptr) {
        std::vector<int> counts(static_cast<size_t>(tt.procs), kCols), displs(counts.size());
        for (size_t r = 0; r < displs.size(); ++r)
            displs[r] = static_cast<int>(r) * kCols;
        comm->allgatherv(tt.rows.data(), counts, displs);
    }
    return tt;
}

// timing.csv: one row per process (rank, steps, the seconds of each phase, other, wall)
std::string timing_csv(const TimingTable& tt) {
    std::string csv = "rank,steps";
    for (int k = 0; k < fdem::kStepPhases; ++k)
        csv += std::string(",") + fdem::kStepPhaseKeys[k];
    csv += ",other,wall\n";
    for (int r = 0; r < tt.procs; ++r) {
        csv += fmt::format("{},{}", r, tt.steps);
        for (int k = 0; k < TimingTable::kCols; ++k)
            csv += fmt::format(",{:.9g}", tt.at(r, k));
        csv += "\n";
    }
    return csv;
}

void print_timing(const TimingTable& tt) {
    if (tt.procs == 0 || tt.steps == 0) return;
    struct Stat {
        double min, mean, max;
    };
    const auto stat = [&](int k) {
        Stat st{tt.at(0, k), 0.0, tt.at(0, k)};
        for (int r = 0; r < tt.procs; ++r) {
            st.min = std::min(st.min, tt.at(r, k));
            st.max = std::max(st.max, tt.at(r, k));
            st.mean += tt.at(r, k);
        }
        st.mean /= tt.procs;
        return st;
    };
    const auto name = [](int k) {
        return k < fdem::kStepPhases ? fdem::kStepPhaseNames[k] : "other";
    };
    const double wall = stat(TimingTable::kWall).mean;
    const double scale = wall > 0 ? 100.0 / wall : 0.0;
    if (tt.procs == 1) {
        fmt::print(
            "timing     wall seconds of the {} steps by phase (% of {:.4g} s); other = output, "
            "checks, checkpoints\n",
            tt.steps, wall);
    } else {
        fmt::print(
            "timing     wall seconds of the {} steps by phase over {} processes: min / mean / "
            "max (% of the mean {:.4g} s); communication includes the waits for the other "
            "processes\n",
            tt.steps, tt.procs, wall);
    }
    for (int k = 0; k <= TimingTable::kOther; ++k) {
        const Stat st = stat(k);
        if (tt.procs == 1) {
            if (k == static_cast<int>(fdem::StepPhase::Communication)) continue;
            fmt::print("           {:<14} {:10.4g} s {:6.1f} %\n", name(k), st.mean,
                       scale * st.mean);
        } else {
            fmt::print("           {:<14} {:10.4g} {:10.4g} {:10.4g} s {:6.1f} %\n", name(k),
                       st.min, st.mean, st.max, scale * st.mean);
        }
    }
}

// text to path; false, with errno set, if it cannot be written
bool write_text_file(const std::string& path, const std::string& text) {
    std::FILE* fp = std::fopen(path.c_str(), "w");
    if (fp == nullptr) return false;
    const bool wrote = std::fputs(text.c_str(), fp) >= 0;
    const int saved = errno;
    const bool closed = std::fclose(fp) == 0;
    if (!wrote) errno = saved;
    return wrote && closed;
}

// Broken joints per mode, W_frac and the fracture-energy audit (docs/theory.md eq. 9.20):
// Gamma = W_frac / broken length, and per mode the work of its broken joints over their length.
void print_fracture_summary(const fdem::Model& m, const fdem::State& s) {
    const fdem::Joints& J = m.joints;
    const fdem::JointState& js = s.joints;
    int64_t broken[4] = {0, 0, 0, 0}, softening = 0;  // by JointMode
    double work[4] = {0, 0, 0, 0}, length[4] = {0, 0, 0, 0};
    for (size_t j = 0; j < js.status.size(); ++j) {
        if (js.status[j] == fdem::JointStatus::Softening) ++softening;
        if (js.status[j] != fdem::JointStatus::Broken) continue;
        const auto k = static_cast<size_t>(js.mode[j]);  // None: pre-broken
        ++broken[k];
        work[k] += js.work[j];
        length[k] += J.length0[j];
    }
    const int64_t n_broken = broken[0] + broken[1] + broken[2] + broken[3];
    const double crack = length[1] + length[2] + length[3];  // pre-broken joints excluded
    fmt::print(
        "fracture   {} of {} joints broken (mode I {}, II {}, mixed {}; {} pre-broken), "
        "{} softening; crack length {:.6g} m; E_joint {:.6g}, W_frac {:.6g} J/m\n",
        n_broken, J.num_joints(), broken[1], broken[2], broken[3], broken[0], softening, crack,
        s.energy.joint, s.energy.fracture);
    if (crack > 0) {
        auto gamma = [&](size_t k) {
            return length[k] > 0 ? fmt::format("{:.6g}", work[k] / length[k]) : std::string("-");
        };
        fmt::print(
            "Gamma      W_frac / crack length {:.6g} J/m^2; per mode sum W_J / sum h0 "
            "(eq. 9.20): I {}, II {}, mixed {} J/m^2\n",
            s.energy.fracture / crack, gamma(1), gamma(2), gamma(3));
    }
}

void print_summary(const fdem::Scenario& sc) {
    const fdem::Model& m = sc.model;
    size_t fixed = 0;
    for (const auto& b : m.bodies)
        fixed += b.fixed ? 1 : 0;
    fmt::print("scenario   {}\n", sc.path);
    fmt::print("bodies     {} ({} fixed) from {} body entries\n", m.num_bodies(), fixed,
               m.group_names.size());
    fmt::print("nodes      {}\ntriangles  {}\nmaterials  {}\n", m.num_nodes(), m.num_tris(),
               m.materials.size());
    // loads (docs/scenario.md [[load]]): what was found on the group, so a wrong group shows
    for (const fdem::Load& ld : m.loads) {
        std::string what;
        if (ld.kind == fdem::LoadKind::Force) {
            what = fmt::format("force [{:g}, {:g}] N/m on {} node(s)", ld.vector.x, ld.vector.y,
                               ld.nodes.size());
        } else {
            double length = 0;
            for (const double l : ld.edge_length0)
                length += l;
            what = ld.kind == fdem::LoadKind::Pressure
                       ? fmt::format("pressure {:g} Pa", ld.pressure)
                       : fmt::format("traction [{:g}, {:g}] Pa", ld.vector.x, ld.vector.y);
            what += fmt::format(" on {} edge(s), {:.4g} m", ld.edges.size(), length);
        }
        const fdem::TimeFunction& tf = ld.time_function;
        const std::string when = tf.kind == fdem::TimeFunction::Kind::Constant ? "constant"
                                 : tf.kind == fdem::TimeFunction::Kind::Ramp
                                     ? fmt::format("ramp over {:g} s", tf.ramp_time)
                                     : fmt::format("table of {} points", tf.table.size());
        fmt::print("load       {}: {}, {}\n", ld.name, what, when);
    }
    if (sc.run.limiting_tri != fdem::kNone) {
        fmt::print("stable dt  {:.4g} s (limited by triangle {}, material \"{}\")\n",
                   sc.run.stable_dt, sc.run.limiting_tri,
                   m.materials[m.tri_material[sc.run.limiting_tri]].name);
    } else {
        const bool joints = fdem::joint_critical_dt(m.joints, m.node_mass) <
                            fdem::contact_stable_dt(m, fdem::build_topology(m));
        fmt::print("stable dt  {:.4g} s (limited by the {})\n", sc.run.stable_dt,
                   joints ? "cohesive joints" : "contact penalty");
    }
    fmt::print("dt         {:.4g} s{}\n", sc.run.dt,
               sc.run.dt_auto ? fmt::format(" (auto: {:.3g} x stable)", sc.run.dt_fraction) : "");
    fmt::print("end time   {:.6g} s ({} steps)\n", sc.run.end_time,
               static_cast<long long>(std::ceil(sc.run.end_time / sc.run.dt - 1e-9)));
    fmt::print("memory     {:.2f} MB (model + state, estimate; {:.0f} B per triangle)\n",
               memory_estimate(m) / 1e6,
               static_cast<double>(memory_estimate(m)) / std::max(1, m.num_tris()));
    // the vector kernels this CPU runs (docs/architecture.md "Vector kernels"; the same bits on
    // every path) and the threads: what a timing depends on
    fmt::print("kernels    CST {}, node update {}, {}broad-phase scan {}; {} OpenMP thread(s)\n",
               fdem::cst_kernel_name(), fdem::node_update_kernel_name(),
               m.joints.num_joints() > 0
                   ? fmt::format("joints {}, ", fdem::detail::joint_path_name())
                   : std::string(),
               fdem::broad_scan_kernel_name(), omp_get_max_threads());
    print_fracture(sc);

    // contact: which algorithm and why; which bodies it sees (two fixed bodies never interact)
    const char* alg =
        m.contact.algorithm == fdem::ContactAlgorithm::Smooth           ? "smooth"
        : m.contact.algorithm == fdem::ContactAlgorithm::LegacyTriangle ? "legacy-triangle"
        : m.contact.algorithm == fdem::ContactAlgorithm::LegacyBoundary ? "legacy-boundary"
                                                                        : "none";
    const size_t movable = m.bodies.size() - fixed;
    const bool on = m.contact.algorithm != fdem::ContactAlgorithm::None;
    std::string why;
    if (sc.contact_default) {
        why = on ? "default without [contact]: two or more bodies, at least one movable; "
                   "[contact] algorithm = \"none\" switches it off"
                 : (m.bodies.size() < 2 ? "default without [contact]: one body"
                                        : "default without [contact]: every body is fixed");
    } else {
        why = "[contact] algorithm";
    }
    fmt::print("contact    {} ({})\n", alg, why);

    // every body: id, entry name, triangles, mass, contact (long lists are cut after 200 rows)
    constexpr size_t kMaxRows = 200;
    fmt::print("body list  id  name  triangles  mass [kg/m]  fixed  contact\n");
    for (size_t b = 0; b < m.bodies.size() && b < kMaxRows; ++b) {
        const fdem::Body& body = m.bodies[b];
        double mass = 0;
        for (fdem::NodeId n = body.node_begin; n < body.node_end; ++n)
            mass += m.node_mass[static_cast<size_t>(n)];
        const bool seen = on && m.bodies.size() >= 2 && (!body.fixed || movable > 0);
        fmt::print("  {:>6}  \"{}\"  {}  {:.6g}  {}  {}\n", b, body.name,
                   body.tri_end - body.tri_begin, mass, body.fixed ? "yes" : "no",
                   seen  ? "yes"
                   : !on ? "no (contact off)"
                         : "no (nothing that moves can reach it)");
    }
    if (m.bodies.size() > kMaxRows) {
        fmt::print(
            "  ... {} more bodies (ids {} to {}; their names, ids and masses are in every "
            "VTU frame)\n",
            m.bodies.size() - kMaxRows, kMaxRows, m.bodies.size() - 1);
    }
    for (const fdem::ProbeSpec& p : sc.run.output.probes) {
        if (p.kind == fdem::ProbeSpec::Kind::Node) {
            const fdem::Vec2 x = m.node_x0[p.nodes[0]];
            fmt::print(
                "probe      \"{}\": node {} at ({:.6g}, {:.6g}) m, {:.3g} m from the given "
                "position, stress of triangle {}\n",
                p.name, p.nodes[0], x.x, x.y, fdem::norm(x - p.position), p.tris[0]);
        } else {
            fmt::print("probe      \"{}\": mean over {} nodes and {} triangles\n", p.name,
                       p.nodes.size(), p.tris.size());
        }
    }
}

void print_warnings(const fdem::Scenario& sc) {
    for (const std::string& w : sc.warnings)
        fmt::print(stderr, "{}\n", w);
}

/// CLI validator: a finite number > 0 (CLI::PositiveNumber lets nan through, and prints
/// DBL_MAX in full as its bound).
const CLI::Validator kFinitePositive(
    [](const std::string& text) -> std::string {
        double v = 0;
        try {
            size_t used = 0;
            v = std::stod(text, &used);
            if (used != text.size()) return fmt::format("expected a number in s, got '{}'", text);
        } catch (...) {
            return fmt::format("expected a number in s, got '{}'", text);
        }
        if (!std::isfinite(v) || !(v > 0)) {
            return fmt::format("expected a finite number of seconds > 0, got {}", text);
        }
        return {};
    },
    "SECONDS > 0", "finite positive");

// The processes of a distributed run (mpirun -np P with P > 1, builds with -DFDEM_MPI=ON);
// nullptr for a one-process run.
const fdem::Comm* g_comm = nullptr;

// The summary's "pages" line: how much of this process's memory transparent huge pages back
// (core/huge_pages.hpp), or why none.
void print_huge_pages(bool off) {
    const size_t page = fdem::huge_page_size();
    if (off) {
        fmt::print("pages      4 KiB (--no-huge-pages)\n");
    } else if (page == 0) {
        fmt::print("pages      4 KiB (this kernel has no transparent huge pages)\n");
    } else {
        fmt::print("pages      {:.1f} MB of this process on {} transparent huge pages\n",
                   static_cast<double>(fdem::huge_page_bytes_in_use()) / 1e6,
                   page % (1 << 20) == 0 ? fmt::format("{} MiB", page >> 20)
                                         : fmt::format("{} KiB", page >> 10));
    }
}

int run(const RunOptions& opt) {
    using clock = std::chrono::steady_clock;
    fdem::set_huge_pages(!opt.no_huge_pages);  // (before the model's arrays are built)
    // a distributed run: process 0 reads (meshes) each mesh file once and broadcasts it
    fdem::Scenario sc =
        fdem::load_scenario(opt.scenario, g_comm != nullptr ? fdem::broadcast_mesh_reader(*g_comm)
                                                            : fdem::MeshReader{});
    if (opt.end_time_given) {
        sc.run.end_time = opt.end_time;
        fdem::check_step_count(sc.run, {"--end-time", 0, 0}, "--end-time");
        for (const fdem::VelocityKick& k : sc.model.kicks) {
            if (k.time >= sc.run.end_time) {
                sc.warnings.push_back(fmt::format(
                    "warning: --end-time {:g} s ends the run before the kick of body \"{}\" at "
                    "t = {:g} s",
                    sc.run.end_time, sc.model.group_names[static_cast<size_t>(k.group)], k.time));
            }
        }
    }
    if (opt.out_given) sc.run.output.dir = opt.out;
    if (opt.threads > 0) omp_set_num_threads(opt.threads);
    const bool tty = isatty(STDERR_FILENO) && !opt.quiet;
    // batch runs (stderr to a file or pipe): a full progress line every progress_every seconds
    const bool batch = !isatty(STDERR_FILENO) && !opt.quiet && opt.progress_every > 0;
    if (!opt.quiet) print_summary(sc);
    print_warnings(sc);

    fdem::Simulation sim(std::move(sc));
    const fdem::Model& m = sim.model();
    const fdem::State& s = sim.state();
    if (g_comm != nullptr) {  // before open_output: process 0 writes
        // the process of each node group (docs/parallel.md): any assignment gives the same bits
        std::vector<int32_t> owner;
        if (opt.partition == "random") {  // a test of partition independence (spec T3)
            owner = fdem::group_owners(m, "random", g_comm->size());
        } else if (opt.partition == "rcb") {
#ifdef FDEM_HAVE_MPI
            owner = fdem::rcb_group_owners(dynamic_cast<const fdem::MpiComm&>(*g_comm), m);
#endif
        }
        sim.distribute(*g_comm, owner);
        // load balancing on broad-phase searches (spec D10, docs/parallel.md "Rebalancing"):
        // the same rule as the first partition, from the current centres and estimated work
        fdem::Simulation::Rebalance rb;
        rb.every = opt.rebalance_every;
        rb.imbalance = opt.imbalance;
        const int32_t procs = g_comm->size();
        if (opt.partition == "rcb") {
#ifdef FDEM_HAVE_MPI
            const auto* mpi = dynamic_cast<const fdem::MpiComm*>(g_comm);
            rb.partition = [mpi](std::span<const fdem::Vec2> c, std::span<const double> w,
                                 int64_t) { return fdem::rcb_group_owners(*mpi, c, w); };
#endif
        } else {
            rb.partition = [rule = opt.partition, procs](std::span<const fdem::Vec2>,
                                                         std::span<const double> w, int64_t round) {
                return fdem::group_owners(w, rule, procs, static_cast<uint64_t>(round) + 1);
            };
        }
        sim.set_rebalance(std::move(rb));
    }
    sim.open_output("", opt.out_given ? std::string("--out") : std::string());
    const std::string out = sim.output_dir();
    if (!opt.restart.empty()) {
        sim.restore_checkpoint(opt.restart);
        if (!opt.quiet) {
            fmt::print("restart    {} at step {} (t = {:.6g} s)\n", opt.restart, s.step, s.time);
        }
    }
    sim.set_checkpoint_every(opt.checkpoint_every);
    sim.set_warning_handler([tty](const std::string& warning) {
        fmt::print(stderr, "{}{} (further warnings suppressed)\n", tty ? "\n" : "", warning);
    });

    g_sim = &sim;
    install_signal_handlers();
    const auto t0 = clock::now();
    auto last_progress = t0;
    const int64_t start_step = s.step;
    const int64_t total_steps = sim.steps_to(sim.settings().end_time);
    // the progress lines: a callback after every step (a clock read; none when quiet)
    const fdem::Simulation::StepCallback progress = [&](fdem::Simulation&) {
        if (batch) {
            const auto now = clock::now();
            if (std::chrono::duration<double>(now - last_progress).count() >= opt.progress_every) {
                last_progress = now;
                const double wall = std::chrono::duration<double>(now - t0).count();
                const double sps = static_cast<double>(s.step - start_step) / wall;
                fmt::print(stderr,
                           "progress   step {} / {}  t = {:.6g} s  {:.3g} steps/s  ETA {:.0f} s\n",
                           s.step, total_steps, s.time, sps,
                           static_cast<double>(total_steps - s.step) / sps);
            }
        }
        if (tty) {
            const auto now = clock::now();
            if (now - last_progress > std::chrono::milliseconds(500)) {
                last_progress = now;
                const double wall = std::chrono::duration<double>(now - t0).count();
                const double sps = static_cast<double>(s.step - start_step) / wall;
                fmt::print(stderr,
                           "\rstep {:>9} / {}  t = {:.4e} s  {:.3g} steps/s  ETA {:.0f} s   ",
                           s.step, total_steps, s.time, sps,
                           static_cast<double>(total_steps - s.step) / sps);
            }
        }
        return true;
    };
    // wall time per phase of the steps (the `timing` table below; no result depends on it;
    // ~10 clock reads per step, none with --quiet)
    sim.state().timing.on = !opt.quiet;
    sim.state().timing.reset();
    try {
        const fdem::RunResult res =
            sim.run_to_end(tty || batch ? progress : fdem::Simulation::StepCallback{});
        if (res.status == fdem::RunStatus::Stopped) {
            // a distributed run stopped on every process at the same step, also those the
            // signal did not reach: the signal of the run is the one any process saw
            const int sig = g_comm != nullptr ? static_cast<int>(g_comm->max(g_stop_signal))
                                              : static_cast<int>(g_stop_signal);
            if (tty) fmt::print(stderr, "\n");
            fmt::print(stderr,
                       "stopped by {} after step {} (t = {:.6g} s); checkpoint written to {}\n"
                       "continue with: fdem run {} --out {} --restart {}\n",
                       sig == SIGINT ? "SIGINT" : "SIGTERM", s.step, s.time, sim.checkpoint_path(),
                       opt.scenario, out, sim.checkpoint_path());
            return 128 + sig;
        }
    } catch (const fdem::SimulationError& err) {
        if (tty) fmt::print(stderr, "\n");
        fmt::print(stderr, "error: {}\n", err.what());
        if (!sim.failure_write_error().empty()) {
            fmt::print(stderr, "error: {}\n", sim.failure_write_error());
            return kExitSimulation;
        }
        if (!sim.failure_file().path.empty()) {
            fmt::print(stderr, "the state at failure is in {}\n", sim.failure_file().path);
        }
        if (const fdem::WrittenFile& f = sim.last_frame(); !f.path.empty()) {
            fmt::print(stderr, "last good output frame: {} (t = {:.6g} s)\n", f.path, f.time);
        }
        if (const fdem::WrittenFile& c = sim.last_checkpoint(); !c.path.empty()) {
            fmt::print(stderr, "last good checkpoint: {} (step {}, t = {:.6g} s)\n", c.path, c.step,
                       c.time);
        }
        return kExitSimulation;
    }
    if (tty) fmt::print(stderr, "\n");
    const double wall = std::chrono::duration<double>(clock::now() - t0).count();
    if (g_comm != nullptr) {
        // what each process owned and exchanged per step at the end (the counts `fdem
        // decompose` gives without MPI; docs/parallel.md)
        const std::string csv = sim.partition_csv();
        if (g_comm->rank() == 0) {
            const std::string path = (std::filesystem::path(out) / "partition.csv").string();
            if (!write_text_file(path, csv)) {
                fmt::print(stderr, "warning: cannot write {}: {}\n", path, std::strerror(errno));
            } else if (!opt.quiet) {
                fmt::print("processes  {} ({} partition); per process and step: {}\n",
                           g_comm->size(), opt.partition, path);
            }
            const fdem::Simulation::RebalanceStats& rs = sim.rebalance_stats();
            if (!opt.quiet && opt.rebalance_every > 0) {
                fmt::print(
                    "rebalance  {} new partitions in {} checks (every {} broad-phase searches, "
                    "at max/mean >= {:g} of the estimated work); max/mean at the last check "
                    "{:.3f}, the worst {:.3f}\n",
                    rs.rebalances, rs.checks, opt.rebalance_every, opt.imbalance, rs.last_imbalance,
                    rs.worst_imbalance);
            } else if (!opt.quiet) {
                fmt::print("rebalance  off (--rebalance-every 0)\n");
            }
        }
    }
    const uint64_t hash = sim.state_hash();
    // (collective in a distributed run: every process takes part, process 0 prints)
    const TimingTable timing = opt.quiet ? TimingTable{} : timing_table(s.timing, wall, g_comm);
    if (timing.procs > 0 && (g_comm == nullptr || g_comm->rank() == 0)) {
        const std::string path = (std::filesystem::path(out) / "timing.csv").string();
        if (!write_text_file(path, timing_csv(timing)))
            fmt::print(stderr, "warning: cannot write {}: {}\n", path, std::strerror(errno));
    }
    if (!opt.quiet) {
        const double steps = static_cast<double>(s.step - start_step);
        fmt::print("done       {} steps in {:.2f} s ({:.3g} steps/s, {:.3g} element-steps/s)\n",
                   s.step - start_step, wall, steps / wall, steps * m.num_tris() / wall);
        fmt::print(
            "energy     kinetic {:.6g}, strain {:.6g}, contact {:.6g}, dissipated {:.6g} J/m\n",
            s.energy.kinetic, s.energy.strain, s.energy.contact,
            s.energy.dissipated_viscous + s.energy.dissipated_contact);
        if (!m.joints.nodes.empty()) print_fracture_summary(m, s);
        const fdem::EnergyMonitor& e = sim.energy_monitor();
        fmt::print(
            "balance    max |E_total - E_0| = {:.3g} J/m = {:.3g} % of the energy scale "
            "{:.6g} J/m\n",
            e.max_error, e.scale > 0 ? 100.0 * e.max_error / e.scale : 0.0, e.scale);
        // the last step's pair counts (issue #16 item 1): candidates = what the narrow phase
        // examined, in contact = those with a force; the rest were rejected
        if (m.contact.algorithm != fdem::ContactAlgorithm::None) {
            const fdem::Simulation::ContactCounts c = sim.contact_counts();
            fmt::print(
                "pairs      last step: {} candidate {}, {} in contact; {} broad-phase "
                "searches since t = 0\n",
                c.candidates, c.triangle_couples ? "triangle couples" : "(node, body) pairs",
                c.in_contact, c.broad_phase_runs);
        }
        print_huge_pages(opt.no_huge_pages);
        print_timing(timing);  // (and timing.csv: one row per process)
        fmt::print("output     {} ({} frames; open series.pvd in ParaView)\n", out,
                   sim.frames_written());
        fmt::print("state      step {}, t = {:.6g} s, hash {:016x} (x, v, energies)\n", s.step,
                   s.time, hash);
    } else if (opt.print_hash) {
        fmt::print("hash {:016x}\n", hash);
    }
    return 0;
}

struct DecomposeOptions {
    std::string scenario;
    std::vector<int> parts;
    std::string partition = "rcb";
    double end_time = -1;  ///< < 0: one step
    std::string csv;
    int threads = 0;
};

// `fdem decompose`: the counts of a distributed run with P processes (docs/parallel.md "fdem
// decompose"), from one process: the scenario is run serially to the end time (default: one
// step, so the candidate pairs of t = 0 exist), then every part's plan and ghost lists are made
// as each process of `mpirun -np P fdem run` makes its own (parallel/decompose.hpp).
int decompose_command(const DecomposeOptions& opt, const fdem::Comm* rcb_comm) {
    using clock = std::chrono::steady_clock;
    fdem::Scenario sc = fdem::load_scenario(opt.scenario);
    print_warnings(sc);
    // (a run that writes bodies.csv sums each set on one process, which then needs the contact
    // forces of the set's nodes: they count in the exchange)
    const bool bodies = sc.run.output.bodies;
    if (opt.threads > 0) omp_set_num_threads(opt.threads);
    if (opt.partition == "rcb" && rcb_comm == nullptr) {
        throw fdem::InputError({}, "--partition",
                               "--partition rcb needs Zoltan, which this fdem was built without "
                               "(build with -DFDEM_MPI=ON, docs/parallel.md); use --partition ids "
                               "or random");
    }
    const double end = opt.end_time;
    fdem::Simulation sim(std::move(sc));
    const fdem::Model& m = sim.model();
    const fdem::State& s = sim.state();
    const auto t0 = clock::now();
    if (end > 0) {
        sim.run(end);
    } else {
        sim.step();
    }
    const double t_run = std::chrono::duration<double>(clock::now() - t0).count();
    fmt::print(
        "model      {} nodes, {} triangles, {} bodies; state at step {} (t = {:.6g} s, "
        "{:.2f} s to get there)\n",
        m.num_nodes(), m.num_tris(), m.num_bodies(), s.step, s.time, t_run);
    const fdem::Simulation::ContactCounts cc = sim.contact_counts();
    fmt::print("contact    {} candidate pairs, {} in contact\n", cc.candidates, cc.in_contact);
    std::unique_ptr<fdem::Resultants> sets;
    if (bodies) sets = std::make_unique<fdem::Resultants>(m, s.topology);
    std::string csv;
    for (const int P : opt.parts) {
        const auto t1 = clock::now();
        std::vector<int32_t> owner;
        if (opt.partition == "rcb") {
#ifdef FDEM_HAVE_MPI
            owner = fdem::rcb_group_owners(dynamic_cast<const fdem::MpiComm&>(*rcb_comm), m, P);
#endif
        } else {
            owner = fdem::group_owners(m, opt.partition, P);
        }
        const std::vector<fdem::PartCounts> parts = fdem::decompose(m, s, owner, P, sets.get());
        const double t_dec = std::chrono::duration<double>(clock::now() - t1).count();
        std::string rows = fdem::partition_csv(parts);
        csv += csv.empty() ? rows : rows.substr(rows.find('\n') + 1);
        // the summary: mean and max over the parts, and the step's totals
        auto stat = [&](auto field) {
            double sum = 0, mx = 0;
            for (const fdem::PartCounts& c : parts) {
                const double v = static_cast<double>(field(c));
                sum += v;
                mx = std::max(mx, v);
            }
            return std::pair<double, double>{sum / static_cast<double>(parts.size()), mx};
        };
        const auto [n_mean, n_max] = stat([](const fdem::PartCounts& c) { return c.nodes; });
        const auto [tr_mean, tr_max] = stat([](const fdem::PartCounts& c) { return c.tris_run; });
        const auto [g_mean, g_max] = stat([](const fdem::PartCounts& c) { return c.ghost_nodes; });
        const auto [msg_mean, msg_max] =
            stat([](const fdem::PartCounts& c) { return c.recv_from + c.send_to; });
        const auto [b_mean, b_max] = stat([](const fdem::PartCounts& c) {
            return fdem::ghost_bytes_in(c) + fdem::ghost_bytes_out(c);
        });
        const auto [p_mean, p_max] =
            stat([](const fdem::PartCounts& c) { return c.candidate_pairs; });
        const auto [rec_mean, rec_max] = stat([](const fdem::PartCounts& c) {
            return fdem::contact_bytes_in(c) + fdem::contact_bytes_out(c);
        });
        const auto [j_mean, j_max] = stat([](const fdem::PartCounts& c) { return c.joints_run; });
        int64_t gathered = 0, records = 0, sent = 0, counted = 0;
        for (const fdem::PartCounts& c : parts) {
            gathered += fdem::gathered_bytes(c);
            records += c.contact_records;
            sent += c.contact_sent;
            counted += c.tris_counted;  // the triangles of movable bodies, each counted once
        }
        const double T = static_cast<double>(counted);
        fmt::print(
            "parts {:>5} ({}, {:.1f} s): nodes per part {:.0f} mean / {:.0f} max; triangles run "
            "{:.0f} / {:.0f} ({:+.1f} % redundant); ghost nodes {:.0f} / {:.0f}; messages {:.1f} "
            "/ {:.0f}; point-to-point bytes in + out {:.0f} / {:.0f}; candidate pairs {:.0f} / "
            "{:.0f}; pairs in contact {}, {} record copies sent (bytes in + out {:.0f} / {:.0f}); "
            "all-gathered per step {} bytes to every part{}\n",
            P, opt.partition, t_dec, n_mean, n_max, tr_mean, tr_max,
            T > 0 ? 100.0 * (tr_mean * P / T - 1.0) : 0.0, g_mean, g_max, msg_mean, msg_max, b_mean,
            b_max, p_mean, p_max, records, sent, rec_mean, rec_max, gathered,
            m.joints.nodes.empty()
                ? std::string()
                : fmt::format("; joints run {:.0f} mean / {:.0f} max", j_mean, j_max));
    }
    if (!opt.csv.empty()) {
        if (!write_text_file(opt.csv, csv)) {
            throw fdem::InputError({}, "--csv",
                                   fmt::format("--csv: cannot write \"{}\": {}; expected a "
                                               "writable file path",
                                               opt.csv, std::strerror(errno)));
        }
        fmt::print("csv        {} (one row per part)\n", opt.csv);
    }
    return 0;
}

}  // namespace

// The number of processes mpirun (Open MPI, or a PMI launcher such as MPICH's or Slurm's) started
// this program as one of; 1 when it was not started by an MPI launcher.
int launcher_processes() {
    for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"}) {
        if (const char* v = std::getenv(var)) {
            const int n = std::atoi(v);
            if (n > 0) return n;
        }
    }
    return 1;
}

int main(int argc, char** argv) {
    // line-buffered stdout: a batch log (stdout to a file) shows each line when it is printed,
    // not at exit
    std::setvbuf(stdout, nullptr, _IOLBF, 0);
    CLI::App app{"fdem: 2-D combined finite-discrete element simulator with smooth contact"};
    app.set_version_flag("--version", std::string("fdem ") + FDEM_VERSION);
    app.require_subcommand(1);

    RunOptions ro;
    auto* run_cmd = app.add_subcommand("run", "run a scenario");
    run_cmd->add_option("scenario", ro.scenario, "scenario file (TOML)")->required();
    run_cmd->add_option("--out", ro.out, "output folder (default: [output] dir of the scenario)")
        ->check(CLI::Validator(
            [](const std::string& v) -> std::string {
                return v.empty() ? "expected a non-empty folder path, got \"\"" : "";
            },
            "DIR", "non-empty"));
    run_cmd->add_option("--end-time", ro.end_time, "override the end time [s]")
        ->check(kFinitePositive);
    run_cmd->add_option("--threads", ro.threads, "OpenMP threads (default: all cores)")
        ->check(CLI::Range(1, 1024));
    run_cmd->add_flag("--quiet", ro.quiet, "no summary and no progress line");
    run_cmd->add_flag("--no-huge-pages", ro.no_huge_pages,
                      "leave the model's and state's arrays on 4 KiB pages (default: the large "
                      "ones on 2 MiB transparent huge pages where Linux allows; same results)");
    run_cmd
        ->add_option("--checkpoint-every", ro.checkpoint_every,
                     "write OUT/checkpoint.fdck every T simulated seconds and at the end")
        ->check(kFinitePositive);
    run_cmd->add_option("--restart", ro.restart,
                        "continue from a checkpoint written for the same scenario");
    run_cmd->add_flag("--print-hash", ro.print_hash,
                      "with --quiet: print only 'hash <hex>' of the final x, v and energies");
    run_cmd
        ->add_option("--partition", ro.partition,
                     "distributed runs (mpirun -np P): which process owns each group of 64 "
                     "nodes: rcb (Zoltan recursive coordinate bisection, default), ids "
                     "(contiguous node ids) or random (a test: every choice gives the same "
                     "result); no effect on a one-process run")
        ->check(CLI::IsMember({"rcb", "ids", "random"}));
    run_cmd
        ->add_option("--rebalance-every", ro.rebalance_every,
                     "distributed runs: compare the processes' estimated work every N "
                     "broad-phase searches and repartition (same rule as --partition) when "
                     "max/mean >= --imbalance (default 10; 0 = never); no effect on a "
                     "one-process run")
        ->check(CLI::Range(0, std::numeric_limits<int>::max()));
    run_cmd
        ->add_option("--imbalance", ro.imbalance,
                     "distributed runs: the max/mean of the processes' estimated work that "
                     "repartitions (default 1.1; 1 = at every check)")
        ->check(CLI::Validator(
            [](const std::string& text) -> std::string {
                char* end = nullptr;
                const double d = std::strtod(text.c_str(), &end);
                if (end == text.c_str() || *end != '\0' || !std::isfinite(d) || d < 1) {
                    return fmt::format("expected a finite ratio >= 1, got '{}'", text);
                }
                return "";
            },
            "RATIO >= 1", "ratio"));
    run_cmd
        ->add_option("--progress-every", ro.progress_every,
                     "when stderr is not a terminal: a progress line every S wall-clock seconds "
                     "(default 30; 0 = none)")
        ->check(
            [](const std::string& v) -> std::string {
                char* end = nullptr;
                const double d = std::strtod(v.c_str(), &end);
                if (end == v.c_str() || *end != '\0' || !std::isfinite(d) || d < 0) {
                    return fmt::format("--progress-every: expected seconds >= 0, got '{}'", v);
                }
                return "";
            },
            "SECONDS");

    std::string check_path;
    auto* check_cmd = app.add_subcommand("check", "validate a scenario and print a model summary");
    check_cmd->add_option("scenario", check_path, "scenario file (TOML)")->required();

    DecomposeOptions dop;
    auto* dec_cmd = app.add_subcommand(
        "decompose",
        "what each of P processes would own and exchange per step (one process, no mpirun)");
    dec_cmd->add_option("scenario", dop.scenario, "scenario file (TOML)")->required();
    dec_cmd->add_option("--parts", dop.parts, "process counts P, e.g. 2,4,64,1024")
        ->required()
        ->delimiter(',')
        ->check(CLI::Range(1, 1 << 20));
    dec_cmd
        ->add_option("--partition", dop.partition,
                     "rcb (Zoltan, the default of fdem run), ids or random, as fdem run")
        ->check(CLI::IsMember({"rcb", "ids", "random"}));
    dec_cmd
        ->add_option("--end-time", dop.end_time,
                     "run serially to this time first [s] (default: one step)")
        ->check(kFinitePositive);
    dec_cmd->add_option("--csv", dop.csv, "write one row per part (the columns of partition.csv)");
    dec_cmd->add_option("--threads", dop.threads, "OpenMP threads (default: all cores)")
        ->check(CLI::Range(1, 1024));

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? 0 : kExitInput;
    }

    ro.out_given = run_cmd->count("--out") > 0;
    ro.end_time_given = run_cmd->count("--end-time") > 0;
    try {
        if (*run_cmd) {
            const int procs = launcher_processes();
#ifdef FDEM_HAVE_MPI
            if (procs > 1) {
                // a distributed run (issue #15 M2a, docs/parallel.md): every process loads the
                // scenario and steps its share; only process 0 prints and writes, every process
                // ends with the same exit code (input and simulation errors arise on all alike)
                static fdem::MpiSession session(&argc, &argv);
                static const fdem::MpiComm comm;
                if (comm.rank() != 0) {
                    if (std::freopen("/dev/null", "w", stdout) == nullptr ||
                        std::freopen("/dev/null", "w", stderr) == nullptr) {
                        return kExitSimulation;
                    }
                }
                g_comm = &comm;
                return run(ro);
            }
#endif
            // P copies of a serial run would each run the whole scenario and write the same
            // files: refuse instead
            if (procs > 1) {
                throw fdem::InputError(
                    {}, "mpirun",
                    fmt::format("this fdem was started as one of {} MPI processes, but it was "
                                "built without MPI and runs a scenario in one process only; each "
                                "process would run the whole scenario and write the same files. "
                                "Run it without mpirun (or with -np 1), use --threads for the "
                                "cores of one machine, or build with -DFDEM_MPI=ON "
                                "(docs/parallel.md)",
                                procs));
            }
            return run(ro);
        }
        if (*dec_cmd) {
            const fdem::Comm* rcb_comm = nullptr;
#ifdef FDEM_HAVE_MPI
            if (dop.partition == "rcb") {  // Zoltan needs MPI: a one-process world
                static fdem::MpiSession session(&argc, &argv);
                static const fdem::MpiComm comm;
                rcb_comm = &comm;
            }
#endif
            return decompose_command(dop, rcb_comm);
        }
        if (*check_cmd) {
            const fdem::Scenario sc = fdem::load_scenario(check_path);
            print_summary(sc);
            print_warnings(sc);
            return 0;
        }
    } catch (const fdem::InputError& e) {
        fmt::print(stderr, "{}\n", e.what());
        return kExitInput;
    } catch (const std::exception& e) {
        fmt::print(stderr, "error: {}\n", e.what());
        return kExitSimulation;
    }
    return 0;
}
