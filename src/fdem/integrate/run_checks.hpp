// Run-level failure checks called by the CLI after every step ([checks] table of the scenario,
// docs/scenario.md): contact penetration beyond the contact layer and energy-balance drift.
// NaN/Inf and inverted elements are check_state() and step() (simulate.hpp).
#pragma once

#include <string>

#include "fdem/checks.hpp"
#include "fdem/model.hpp"
#include "fdem/scenario.hpp"
#include "fdem/state.hpp"

namespace fdem {

/// Update the energy monitor with the energies of the step just done and apply the [checks]:
///   * penetration: a target node left the contact layer inwards this step
///     (ContactState::lost_inside > 0): "fail" throws, "warn" returns a warning text;
///   * energy: |E_total - E_0| > energy_tolerance * scale, where E_0 is the total after the
///     first step and scale the largest of kinetic + strain + contact, |gravity work| and
///     |external work| seen so far and of energy_floor(m) (docs/theory.md §4, eq. 4.9: a model
///     at rest has energies of round-off size), throws. Checked only after steps that
///     evaluated the strain energy (State::need_energy; the CLI sets it every 16 steps).
/// Every SimulationError names step, time, the quantity and a remedy (the stable dt).
/// Returns "" when there is nothing to warn about.
std::string check_run(const Model& m, const State& s, const RunSettings& run, EnergyMonitor& mon);

/// Absolute floor of the energy scale of the check (docs/theory.md eq. 4.9): 1e-12 x (the strain
/// energy of a unit strain of every movable triangle, sum A0 (lambda + 2 mu) / 2, plus every
/// movable mass falling by the diagonal of the model's bounding box, M |g| L) [J/m].
Real energy_floor(const Model& m);

}  // namespace fdem
