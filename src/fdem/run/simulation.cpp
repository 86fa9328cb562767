// The run loop (include/fdem/simulation.hpp; docs/architecture.md "The run loop").
#include "fdem/simulation.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "fdem/build.hpp"
#include "fdem/error.hpp"
#include "fdem/measure.hpp"
#include "fdem/output.hpp"
#include "fdem/simulate.hpp"
#include "integrate/run_checks.hpp"
#include "io/checkpoint.hpp"
#include "io/fracture_output.hpp"
#include "parallel/decompose.hpp"
#include "parallel/distributed.hpp"

namespace fdem {

namespace fs = std::filesystem;

// a signal handler stores into the stop flag: only a lock-free atomic is async-signal-safe
static_assert(std::atomic<int>::is_always_lock_free);

struct Simulation::Impl {
    std::string name;
    Model model;
    RunSettings run;
    State state;
    RunProgress prog;        ///< output bookkeeping and energy monitor (saved in checkpoints)
    bool restarted = false;  ///< the state came from a checkpoint: continue its output files

    std::string out_dir;  ///< "" = no output
    std::unique_ptr<HistoryWriter> history;
    std::unique_ptr<PvdSeries> series;
    std::unique_ptr<Resultants> resultants;  ///< bodies.csv sums (output.bodies)
    std::vector<uint8_t> my_sets;            ///< distributed: the Resultants sets this process sums
    std::vector<int32_t> set_rank;           ///< distributed: the process that sums each set
    std::unique_ptr<BodiesWriter> bodies;
    std::unique_ptr<ProbesWriter> probes;  ///< probes.csv ([[probe]] entries)
    /// cracks.csv, fragments.csv, joints_NNNNNN.vtu + joints.pvd (models with joints only)
    std::unique_ptr<FractureOutput> fracture;
    WrittenFile last_frame, last_checkpoint, failure;
    std::string failure_error;
    Real checkpoint_every = 0;
    Real next_checkpoint = 0;

    std::atomic<int> stop{0};
    std::string first_warning;
    int64_t warnings = 0;
    std::function<void(const std::string&)> on_warning;
    std::function<void(const std::string&)> on_notice = [](const std::string& text) {
        fmt::print(stderr, "{}\n", text);
    };
    std::string restart_from;  ///< folder of the checkpoint restored ("" = none)
    /// distributed run (distribute()): the communicator and this process's share of the step;
    /// only process 0 writes files (writes)
    const Comm* comm = nullptr;
    std::unique_ptr<StepPlan> plan;
    VtuPiece piece;  ///< this process's piece of the frames (frame_in_pieces())
    bool writes = true;
    Rebalance rebalance;         ///< load balancing of a distributed run (set_rebalance())
    RebalanceStats rebalanced;   ///< what it did
    int64_t searches_seen = 0;   ///< broad-phase searches at the last look
    int64_t searches_since = 0;  ///< broad-phase searches since the last imbalance check

    Impl(std::string n, Model&& m, RunSettings r)
        : name(std::move(n)),
          model(std::move(m)),
          run(std::move(r)),
          state(make_state(model, run.dt)) {}

    int64_t steps_to(Real t) const { return static_cast<int64_t>(std::ceil(t / state.dt - 1e-9)); }

    /// fn, which only process 0 does (its files): in a distributed run every process takes part,
    /// so that an error of process 0 (a full disk, a folder in the way) stops every process with
    /// its message instead of leaving the others waiting in the next step's collectives (spec
    /// D9; test mpi.same_failure.output_*). The same call on every process.
    template <class F>
    void on_writer(F&& fn) {
        if (plan && comm->size() > 1) {
            run_collectively(*comm, [&] {
                if (writes) fn();
            });
        } else if (writes) {
            fn();
        }
    }

    bool writers_open = false;  ///< ensure_writers() ran (on every process)

    // The writers are created at the first run, after a possible restore_checkpoint(), so that a
    // restart continues history.csv instead of truncating it.
    void ensure_writers() {
        if (out_dir.empty() || writers_open) return;
        on_writer([&] { open_writers(); });
        writers_open = true;  // (not after an error: the next run tries again, as before)
        share_resultants();
    }

