// Recursive coordinate bisection by Zoltan (issue #15; spec parallel-and-python.md D10): the
// partitioner of the distributed run. Built into fdem_mpi with -DFDEM_MPI=ON.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "fdem/math.hpp"
#include "fdem/model.hpp"
#include "parallel/mpi/mpi_comm.hpp"

namespace fdem {

/// The part (0 .. parts - 1) of each of this process's points (x, weight, a global id unique
/// over all processes), from Zoltan's RCB over the points of every process (LB_METHOD = RCB,
/// DETERMINISTIC = 1: the same input on the same process count gives the same parts). Collective.
/// Throws std::runtime_error on every process if Zoltan reports an error on any.
std::vector<int> rcb_parts(const MpiComm& comm, std::span<const Vec2> x,
                           std::span<const double> weight, std::span<const uint64_t> gid,
                           int parts);

/// The process of every node group of m (distributed.hpp node_group_points(): centres and
/// weights) by rcb_parts() with `parts` parts (<= 0: one per process): each process hands
/// Zoltan a contiguous share of the groups, and the parts are all-gathered, so every process
/// returns the same vector. The parts are numbered in the order of their first group (Zoltan's
/// numbering of the same cuts differs with the process count), so one process asked for P
/// parts (`fdem decompose`) gives the owners of P processes. With fewer groups than parts,
/// Zoltan is not called: group g goes to part g (the other parts own nothing). Collective.
std::vector<int32_t> rcb_group_owners(const MpiComm& comm, const Model& m, int parts = 0);

/// The same from given centres and weights of the node groups (the same on every process), e.g.
/// the current positions and estimated work of a running model (distributed.hpp
/// node_group_work(): rebalancing, spec D10). Collective.
std::vector<int32_t> rcb_group_owners(const MpiComm& comm, std::span<const Vec2> centre,
                                      std::span<const double> weight, int parts = 0);

}  // namespace fdem
