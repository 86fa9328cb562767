// Mesh input: a raw triangle mesh with physical groups, as read from Gmsh (.msh / .geo)
// or generated in code for tests and benchmarks.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "fdem/math.hpp"

namespace fdem {

/// One physical group of a mesh: a named set of elements of one dimension.
struct PhysicalGroup {
    std::string name;               ///< "" if the file gives the group no name
    int dim = 0;                    ///< 0 = points, 1 = lines, 2 = triangles
    int tag = 0;                    ///< Gmsh physical tag (unique per dimension)
    std::vector<int32_t> elements;  ///< sorted indices into points / lines / tris (by dim)
};

/// A triangle mesh as it comes from a file, before it is split into bodies.
/// Orientation is not yet fixed; node ids are 0-based indices into nodes.
///
/// Second-order meshes (Gmsh 6-node triangles, type 9, and 3-node lines, type 8) keep the
/// corners in tris / lines, so everything that selects elements works unchanged, and add the
/// mid-edge nodes in the parallel arrays tri_mid / line_mid. Gmsh's node order of a 6-node
/// triangle is corners 0, 1, 2 then mid-edge nodes 3 (edge 0-1), 4 (edge 1-2), 5 (edge 2-0):
/// tris[t] = {g0, g1, g2}, tri_mid[t] = {g3, g4, g5}. A mesh is entirely first or second order.
struct MeshData {
    std::string file;  ///< for messages
    std::vector<Vec2> nodes;
    std::vector<std::array<int32_t, 3>> tris;  ///< corner nodes
    /// Mid-edge nodes of 6-node triangles, parallel to tris: tri_mid[t][k] lies on the edge
    /// tris[t][k] - tris[t][(k + 1) % 3]. Empty for a first-order mesh.
    std::vector<std::array<int32_t, 3>> tri_mid;
    std::vector<int32_t> tri_tag;               ///< first physical tag of each triangle (0 = none)
    std::vector<std::array<int32_t, 2>> lines;  ///< end nodes of line elements
    std::vector<int32_t> line_mid;  ///< mid node of 3-node lines, parallel to lines (or empty)
    std::vector<int32_t> line_tag;
    std::vector<int32_t> points;  ///< 1-node point elements
    std::vector<int32_t> point_tag;
    std::map<std::string, std::pair<int, int>> physical;  ///< name -> (dimension, tag)
    /// Every physical group, sorted by (dim, tag). An element may belong to several groups, so
    /// use this (not the *_tag arrays) to select elements by group.
    std::vector<PhysicalGroup> groups;

    /// True for a mesh of 6-node triangles (tri_mid filled).
    bool second_order() const { return !tri_mid.empty(); }

    /// Sorted, unique mesh node ids used by the elements of a group (mid-edge nodes included).
    std::vector<int32_t> group_nodes(const PhysicalGroup& g) const;
};

/// Read a mesh through the gmsh library: .msh (2.2/4.1, ASCII or binary) or .geo (meshed now
/// with characteristic length mesh_size [m]; <= 0 keeps the .geo's own sizes). order = 2 makes
/// a .geo mesh second order (6-node triangles, gmsh::model::mesh::setOrder(2) after generate);
/// a .msh file keeps the order it was written with. Accepted elements: 3- and 6-node
/// triangles, 2- and 3-node lines, points. Throws InputError naming the file on any failure.
MeshData read_mesh(const std::string& path, Real mesh_size = 0, int order = 1);

/// Limits on meshing a .geo ([[body]] max_triangles, mesh_time_limit; docs/scenario.md).
struct MeshLimits {
    /// refuse a .geo whose estimated triangle count 2 A / mesh_size^2 (A: area of the bounding
    /// box of its surfaces) is larger, before Gmsh meshes it (Gmsh 4.8 aborts the process from
    /// its own threads when it runs out of memory)
    Real max_triangles = 2e6;
    /// wall-clock seconds Gmsh may spend on reading and meshing a .geo; beyond, the process
    /// prints an InputError-style message and exits with code 2 (Gmsh cannot be interrupted)
    Real time_limit = 600;
};

/// read_mesh with limits; an estimate above limits.max_triangles is an InputError with key
/// "max_triangles".
MeshData read_mesh(const std::string& path, Real mesh_size, int order, const MeshLimits& limits);

/// Structured rectangle [x0, x0+w] x [y0, y0+h] with nx x ny cells, each split into two
/// right triangles (alternating diagonals when alternate = true). Physical groups (dim 1):
/// "bottom", "right", "top", "left"; triangles carry tag 1 named "domain".
MeshData make_rectangle_mesh(Real x0, Real y0, Real w, Real h, int nx, int ny,
                             bool alternate = false);

/// Second-order version of make_rectangle_mesh: the same 2 nx ny corner triangles (same
/// diagonals), each a 6-node triangle with straight edges and mid-edge nodes at the edge
/// midpoints (tri_mid filled; boundary lines are 3-node lines with line_mid). The corner nodes
/// keep the ids of make_rectangle_mesh (j (nx + 1) + i); mid-edge nodes follow.
MeshData make_rectangle_mesh_order2(Real x0, Real y0, Real w, Real h, int nx, int ny,
                                    bool alternate = false);

}  // namespace fdem
