// Sectors (logical vertices) and fragments of a jointed mesh (spec fracture.md §4.1-4.2,
// docs/theory.md §6.15): pure functions of the Model and the joint statuses, called by make_state()
// and by the break processing of the step (spec §7 step 3c). Both forms (full and incremental)
// give the same arrays for the same statuses, whatever the order in which joints broke.
#pragma once

#include <span>
#include <vector>

#include "fdem/fracture.hpp"
#include "fdem/model.hpp"

namespace fdem {

/// node_sector[n] = representative of n's sector: the copies of one original vertex connected
/// around it through joints that are not Broken form one sector, represented by its smallest
/// node id (spec §4.2). A node with no joint is its own sector (node_sector[n] = n). status has
/// one entry per joint of m.joints. Empty m.joints: node_sector is cleared (no fracture).
void compute_node_sectors(const Model& m, std::span<const JointStatus> status,
                          std::vector<NodeId>& node_sector);

/// Update node_sector (the full form's result for the statuses before) after the joints
/// `broken` (ids, any order, duplicates allowed) became Broken in status: only the copies of
/// the vertices of those joints are recomputed. Needs the gather lists (finalize_joints). Gives
/// the full form's result for status (tested). Allocates (a steps-with-breaks-only cost).
void update_node_sectors(const Model& m, std::span<const JointStatus> status,
                         std::span<const int32_t> broken, std::vector<NodeId>& node_sector);

/// tri_fragment[t] = id of t's fragment: the connected component of triangles over shared nodes
/// and joints that are not Broken, identified by its smallest triangle id (spec §4.1). Bodies
/// without fracture are one fragment each (their components are those of the mesh).
void compute_fragments(const Model& m, std::span<const JointStatus> status,
                       std::vector<TriId>& tri_fragment);

/// Update tri_fragment (the full form's result for the statuses before) after the joints
/// `broken` became Broken: the fragments of the bodies holding them are recomputed. Gives the
/// full form's result for status (tested). Allocates.
void update_fragments(const Model& m, std::span<const JointStatus> status,
                      std::span<const int32_t> broken, std::vector<TriId>& tri_fragment);

/// Mass of the largest fragment of the bodies with fracture over the mass of those bodies (the
/// history.csv column largest_fragment_mass_fraction, docs/output.md): fragment masses are sums
/// of the lumped node masses m.node_mass of the fragment's nodes (a node lies in the fragment of
/// its triangles, tri_fragment). 0 when no body has fracture or their mass is 0. Scratch, sized
/// by the caller and overwritten: node_fragment (num_nodes), fragment_mass (num_tris). No
/// allocation; two passes over the fracture bodies' triangles and nodes.
Real largest_fragment_mass_fraction(const Model& m, std::span<const TriId> tri_fragment,
                                    std::span<TriId> node_fragment, std::span<Real> fragment_mass);

}  // namespace fdem
