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
#include <span>
#include <utility>
#include <vector>

#include "contact/contact.hpp"
#include "element/cst.hpp"
#include "fdem/model.hpp"
#include "fdem/state.hpp"
#include "fracture/joints.hpp"
#include "integrate/node_update.hpp"
#include "parallel/comm.hpp"

namespace fdem {

// kNodeGroup (integrate/node_update.hpp): the unit of node ownership.

/// A set of nodes as ranges [first, second) ascending, with the prefix counts that let threads
/// split it evenly (StepPlan::clear_f, clear_fc).
struct NodeRuns {
    std::vector<std::pair<NodeId, NodeId>> runs;
    std::vector<NodeId> first;  ///< nodes before run k (prefix sums; one more entry: count)
    NodeId count = 0;           ///< the number of nodes
};

/// Ghost nodes of a process (spec D6): the nodes it reads but does not own, whose x and v its
/// owners send after every step instead of an all-gather of every node. They are the nodes of
/// the element chunks it runs (D6.1, "owner computes"), of the joints it runs (JointShare), of
/// the loads (every process evaluates them) and, for every candidate pair of its targets, the
/// target's nodes and the contact nodes of the contactor body (the vertices of its
/// sub-triangles, virtual nodes' parents, and every copy of their sectors where the body is
/// welded: what its sub-triangles, box and welded positions read, D6.2), recomputed on every
/// broad-phase rebuild. Other nodes' x and v are stale on this process between output steps;
/// every reader of them (output, checkpoints, kicks, the broad phase, the lost-contact test,
/// cracks.csv after a step with breaks) all-gathers first. Not active (x and v all-gathered
/// every step, M2a) for baseline A.
struct GhostExchange {
    bool active = false;
    bool dirty = true;                          ///< recompute before the next step
    std::vector<NodeId> static_need;            ///< element and load nodes not owned, ascending
    std::vector<NodeId> recv_nodes;             ///< ghosts by owner, ascending within
    std::vector<int> recv_counts, recv_displs;  ///< per process, in doubles (4 per node)
    std::vector<NodeId> send_nodes;             ///< owned nodes others need, by process
    std::vector<int> send_counts, send_displs;  ///< per process, in doubles (4 per node)
    std::vector<double> send_buf, recv_buf;
    std::vector<uint8_t> node_mark;           ///< scratch of rebuild_ghosts()
    std::vector<char> need_bytes, all_bytes;  ///< scratch of rebuild_ghosts()
};

/// The joints of a distributed run (theory §9; docs/parallel.md "Joints"): each process runs
/// its JointSubset (fracture/joints.hpp); the history of the joints it does not run is stale on
/// it until gather_joint_state() (output, checkpoints, failures, a new plan), except the breaks,
/// which share_breaks() gives every process on the step they happen (the fragments and the
/// contact topology follow every break on every process).
struct JointShare {
    JointSubset subset;
    /// this process's work increments (eq. 9.17) since the last sum over the processes: added
    /// to JointState::total_work_sum on energy steps and by gather_joint_state() (exact sums:
    /// the same bits as the serial running sum)
    mutable ExactSum work;
    mutable std::vector<char> bytes, all;  ///< scratch of the exchanges
};

struct StepPlan {
    int32_t rank = 0;
    int32_t procs = 1;
    std::vector<int32_t> node_owner;  ///< per node (whole groups of kNodeGroup ids)
    /// the owned nodes as ranges [first, second) of whole groups, ascending
    std::vector<std::pair<NodeId, NodeId>> own_runs;
    /// the layout of the all-gather of node values: node ids by (owner, id); process p's part
    /// is [node_displs[p], + node_counts[p]) / 2 (counts in doubles, 2 per node)
    std::vector<NodeId> gather_order;
    std::vector<int> node_counts, node_displs;
    mutable std::vector<double> gather_buffer;  ///< 2 per node
    ElementSubset elements;                     ///< owner computes (element/cst.hpp)
    ContactShare contact;                       ///< the pairs of the owned targets
    std::vector<int32_t> bc_order;              ///< support slots by owner, then slot
    std::vector<int> bc_counts, bc_displs;      ///< per process, in doubles (2 per slot)
    mutable std::vector<double> bc_buffer;      ///< gather buffer (2 per slot)
    mutable GhostExchange ghosts;               ///< neighbour exchange of x and v
    mutable Real max_speed2 = 0;  ///< this step's skin speed max |v|^2 over all processes
    /// the nodes whose f the step clears: those this process adds forces to (owned,
    /// GhostExchange::static_need, the nodes of the bodies.csv sets it sums whose f it reads:
    /// ContactShare::f_readers), with ghosts and smooth or no contact (else every node); the
    /// other nodes' forces are neither written nor read by it (owners' values arrive by
    /// gather_nodes() where they are written out). Made by the first step of the plan and
    /// after set_force_readers() (clear_valid = false)
    mutable NodeRuns clear_f;
    /// the nodes whose f_contact the step clears when ContactState::fc_nodes does not list
    /// them: clear_f's and those of the sets it sums whose f_contact only it reads
    mutable NodeRuns clear_fc;
    mutable bool clear_valid = false;
    bool viscous = false;  ///< a material has viscosity: the viscous power every step
    JointShare joints;     ///< models with joints
};

/// Whether plan's process exchanges ghosts (GhostExchange::active) and the ghosts it always
/// needs (element chunks, loads); make_step_plan() calls it.
void init_ghosts(const Model& m, StepPlan& plan);

/// check_state()'s failure for node i (integrate/step.cpp).
[[noreturn]] void throw_not_finite(const Model& m, const State& s, NodeId i);

/// The ghost lists of plan.rank from the current candidate pairs of s (after a broad-phase
/// rebuild, a restore, or at the first step): each process tells the owners which of their
/// nodes it needs. Collective.
void rebuild_ghosts(const Model& m, const State& s, const StepPlan& plan, const Comm& comm);

/// The receive half of rebuild_ghosts(), local to plan's process: plan.ghosts.recv_nodes,
/// recv_counts and recv_displs from the current candidate pairs of s. `fdem decompose` calls it
/// for every part in one process (parallel/decompose.hpp).
void ghost_receive_lists(const Model& m, const State& s, const StepPlan& plan);

/// x and v of every ghost node from its owner (Comm::exchange). Collective.
void exchange_ghosts(State& s, const StepPlan& plan, const Comm& comm);

/// Every process holds the same replicated scalars (time, energies, contact counters): else a
/// SimulationError on every process (a process read a stale value: a bug). Collective; run
/// on output steps.
void check_agreement(const State& s, const Comm& comm);

/// check_state() of a distributed run: each process checks its own nodes; the first bad node
/// id over all processes is reported by every process with the serial message. Collective.
void check_state_distributed(const Model& m, const State& s, const StepPlan& plan,
                             const Comm& comm);

/// The node groups (kNodeGroup consecutive node ids), the unit of ownership: the centre of
/// each group's reference positions, in units of the groups' mean extent along each axis (so
/// that RCB cuts across the fewest groups), and its weight (the triangles its nodes start, + 1),
/// the input of a partitioner (parallel/mpi/rcb.hpp rcb_group_owners()).
void node_group_points(const Model& m, std::vector<Vec2>& centre, std::vector<double>& weight);

/// The input of a new partition of a running model (rebalancing, spec D10): the centre of each
/// node group at the current positions s.x (in the units of node_group_points()) and its
/// estimated work per step [ns]
/// (decompose.hpp: kWorkPerTriangle per triangle of a movable body its nodes start,
/// kWorkPerCandidate per candidate pair and kWorkPerContact per pair in contact whose target node
/// it holds, + 1). s must be complete (every node's x, the serial candidate list: Simulation
/// gathers them first), so that every process computes the same values.
void node_group_work(const Model& m, const State& s, std::vector<Vec2>& centre,
                     std::vector<double>& weight);

/// The plan of process `rank` of `procs`. group_owner: the process of every node group (any
/// assignment gives the same bits: spec D10); empty: contiguous ranges of about the same
/// number of groups each.
StepPlan make_step_plan(const Model& m, int32_t rank, int32_t procs,
                        std::span<const int32_t> group_owner = {});

/// The process of every node from the process of every node group (values in [0, procs));
/// empty: contiguous ranges of about the same number of groups each. Throws
/// std::invalid_argument for a wrong length or an owner out of range.
std::vector<int32_t> node_owners(const Model& m, int32_t procs,
                                 std::span<const int32_t> group_owner);

/// The part of make_step_plan() that does not need the all-gather layout (no gather_order,
/// node_counts, gather_buffer): the owned runs, the element subset, the ghosts' static need
/// and the support slots of process `rank`, for node_owner[n] in [0, procs) constant on every
/// node group. `fdem decompose` makes one per part (parallel/decompose.hpp).
StepPlan make_part_plan(const Model& m, int32_t rank, int32_t procs,
                        std::vector<int32_t> node_owner);

/// step(m, s) as one of plan.procs processes (integrate/step.cpp). Collective. Afterwards
/// f_contact, the support reactions and the energies are the serial ones on every process; x
/// and v on the nodes the process owns or reads (plan.ghosts; every node when ghosts are not
/// active); f only on the nodes it owns and on the nodes of fixed bodies (no element forces):
/// gather_nodes() and gather_forces() make them complete (Simulation does before output).
void step_distributed(const Model& m, State& s, const StepPlan& plan, const Comm& comm);

/// Every process's values a[i] of the nodes it owns, on every process (an all-gather in the
/// layout plan.gather_order). Collective.
void gather_nodes(Vec2* a, const StepPlan& plan, const Comm& comm);

/// Make s.f complete on every process (an all-gather of the owned parts). Collective.
void gather_forces(State& s, const StepPlan& plan, const Comm& comm);

/// The history of every joint (JointState) on every process, each chunk's from the process that
/// sums it (JointSubset::counts), and JointState::total_work_sum with the work of every process
/// (JointShare::work). Collective; no-op without joints.
void gather_joint_state(const Model& m, State& s, const StepPlan& plan, const Comm& comm);

/// The joints broken by this step (JointState::break_step == s.step) in the chunks each process
/// sums, with their history, on every process. Collective.
void share_breaks(const Model& m, State& s, const StepPlan& plan, const Comm& comm);

}  // namespace fdem