    /// A distributed run: the per-step sums of bodies.csv (Resultants::accumulate(), O(nodes
    /// that can carry a contact force) per step) are shared between the processes by whole
    /// sets, each set summed by one process in the serial order (the same bits); the impulses
    /// are all-gathered before output and checkpoints (gather_impulses()). Without this,
    /// process 0 alone summed every set every step (4.5 % of its instructions in a 3 600-grain
    /// pile on 2 processes, an Amdahl term that grows with P). Each set goes to the process that
    /// owns most of its nodes (Resultants::set_ranks()): a set summed elsewhere needs the contact
    /// forces of all its nodes sent there every step (with sets dealt by load alone, half of a
    /// 6 400-block pack's were, and the 2-process step ran 31 % more instructions with bodies.csv
    /// than without).
    void share_resultants() {
        my_sets.clear();
        set_rank.clear();
        if (!plan || comm->size() < 2 || !run.output.bodies) return;
        if (!resultants) {  // (process 0 made it in open_writers())
            resultants = std::make_unique<Resultants>(model, state.topology);
            if (prog.impulses.contact.size() != static_cast<size_t>(resultants->num_sets()))
                prog.impulses = resultants->make_impulses();
        }
        assign_sets();
    }

    /// The sets' processes for the current plan, and the force readers that follow from them.
    void assign_sets() {
        set_rank = resultants->set_ranks(comm->size(), plan->node_owner);
        my_sets.assign(set_rank.size(), 0);
        for (size_t k = 0; k < set_rank.size(); ++k)
            my_sets[k] = set_rank[k] == comm->rank();
        share_force_readers();
    }

    /// After a new plan: the sets follow their nodes to their new owners. The impulses summed
    /// so far are all-gathered first, so each set's new process continues its running sum (the
    /// same bits as one process). Collective.
    void sets_follow_plan() {
        if (set_rank.empty()) return;  // (not shared yet: share_resultants() assigns them)
        gather_impulses();
        assign_sets();
    }

    /// The contact forces of a distributed step are added only to the nodes a process needs
    /// (contact.hpp add_contact_forces()): tell the plan which nodes each process's sets read
    /// beside its own. Every process computes the same lists. After share_resultants() and
    /// every new plan.
    void share_force_readers() {
        if (!plan || set_rank.empty() || !resultants) return;
        std::vector<std::vector<NodeId>> contact(set_rank.size()), force(set_rank.size());
        for (size_t k = 0; k < contact.size(); ++k) {
            contact[k] = resultants->contact_read_nodes(static_cast<int32_t>(k));
            force[k] = resultants->force_read_nodes(static_cast<int32_t>(k));
        }
        set_force_readers(*plan, contact, force, set_rank);
    }

    /// Every set's impulses from the process that sums it, on every process. Collective.
    void gather_impulses() {
        if (my_sets.empty()) return;
        std::vector<char> mine, all;
        for (size_t k = 0; k < my_sets.size(); ++k) {
            if (!my_sets[k]) continue;
            const double rec[5] = {static_cast<double>(k), prog.impulses.contact[k].x,
                                   prog.impulses.contact[k].y, prog.impulses.reaction[k].x,
                                   prog.impulses.reaction[k].y};
            const char* b = reinterpret_cast<const char*>(rec);
            mine.insert(mine.end(), b, b + sizeof rec);
        }
        comm->allgather_bytes(mine, all);
        for (size_t at = 0; at + 5 * sizeof(double) <= all.size(); at += 5 * sizeof(double)) {
            double rec[5];
            std::memcpy(rec, all.data() + at, sizeof rec);
            const size_t k = static_cast<size_t>(rec[0]);
            prog.impulses.contact[k] = {rec[1], rec[2]};
            prog.impulses.reaction[k] = {rec[3], rec[4]};
        }
    }

