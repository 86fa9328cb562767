// Scenario files (TOML): materials, bodies, boundary conditions, time stepping, output, contact.
// Every key is documented in docs/scenario.md.
#pragma once

#include <string>
#include <vector>

#include "fdem/model.hpp"

namespace fdem {

struct OutputSettings {
    Real interval = 0;        ///< simulated time between output frames [s]; 0 = 100 frames
    bool vtu = true;          ///< write VTU frames and a PVD series
    std::string dir = "out";  ///< output folder (relative to the working directory)
};

/// What the [checks] table does when a node passes through the contact layer.
enum class PenetrationCheck { Fail, Warn, Off };

/// Run-time failure checks ([checks] table, docs/scenario.md).
struct CheckSettings {
    Real energy_tolerance = 0.1;  ///< stop when |E_total - E_0| > this x energy scale; 0 = off
    PenetrationCheck penetration = PenetrationCheck::Fail;
};

struct RunSettings {
    Real dt = 0;                 ///< time step [s] actually used
    bool dt_auto = false;        ///< dt = "auto" was given
    Real dt_fraction = 0.5;      ///< safety fraction of the stable limit used by dt = "auto"
    Real end_time = 0;           ///< [s]
    Real stable_dt = 0;          ///< stable limit computed at load [s]
    TriId limiting_tri = kNone;  ///< element setting the stable limit
    OutputSettings output;
    CheckSettings checks;
};

struct Scenario {
    std::string path;  ///< the scenario file (or virtual name)
    Model model;
    RunSettings run;
};

/// Read, validate and build a scenario. Relative mesh paths are resolved against the scenario's
/// folder. Throws InputError (file:line:column, key, value, expectation) on any bad input.
Scenario load_scenario(const std::string& path);

/// Same from a string; base_dir resolves relative mesh paths; name appears in messages.
Scenario load_scenario_from_string(const std::string& text, const std::string& name,
                                   const std::string& base_dir = ".");

}  // namespace fdem
