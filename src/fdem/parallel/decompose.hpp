// What each process of a distributed run owns, computes and exchanges per step (issue #15,
// spec parallel-and-python.md §4.3, milestone M5): counted from the same plan and ghost lists
// a distributed run uses, either by the run itself (each process its own part, Simulation::
// partition_counts()) or for any number of parts in one process (`fdem decompose --parts P`,
// decompose()), so that the counts of a dry run for P = 1024 are those P processes would have.
// Part of libfdem (no MPI).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "fdem/model.hpp"
#include "fdem/state.hpp"

namespace fdem {

struct StepPlan;   // parallel/distributed.hpp
class Resultants;  // fdem/measure.hpp

/// One part (process) of a decomposition, at the current candidate pairs and pairs in contact.
/// Per step a part receives 4 doubles (x, v) of each ghost node in one message from each
/// process in recv_from and sends those of its send_nodes in one message to each of send_to
/// (point to point); sends each of its pairs in contact as a record (kContactRecordBytes) to
/// the other processes that need a node the pair's forces reach, after one message with the
/// record count to and from each of its contact_neighbours (point to point); all-gathers its
/// support reactions; and joins the collectives of the step.
struct PartCounts {
    int32_t part = 0;
    int64_t nodes = 0;               ///< owned nodes (whole groups of kNodeGroup ids)
    int64_t tris_counted = 0;        ///< triangles of the element chunks whose energy it counts
    int64_t tris_run = 0;            ///< triangles it runs on a step without energies (of owned
                                     ///< nodes; counted chunks whole with viscous materials)
    int64_t chunks_run = 0;          ///< element chunks it runs
    int64_t ghost_nodes = 0;         ///< nodes it receives every step
    int64_t send_nodes = 0;          ///< node copies it sends every step (summed over receivers)
    int32_t recv_from = 0;           ///< processes it receives ghosts from (messages in per step)
    int32_t send_to = 0;             ///< processes it sends ghosts to (messages out per step)
    int64_t candidate_pairs = 0;     ///< candidate pairs of its targets (its narrow phase)
    int64_t contact_records = 0;     ///< pairs of its targets in contact
    int64_t support_slots = 0;       ///< supported nodes it owns (reactions it all-gathers)
    int32_t contact_neighbours = 0;  ///< processes it exchanges contact records with
    int64_t contact_sent = 0;        ///< record copies it sends (summed over receivers)
    int64_t contact_received = 0;    ///< records it receives
    int64_t joints_run = 0;          ///< joints it runs that are not broken (JointSubset)
};

/// The counts of plan's process (its ghost lists must be current: after a step of the
/// distributed run, or ghost_receive_lists() plus the send half, as decompose() does).
PartCounts part_counts(const Model& m, const State& s, const StepPlan& plan);

/// The counts of every part of the decomposition `group_owner` (the part of each node group,
/// values in [0, parts)) at the candidate pairs and pairs in contact of s: what
/// Simulation::partition_counts() of a run with `parts` processes and the same group owners
/// reports at the same step. sets: the bodies.csv sets of a run that writes them (each summed by
/// one process, whose nodes' contact forces it then needs: Resultants::set_ranks()), or null.
/// One process; O(parts x (nodes + triangles)) time.
std::vector<PartCounts> decompose(const Model& m, const State& s,
                                  std::span<const int32_t> group_owner, int32_t parts,
                                  const Resultants* sets = nullptr);

/// The owner of each node group for `parts` processes by a named rule that needs no MPI: "ids"
/// (contiguous ranges of about the same number of groups, make_step_plan()'s default) or
/// "random" (a fixed hash of the group id: a test of partition independence, spec T3).
std::vector<int32_t> group_owners(const Model& m, const std::string& rule, int32_t parts);

/// The same rules for a new partition of a running model (rebalancing, spec D10), from every
/// node group's estimated work per step (node_group_work()): "ids" cuts the groups, in id order,
/// into `parts` contiguous ranges of about equal summed weight (a part may get none when one
/// group outweighs a share); "random" is the hash of group_owners() seeded by `round` (the count
/// of partitions so far), so that each rebalance of a test moves the groups anew. Throws
/// std::invalid_argument for another rule or parts < 1.
std::vector<int32_t> group_owners(std::span<const double> weight, const std::string& rule,
                                  int32_t parts, uint64_t round);

/// Estimated cost of one step on one core [ns], by what the step does per item (docs/
/// performance.md, one thread): the element pass and node update per triangle run
/// (BM_StepNoEnergy: 7 ns), a candidate pair the narrow phase rejects (BM_NarrowPhaseSplit:
/// 3-7 ns) and a pair in contact (87-150 ns). The weights of load balancing (spec D10): only
/// their ratios matter. Joints are not weighted (docs/parallel.md "Joints": a weight per joint
/// split a small jointed body between processes and made the step slower, tried 2026-12-03).
inline constexpr double kWorkPerTriangle = 7.0;
inline constexpr double kWorkPerCandidate = 4.0;
inline constexpr double kWorkPerContact = 100.0;

/// A part's estimated work per step [ns]: the weights above times its triangles run (on steps
/// without energies), its candidate pairs and its pairs in contact.
double estimated_work(const PartCounts& c);

/// partition.csv: a header line and one row per part (the fields of PartCounts, then the bytes
/// per step it receives and sends point to point and all-gathers, then joints_run).
std::string partition_csv(std::span<const PartCounts> parts);

/// Bytes per step a part exchanges: ghost bytes in and out (32 per node), contact records in
/// and out (kContactRecordBytes each, point to point) and the bytes of the step's all-gathers
/// it contributes (support reactions).
int64_t ghost_bytes_in(const PartCounts& c);
int64_t ghost_bytes_out(const PartCounts& c);
int64_t contact_bytes_in(const PartCounts& c);
int64_t contact_bytes_out(const PartCounts& c);
int64_t gathered_bytes(const PartCounts& c);

}  // namespace fdem