    void open_writers() {
        const fs::path out = out_dir;
        if (!restart_from.empty()) adopt_earlier_output();
        history = restarted
                      ? std::make_unique<HistoryWriter>((out / "history.csv").string(), state.step,
                                                        !model.joints.nodes.empty())
                      : std::make_unique<HistoryWriter>((out / "history.csv").string(),
                                                        !model.joints.nodes.empty());
        history->prepare(model);  // the fracture columns' scratch, before the step loop
        // bodies.csv: resultants, reactions and mean motion per body entry and boundary group
        const int64_t resume = restarted ? state.step : -1;
        if (run.output.bodies) {
            resultants = std::make_unique<Resultants>(model, state.topology);
            bodies =
                std::make_unique<BodiesWriter>((out / "bodies.csv").string(), *resultants, resume);
            if (prog.impulses.contact.size() != static_cast<size_t>(resultants->num_sets())) {
                prog.impulses = resultants->make_impulses();  // fresh, or the checkpoint had none
            }
            if (bodies->header_changed() && on_notice) {
                on_notice(fmt::format("note: {} had other columns; its earlier rows were dropped",
                                      (out / "bodies.csv").string()));
            }
        }
        // probes.csv: the [[probe]] entries
        if (!run.output.probes.empty()) {
            probes = std::make_unique<ProbesWriter>((out / "probes.csv").string(),
                                                    run.output.probes, resume);
            if (probes->header_changed() && on_notice) {
                on_notice(fmt::format("note: {} had other columns; its earlier rows were dropped",
                                      (out / "probes.csv").string()));
            }
        }
        series = std::make_unique<PvdSeries>((out / "series.pvd").string());
        for (const auto& [t, file] : prog.frames)
            series->add(t, file);
        if (!model.joints.nodes.empty()) {
            fracture = std::make_unique<FractureOutput>(out_dir, model, state, run.fracture,
                                                        run.output.vtu, restarted, prog.frames);
            for (const std::string& f : fracture->changed_headers()) {
                if (on_notice) {
                    on_notice(fmt::format(
                        "note: {} had other columns; its earlier rows were dropped", f));
                }
            }
        }
    }

    void close_writers() {
        history.reset();
        writers_open = false;
        series.reset();
        bodies.reset();
        resultants.reset();
        probes.reset();
        fracture.reset();
    }

    // Continuing into another folder: the frames and history rows written before the checkpoint
    // stay next to it; series.pvd refers to those frames by a relative path and history.csv
    // starts with the old rows, so the new folder describes the whole run.
    void adopt_earlier_output() {
        const fs::path out = out_dir;
        const fs::path from = restart_from;
        restart_from.clear();
        std::error_code ec;
        if (fs::equivalent(from, out, ec)) return;
        for (auto& [t, file] : prog.frames) {
            if (fs::exists(out / file, ec)) continue;
            if (fs::exists(from / file, ec)) {
                file = fs::relative(from / file, fs::absolute(out)).string();
            } else if (on_notice) {
                on_notice(
                    fmt::format("warning: frame {} (t = {:.6g} s) of the run before the "
                                "restart is not in {} nor in {}; series.pvd lists it anyway",
                                file, t, from.string(), out.string()));
            }
        }
        for (const char* csv : {"history.csv", "cracks.csv", "fragments.csv"}) {
            if (!fs::exists(out / csv, ec) && fs::exists(from / csv, ec)) {
                fs::copy_file(from / csv, out / csv, ec);
            }
        }
    }

    /// a distributed step leaves f, and with ghosts x and v, complete only on the nodes a
    /// process owns or reads (step_distributed()): gather them before they are written.
    /// Collective.
    /// checkpoint: also the candidate pairs, of which each process holds its own targets'
    /// (the file holds the serial list). The joints' history always (each process runs its
    /// own: frames, fragments.csv, checkpoints and a new plan read every joint).
    void complete_state(bool checkpoint = false) {
        if (!plan) return;
        if (plan->ghosts.active) {
            gather_nodes(state.x.data(), *plan, *comm);
            gather_nodes(state.v.data(), *plan, *comm);
        }
        gather_forces(state, *plan, *comm);
        gather_impulses();
        gather_joint_state(model, state, *plan, *comm);  // (each process runs its joints)
        const ContactAlgorithm a = model.contact.algorithm;
        const bool pairs = a != ContactAlgorithm::None && a != ContactAlgorithm::LegacyTriangle;
        // (each process adds the contact forces of the nodes it needs only)
        if (pairs) {
            gather_nodes(state.f_contact.data(), *plan, *comm);
            state.contact.fc_sparse = false;  // (every node written: the next clear is of all)
        }
        if (checkpoint && pairs) {
            gather_candidates(state, *plan, *comm);
            gather_active(state, *plan, *comm);
        }
    }

