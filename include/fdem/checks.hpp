// Data of the run-time checks ([checks] of the scenario, docs/scenario.md) that lives across
// steps and restarts. The checks themselves are src/fdem/integrate/run_checks.hpp; the
// checkpoint writer (io/) saves this struct, so io/ depends on the checks and not the reverse.
#pragma once

#include "fdem/math.hpp"

namespace fdem {

/// Running energy-balance monitor (the [checks] energy test, integrate/run_checks.hpp), kept in
/// checkpoints so a restarted run measures the drift from the same E_0.
struct EnergyMonitor {
    bool has_reference = false;
    Real e0 = 0;         ///< total energy after the first step [J/m]
    Real scale = 0;      ///< largest energy scale seen so far [J/m]
    Real max_error = 0;  ///< largest |E_total - E_0| so far [J/m]
    /// absolute floor of scale, energy_floor() of the model (run_checks.hpp); derived from the
    /// model at the first check, so not saved in checkpoints (0 = not yet computed) [J/m]
    Real floor = 0;
};

}  // namespace fdem
