// One process's share of a time step in a distributed run (issue #15, docs/parallel.md "M2a").
// Part of libfdem (no MPI): the communication goes through Comm (parallel/comm.hpp).
//
// M2a keeps the whole State on every process (replicated data): each process updates the nodes
// it owns (whole groups of kNodeGroup consecutive node ids) and computes the element forces of
// those nodes (owner computes, element/cst.hpp ElementSubset); loads, kicks, joints and contact
// are computed by every process alike; after the node update the processes exchange the owned
// parts of x, v, f, f_contact and the support reactions, so every process holds the serial State
// again. Energies summed over owned parts go through exact sums (theory §4.4). The result is
// bitwise the serial step's for any process count.
#pragma once

#include <cstdint>
#include <vector>

#include "contact/contact.hpp"
#include "element/cst.hpp"
#include "fdem/model.hpp"
#include "fdem/state.hpp"
#include "integrate/node_update.hpp"
#include "parallel/comm.hpp"

namespace fdem {

// kNodeGroup (integrate/node_update.hpp): the unit of node ownership.

struct StepPlan {
    int32_t rank = 0;
    int32_t procs = 1;
    NodeId node_begin = 0;  ///< owned nodes [node_begin, node_end): whole groups
    NodeId node_end = 0;
    std::vector<int32_t> node_owner;            ///< per node
    std::vector<int> node_counts, node_displs;  ///< per process, in doubles (2 per node)
    ElementSubset elements;                     ///< owner computes (element/cst.hpp)
    ContactShare contact;                       ///< the pairs of the owned targets
    std::vector<int32_t> bc_order;              ///< support slots by owner, then slot
    std::vector<int> bc_counts, bc_displs;      ///< per process, in doubles (2 per slot)
    mutable std::vector<double> bc_buffer;      ///< gather buffer (2 per slot)
};

/// The plan of process `rank` of `procs`: node groups split into contiguous ranges with about
/// the same number of element triangles each (the node update is cheaper than the elements).
StepPlan make_step_plan(const Model& m, int32_t rank, int32_t procs);

/// step(m, s) as one of plan.procs processes (integrate/step.cpp). Collective. Afterwards x, v,
/// f_contact and the support reactions are the serial ones on every process; f is complete
/// only on the nodes the process owns, on the nodes of fixed bodies (no element forces), and
/// everywhere after a step with s.need_energy (output steps): call gather_forces() before
/// reading it on other steps.
void step_distributed(const Model& m, State& s, const StepPlan& plan, const Comm& comm);

/// Make s.f complete on every process (an all-gather of the owned parts). Collective.
void gather_forces(State& s, const StepPlan& plan, const Comm& comm);

}  // namespace fdem