    /// a distributed frame as pieces (spec D13) rather than one file by process 0
    bool frame_in_pieces() const {
        return plan && comm->size() > 1 && run.output.vtu && !run.output.merge;
    }

    /// every process writes its piece frame_NNNNNN/pRRRR.vtu; an error on any process stops
    /// all of them with the same message (spec D9). Collective.
    void write_piece() {
        const fs::path dir = fs::path(out_dir) / fmt::format("frame_{:06d}", prog.frame);
        run_collectively(*comm, [&] {
            std::error_code ec;
            fs::create_directories(dir, ec);
            if (ec) {
                throw SimulationError(
                    state.step, state.time, dir.string(),
                    "cannot create the folder of the frame's pieces: " + ec.message());
            }
            write_vtu_piece((dir / fmt::format("p{:04d}.vtu", comm->rank())).string(), model, state,
                            piece);
        });
    }

    void write_output(bool last) {
        // a distributed run: the whole State where a writer reads nodal values (frames,
        // bodies.csv, probes, fracture output) and at the last step (the final state); a
        // history row reads replicated scalars and the joints' state only, so its steps gather
        // that alone (the all-gathers of x, v, f and f_contact at each of the default 100 rows
        // were 0.04-0.07 s of each process's ~1.2-1.6 s on the 10 000-block saturated pack's 200
        // steps, the timing table's "other"; docs/parallel.md, stop 52)
        // (the settings, the same on every process: the writers exist on the writer only)
        if (last || run.output.vtu || run.output.bodies || !run.output.probes.empty() ||
            !model.joints.nodes.empty()) {
            complete_state();
        } else if (plan) {
            gather_joint_state(model, state, *plan, *comm);
        }
        if (frame_in_pieces()) write_piece();
        on_writer([&] { write_files(last); });
        // (the bookkeeping of every process, also those that do not write)
        if (resultants) prog.impulses.clear();
        ++prog.frame;
        const Real interval = run.output.interval > 0 ? run.output.interval : run.end_time / 100.0;
        prog.next_output += interval;
    }

    // process 0's part of write_output()
    void write_files(bool last) {
        const fs::path out = out_dir;
        history->write(model, state);
        if (bodies) {
            bodies->write(model, state, prog.impulses);
            prog.impulses.clear();
        }
        if (probes) probes->write(model, state);
        if (frame_in_pieces()) {
            const std::string frame = fmt::format("frame_{:06d}.pvtu", prog.frame);
            std::vector<std::string> sources;
            for (int r = 0; r < comm->size(); ++r)
                sources.push_back(fmt::format("frame_{:06d}/p{:04d}.vtu", prog.frame, r));
            write_pvtu((out / frame).string(), model, state, sources);
            series->add(state.time, frame);
            prog.frames.emplace_back(state.time, frame);
            last_frame = {(out / frame).string(), state.step, state.time};
        } else if (run.output.vtu) {
            const std::string frame = fmt::format("frame_{:06d}.vtu", prog.frame);
            write_vtu((out / frame).string(), model, state);
            series->add(state.time, frame);
            prog.frames.emplace_back(state.time, frame);
            last_frame = {(out / frame).string(), state.step, state.time};
        }
        if (fracture) fracture->write_output(model, state, prog.frame, last);
    }

    std::string checkpoint_path() const {
        return out_dir.empty() ? std::string() : (fs::path(out_dir) / "checkpoint.fdck").string();
    }

    void write_checkpoint_file(const std::string& path) {
        complete_state(true);
        on_writer([&] {
            write_checkpoint(path, model, state, prog);
            last_checkpoint = {path, state.step, state.time};
        });
    }

