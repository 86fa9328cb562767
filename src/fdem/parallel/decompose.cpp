// Counts of a decomposition: see parallel/decompose.hpp.
#include "parallel/decompose.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "contact/contact.hpp"
#include "fdem/measure.hpp"
#include "integrate/node_update.hpp"
#include "parallel/distributed.hpp"

namespace fdem {

namespace {

constexpr int64_t kGhostBytes = 4 * sizeof(double);  // x and v of a node (exchange_ghosts())

// the counts that depend only on the plan's own lists (with ghost lists, the send side is
// what the others need from it: filled by the callers)
PartCounts own_counts(const Model& m, const State& s, const StepPlan& p) {
    PartCounts c;
    c.part = p.rank;
    for (const auto& [b, e] : p.own_runs)
        c.nodes += e - b;
    const ElementSubset& es = p.elements;
    c.chunks_run = static_cast<int64_t>(es.chunks.size());
    for (size_t k = 0; k < es.chunks.size(); ++k) {
        const auto [b, e] = m.element_schedule.chunk_tris[static_cast<size_t>(es.chunks[k])];
        if (es.counts_energy[k]) c.tris_counted += e - b;
        // a step without energies: the runs, and the counted chunks whole with viscous power
        if (es.counts_energy[k] && p.viscous) {
            c.tris_run += e - b;
        } else {
            for (int32_t r = es.run_begin[k]; r < es.run_begin[k + 1]; ++r)
                c.tris_run +=
                    es.runs[static_cast<size_t>(r)][1] - es.runs[static_cast<size_t>(r)][0];
        }
    }
    // the joints it runs (its JointSubset: the chunks it sums whole, the ranges of the others)
    // that are not broken (a broken joint costs a status test)
    if (!m.joints.nodes.empty() && s.joints.status.size() == m.joints.nodes.size()) {
        for_each_joint_range(p.joints.subset, m.joints.num_joints(), [&](int32_t b, int32_t e) {
            for (int32_t j = b; j < e; ++j)
                c.joints_run += s.joints.status[static_cast<size_t>(j)] != JointStatus::Broken;
        });
    }
    const ContactTopology& ct = s.topology;
    const int32_t* owner = p.node_owner.data();
    if (m.contact.algorithm != ContactAlgorithm::None &&
        m.contact.algorithm != ContactAlgorithm::LegacyTriangle) {
        for (const NodeId j : s.contact.cand.node)
            c.candidate_pairs += owner[target_node(ct, j)] == p.rank;
        for (const ActiveContact& a : s.contact.active)
            c.contact_records += owner[target_node(ct, a.node)] == p.rank;
    }
    if (!p.bc_counts.empty()) c.support_slots = p.bc_counts[static_cast<size_t>(p.rank)] / 2;
    const GhostExchange& g = p.ghosts;
    if (g.active) {
        for (int q = 0; q < p.procs; ++q) {
            const int r = g.recv_counts[static_cast<size_t>(q)] / 4;
            c.ghost_nodes += r;
            c.recv_from += r > 0;
        }
    } else if (p.procs > 1) {
        // no ghost lists (joints, baseline A): x and v of every node all-gathered every step
        c.ghost_nodes = m.num_nodes() - c.nodes;
        c.recv_from = p.procs - 1;
        c.send_nodes = c.nodes * (p.procs - 1);
        c.send_to = p.procs - 1;
    }
    return c;
}

}  // namespace

PartCounts part_counts(const Model& m, const State& s, const StepPlan& p) {
    PartCounts c = own_counts(m, s, p);
    // the records of its last step (decompose() counts them from the pairs of its targets in
    // the active list: the test of the two is mpi.decompose_*)
    if (m.contact.algorithm != ContactAlgorithm::None &&
        m.contact.algorithm != ContactAlgorithm::LegacyTriangle) {
        c.contact_records = p.contact.own_records;
        c.contact_sent = p.contact.records_sent;
        c.contact_received = p.contact.records_received;
        c.contact_neighbours = static_cast<int32_t>(p.contact.neighbours.size());
    }
    const GhostExchange& g = p.ghosts;
    if (g.active) {
        for (int q = 0; q < p.procs; ++q) {
            const int n = g.send_counts[static_cast<size_t>(q)] / 4;
            c.send_nodes += n;
            c.send_to += n > 0;
        }
    }
    return c;
}

std::vector<PartCounts> decompose(const Model& m, const State& s,
                                  std::span<const int32_t> group_owner, int32_t parts,
                                  const Resultants* sets) {
    if (parts < 1) throw std::invalid_argument("decompose: parts must be >= 1");
    std::vector<PartCounts> out(static_cast<size_t>(parts));
    // the contact records: the processes that read each set's nodes, and per part the records
    // to each other part and its neighbours (both directions of may_send: P x P marks)
    const bool pairs = m.contact.algorithm != ContactAlgorithm::None &&
                       m.contact.algorithm != ContactAlgorithm::LegacyTriangle;
    const size_t np = static_cast<size_t>(parts);
    std::vector<uint8_t> neighbour(pairs ? np * np : 0, 0);
    std::vector<int64_t> to, received(np, 0);
    std::vector<uint8_t> may_send;
    // what each part receives from each other: (from, to, nodes)
    struct Flow {
        int32_t from, to;
        int64_t nodes;
    };
    std::vector<Flow> flows;
    // a plan per part (O(nodes + triangles) each: ~10^3 parts of 10^7 triangles in minutes),
    // the node owners handed from one to the next
    std::vector<int32_t> node_owner = node_owners(m, parts, group_owner);
    // the bodies.csv sets, each summed by the process that owns most of its nodes (as a run)
    std::vector<std::vector<NodeId>> set_contact_nodes, set_force_nodes;
    std::vector<int32_t> set_rank;
    if (pairs && sets != nullptr && parts > 1) {
        set_rank = sets->set_ranks(parts, node_owner);
        for (int32_t k = 0; k < sets->num_sets(); ++k) {
            set_contact_nodes.push_back(sets->contact_read_nodes(k));
            set_force_nodes.push_back(sets->force_read_nodes(k));
        }
    }
    for (int32_t r = 0; r < parts; ++r) {
        StepPlan p = make_part_plan(m, r, parts, std::move(node_owner));
        if (p.ghosts.active) ghost_receive_lists(m, s, p);
        out[static_cast<size_t>(r)] = own_counts(m, s, p);
        if (pairs) {
            if (!set_rank.empty())
                set_force_readers(p, set_contact_nodes, set_force_nodes, set_rank);
            contact_exchange_counts(m, s, p, to, may_send);
            for (int32_t q = 0; q < parts; ++q) {
                const size_t u = static_cast<size_t>(q), ru = static_cast<size_t>(r);
                out[ru].contact_sent += to[u];
                received[u] += to[u];
                if (may_send[u]) neighbour[ru * np + u] = neighbour[u * np + ru] = 1;
            }
        }
        if (p.ghosts.active) {
            for (int32_t q = 0; q < parts; ++q) {
                const int n = p.ghosts.recv_counts[static_cast<size_t>(q)] / 4;
                if (n > 0) flows.push_back({q, r, n});
            }
        }
        node_owner = std::move(p.node_owner);
    }
    // what a part sends: what the others receive from it (rebuild_ghosts() learns it from an
    // all-gather of the receive lists; a run's counts check this, test mpi.decompose_*)
    for (const Flow& f : flows) {
        PartCounts& c = out[static_cast<size_t>(f.from)];
        c.send_nodes += f.nodes;
        ++c.send_to;
    }
    for (size_t r = 0; r < np && pairs; ++r) {
        out[r].contact_received = received[r];
        for (size_t q = 0; q < np; ++q)
            out[r].contact_neighbours += neighbour[r * np + q];
    }
    return out;
}

std::vector<int32_t> group_owners(const Model& m, const std::string& rule, int32_t parts) {
    const int32_t groups = (m.num_nodes() + kNodeGroup - 1) / kNodeGroup;
    std::vector<int32_t> owner(static_cast<size_t>(groups));
    if (rule == "random") {
        uint64_t h = 0x9e3779b97f4a7c15ull;
        for (int32_t g = 0; g < groups; ++g) {
            h ^= h >> 31;
            h *= 0xbf58476d1ce4e5b9ull;
            h ^= h >> 27;
            owner[static_cast<size_t>(g)] = static_cast<int32_t>(h % static_cast<uint64_t>(parts));
        }
    } else if (rule == "ids") {
        for (int32_t r = 0; r < parts; ++r) {
            for (int32_t g = static_cast<int32_t>(int64_t{groups} * r / parts);
                 g < static_cast<int32_t>(int64_t{groups} * (r + 1) / parts); ++g)
                owner[static_cast<size_t>(g)] = r;
        }
    } else {
        throw std::invalid_argument("group_owners: unknown rule \"" + rule + "\"");
    }
    return owner;
}

std::vector<int32_t> group_owners(std::span<const double> weight, const std::string& rule,
                                  int32_t parts, uint64_t round) {
    if (parts < 1) throw std::invalid_argument("group_owners: parts must be >= 1");
    const size_t groups = weight.size();
    std::vector<int32_t> owner(groups, 0);
    if (rule == "random") {
        uint64_t h = 0x9e3779b97f4a7c15ull + 0x632be59bd9b4e019ull * round;
        for (size_t g = 0; g < groups; ++g) {
            h ^= h >> 31;
            h *= 0xbf58476d1ce4e5b9ull;
            h ^= h >> 27;
            owner[g] = static_cast<int32_t>(h % static_cast<uint64_t>(parts));
        }
    } else if (rule == "ids") {
        // part r takes the groups whose weight midpoint lies in [W r / P, W (r + 1) / P):
        // contiguous, in id order, about W / P each
        double total = 0;
        for (const double w : weight)
            total += w;
        double before = 0;
        for (size_t g = 0; g < groups; ++g) {
            const double mid = before + 0.5 * weight[g];
            before += weight[g];
            const double share = total > 0 ? mid / total : 0.0;
            owner[g] = std::clamp(static_cast<int32_t>(share * parts), int32_t{0}, parts - 1);
        }
    } else {
        throw std::invalid_argument("group_owners: unknown rule \"" + rule + "\"");
    }
    return owner;
}

double estimated_work(const PartCounts& c) {
    return kWorkPerTriangle * static_cast<double>(c.tris_run) +
           kWorkPerCandidate * static_cast<double>(c.candidate_pairs) +
           kWorkPerContact * static_cast<double>(c.contact_records);
}

int64_t ghost_bytes_in(const PartCounts& c) {
    return kGhostBytes * c.ghost_nodes;
}
int64_t ghost_bytes_out(const PartCounts& c) {
    return kGhostBytes * c.send_nodes;
}
int64_t contact_bytes_in(const PartCounts& c) {
    return static_cast<int64_t>(kContactRecordBytes) * c.contact_received;
}
int64_t contact_bytes_out(const PartCounts& c) {
    return static_cast<int64_t>(kContactRecordBytes) * c.contact_sent;
}
int64_t gathered_bytes(const PartCounts& c) {
    return static_cast<int64_t>(2 * sizeof(double)) * c.support_slots;
}

std::string partition_csv(std::span<const PartCounts> parts) {
    std::string out =
        "parts,part,nodes,tris_counted,tris_run,chunks_run,ghost_nodes,send_nodes,recv_from,"
        "send_to,candidate_pairs,contact_records,support_slots,ghost_bytes_in,ghost_bytes_out,"
        "gathered_bytes,contact_neighbours,contact_sent,contact_received,contact_bytes_in,"
        "contact_bytes_out,joints_run\n";
    for (const PartCounts& c : parts) {
        out +=
            fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
                        parts.size(), c.part, c.nodes, c.tris_counted, c.tris_run, c.chunks_run,
                        c.ghost_nodes, c.send_nodes, c.recv_from, c.send_to, c.candidate_pairs,
                        c.contact_records, c.support_slots, ghost_bytes_in(c), ghost_bytes_out(c),
                        gathered_bytes(c), c.contact_neighbours, c.contact_sent, c.contact_received,
                        contact_bytes_in(c), contact_bytes_out(c), c.joints_run);
    }
    return out;
}

}  // namespace fdem
