// What a run measures besides energies: force resultants, support reactions and mean motion of
// every [[body]] entry and every boundary group (bodies.csv), docs/output.md and theory §8.
// Computed by the library from State after each step; the CSV writers are in output.hpp.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "fdem/model.hpp"
#include "fdem/state.hpp"

namespace fdem {

/// Impulses since the last bodies.csv row, one entry per measured set (Resultants): the
/// interval averages are impulse / time (theory eq. 8.4). Kept in checkpoints so a restarted run
/// writes the same averages.
struct IntervalImpulses {
    std::vector<Vec2> contact;   ///< sum over steps of dt_v x contact resultant [N s/m]
    std::vector<Vec2> reaction;  ///< sum over steps of dt_v x support reaction [N s/m]
    Real time = 0;               ///< sum of dt_v over those steps [s]
    /// Zero every impulse (after a row); no allocation.
    void clear() {
        for (Vec2& q : contact)
            q = {};
        for (Vec2& q : reaction)
            q = {};
        time = 0;
    }
};

/// One row of one measured set (bodies.csv, docs/output.md). Forces per unit thickness.
struct SetValues {
    Vec2 u;             ///< mass-weighted mean displacement x - X at t^{n+1} [m]
    Vec2 v;             ///< mass-weighted mean velocity v^{n+1/2} [m/s]
    Vec2 contact;       ///< resultant contact force of the last step (at x^n) [N/m]
    Vec2 contact_avg;   ///< contact impulse since the last row / its time [N/m]
    Vec2 reaction;      ///< support reaction of the last step [N/m] (theory eqs. 8.1-8.2)
    Vec2 reaction_avg;  ///< reaction impulse since the last row / its time [N/m]
};

/// The measured sets of a model and how to sum them. Sets [0, num_entries()) are the scenario's
/// [[body]] entries (Model::group_names: every body an entry produced, e.g. all pieces of
/// pieces = "separate"); the others are the boundary groups, one per distinct
/// BoundaryCondition::name ("body/group"), in order of first appearance, holding the union of
/// the nodes of the supports of that name.
///
/// Every sum runs in a fixed order (set, then node id or support slot), so the numbers are the
/// same for any thread count. The constructor allocates; accumulate() and evaluate() do not.
class Resultants {
public:
    /// The node sets of m; ct (State::topology) tells which nodes can carry a contact force.
    /// A topology rebuilt during the run (new boundary) needs a new Resultants.
    Resultants(const Model& m, const ContactTopology& ct);
    /// The same with the topology of the unbroken bodies (build_topology(m)).
    explicit Resultants(const Model& m);

    int32_t num_sets() const { return static_cast<int32_t>(sets_.size()); }
    int32_t num_entries() const { return num_entries_; }
    /// [[body]] entry name, or "body/group" of a boundary group
    const std::string& name(int32_t set) const { return sets_[static_cast<size_t>(set)].name; }

    /// Zeroed impulses of the right size.
    IntervalImpulses make_impulses() const;

    /// After every step: add the step's contact resultant and reaction of every set, times the
    /// step's velocity increment time dt_v (dt/2 on the first step, theory eq. 5.1), to acc.
    void accumulate(const Model& m, const State& s, IntervalImpulses& acc) const;
    /// The same for the sets k with mine[k] != 0 only (the others' impulses unchanged; acc.time
    /// advances as above): a distributed run shares the sets between its processes.
    void accumulate(const Model& m, const State& s, IntervalImpulses& acc,
                    const std::vector<uint8_t>& mine) const;
    /// The work of accumulate() for one set per step: the nodes and slots it sums over (+ 1).
    int64_t set_cost(int32_t set) const;
    /// The process that sums each set in a run of `procs` processes whose node i is owned by
    /// node_owner[i]: the sets by falling cost (set_cost(), ties by id), each to the process
    /// that owns most of its read_nodes() (ties: the least loaded so far, then the lowest rank),
    /// so that few contact forces have to reach a process that does not own their node; a set
    /// without read nodes to the least loaded process so far (the first of equals).
    std::vector<int32_t> set_ranks(int32_t procs, std::span<const int32_t> node_owner) const;