    /// One step of the loop: energies where they are read, step, checks, output and checkpoint
    /// when due. total: steps to end_time (final frame and checkpoint); target: last step of
    /// this run. Returns whether a stop was requested (the checkpoint is then written).
    bool advance(int64_t total, int64_t target, bool all_energy, int64_t energy_every = 0) {
        State& s = state;
        const Model& m = model;
        const bool out = !out_dir.empty();
        const bool ck = out && checkpoint_every > 0;
        // the strain energy (a log per triangle) only where it is read: the first step (E_0),
        // every 16th step (energy-balance check), output and checkpoint steps, the last step
        // (State::need_energy; x and v are bitwise the same either way)
        const Real t_next = s.time + s.dt;
        s.need_energy = all_energy || s.step == 0 || (s.step + 1) % 16 == 0 ||
                        s.step + 1 == total || s.step + 1 == target ||
                        (energy_every > 0 && (s.step + 1) % energy_every == 0) ||
                        (out && t_next >= prog.next_output - 0.5 * s.dt) ||
                        (ck && t_next >= next_checkpoint - 0.5 * s.dt);
        const int64_t step_before = s.step;
        const Real time_before = s.time;
        if (plan) {
            step_distributed(m, s, *plan, *comm);
        } else {
            fdem::step(m, s);
        }
        if (fracture) fracture->after_step(m, s, step_before, time_before);
        if (resultants) {
            if (my_sets.empty()) {
                resultants->accumulate(m, s, prog.impulses);
            } else {
                resultants->accumulate(m, s, prog.impulses, my_sets);
            }
        }
        if (plan) maybe_rebalance();
        const std::string warning = check_run(m, s, run, prog.energy);
        if (!warning.empty() && warnings++ == 0) {
            first_warning = warning;
            if (on_warning) on_warning(first_warning);
        }
        const bool last = s.step == total;
        const bool output_due = out && (s.time >= prog.next_output - 0.5 * s.dt || last);
        const bool checkpoint_due = ck && (s.time >= next_checkpoint - 0.5 * s.dt || last);
        // a distributed run stops at the same step on every process: the first 16th step after
        // any process saw the request (SIGINT/SIGTERM reach each process at its own time)
        bool stop_asked = stop.load(std::memory_order_relaxed) != 0;
        if (plan) stop_asked = s.step % 16 == 0 && comm->max(stop_asked ? 1.0 : 0.0) > 0;
        // NaN/Inf check every 16 steps and before anything is written: files hold good states
        if (s.step % 16 == 0 || output_due || checkpoint_due || stop_asked) {
            if (plan) {
                check_state_distributed(m, s, *plan, *comm);  // (x, v of other nodes may be stale)
                if (output_due || checkpoint_due) check_agreement(s, *comm);
            } else {
                check_state(m, s);
            }
        }
        if (output_due) write_output(last);
        if (checkpoint_due) {
            write_checkpoint_file(checkpoint_path());
            while (next_checkpoint <= s.time + 0.5 * s.dt)
                next_checkpoint += checkpoint_every;
        }
        if (stop_asked && out && !checkpoint_due) write_checkpoint_file(checkpoint_path());
        return stop_asked;
    }

    /// The broad-phase searches so far (the same count on every process).
    int64_t broad_phase_searches() const {
        const ContactAlgorithm a = model.contact.algorithm;
        if (a == ContactAlgorithm::None) return 0;
        return a == ContactAlgorithm::LegacyTriangle ? state.contact.legacy.rebuilds
                                                     : state.contact.rebuilds;
    }

