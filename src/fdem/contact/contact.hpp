// Contact entry points called by the step pipeline and by finalize_model().
#pragma once

#include "fdem/model.hpp"
#include "fdem/state.hpp"

namespace fdem {

/// Derive the contact topology of m (boundary entities, virtual nodes, contactor
/// sub-triangles, nodal distances, m_bar) from its mesh. Called by finalize_model().
void build_contact_topology(Model& m);

/// Prepare contact state for a fresh run (sizes buffers; no allocation later).
void init_contact_state(const Model& m, State& s);

/// Add contact forces to s.f and s.f_contact for positions s.x and velocities s.v (v^{n-1/2});
/// update pair history, contact energy and contact dissipation in s.energy / s.contact.
void add_contact_forces(const Model& m, State& s);

/// Positions and velocities of the virtual contact nodes (s.contact.xv, vv) from s.x, s.v
/// (spec §4.4-2). add_contact_forces() calls it first; exposed for tests and output.
void update_virtual_nodes(const Model& m, State& s);

/// Largest stable dt [s] imposed by the contact penalty (spec §3.4); +inf without contact.
Real contact_stable_dt(const Model& m);

}  // namespace fdem
