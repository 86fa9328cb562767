// Simulation: the run loop of fdem as a library object (docs/architecture.md "The run loop").
// It owns a Model, a State, the RunSettings, the energy monitor and the output writers, and does
// what `fdem run` does: steps, evaluates the energies where they are read, applies the run-time
// checks, writes output frames, history and checkpoints when due, and reports a failure as a
// typed error after writing failure.vtu. The command-line program is a thin client of it.
//
//   fdem::Simulation sim = fdem::Simulation::from_file("scenario.toml");
//   sim.open_output("out");                      // optional: VTU/PVD, history.csv, checkpoints
//   sim.run(0.01, [](fdem::Simulation& s) { std::printf("%g\n", s.state().time); return true; },
//           100);                                // to t = 0.01, a callback every 100th step
//   uint64_t h = sim.state_hash();               // equals `fdem run --quiet --print-hash`
//
// Lifetime: model() and state() are allocated once; their arrays keep their addresses for the
// life of the Simulation (also across a move of the Simulation object and across
// restore_checkpoint), so views of them (the Python module's NumPy arrays) stay valid.
// Threads: nothing global is touched in the loop (the stop flag is per Simulation), so run() may
// be called without any lock of the caller held; one Simulation must not be stepped from two
// threads at once. request_stop() may be called from any thread or a signal handler.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "fdem/checks.hpp"
#include "fdem/model.hpp"
#include "fdem/scenario.hpp"
#include "fdem/state.hpp"

namespace fdem {

/// Why run() returned.
enum class RunStatus {
    Reached,         ///< the requested time (its step count) was reached
    Stopped,         ///< request_stop() was called (e.g. from a signal handler)
    CallbackStopped  ///< the callback returned false
};

struct RunResult {
    RunStatus status = RunStatus::Reached;
    int64_t steps = 0;  ///< steps taken by this call
};

/// A file the run wrote, with the state it holds.
struct WrittenFile {
    std::string path;  ///< "" = none yet
    int64_t step = 0;
    Real time = 0;  ///< [s]
};

class Comm;  // src/fdem/parallel/comm.hpp (distributed runs, issue #15)

class Simulation {
public:
    /// Called after a step (see run()); return false to stop the run after that step.
    using StepCallback = std::function<bool(Simulation&)>;

    /// Take a loaded scenario (load_scenario / load_scenario_from_string).
    explicit Simulation(Scenario scenario);
    /// A model built in code (build.hpp) with its run settings. run.dt <= 0 chooses
    /// run.dt_fraction x the stable time step (as dt = "auto"); name appears in messages.
    /// Throws InputError (key "dt") if dt cannot be chosen.
    Simulation(Model model, RunSettings run, std::string name = "model");
    /// load_scenario(path); throws InputError on bad input.
    static Simulation from_file(const std::string& path);

    ~Simulation();
    Simulation(Simulation&&) noexcept;
    Simulation& operator=(Simulation&&) noexcept;
    Simulation(const Simulation&) = delete;
    Simulation& operator=(const Simulation&) = delete;

    const Model& model() const;
    const State& state() const;
    /// Mutable state between steps (e.g. velocities). Changing x needs
    /// state().contact.need_rebuild = true.
    State& state();
    /// end_time, output interval and checks may be changed between steps; dt may not.
    const RunSettings& settings() const;
    RunSettings& settings();
    const std::string& name() const;  ///< scenario file or the given name

