// Discrete fracture in the time step (docs/theory.md §9, spec fracture.md §7 steps 3b-3c): the
// initial joint state of make_state() and the break processing after the joint kernel.
#pragma once

#include "fdem/model.hpp"
#include "fdem/state.hpp"

namespace fdem {

/// make_state() part: State::joints from the Model (make_joint_state), the pre-broken joints
/// marked broken with zero work (Model::prebroken_joints), node_sector and tri_fragment. Leaves
/// everything empty for a model without joints. Call before the contact topology is built.
void init_fracture_state(const Model& m, State& s);

/// Step 3c (spec fracture.md §7): after joints broke in this step (JointState::break_step ==
/// s.step), recompute node_sector and tri_fragment, rebuild the contact topology of the bodies
/// of the broken joints (rebuild_topology) and make the broad phase run again. Allocates; runs
/// only on steps with breaks (docs/architecture.md: the cost is O(nodes + joints) per such step
/// plus the rebuild of the dirty bodies' topology).
void process_breaks(const Model& m, State& s);

/// node_sector, tri_fragment and the contact topology from the saved joint status (restore from
/// a checkpoint: none of them is saved).
void rebuild_fracture_views(const Model& m, State& s);

}  // namespace fdem
