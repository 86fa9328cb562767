// fdem command-line program: run or check a scenario.
//   fdem run SCENARIO [--out DIR] [--end-time T] [--threads N] [--quiet]
//                     [--checkpoint-every T] [--restart FILE] [--print-hash]
//                     [--progress-every S]
//   fdem check SCENARIO
// Exit codes: 0 success, 1 simulation failure, 2 usage or input error (including a checkpoint
// that does not belong to the scenario), 130 / 143 stopped by SIGINT / SIGTERM after writing a
// checkpoint (128 + signal number, the shell convention).
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>

#include <fmt/format.h>
#include <omp.h>
#include <CLI/CLI.hpp>

#include "fdem/fdem.hpp"
#include "integrate/run_checks.hpp"
#include "io/checkpoint.hpp"

namespace {

constexpr int kExitSimulation = 1;
constexpr int kExitInput = 2;

/// Signal number of a pending SIGINT / SIGTERM (0: none). The run finishes its step, writes a
/// checkpoint and exits with 128 + signal.
volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void on_stop_signal(int sig) {
    g_stop_signal = sig;
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
    double progress_every = 30;  ///< wall seconds between progress lines when stderr is no tty
};

// Rough resident size of the model and state [bytes], for `fdem check`.
size_t memory_estimate(const fdem::Model& m) {
    const size_t nn = static_cast<size_t>(m.num_nodes()), nt = static_cast<size_t>(m.num_tris());
    const size_t model =
        nn * (2 * sizeof(fdem::Vec2) + 2 * sizeof(double) + sizeof(int32_t)) +
        nt * (3 * sizeof(int32_t) + 2 * sizeof(int32_t) + sizeof(fdem::Mat2) + 2 * sizeof(double));
    const size_t state = nn * 4 * sizeof(fdem::Vec2);
    return model + state;
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
        const std::string when =
            tf.kind == fdem::TimeFunction::Kind::Constant ? "constant"
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
        fmt::print("stable dt  {:.4g} s (limited by the contact penalty)\n", sc.run.stable_dt);
    }
    fmt::print("dt         {:.4g} s{}\n", sc.run.dt,
               sc.run.dt_auto ? fmt::format(" (auto: {:.3g} x stable)", sc.run.dt_fraction) : "");
    fmt::print("end time   {:.6g} s ({} steps)\n", sc.run.end_time,
               static_cast<long long>(std::ceil(sc.run.end_time / sc.run.dt - 1e-9)));
    fmt::print("memory     {:.2f} MB (model + state, estimate)\n", memory_estimate(m) / 1e6);

