// A MeshData as bytes and back, bit for bit (doubles copied, not printed): how process 0 of a
// distributed run hands the mesh it read to the other processes (parallel/mesh_broadcast.hpp).
#pragma once

#include <string>
#include <string_view>

#include "fdem/mesh.hpp"

namespace fdem {

/// Every field of mesh in one byte string (native byte order: the processes of a run share it).
std::string mesh_to_bytes(const MeshData& mesh);

/// The mesh mesh_to_bytes wrote. Throws std::runtime_error on a truncated or malformed string.
MeshData mesh_from_bytes(std::string_view bytes);

}  // namespace fdem