    /// Spec D10, after a step of a distributed run: on the every-th broad-phase search, the
    /// imbalance of the estimated work; above the threshold, a new partition. Every decision
    /// depends on replicated values only (the search count, reduced work), so every process
    /// takes the same branch and the collectives match. Collective.
    void maybe_rebalance() {
        if (rebalance.every <= 0 || comm->size() < 2) return;
        const int64_t searches = broad_phase_searches();
        if (searches == searches_seen) return;
        searches_since += searches - searches_seen;
        searches_seen = searches;
        if (searches_since < rebalance.every) return;
        searches_since = 0;
        // (whole ns on both sides, so that max >= mean holds exactly)
        const int64_t mine = std::llround(estimated_work(part_counts(model, state, *plan)));
        const double most = comm->max(static_cast<double>(mine));
        const int64_t total = comm->sum(mine);
        const double mean = static_cast<double>(total) / comm->size();
        const double ratio = mean > 0 ? most / mean : 1.0;
        ++rebalanced.checks;
        rebalanced.last_imbalance = ratio;
        rebalanced.worst_imbalance = std::max(rebalanced.worst_imbalance, ratio);
        if (!(ratio >= rebalance.imbalance)) return;
        // the whole State on every process, then the new owners and the plan for them; the
        // serial candidate list stays until the next search (the owner filters of the step
        // keep it correct, as after a restore)
        complete_state(true);
        std::vector<Vec2> centre;
        std::vector<double> weight;
        node_group_work(model, state, centre, weight);
        std::vector<int32_t> owner = rebalance.partition(centre, weight, rebalanced.rebalances);
        if (owner.size() != weight.size()) {
            throw std::runtime_error("rebalance: the partition gave " +
                                     std::to_string(owner.size()) + " owners for " +
                                     std::to_string(weight.size()) + " node groups");
        }
        std::vector<double> part(static_cast<size_t>(comm->size()), 0.0);
        for (size_t g = 0; g < owner.size(); ++g) {
            if (owner[g] < 0 || owner[g] >= comm->size()) {
                throw std::runtime_error("rebalance: the partition gave a node group to process " +
                                         std::to_string(owner[g]));
            }
            part[static_cast<size_t>(owner[g])] += weight[g];
        }
        double part_sum = 0, part_max = 0;
        for (const double w : part) {
            part_sum += w;
            part_max = std::max(part_max, w);
        }
        plan = std::make_unique<StepPlan>(make_step_plan(model, comm->rank(), comm->size(), owner));
        plan->contact.total_candidates = static_cast<int64_t>(state.contact.cand.node.size());
        sets_follow_plan();
        piece = make_vtu_piece(model, plan->node_owner, comm->rank());
        ++rebalanced.rebalances;
        rebalanced.planned_after = part_sum > 0 ? part_max * comm->size() / part_sum : 1.0;
        rebalanced.last_step = state.step;
    }

    void write_failure() {
        failure = {};
        failure_error.clear();
        complete_state();  // (every process fails at the same point: spec D9)
        if (out_dir.empty() || !writes) return;
        const std::string path = (fs::path(out_dir) / "failure.vtu").string();
        try {
            write_vtu(path, model, state);
            failure = {path, state.step, state.time};
        } catch (const std::exception& e) {
            failure_error = e.what();
        }
    }
};

Simulation::Simulation(Scenario scenario)
    : impl_(std::make_unique<Impl>(std::move(scenario.path), std::move(scenario.model),
                                   std::move(scenario.run))) {}

namespace {
RunSettings with_dt(const Model& m, RunSettings run, const std::string& name) {
    TriId tri = kNone;
    const Real stable = stable_time_step(m, &tri);
    run.stable_dt = stable;
    run.limiting_tri = tri;
    if (run.dt > 0 && std::isfinite(run.dt)) return run;
    if (!std::isfinite(stable) || !(run.dt_fraction > 0)) {
        throw InputError({name, 0, 0}, "dt",
                         "no dt given and none can be chosen: no stable time step limit (no body "
                         "moves and contact is off) or dt_fraction <= 0; give dt in s");
    }
    run.dt = run.dt_fraction * stable;
    run.dt_auto = true;
    return run;
}
}  // namespace

Simulation::Simulation(Model model, RunSettings run, std::string name) {
    RunSettings r = with_dt(model, std::move(run), name);
    impl_ = std::make_unique<Impl>(std::move(name), std::move(model), std::move(r));
}

Simulation Simulation::from_file(const std::string& path) {
    return Simulation(load_scenario(path));
}

Simulation::~Simulation() = default;
Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;

const Model& Simulation::model() const {
    return impl_->model;
}
const State& Simulation::state() const {
    return impl_->state;
}
State& Simulation::state() {
    return impl_->state;
}
const RunSettings& Simulation::settings() const {
    return impl_->run;
}
RunSettings& Simulation::settings() {
    return impl_->run;
}
const std::string& Simulation::name() const {
    return impl_->name;
}

void Simulation::open_output(const std::string& dir, const std::string& origin) {
    Impl& I = *impl_;
    const fs::path out = dir.empty() ? I.run.output.dir : dir;
    if (!I.writes) {  // process 0 creates and writes the folder
        I.out_dir = out.string();
        I.run.output.dir = I.out_dir;
        return;
    }
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) {
        throw InputError(
            {I.name, 0, 0}, "output.dir",
            fmt::format("cannot create output folder '{}': {}", out.string(), ec.message()));
    }
    {
        // a folder that exists but cannot be written is an input problem, found before step 0
        const fs::path probe = out / ".fdem_write_test";
        std::FILE* f = std::fopen(probe.c_str(), "w");
        const int err = errno;
        if (f == nullptr) {
            throw InputError({origin.empty() ? I.name : origin, 0, 0}, "output.dir",
                             fmt::format("cannot write into the output folder '{}': {}; expected "
                                         "a writable folder ([output] dir or --out)",
                                         out.string(), std::strerror(err)));
        }
        std::fclose(f);
        fs::remove(probe, ec);
    }
    I.close_writers();
    I.out_dir = out.string();
    I.run.output.dir = I.out_dir;
}

