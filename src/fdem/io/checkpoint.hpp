// Binary checkpoints of a run: the complete State (including the contact pair history and
// candidate lists) plus the CLI's run bookkeeping, so a restarted run continues bit for bit.
//
// File layout (native little-endian; docs/output.md "Checkpoints"):
//   "FDEMCKPT" | u32 format version | u32 endian marker 0x01020304 | string fdem version |
//   u64 model hash | payload ... | u64 FNV-1a hash of every byte before it
// Strings and arrays are a u64 count followed by the elements; structs are written field by
// field (never raw, so padding bytes never reach the file and equal states give equal files).
//
// What is saved: every State field that carries information from one step to the next: step,
// time, dt, x, v, f, f_contact, energy, next_kick, the controls (bc_velocity, bc_enabled) and the
// ContactState (candidates, pair history, broad-phase skin, baseline A couples with their sliding
// history). scratch_bc_v, bc_reaction
// (rewritten by every step before bodies.csv reads it), scratch_sums,
// ContactState::pair_out and the baseline A grid/result scratch are rewritten before they are
// read in every step and are not saved. tests/unit/io/checkpoint_test.cpp pins the struct
// sizes, so a new field in State or ContactState fails a test until it is handled here.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "fdem/checks.hpp"
#include "fdem/measure.hpp"
#include "fdem/model.hpp"
#include "fdem/state.hpp"

namespace fdem {

/// Version of the checkpoint layout; bump it whenever the payload changes.
constexpr uint32_t kCheckpointFormat = 13;  // 2: baseline A couples (ContactState::legacy)
                                            // 3: Energy::work_external_pending
                                            // 4: PairHistory::f_damp
                                            // 5: RunProgress::impulses (bodies.csv)
                                            // 6: State::bc_velocity, bc_enabled (controls)
                                            // 7: Energy::joint, fracture (issue #14)
                                            // 8: JointState history (State::joints)
                                            // 9: PairHistory::d0 (birth depth, eq. 9.25)
                                            // 11: State::energy_sums, JointState::
                                            //     total_work_sum (exact sums, theory §4.4)
                                            // 10: PairHistory::sub (eq. 9.27)
                                            // 12: JointState::dn_max, ds_max, JointLaw::mixed
                                            //     (MixedMode::Proportional, theory eq. 9.30)
                                            // 13: JointState::an_min, as_min (eq. 9.32)

/// CLI bookkeeping that must survive a restart so output continues where it stopped.
struct RunProgress {
    int64_t frame = 0;     ///< number of output frames written
    Real next_output = 0;  ///< simulated time of the next output frame [s]
    EnergyMonitor energy;
    std::vector<std::pair<Real, std::string>> frames;  ///< (time, file) of the PVD series
    IntervalImpulses impulses;  ///< bodies.csv: impulses since its last row (empty: no bodies.csv)
};

/// Hash of everything in the built Model that affects the physics (geometry, masses,
/// materials, boundary conditions, kicks, damping, gravity, contact parameters), of the contact
/// topology t it was run with (State::topology) and of dt. End time and output settings are not
/// included: a restart may change them.
uint64_t model_hash(const Model& m, const ContactTopology& t, Real dt);

/// Write a checkpoint atomically (temporary file, then rename). Throws SimulationError naming
/// the file if it cannot be written.
void write_checkpoint(const std::string& path, const Model& m, const State& s,
                      const RunProgress& progress);

/// Read a checkpoint into s (which must come from make_state(m, dt)) and progress. Throws
/// InputError (key "--restart") if the file is missing, truncated, corrupt, of another format
/// or fdem version, or was written for a different model or dt.
void read_checkpoint(const std::string& path, const Model& m, State& s, RunProgress& progress);

}  // namespace fdem
