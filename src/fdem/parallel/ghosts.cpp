// Ghost nodes of a distributed run (spec parallel-and-python.md D6; parallel/distributed.hpp
// GhostExchange): which nodes a process reads but does not own, who sends them, and the
// exchange of their x and v after every step.
#include <algorithm>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "fdem/error.hpp"
#include "parallel/distributed.hpp"

namespace fdem {

namespace {

// the nodes of the triangles the process runs (the runs of its chunks; the chunks it counts
// whole, as on energy steps) and of every load, not owned (ascending)
std::vector<NodeId> static_need(const Model& m, const StepPlan& p) {
    std::vector<uint8_t> mark(static_cast<size_t>(m.num_nodes()), 0);
    const ElementSubset& es = p.elements;
    auto mark_tris = [&](TriId b, TriId e) {
        for (TriId t = b; t < e; ++t) {
            for (const NodeId i : m.tri_nodes[static_cast<size_t>(t)])
                mark[static_cast<size_t>(i)] = 1;
        }
    };
    for (size_t k = 0; k < es.chunks.size(); ++k) {
        if (es.counts_energy[k]) {
            const auto [b, e] = m.element_schedule.chunk_tris[static_cast<size_t>(es.chunks[k])];
            mark_tris(b, e);
        } else {
            for (int32_t r = es.run_begin[k]; r < es.run_begin[k + 1]; ++r)
                mark_tris(es.runs[static_cast<size_t>(r)][0], es.runs[static_cast<size_t>(r)][1]);
        }
    }
    // the joints it runs (its JointSubset: the chunks it sums whole, the ranges of the others)
    auto mark_joints = [&](int32_t b, int32_t e) {
        for (int32_t j = b; j < e; ++j) {
            for (const NodeId i : m.joints.nodes[static_cast<size_t>(j)])
                mark[static_cast<size_t>(i)] = 1;
        }
    };
    for_each_joint_range(p.joints.subset, m.joints.num_joints(), mark_joints);
    for (const Load& ld : m.loads) {  // evaluated by every process (x, v of its nodes)
        for (const NodeId i : ld.nodes)
            mark[static_cast<size_t>(i)] = 1;
        for (const auto& e : ld.edges) {
            mark[static_cast<size_t>(e[0])] = 1;
            mark[static_cast<size_t>(e[1])] = 1;
        }
    }
    std::vector<NodeId> need;
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        if (mark[static_cast<size_t>(i)] && p.node_owner[static_cast<size_t>(i)] != p.rank)
            need.push_back(i);
    }
    return need;
}

}  // namespace

void init_ghosts(const Model& m, StepPlan& p) {
    GhostExchange& g = p.ghosts;
    // baseline A pairs every triangle of every body: it reads all nodes (x, v all-gathered)
    g.active = p.procs > 1 && m.contact.algorithm != ContactAlgorithm::LegacyTriangle;
    g.dirty = true;
    if (!g.active) return;
    g.static_need = static_need(m, p);
    g.node_mark.assign(static_cast<size_t>(m.num_nodes()), 0);
    g.recv_counts.assign(static_cast<size_t>(p.procs), 0);
    g.recv_displs.assign(static_cast<size_t>(p.procs), 0);
    g.send_counts.assign(static_cast<size_t>(p.procs), 0);
    g.send_displs.assign(static_cast<size_t>(p.procs), 0);
}

