// Spatial renumbering of nodes and triangles for memory locality (docs/performance.md).
#pragma once

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
bool renumber_spatially(Model& m);

}  // namespace fdem