    // contact: which algorithm and why; which bodies it sees (two fixed bodies never interact)
    const char* alg = m.contact.algorithm == fdem::ContactAlgorithm::Smooth ? "smooth"
                      : m.contact.algorithm == fdem::ContactAlgorithm::LegacyTriangle
                          ? "legacy-triangle"
                      : m.contact.algorithm == fdem::ContactAlgorithm::LegacyBoundary
                          ? "legacy-boundary"
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
        fmt::print("  {:>6}  \"{}\"  {}  {:.6g}  {}  {}\n", b, body.name, body.tri_end - body.tri_begin,
                   mass, body.fixed ? "yes" : "no",
                   seen ? "yes"
                   : !on ? "no (contact off)"
                         : "no (nothing that moves can reach it)");
    }
    if (m.bodies.size() > kMaxRows) {
        fmt::print("  ... {} more bodies (ids {} to {}; their names, ids and masses are in every "
                   "VTU frame)\n",
                   m.bodies.size() - kMaxRows, kMaxRows, m.bodies.size() - 1);
    }
    for (const fdem::ProbeSpec& p : sc.run.output.probes) {
        if (p.kind == fdem::ProbeSpec::Kind::Node) {
            const fdem::Vec2 x = m.node_x0[p.nodes[0]];
            fmt::print("probe      \"{}\": node {} at ({:.6g}, {:.6g}) m, {:.3g} m from the given "
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

int run(const RunOptions& opt) {
    using clock = std::chrono::steady_clock;
    fdem::Scenario sc = fdem::load_scenario(opt.scenario);
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
    const fdem::Model& m = sc.model;
    const bool tty = isatty(STDERR_FILENO) && !opt.quiet;
    // batch runs (stderr to a file or pipe): a full progress line every progress_every seconds
    const bool batch = !isatty(STDERR_FILENO) && !opt.quiet && opt.progress_every > 0;
    if (!opt.quiet) print_summary(sc);
    print_warnings(sc);

    namespace fs = std::filesystem;
    const fs::path out = sc.run.output.dir;
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) {
        throw fdem::InputError(
            {sc.path, 0, 0}, "output.dir",
            fmt::format("cannot create output folder '{}': {}", out.string(), ec.message()));
    }
    {
        // a folder that exists but cannot be written is an input problem, found before step 0
        const fs::path probe = out / ".fdem_write_test";
        std::FILE* f = std::fopen(probe.c_str(), "w");
        const int err = errno;
        if (f == nullptr) {
            throw fdem::InputError(
                {opt.out_given ? std::string("--out") : sc.path, 0, 0}, "output.dir",
                fmt::format("cannot write into the output folder '{}': {}; expected a writable "
                            "folder ([output] dir or --out)",
                            out.string(), std::strerror(err)));
        }
        std::fclose(f);
        fs::remove(probe, ec);
    }
    const std::string checkpoint_path = (out / "checkpoint.fdck").string();

    // fresh state, or the state and output bookkeeping of a checkpoint
    fdem::State s = fdem::make_state(m, sc.run.dt);
    fdem::RunProgress prog;
    if (!opt.restart.empty()) {
        fdem::read_checkpoint(opt.restart, m, s, prog);
        if (!opt.quiet) {
            fmt::print("restart    {} at step {} (t = {:.6g} s)\n", opt.restart, s.step, s.time);
        }
        // continuing into another folder: the frames and history rows written before the
        // checkpoint stay next to it; series.pvd refers to those frames by a relative path and
        // history.csv starts with the old rows, so the new folder describes the whole run
        const fs::path from = fs::absolute(fs::path(opt.restart)).parent_path();
        if (!fs::equivalent(from, out, ec)) {
            for (auto& [t, file] : prog.frames) {
                if (fs::exists(out / file, ec)) continue;
                if (fs::exists(from / file, ec)) {
                    file = fs::relative(from / file, fs::absolute(out)).string();
                } else {
                    fmt::print(stderr,
                               "warning: frame {} (t = {:.6g} s) of the run before the restart "
                               "is not in {} nor in {}; series.pvd lists it anyway\n",
                               file, t, from.string(), out.string());
                }
            }
            if (!fs::exists(out / "history.csv", ec) && fs::exists(from / "history.csv", ec)) {
                fs::copy_file(from / "history.csv", out / "history.csv", ec);
            }
        }
    }
    std::unique_ptr<fdem::HistoryWriter> history =
        opt.restart.empty()
            ? std::make_unique<fdem::HistoryWriter>((out / "history.csv").string())
            : std::make_unique<fdem::HistoryWriter>((out / "history.csv").string(), s.step);
    // bodies.csv: resultants, reactions and mean motion per body entry and boundary group
    std::unique_ptr<fdem::Resultants> resultants;
    std::unique_ptr<fdem::BodiesWriter> bodies;
    if (sc.run.output.bodies) {
        resultants = std::make_unique<fdem::Resultants>(m);
        bodies = std::make_unique<fdem::BodiesWriter>((out / "bodies.csv").string(), *resultants,
                                                      opt.restart.empty() ? -1 : s.step);
        if (prog.impulses.contact.size() != static_cast<size_t>(resultants->num_sets())) {
            prog.impulses = resultants->make_impulses();  // fresh, or the checkpoint had none
        }
        if (bodies->header_changed()) {
            fmt::print(stderr, "note: {} had other columns; its earlier rows were dropped\n",
                       (out / "bodies.csv").string());
        }
    }
    // probes.csv: the [[probe]] entries
    std::unique_ptr<fdem::ProbesWriter> probes;
    if (!sc.run.output.probes.empty()) {
        probes = std::make_unique<fdem::ProbesWriter>((out / "probes.csv").string(),
                                                      sc.run.output.probes,
                                                      opt.restart.empty() ? -1 : s.step);
        if (probes->header_changed()) {
            fmt::print(stderr, "note: {} had other columns; its earlier rows were dropped\n",
                       (out / "probes.csv").string());
        }
    }
    fdem::PvdSeries series((out / "series.pvd").string());
    for (const auto& [t, file] : prog.frames)
        series.add(t, file);

    const double interval =
        sc.run.output.interval > 0 ? sc.run.output.interval : sc.run.end_time / 100.0;
    std::string last_frame;  // last output frame written by this process (a good state)
    auto write_output = [&]() {
        history->write(m, s);
        if (bodies) {
            bodies->write(m, s, prog.impulses);
            prog.impulses.clear();
        }
        if (probes) probes->write(m, s);
        if (sc.run.output.vtu) {
            const std::string name = fmt::format("frame_{:06d}.vtu", prog.frame);
            fdem::write_vtu((out / name).string(), m, s);
            series.add(s.time, name);
            prog.frames.emplace_back(s.time, name);
            last_frame = fmt::format("{} (t = {:.6g} s)", (out / name).string(), s.time);
        }
        ++prog.frame;
        prog.next_output += interval;
    };
    std::string last_checkpoint;
    auto write_checkpoint = [&]() {
        fdem::write_checkpoint(checkpoint_path, m, s, prog);
        last_checkpoint =
            fmt::format("{} (step {}, t = {:.6g} s)", checkpoint_path, s.step, s.time);
    };
    double next_checkpoint = s.time + opt.checkpoint_every;

    install_signal_handlers();
    const auto t0 = clock::now();
    auto last_progress = t0;
    const int64_t start_step = s.step;
    const int64_t total_steps = static_cast<int64_t>(std::ceil(sc.run.end_time / s.dt - 1e-9));
    bool warned = false;
    try {
        while (s.step < total_steps) {
            // the strain energy (a log per triangle) only where it is read: the first step (E_0),
            // every 16th step (energy-balance check), output and checkpoint steps, the last step
            // (State::need_energy; x and v are bitwise the same either way)
            const double t_next = s.time + s.dt;
            s.need_energy = s.step == 0 || (s.step + 1) % 16 == 0 || s.step + 1 == total_steps ||
                            t_next >= prog.next_output - 0.5 * s.dt ||
                            (opt.checkpoint_every > 0 && t_next >= next_checkpoint - 0.5 * s.dt);
            fdem::step(m, s);
            if (resultants) resultants->accumulate(m, s, prog.impulses);
            const std::string warning = fdem::check_run(m, s, sc.run, prog.energy);
            if (!warning.empty() && !warned) {
                fmt::print(stderr, "{}{} (further warnings suppressed)\n", tty ? "\n" : "",
                           warning);
                warned = true;
            }
            const bool last = s.step == total_steps;
            const bool output_due = s.time >= prog.next_output - 0.5 * s.dt || last;
            const bool checkpoint_due =
                opt.checkpoint_every > 0 && (s.time >= next_checkpoint - 0.5 * s.dt || last);
            // NaN/Inf check every 16 steps and before anything is written: files hold good states
            if (s.step % 16 == 0 || output_due || checkpoint_due || g_stop_signal != 0) {
                fdem::check_state(m, s);
            }
            if (output_due) write_output();
            if (checkpoint_due) {
                write_checkpoint();
                while (next_checkpoint <= s.time + 0.5 * s.dt)
                    next_checkpoint += opt.checkpoint_every;
            }
            if (g_stop_signal != 0) {
                const int sig = g_stop_signal;
                if (!checkpoint_due) write_checkpoint();
                if (tty) fmt::print(stderr, "\n");
                fmt::print(stderr,
                           "stopped by {} after step {} (t = {:.6g} s); checkpoint written to {}\n"
                           "continue with: fdem run {} --out {} --restart {}\n",
                           sig == SIGINT ? "SIGINT" : "SIGTERM", s.step, s.time, checkpoint_path,
                           opt.scenario, out.string(), checkpoint_path);
                return 128 + sig;
            }
            if (batch) {
                const auto now = clock::now();
                if (std::chrono::duration<double>(now - last_progress).count() >=
                    opt.progress_every) {
                    last_progress = now;
                    const double wall = std::chrono::duration<double>(now - t0).count();
                    const double sps = static_cast<double>(s.step - start_step) / wall;
                    fmt::print(stderr,
                               "progress   step {} / {}  t = {:.6g} s  {:.3g} steps/s  ETA {:.0f} "
                               "s\n",
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
        }
    } catch (const fdem::SimulationError& err) {
        if (tty) fmt::print(stderr, "\n");
        fmt::print(stderr, "error: {}\n", err.what());
        fdem::write_vtu((out / "failure.vtu").string(), m, s);
        fmt::print(stderr, "the state at failure is in {}\n", (out / "failure.vtu").string());
        if (!last_frame.empty()) fmt::print(stderr, "last good output frame: {}\n", last_frame);
        if (!last_checkpoint.empty()) {
            fmt::print(stderr, "last good checkpoint: {}\n", last_checkpoint);
        }
        return kExitSimulation;
    }
    if (tty) fmt::print(stderr, "\n");
    const double wall = std::chrono::duration<double>(clock::now() - t0).count();
    const uint64_t hash = fdem::state_hash(s);
    if (!opt.quiet) {
        const double steps = static_cast<double>(s.step - start_step);
        fmt::print("done       {} steps in {:.2f} s ({:.3g} steps/s, {:.3g} element-steps/s)\n",
                   s.step - start_step, wall, steps / wall, steps * m.num_tris() / wall);
        fmt::print(
            "energy     kinetic {:.6g}, strain {:.6g}, contact {:.6g}, dissipated {:.6g} J/m\n",
            s.energy.kinetic, s.energy.strain, s.energy.contact,
            s.energy.dissipated_viscous + s.energy.dissipated_contact);
        const fdem::EnergyMonitor& e = prog.energy;
        fmt::print(
            "balance    max |E_total - E_0| = {:.3g} J/m = {:.3g} % of the energy scale "
            "{:.6g} J/m\n",
            e.max_error, e.scale > 0 ? 100.0 * e.max_error / e.scale : 0.0, e.scale);
        fmt::print("output     {} ({} frames; open series.pvd in ParaView)\n", out.string(),
                   prog.frame);
        fmt::print("state      step {}, t = {:.6g} s, hash {:016x} (x, v, energies)\n", s.step,
                   s.time, hash);
    } else if (opt.print_hash) {
        fmt::print("hash {:016x}\n", hash);
    }
    return 0;
}

}  // namespace

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
    run_cmd
        ->add_option("--out", ro.out, "output folder (default: [output] dir of the scenario)")
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
    run_cmd
        ->add_option("--checkpoint-every", ro.checkpoint_every,
                     "write OUT/checkpoint.fdck every T simulated seconds and at the end")
        ->check(kFinitePositive);
    run_cmd->add_option("--restart", ro.restart,
                        "continue from a checkpoint written for the same scenario");
    run_cmd->add_flag("--print-hash", ro.print_hash,
                      "with --quiet: print only 'hash <hex>' of the final x, v and energies");
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

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? 0 : kExitInput;
    }

    ro.out_given = run_cmd->count("--out") > 0;
    ro.end_time_given = run_cmd->count("--end-time") > 0;
    try {
        if (*run_cmd) return run(ro);
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