    // ---- output ------------------------------------------------------------------------------
    /// Write output to dir (created if missing: InputError key "output.dir" if it cannot be):
    /// VTU frames + series.pvd (if settings().output.vtu), history.csv, bodies.csv (if
    /// settings().output.bodies) and probes.csv (if there are [[probe]] entries) every
    /// settings().output.interval of simulated time (0: end_time / 100) and at end_time,
    /// checkpoints (set_checkpoint_every), failure.vtu on a SimulationError. After
    /// restore_checkpoint() the files of the interrupted run are continued. dir "" =
    /// settings().output.dir. Without this call nothing is written. Throws SimulationError if a
    /// writer cannot open its file.
    /// The folder must be writable (a probe file is created and removed): InputError key
    /// "output.dir" located at `origin` (e.g. "--out"; "" = name()) if not.
    void open_output(const std::string& dir = "", const std::string& origin = "");
    /// Run as one process of comm (issue #15, docs/parallel.md "M2a"): every process makes this
    /// Simulation from the same input and calls distribute() before open_output() and the first
    /// step; each then updates its share of the nodes and elements, and the State stays the same
    /// on all processes, bitwise the one-process run's. Only process 0 writes files; the others
    /// keep the output bookkeeping. comm must outlive the Simulation. Every later call that
    /// steps is collective. group_owner: the process of every node group (64 consecutive node
    /// ids; e.g. parallel/mpi/rcb.hpp rcb_group_owners()), the same on every process; empty:
    /// contiguous ranges of node ids. Any assignment gives the same bits.
    void distribute(const Comm& comm, const std::vector<int32_t>& group_owner = {});

    /// Load balancing of a distributed run (spec D10, docs/parallel.md "Rebalancing"): after
    /// every `every`-th broad-phase search the processes compare their estimated work per step
    /// (parallel/decompose.hpp estimated_work(): triangles run, candidate pairs, pairs in
    /// contact); when max / mean >= imbalance, every process gathers the whole State (x, v, f,
    /// the candidate pairs) and the node groups get new owners from `partition`, called with
    /// every group's centre at the current positions and its estimated work
    /// (node_group_work()) and the number of partitions made before. The result does not depend
    /// on the partition: the run stays bitwise the one-process run.
    struct Rebalance {
        int32_t every = 0;       ///< broad-phase searches between checks; 0: never
        double imbalance = 1.1;  ///< the max / mean of the estimated work that rebalances (>= 1)
        /// the process of every node group, the same on every process (it may be collective)
        std::function<std::vector<int32_t>(std::span<const Vec2> centre,
                                           std::span<const double> weight, int64_t round)>
            partition;
    };
    /// Set the load balancing of a distributed run (after distribute()); no effect on a
    /// one-process run. Throws std::invalid_argument for every < 0, imbalance < 1 (or not
    /// finite) or every > 0 without a partition function.
    void set_rebalance(Rebalance r);
    /// What the load balancing did so far in this object (not saved in checkpoints).
    struct RebalanceStats {
        int64_t checks = 0;          ///< imbalance evaluations
        int64_t rebalances = 0;      ///< new partitions adopted
        double last_imbalance = 1;   ///< max / mean estimated work at the last check
        double worst_imbalance = 1;  ///< the largest max / mean of any check
        double planned_after = 1;  ///< max / mean of the group weights under the last new partition
        int64_t last_step = -1;    ///< step after which the last new partition was adopted
    };
    const RebalanceStats& rebalance_stats() const;
    bool output_open() const;
    const std::string& output_dir() const;  ///< "" while output is not open
    int64_t frames_written() const;         ///< output rows/frames so far (also before restart)
    const WrittenFile& last_frame() const;  ///< last VTU frame written by this object
    const WrittenFile& last_checkpoint() const;  ///< last checkpoint written by this object

    // ---- checkpoints -------------------------------------------------------------------------
    /// Write output_dir()/checkpoint.fdck every `seconds` of simulated time, at end_time and when
    /// a run is stopped by request_stop(); 0 = only when stopped. Needs open_output().
    void set_checkpoint_every(Real seconds);
    std::string checkpoint_path() const;  ///< output_dir()/checkpoint.fdck
    /// The complete state plus the run's bookkeeping (energy monitor, output frames), so a
    /// restored run continues bit for bit. Throws SimulationError if it cannot be written.
    void save_checkpoint(const std::string& path);
    /// Continue from a checkpoint of the same model and dt. Throws InputError (key "--restart")
    /// if the file is bad or belongs to another model; the state is unchanged then. The output
    /// files of the interrupted run are continued at the next step: when the output folder is
    /// not the checkpoint's folder, series.pvd refers to the earlier frames next to the
    /// checkpoint and history.csv starts as a copy of the one there (a notice names frames
    /// found in neither folder).
    void restore_checkpoint(const std::string& path);