void Simulation::distribute(const Comm& comm, const std::vector<int32_t>& group_owner) {
    Impl& I = *impl_;
    I.comm = &comm;
    I.writes = comm.rank() == 0;
    I.plan =
        std::make_unique<StepPlan>(make_step_plan(I.model, comm.rank(), comm.size(), group_owner));
    I.piece = make_vtu_piece(I.model, I.plan->node_owner, comm.rank());
    // the state's list so far is a serial one (every target's pairs) until the next broad phase
    I.plan->contact.total_candidates = static_cast<int64_t>(I.state.contact.cand.node.size());
    I.sets_follow_plan();
}

void Simulation::set_rebalance(Rebalance r) {
    if (r.every < 0) throw std::invalid_argument("set_rebalance: every must be >= 0");
    if (!(r.imbalance >= 1) || !std::isfinite(r.imbalance))
        throw std::invalid_argument("set_rebalance: imbalance must be a finite number >= 1");
    if (r.every > 0 && !r.partition)
        throw std::invalid_argument("set_rebalance: every > 0 needs a partition function");
    Impl& I = *impl_;
    I.rebalance = std::move(r);
    I.searches_seen = I.broad_phase_searches();
    I.searches_since = 0;
}

const Simulation::RebalanceStats& Simulation::rebalance_stats() const {
    return impl_->rebalanced;
}

bool Simulation::output_open() const {
    return !impl_->out_dir.empty();
}
const std::string& Simulation::output_dir() const {
    return impl_->out_dir;
}
int64_t Simulation::frames_written() const {
    return impl_->prog.frame;
}
const WrittenFile& Simulation::last_frame() const {
    return impl_->last_frame;
}
const WrittenFile& Simulation::last_checkpoint() const {
    return impl_->last_checkpoint;
}

void Simulation::set_checkpoint_every(Real seconds) {
    if (!(seconds >= 0) || !std::isfinite(seconds)) {
        throw std::invalid_argument("set_checkpoint_every: expected seconds >= 0");
    }
    impl_->checkpoint_every = seconds;
    impl_->next_checkpoint = impl_->state.time + seconds;
}

std::string Simulation::checkpoint_path() const {
    return impl_->checkpoint_path();
}

void Simulation::save_checkpoint(const std::string& path) {
    impl_->write_checkpoint_file(path);
}

void Simulation::restore_checkpoint(const std::string& path) {
    Impl& I = *impl_;
    State s = make_state(I.model, I.state.dt);
    RunProgress prog;
    read_checkpoint(path, I.model, s, prog);
    // copy-assignment keeps the storage of the equally sized arrays (x, v, f, ...): views of
    // them stay valid; the step timing goes on (it is no part of the state of the run)
    s.timing = I.state.timing;
    I.state = s;
    I.prog = std::move(prog);
    I.restarted = true;
    I.restart_from = fs::absolute(fs::path(path)).parent_path().string();
    I.close_writers();
    I.next_checkpoint = I.state.time + I.checkpoint_every;
    if (I.plan) {                     // other candidates: new ghost lists and box lists
        I.plan->joints.work.clear();  // (the file's total_work_sum holds every process's work)
        I.plan->ghosts.dirty = true;
        I.plan->contact.boxes_valid = false;
        I.plan->contact.dest_valid = false;
        I.plan->contact.active_full = true;  // (the serial list of pairs in contact)
        // the file holds the serial list (every process has it until its next broad phase)
        I.plan->contact.total_candidates = static_cast<int64_t>(I.state.contact.cand.node.size());
    }
    // the partition of distribute() was made from the reference positions: check the balance
    // at the first broad-phase search of the continued run
    I.searches_seen = I.broad_phase_searches();
    I.searches_since = std::max(0, I.rebalance.every - 1);
}

