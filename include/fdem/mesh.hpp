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
struct MeshData {
    std::string file;  ///< for messages
    std::vector<Vec2> nodes;
    std::vector<std::array<int32_t, 3>> tris;
    std::vector<int32_t> tri_tag;               ///< first physical tag of each triangle (0 = none)
    std::vector<std::array<int32_t, 2>> lines;  ///< 2-node line elements
    std::vector<int32_t> line_tag;
    std::vector<int32_t> points;  ///< 1-node point elements
    std::vector<int32_t> point_tag;
    std::map<std::string, std::pair<int, int>> physical;  ///< name -> (dimension, tag)
    /// Every physical group, sorted by (dim, tag). An element may belong to several groups, so
    /// use this (not the *_tag arrays) to select elements by group.
    std::vector<PhysicalGroup> groups;

    /// Sorted, unique mesh node ids used by the elements of a group.
    std::vector<int32_t> group_nodes(const PhysicalGroup& g) const;
};

/// Read a mesh through the gmsh library: .msh (2.2/4.1, ASCII or binary) or .geo (meshed now
/// with characteristic length mesh_size [m]; <= 0 keeps the .geo's own sizes).
/// Throws InputError naming the file on any failure.
MeshData read_mesh(const std::string& path, Real mesh_size = 0);

/// Structured rectangle [x0, x0+w] x [y0, y0+h] with nx x ny cells, each split into two
/// right triangles (alternating diagonals when alternate = true). Physical groups (dim 1):
/// "bottom", "right", "top", "left"; triangles carry tag 1 named "domain".
MeshData make_rectangle_mesh(Real x0, Real y0, Real w, Real h, int nx, int ny,
                             bool alternate = false);

}  // namespace fdem
