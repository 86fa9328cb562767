// Spatial renumbering of nodes and triangles for memory locality (docs/performance.md).
#pragma once

#include <cstdint>
#include <vector>

#include "fdem/model.hpp"

namespace fdem {

/// Bodies with fewer triangles are left as they are: they fit in cache anyway, and small test
/// meshes keep the ids their authors drew.
inline constexpr TriId kRenumberMinTris = 4096;

/// Renumber the triangles of each body (with at least kRenumberMinTris triangles) along a Morton
/// (Z-order) curve through their centroids, and its nodes in order of first use by the sorted
/// triangles. Body ranges stay contiguous and in order; boundary-condition node lists are
/// remapped (and re-sorted). Call before any derived per-node or per-triangle array exists
/// (finalize_model() calls it first). Returns true if some body was renumbered.
/// node_new (if not null) receives old node id -> new node id (the identity when nothing
/// changed), for node lists kept outside the Model (the scenario reader's mesh-node maps).
bool renumber_spatially(Model& m, std::vector<int32_t>* node_new = nullptr);

/// finalize_model() that also gives the renumbering of renumber_spatially() (node_new).
void finalize_model(Model& m, std::vector<int32_t>& node_new);

}  // namespace fdem