    /// Values of every set for the state after a step (out: num_sets() entries); the averages
    /// are acc / acc.time (the last instant values where acc.time is 0).
    void evaluate(const Model& m, const State& s, const IntervalImpulses& acc,
                  SetValues* out) const;

    /// The nodes whose f or f_contact forces() reads for one set, ascending (a distributed run
    /// delivers their contact forces to the process that sums the set).
    std::vector<NodeId> read_nodes(int32_t set) const;
    /// The part of read_nodes() whose f_contact forces() reads (the nodes that can carry a
    /// contact force), ascending.
    const std::vector<NodeId>& contact_read_nodes(int32_t set) const {
        return sets_[static_cast<size_t>(set)].force_nodes;
    }
    /// The part of read_nodes() whose f forces() reads (the fixed bodies' nodes a contact or a
    /// load can act on: their reaction, eq. 8.2), ascending.
    const std::vector<NodeId>& force_read_nodes(int32_t set) const {
        return sets_[static_cast<size_t>(set)].fixed_nodes;
    }

    /// Contact resultant and reaction of one set for the last step [N/m].
    void forces(const Model& m, const State& s, int32_t set, Vec2& contact, Vec2& reaction) const;

private:
    /// accumulate() of every set (mine null) or of the sets with mine[k] != 0
    void accumulate_sets(const Model& m, const State& s, IntervalImpulses& acc,
                         const uint8_t* mine) const;
    struct Set {
        std::string name;
        std::vector<NodeId> nodes;         ///< group: its nodes; entry: empty (bodies below)
        std::vector<BodyId> bodies;        ///< entry: its bodies, ascending
        std::vector<NodeId> force_nodes;   ///< nodes that can carry a contact force, ascending
        std::vector<int32_t> slots;        ///< its indices into State::bc_reaction, ascending
        std::vector<BodyId> fixed_bodies;  ///< entry: its fixed bodies (reaction eq. 8.2)
        std::vector<NodeId> fixed_nodes;   ///< nodes of those bodies a contact or load can act on
        Real fixed_mass = 0;               ///< mass of those fixed bodies [kg/m]
    };
    std::vector<Set> sets_;
    int32_t num_entries_ = 0;
};

/// A [[probe]] resolved at load (docs/scenario.md): what probes.csv follows. Node and triangle
/// ids are fixed for the run (the probe moves with the material).
struct ProbeSpec {
    enum class Kind {
        Node,   ///< position = [x, y]: the nearest node, the stress of the triangle holding it
        Group,  ///< body + group: mean over the nodes of a physical group
        Body,   ///< body alone: mean over every node and triangle of the entry
    };
    std::string name;
    Kind kind = Kind::Node;
    Vec2 position;              ///< Node: the given reference position [m]
    std::vector<NodeId> nodes;  ///< the node (Node) or the nodes (Group, Body), ascending
    std::vector<TriId> tris;    ///< the triangle(s) whose stress is reported, ascending
};

/// What a probe reports for a state (probes.csv).
struct ProbeValues {
    Vec2 x;       ///< position x^{n+1} of the node; mass-weighted mean for a group or body [m]
    Vec2 v;       ///< velocity v^{n+1/2}, likewise [m/s]
    Mat2 stress;  ///< Cauchy stress of the triangle; current-area-weighted mean over several [Pa]
};

/// The node nearest to p (reference configuration) among the bodies of [[body]] entry `entry`
/// (every body when entry < 0; the lowest id on a tie), and the triangle of that node's body
/// that contains p, or else the one of the node's triangles whose centroid is nearest to p.
void locate_probe(const Model& m, Vec2 p, int32_t entry, NodeId& node, TriId& tri);

/// The triangles a group probe averages over: those with all three nodes in `nodes` (a surface
/// group), or, when there are none (a point or curve group), those with at least one.
std::vector<TriId> probe_triangles(const Model& m, const std::vector<NodeId>& nodes);

/// Values of one probe for the state after a step (theory eq. 8.6). No allocation.
ProbeValues evaluate_probe(const Model& m, const State& s, const ProbeSpec& p);

}  // namespace fdem
