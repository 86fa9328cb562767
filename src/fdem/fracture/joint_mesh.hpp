// Jointed (discontinuous) meshes: every triangle its own three nodes, a joint on every internal
// edge (spec fracture.md §1.2, §7). Used by the tests and the benchmark now, by the model build
// when fracture is wired into the step.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "fracture/joints.hpp"

namespace fdem {

/// A triangle mesh whose triangle t owns nodes 3t, 3t+1, 3t+2 (same corner order).
struct SplitMesh {
    std::vector<Vec2> x0;
    std::vector<std::array<NodeId, 3>> tris;
    std::vector<NodeId> vertex;  ///< original mesh vertex of every node copy
};

/// Give every triangle of (x, tris) its own nodes.
SplitMesh split_mesh(std::span<const Vec2> x, std::span<const std::array<NodeId, 3>> tris);

/// Append a joint with law index `law` on every edge shared by two triangles of a split mesh
/// (triangles counter-clockwise; `vertex` maps node copies to original vertices). A is the lower
/// triangle id, nodes 0, 1 its edge in its own order (theory eq. 9.1); joints are ordered by
/// (A, edge slot), so the numbering depends only on the mesh. Throws std::invalid_argument for
/// an edge of more than two triangles or two neighbours of opposite orientation. Does not call
/// finalize_joints. With `only` (ascending (smaller, larger) vertex pairs), only the shared
/// edges in that list get a joint (the model build's partially jointed bodies; the two sides of
/// an edge not in the list may share their copies).
void add_edge_joints(Joints& J, std::span<const Vec2> x0,
                     std::span<const std::array<NodeId, 3>> tris, std::span<const NodeId> vertex,
                     int32_t law, const std::vector<std::array<NodeId, 2>>* only = nullptr);

}  // namespace fdem