    // ---- stepping ----------------------------------------------------------------------------
    /// One step of the loop of run(): step, checks, output and checkpoint when due. Evaluates
    /// every energy (the strain energy is otherwise skipped on steps nobody reads it).
    void step();
    /// Step until the time `until` (ceil(until / dt - 1e-9) steps from t = 0; nothing if already
    /// there). After each step: run-time checks (check_run every step, check_state every 16th
    /// step and before anything is written), output and checkpoints when due, then the stop
    /// flag, then `callback` if the step number is a multiple of `every` (>= 1). The final
    /// frame and checkpoint are written at settings().end_time, not at `until`, so run(a);
    /// run(b) writes the same files as run(b). Energies are evaluated on the last step, on
    /// every 16th step and on output and checkpoint steps, and, with callback_reads_energy, on
    /// every step the callback is called (otherwise energy.strain, kinetic, work_gravity and the
    /// joint energies may be stale there; x, v and the other energies are the same either way).
    /// Throws SimulationError (after writing failure.vtu when output is open); the state is
    /// then the failed one.
    RunResult run(Real until, const StepCallback& callback = {}, int64_t every = 1,
                  bool callback_reads_energy = false);
    /// run(settings().end_time, ...)
    RunResult run_to_end(const StepCallback& callback = {}, int64_t every = 1);
    /// Ask a running run() to stop after its current step (writing a checkpoint if output is
    /// open). Async-signal-safe and thread-safe. The flag is cleared when run() returns.
    void request_stop() noexcept;

    /// Number of steps from t = 0 to time t (ceil(t / dt - 1e-9)).
    int64_t steps_to(Real t) const;

    // ---- checks and results --------------------------------------------------------------------
    /// NaN/Inf, inverted elements, runaway velocities (check_state): throws SimulationError.
    void check() const;
    const EnergyMonitor& energy_monitor() const;
    /// Contact pair counts of the last step (issue #16 item 1; read from ContactState, nothing
    /// is counted in the step): the candidates the broad phase handed to the narrow phase and
    /// those in contact (with a force) after it. Smooth and legacy-boundary contact count
    /// (target node, contactor body) pairs, legacy-triangle couples of triangles. All zero
    /// without contact and before the first step.
    struct ContactCounts {
        int64_t candidates = 0;
        int64_t in_contact = 0;
        int64_t broad_phase_runs = 0;   ///< candidate searches since t = 0 (kept by checkpoints)
        bool triangle_couples = false;  ///< legacy-triangle: the counts are triangle couples
    };
    ContactCounts contact_counts() const;
    /// A distributed run (distribute()): what each process owns, computes and exchanges per
    /// step at the current candidate pairs, as the text of partition.csv (one row per process,
    /// parallel/decompose.hpp partition_csv(); `fdem decompose` writes the same rows without
    /// MPI). Collective; "" for a one-process run.
    std::string partition_csv() const;
    /// First warning of the run-time checks ("" = none) and how many steps warned.
    const std::string& first_warning() const;
    int64_t warnings() const;
    /// Called once with the first warning (the CLI prints it); later ones are only counted.
    void set_warning_handler(std::function<void(const std::string&)> handler);
    /// Called with every notice about the output files (e.g. a frame of the run before a
    /// restart that is missing); the default prints it to stderr.
    void set_notice_handler(std::function<void(const std::string&)> handler);
    /// failure.vtu written after the last SimulationError of run() ("" = none, or writing it
    /// failed: failure_write_error() then says why).
    const WrittenFile& failure_file() const;
    const std::string& failure_write_error() const;
    /// fdem::state_hash(state()): equals the `hash` printed by `fdem run` for the same run.
    uint64_t state_hash() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace fdem
