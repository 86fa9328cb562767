// External loads of the explicit step (docs/theory.md §4.1, eqs. 4.5-4.7): traction and follower
// pressure on boundary edges, point forces on nodes, each scaled by its time function.
// Private to integrate/step.cpp (and its tests).
#pragma once

#include "fdem/model.hpp"

namespace fdem {

/// Force of every load slot at time t on positions x (theory eqs. 4.5, 4.6): per edge of a
/// traction ½ tr L0 and of a pressure ½ p (-d.y, d.x) with d = x_b - x_a the current edge (the
/// force on each of its two nodes), per node of a point force F / (number of nodes). Writes
/// slot_f[load.slot_begin ...]; serial, in load and slot order.
void evaluate_loads(const Model& m, Real t, const Vec2* x, Vec2* slot_f);

/// f[i] += the slot forces on node i, in load and slot order.
void add_load_forces(const Model& m, const Vec2* slot_f, Vec2* f);

/// Power of the slot forces at velocities v: sum over slots of F.(v_a + v_b) for an edge,
/// F.v_i for a node, in load and slot order [W/m] (theory eq. 4.7).
Real load_power(const Model& m, const Vec2* slot_f, const Vec2* v);

}  // namespace fdem
