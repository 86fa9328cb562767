// The time step (docs/architecture.md): a pipeline of free functions over Model and State.
#pragma once

#include <cstdint>

#include "fdem/model.hpp"
#include "fdem/state.hpp"

namespace fdem {

/// A fresh state at t = 0: x = X, v = initial velocities, contact history empty, the support
/// controls (State::bc_velocity, bc_enabled) equal to the Model's.
State make_state(const Model& m, Real dt);

/// Advance one central-difference step (docs/theory.md §5):
///   forces f^n(x^n, v^{n-1/2}) -> v^{n+1/2} -> x^{n+1}; updates the energy accumulators.
void step(const Model& m, State& s);

/// Stop on NaN/Inf, inverted triangles or runaway velocity: throws SimulationError naming
/// step, time, entity and a remedy.
void check_state(const Model& m, const State& s);

/// FNV-1a over the bytes of x, v and the energies: equal hashes mean bitwise equal states. The
/// hash `fdem run` prints at the end of a run (`--print-hash`), so a program stepping the same
/// scenario through this API can compare its result with the CLI's.
uint64_t state_hash(const State& s);

}  // namespace fdem
