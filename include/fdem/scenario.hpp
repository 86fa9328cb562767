// Scenario files (TOML): materials, bodies, boundary conditions, time stepping, output, contact.
// Every key is documented in docs/scenario.md.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "fdem/error.hpp"
#include "fdem/measure.hpp"
#include "fdem/mesh.hpp"
#include "fdem/model.hpp"

namespace fdem {

struct OutputSettings {
    Real interval = 0;   ///< simulated time between output frames [s]; 0 = 100 frames
    bool vtu = true;     ///< write VTU frames and a PVD series
    bool bodies = true;  ///< write bodies.csv (resultants per body entry and boundary group)
    /// distributed runs: one serial .vtu per frame written by process 0, instead of a .pvtu
    /// with one piece per process (no effect on a one-process run)
    bool merge = false;
    std::vector<ProbeSpec> probes;  ///< [[probe]] entries, resolved (probes.csv when not empty)
    std::string dir = "out";        ///< output folder (relative to the working directory)
};

/// What the [checks] table does when a node passes through the contact layer.
enum class PenetrationCheck { Fail, Warn, Off };

/// Run-time failure checks ([checks] table, docs/scenario.md).
struct CheckSettings {
    Real energy_tolerance = 0.1;  ///< stop when |E_total - E_0| > this x energy scale; 0 = off
    PenetrationCheck penetration = PenetrationCheck::Fail;
};

/// Which joints the joint output writes ([fracture] output_joints, spec fracture.md §8).
enum class JointOutput { Damaged, All, None };
/// When fragments.csv is written ([fracture] fragments, spec fracture.md §8).
enum class FragmentOutput { Interval, End };

/// The global [fracture] table (docs/scenario.md). crack_contact = "self" (rule X, theory §9)
/// and contact_targets = "copies" are the only choices implemented, so they are not stored.
struct FractureSettings {
    JointOutput output_joints = JointOutput::Damaged;  ///< softening and broken joints
    FragmentOutput fragments = FragmentOutput::Interval;
};

struct RunSettings {
    Real dt = 0;           ///< time step [s] actually used
    bool dt_auto = false;  ///< dt = "auto" was given
    /// fraction of the stable limit used by dt = "auto"; without dt_fraction in the scenario,
    /// min(0.5 x element limit, 0.2 x contact limit) / stable limit (docs/theory.md §6.9)
    Real dt_fraction = 0.5;
    Real end_time = 0;           ///< [s]
    Real stable_dt = 0;          ///< stable limit computed at load [s]
    TriId limiting_tri = kNone;  ///< element setting the stable limit
    /// largest planned step count ([simulation] max_steps): more is an input error (item 8 of
    /// issue #12: a unit slip in end_time, dt, E, density or penalty plans 10^11+ steps)
    Real max_steps = 1e8;
    /// why dt has its value, for messages: "dt = \"auto\" = 0.5 x the stable limit ... of
    /// triangle 4 ... (youngs_modulus = ..., density = ...)" or "dt = 1e-06 s (given)"
    std::string dt_cause;
    OutputSettings output;
    CheckSettings checks;
    FractureSettings fracture;
};

struct Scenario {
    std::string path;  ///< the scenario file (or virtual name)
    Model model;
    RunSettings run;
    /// legal but surely unintended input (printed by `fdem run` and `fdem check`), each
    /// "file:line:column: warning: ..."
    std::vector<std::string> warnings;
    /// true: the scenario has no [contact] table and contact is the default (smooth with the
    /// documented defaults when two bodies can meet, none otherwise)
    bool contact_default = false;
};

/// Steps `fdem run` takes for run.end_time and run.dt: ceil(end_time / dt - 1e-9), as a double
/// so that an overflow of the integer step counter shows (1e300 s / 1e-5 s).
Real planned_steps(const RunSettings& run);

/// Refuse a run of fewer than one step (end_time < dt) or more than run.max_steps steps: an
/// InputError at `where` (the end_time key, or "--end-time") naming end_time, dt, the step
/// count and what set dt (run.dt_cause).
void check_step_count(const RunSettings& run, const SourceLocation& where, const std::string& key,
                      const std::string& source_line = {});

/// How a scenario's mesh files are read: read_mesh(path, mesh_size, order, limits) when empty.
/// A distributed run passes one that reads on process 0 and broadcasts the mesh
/// (parallel/mesh_broadcast.hpp), so that P processes do not mesh the same .geo P times.
using MeshReader =
    std::function<MeshData(const std::string& path, Real mesh_size, int order, const MeshLimits&)>;

/// Read, validate and build a scenario. Relative mesh paths are resolved against the scenario's
/// folder. Throws InputError (file:line:column, key, value, expectation) on any bad input.
/// read_meshes (optional): reads each mesh file instead of read_mesh.
Scenario load_scenario(const std::string& path, const MeshReader& read_meshes = {});

/// Meshes given in memory, by name (e.g. built from arrays by the Python module's ModelBuilder).
using MeshStore = std::map<std::string, MeshData>;

/// Same from a string; base_dir resolves relative mesh paths; name appears in messages.
/// meshes (optional): a [[body]] whose `mesh` value is a key of it takes that mesh instead of
/// reading a file (as an already meshed .msh: mesh_size and the .geo limits are errors there);
/// other values are file paths as usual.
Scenario load_scenario_from_string(const std::string& text, const std::string& name,
                                   const std::string& base_dir = ".",
                                   const MeshStore* meshes = nullptr,
                                   const MeshReader& read_meshes = {});

}  // namespace fdem