int64_t Simulation::steps_to(Real t) const {
    return impl_->steps_to(t);
}

void Simulation::step() {
    Impl& I = *impl_;
    I.ensure_writers();
    try {
        I.advance(I.steps_to(I.run.end_time), I.state.step + 1, true);
    } catch (const SimulationError&) {
        I.write_failure();
        throw;
    }
}

RunResult Simulation::run(Real until, const StepCallback& callback, int64_t every,
                          bool callback_reads_energy) {
    if (every < 1) throw std::invalid_argument("Simulation::run: every must be >= 1");
    Impl& I = *impl_;
    struct ClearStop {
        std::atomic<int>& flag;
        ~ClearStop() { flag.store(0, std::memory_order_relaxed); }
    } clear_stop{I.stop};
    I.ensure_writers();
    State& s = I.state;
    const int64_t total = I.steps_to(I.run.end_time);
    const int64_t target = I.steps_to(until);
    RunResult res;
    try {
        while (s.step < target) {
            const bool stop =
                I.advance(total, target, false, callback && callback_reads_energy ? every : 0);
            ++res.steps;
            if (stop) {
                res.status = RunStatus::Stopped;
                break;
            }
            if (callback && s.step % every == 0 && !callback(*this)) {
                res.status = RunStatus::CallbackStopped;
                break;
            }
        }
    } catch (const SimulationError&) {
        I.write_failure();
        throw;
    }
    return res;
}

RunResult Simulation::run_to_end(const StepCallback& callback, int64_t every) {
    return run(impl_->run.end_time, callback, every);
}

void Simulation::request_stop() noexcept {
    impl_->stop.store(1, std::memory_order_relaxed);
}

void Simulation::check() const {
    check_state(impl_->model, impl_->state);
}
const EnergyMonitor& Simulation::energy_monitor() const {
    return impl_->prog.energy;
}
std::string Simulation::partition_csv() const {
    const Impl& I = *impl_;
    if (!I.plan) return "";
    static_assert(std::is_trivially_copyable_v<PartCounts>);
    const PartCounts mine = part_counts(I.model, I.state, *I.plan);
    std::vector<char> bytes(sizeof mine), all;
    std::memcpy(bytes.data(), &mine, sizeof mine);
    I.comm->allgather_bytes(bytes, all);
    std::vector<PartCounts> parts(all.size() / sizeof mine);
    std::memcpy(parts.data(), all.data(), parts.size() * sizeof mine);
    return fdem::partition_csv(parts);
}

Simulation::ContactCounts Simulation::contact_counts() const {
    const ContactModel& cm = impl_->model.contact;
    const ContactState& cs = impl_->state.contact;
    ContactCounts c;
    if (cm.algorithm == ContactAlgorithm::None) return c;
    c.in_contact = cs.active_contacts;
    if (cm.algorithm == ContactAlgorithm::LegacyTriangle) {
        c.candidates = static_cast<int64_t>(cs.legacy.couples.size());
        c.broad_phase_runs = cs.legacy.rebuilds;
        c.triangle_couples = true;
    } else {
        // (a distributed run: each process holds its own targets' pairs; the total is kept)
        c.candidates = impl_->plan ? impl_->plan->contact.total_candidates
                                   : static_cast<int64_t>(cs.cand.node.size());
        c.broad_phase_runs = cs.rebuilds;
    }
    return c;
}
const std::string& Simulation::first_warning() const {
    return impl_->first_warning;
}
int64_t Simulation::warnings() const {
    return impl_->warnings;
}

void Simulation::set_notice_handler(std::function<void(const std::string&)> handler) {
    impl_->on_notice = std::move(handler);
}

void Simulation::set_warning_handler(std::function<void(const std::string&)> handler) {
    impl_->on_warning = std::move(handler);
}

const WrittenFile& Simulation::failure_file() const {
    return impl_->failure;
}
const std::string& Simulation::failure_write_error() const {
    return impl_->failure_error;
}
uint64_t Simulation::state_hash() const {
    return fdem::state_hash(impl_->state);
}

}  // namespace fdem
