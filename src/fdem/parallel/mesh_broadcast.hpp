// Meshes of a distributed run read once (issue #15, docs/parallel.md "Running on a cluster"):
// process 0 reads each mesh file of the scenario (Gmsh meshes a .geo there) and broadcasts it, bit
// for bit, to the other processes, instead of every process meshing the same .geo or reading the
// same .msh.
#pragma once

#include "fdem/scenario.hpp"
#include "parallel/comm.hpp"

namespace fdem {

/// The MeshReader a distributed run passes to load_scenario: on process 0 read_mesh, then the
/// mesh (or the InputError it threw) to every process; every process returns the same MeshData
/// or throws the same InputError (same message, so the same exit code everywhere, spec D9).
/// Collective: every process loads the same scenario, so all call it in the same order. comm
/// must outlive the reader.
MeshReader broadcast_mesh_reader(const Comm& comm);

}  // namespace fdem