void ghost_receive_lists(const Model& m, const State& s, const StepPlan& p) {
    GhostExchange& g = p.ghosts;
    const ContactTopology& ct = s.topology;
    const ContactState& cs = s.contact;
    const int32_t* owner = p.node_owner.data();
    std::vector<uint8_t>& mark = g.node_mark;
    std::fill(mark.begin(), mark.end(), uint8_t{0});
    for (const NodeId i : g.static_need)
        mark[static_cast<size_t>(i)] = 1;
    // the candidate pairs of this process's targets (spec D6.2): the target's nodes, and every
    // node of the contactor (its sub-triangles, the parents of its virtual nodes, its box)
    const size_t npairs = cs.cand.node.size();
    for (size_t pr = 0; pr < npairs; ++pr) {
        const NodeId j = cs.cand.node[pr];
        if (j < ct.num_real_nodes || owner[target_node(ct, j)] != p.rank) continue;
        // an edge target: its second end node too
        mark[static_cast<size_t>(
            ct.boundary_edges[static_cast<size_t>(j - ct.edge_target_base)][1])] = 1;
    }
    // a contactor's contact nodes (ContactTopology::body_cnode: the vertices of its
    // sub-triangles, real ones and virtual ones by their parents) and, where the contactor is
    // welded (theory eq. 6.23), every copy of their sectors: what the narrow phase, the body box
    // and the welded positions and velocities read of it. Only these: a jointed specimen is the
    // contactor of the platens and of itself (rule X), and its inner nodes are never read there
    const bool listed = ct.lists_contact_nodes();
    auto mark_welded = [&](NodeId i) {
        mark[static_cast<size_t>(i)] = 1;
        if (!ct.welded()) return;
        const int32_t grp = ct.weld_group[static_cast<size_t>(i)];
        if (grp < 0) return;
        for (int32_t k = ct.weld_group_begin[static_cast<size_t>(grp)];
             k < ct.weld_group_begin[static_cast<size_t>(grp) + 1]; ++k)
            mark[static_cast<size_t>(ct.weld_copy[static_cast<size_t>(k)])] = 1;
    };
    for (const BodyId b : contactor_bodies(m, s, p)) {
        const Body& body = m.bodies[static_cast<size_t>(b)];
        // a fixed body's nodes never move (x = x0, v = 0 from the start or a restore, on every
        // process): nothing to send (a wall ring around a raster would otherwise reach every
        // process along the walls whole)
        if (body.fixed) continue;
        if (!listed) {  // (a topology without the lists: every node of the body)
            std::fill(mark.begin() + body.node_begin, mark.begin() + body.node_end, uint8_t{1});
            continue;
        }
        for (int32_t e = ct.body_cnode_begin[static_cast<size_t>(b)];
             e < ct.body_cnode_begin[static_cast<size_t>(b) + 1]; ++e) {
            const NodeId i = ct.body_cnode[static_cast<size_t>(e)];
            if (i < ct.num_real_nodes) {
                mark_welded(i);
            } else {
                for (const NodeId q : ct.virt_parent[static_cast<size_t>(i - ct.num_real_nodes)])
                    mark_welded(q);
            }
        }
    }
    // the ghosts, by owner then id, and their count per owner (in doubles, 4 per node)
    const int P = p.procs;
    std::fill(g.recv_counts.begin(), g.recv_counts.end(), 0);
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        if (mark[static_cast<size_t>(i)] && owner[i] != p.rank)
            g.recv_counts[static_cast<size_t>(owner[i])] += 4;
    }
    int total = 0;
    for (int q = 0; q < P; ++q) {
        g.recv_displs[static_cast<size_t>(q)] = total;
        total += g.recv_counts[static_cast<size_t>(q)];
    }
    g.recv_nodes.resize(static_cast<size_t>(total / 4));
    {
        std::vector<int>& at = g.send_counts;  // (scratch: fill positions per owner, in nodes)
        for (int q = 0; q < P; ++q)
            at[static_cast<size_t>(q)] = g.recv_displs[static_cast<size_t>(q)] / 4;
        for (NodeId i = 0; i < m.num_nodes(); ++i) {
            if (mark[static_cast<size_t>(i)] && owner[i] != p.rank)
                g.recv_nodes[static_cast<size_t>(at[static_cast<size_t>(owner[i])]++)] = i;
        }
        std::fill(at.begin(), at.end(), 0);
    }
}

void rebuild_ghosts(const Model& m, const State& s, const StepPlan& p, const Comm& comm) {
    GhostExchange& g = p.ghosts;
    const int32_t* owner = p.node_owner.data();
    const int P = p.procs;
    // the list of all ghosts, prefixed by its length, to every process, which picks the nodes
    // it owns: its send list
    ghost_receive_lists(m, s, p);
    const int32_t n = static_cast<int32_t>(g.recv_nodes.size());
    g.need_bytes.resize(sizeof(int32_t) * (1 + static_cast<size_t>(n)));
    std::memcpy(g.need_bytes.data(), &n, sizeof n);
    if (n > 0) std::memcpy(g.need_bytes.data() + sizeof n, g.recv_nodes.data(), sizeof n * n);
    comm.allgather_bytes(g.need_bytes, g.all_bytes);
    g.send_nodes.clear();
    const char* r = g.all_bytes.data();
    for (int q = 0; q < P; ++q) {
        int32_t nq = 0;
        std::memcpy(&nq, r, sizeof nq);
        r += sizeof nq;
        const size_t before = g.send_nodes.size();
        g.send_displs[static_cast<size_t>(q)] = 4 * static_cast<int>(before);
        for (int32_t k = 0; k < nq; ++k) {
            NodeId i = 0;
            std::memcpy(&i, r + sizeof i * static_cast<size_t>(k), sizeof i);
            if (q != p.rank && owner[i] == p.rank) g.send_nodes.push_back(i);
        }
        r += sizeof(int32_t) * static_cast<size_t>(nq);
        g.send_counts[static_cast<size_t>(q)] = 4 * static_cast<int>(g.send_nodes.size() - before);
    }
    g.send_buf.resize(4 * g.send_nodes.size());
    g.recv_buf.resize(4 * g.recv_nodes.size());
    g.dirty = false;
}

