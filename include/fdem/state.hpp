// State: everything a time step reads and writes. Model is const during a run; State is not.
#pragma once

#include <cstdint>
#include <vector>

#include "fdem/contact_state.hpp"
#include "fdem/contact_topology.hpp"
#include "fdem/exact_sum.hpp"
#include "fdem/fracture.hpp"
#include "fdem/math.hpp"
#include "fdem/step_timing.hpp"

namespace fdem {

/// Energy bookkeeping per unit thickness [J/m] (docs/theory.md §4, spec §3.5).
/// Balance: kinetic + strain + contact - work_gravity - work_external + dissipated == const.
struct Energy {
    Real time = 0;  ///< t^n at which the energies below were evaluated [s]
    /// sum 1/2 m |v^n|^2 with v^n = (v^{n-1/2} + v^{n+1/2})/2 (stale when State::need_energy
    /// was false)
    Real kinetic = 0;
    Real strain = 0;  ///< sum A0 W(F) (stale when State::need_energy was false)
    /// stored contact potential (path-independent part; stale when State::need_energy was false)
    Real contact = 0;
    /// work done by gravity since t = 0 (stale when State::need_energy was false)
    Real work_gravity = 0;
    Real work_external = 0;  ///< work done by prescribed-velocity supports, kicks and loads
    /// the part of the last step's support and load work that belongs after t^n, booked next step
    Real work_external_pending = 0;
    Real dissipated_viscous = 0;  ///< material damping eta D:D and mass damping
    Real dissipated_contact = 0;  ///< contact damping, hysteresis and friction
    Real joint = 0;     ///< stored energy of the cohesive joints E_joint (theory eq. 9.18)
    Real fracture = 0;  ///< fracture dissipation W_frac = joint work - E_joint (eq. 9.19)
    Real total() const {
        return kinetic + strain + contact - work_gravity - work_external + dissipated_viscous +
               dissipated_contact + joint + fracture;
    }
};

/// Exact running sums of the energies integrated over the steps (theory §4.4): after every step
/// Energy::work_external, dissipated_viscous and dissipated_contact are these, rounded once, so
/// they do not depend on how the terms were grouped (threads now, processes later). Saved in
/// checkpoints (format 9).
struct EnergySums {
    ExactSum work_external;
    ExactSum dissipated_viscous;
    ExactSum dissipated_contact;
};

struct State {
    int64_t step = 0;  ///< number of completed steps
    Real time = 0;     ///< simulated time t^n [s]
    Real dt = 0;       ///< time step [s]

    std::vector<Vec2> x;          ///< positions x^n [m]
    std::vector<Vec2> v;          ///< velocities v^{n-1/2} before a step, v^{n+1/2} after [m/s]
    std::vector<Vec2> f;          ///< total nodal force of the last step [N/m]
    std::vector<Vec2> f_contact;  ///< contact part of f [N/m]
    /// Reaction of each supported node in the last step [N/m] (theory eq. 8.1): one entry per
    /// (BoundaryCondition, node) in the order of Model::bcs and their nodes, the force the support
    /// applied so that the prescribed components of v took their value; 0 for an inactive
    /// support and for nodes of fixed bodies (their reaction: Resultants, measure.hpp)
    std::vector<Vec2> bc_reaction;

    /// Controls (MuJoCo's ctrl): the only inputs a caller may change between steps. One entry per
    /// Model::bcs[k], initialised by make_state() from the Model and saved in checkpoints.
    /// bc_velocity[k]: the velocity support k prescribes from the next step on [m/s] (only the
    /// components the support holds, has_x / has_y, are used). bc_enabled[k]: 1 = active inside
    /// the support's [start, end) window, 0 = switched off (its nodes move freely). A change
    /// books its work like a support switching on or off at a window boundary (theory §4).
    /// Before the first step, the enabled supports active at t = dt/2 also set the prescribed
    /// components of v^0 (make_state() did so with the Model's values), so E_0 contains them; a
    /// support switched off before the first step leaves v^0 as make_state() set it.
    std::vector<Vec2> bc_velocity;
    std::vector<uint8_t> bc_enabled;

    Energy energy;
    EnergySums energy_sums;          ///< exact sums behind Energy's integrated terms (theory §4.4)
    std::vector<Vec2> scratch_bc_v;  ///< v^{n-1/2}, then x^n, of supported nodes (step() scratch)
    /// force of each load slot (Load::slot_begin) at t^n: per edge the force on each of its two
    /// nodes, per node of a point load its share (step() scratch, rewritten every step)
    std::vector<Vec2> scratch_load;
    /// per-chunk partial sums of step()'s reductions, combined in chunk order (determinism)
    std::vector<Real> scratch_sums;
    int32_t next_kick = 0;  ///< index of the next VelocityKick to apply
    /// Evaluate the energies of state (strain: a std::log per triangle; kinetic and gravity
    /// work: ordered sums over the nodes; the stored contact energy: an exact sum over the pairs
    /// in contact; the joints' E_joint and W_frac) in the next step().
    /// When false, those keep the values of the last step that evaluated them (stale); x, v and
    /// the integrated energies (work_external, dissipated_*) are bitwise the same either way.
    /// Callers that read the energies only on output / check steps set it for those steps
    /// (docs/performance.md).
    bool need_energy = true;

    /// Discrete fracture (docs/theory.md §9): per-joint history (damage, status, work), empty
    /// without joints; the fragment of every triangle (the smallest triangle id of its connected
    /// component over unbroken joints and shared nodes, spec fracture.md §4.1; empty without
    /// joints); and per node the representative of its contact vertex (sector, spec §4.2: the
    /// smallest copy id among the copies of one original vertex still connected around it by
    /// unbroken joints; empty without joints). All saved in checkpoints or rebuilt on restore.
    JointState joints;
    std::vector<TriId> tri_fragment;
    std::vector<NodeId> node_sector;

    ContactState contact;  ///< pair history, candidate lists, scratch (contact_state.hpp)
    /// The contact topology (boundary, virtual nodes, sub-triangles, nodal distances, target
    /// scales) of the bodies as they are now: built from the Model by make_state()
    /// (build_topology()), rebuilt for the bodies whose mesh changed (rebuild_topology()). Not
    /// saved in checkpoints: a function of the Model (and, with fracture, of the saved joint
    /// state), rebuilt on restore. docs/architecture.md "The contact topology".
    ContactTopology topology;

    /// Wall time per phase of the steps (step_timing.hpp): read only when timing.on, which no
    /// result depends on; not saved in checkpoints.
    StepTiming timing;
};

}  // namespace fdem