void exchange_ghosts(State& s, const StepPlan& p, const Comm& comm) {
    GhostExchange& g = p.ghosts;
    double* sb = g.send_buf.data();
    for (size_t k = 0; k < g.send_nodes.size(); ++k) {
        const size_t i = static_cast<size_t>(g.send_nodes[k]);
        sb[4 * k] = s.x[i].x;
        sb[4 * k + 1] = s.x[i].y;
        sb[4 * k + 2] = s.v[i].x;
        sb[4 * k + 3] = s.v[i].y;
    }
    comm.exchange(sb, g.send_counts, g.send_displs, g.recv_buf.data(), g.recv_counts,
                  g.recv_displs);
    const double* rb = g.recv_buf.data();
    for (size_t k = 0; k < g.recv_nodes.size(); ++k) {
        const size_t i = static_cast<size_t>(g.recv_nodes[k]);
        s.x[i] = {rb[4 * k], rb[4 * k + 1]};
        s.v[i] = {rb[4 * k + 2], rb[4 * k + 3]};
    }
}

void check_state_distributed(const Model& m, const State& s, const StepPlan& p, const Comm& comm) {
    // the first node with a non-finite x or v, over the processes' own nodes: the node the
    // serial check_state() names
    NodeId bad = m.num_nodes();
    for (const auto& [b, e] : p.own_runs) {
        for (NodeId i = b; i < e && i < bad; ++i) {
            if (!std::isfinite(s.x[i].x) || !std::isfinite(s.x[i].y) || !std::isfinite(s.v[i].x) ||
                !std::isfinite(s.v[i].y)) {
                bad = i;
                break;
            }
        }
    }
    bad = static_cast<NodeId>(comm.min(static_cast<double>(bad)));
    if (bad < m.num_nodes()) throw_not_finite(m, s, bad);
}

void check_agreement(const State& s, const Comm& comm) {
    // the replicated scalars of the step (energies, contact counters): every process computes
    // them alike from the values it holds, so a difference means a process read a stale value
    const Energy& e = s.energy;
    const ContactState& c = s.contact;
    constexpr int kN = 13;
    const char* names[kN] = {"time",
                             "kinetic energy",
                             "strain energy",
                             "contact energy",
                             "work of gravity",
                             "external work",
                             "viscous dissipation",
                             "contact dissipation",
                             "joint energy",
                             "fracture work",
                             "active contacts",
                             "contact rebuilds",
                             "lost contacts"};
    double lo[kN] = {s.time,
                     e.kinetic,
                     e.strain,
                     e.contact,
                     e.work_gravity,
                     e.work_external,
                     e.dissipated_viscous,
                     e.dissipated_contact,
                     e.joint,
                     e.fracture,
                     static_cast<double>(c.active_contacts),
                     static_cast<double>(c.rebuilds),
                     static_cast<double>(c.total_lost_inside)};
    double hi[kN];
    for (int k = 0; k < kN; ++k)
        hi[k] = -lo[k];
    comm.min(lo, kN);
    comm.min(hi, kN);  // -max
    for (int k = 0; k < kN; ++k) {
        // (NaN on a process makes min and max disagree with its value; equal NaNs pass)
        if (lo[k] != -hi[k] && !(std::isnan(lo[k]) && std::isnan(hi[k]))) {
            throw SimulationError(
                s.step, s.time, "distributed run",
                fmt::format("the processes disagree on the {} ({:.17g} to {:.17g}): a process "
                            "read a value it does not hold; this is a bug of fdem, please "
                            "report it with the scenario and the process count",
                            names[k], lo[k], -hi[k]));
        }
    }
}

}  // namespace fdem
