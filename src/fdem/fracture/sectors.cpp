// Sectors and fragments of a jointed mesh (spec fracture.md §4.1-4.2, docs/theory.md §6.15).
#include "fracture/sectors.hpp"

#include <algorithm>
#include <numeric>
#include <unordered_set>

#include "fdem/assert.hpp"

namespace fdem {

namespace {

// union-find whose root is always the smallest id of its set (the representative rule of both
// sectors and fragments), with path halving
struct MinUnionFind {
    std::vector<int32_t> parent;
    explicit MinUnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
    int32_t find(int32_t i) {
        while (parent[static_cast<size_t>(i)] != i) {
            const int32_t g = parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
            parent[static_cast<size_t>(i)] = g;
            i = g;
        }
        return i;
    }
    void unite(int32_t a, int32_t b) {
        a = find(a);
        b = find(b);
        if (a == b) return;
        if (a < b) {
            parent[static_cast<size_t>(b)] = a;
        } else {
            parent[static_cast<size_t>(a)] = b;
        }
    }
};

bool intact(std::span<const JointStatus> status, int32_t j) {
    return status[static_cast<size_t>(j)] != JointStatus::Broken;
}

// joint entries 4 j + k of node n (gather lists of finalize_joints), empty if n has no joint
std::span<const int32_t> node_entries(const Joints& J, NodeId n) {
    const auto it = std::lower_bound(J.gather_node.begin(), J.gather_node.end(), n);
    if (it == J.gather_node.end() || *it != n) return {};
    const size_t g = static_cast<size_t>(it - J.gather_node.begin());
    return std::span<const int32_t>(J.gather_entry.data() + J.gather_begin[g],
                                    static_cast<size_t>(J.gather_begin[g + 1] - J.gather_begin[g]));
}

// the node facing local node k of joint j: 0 faces 3, 1 faces 2 (theory eq. 9.1)
NodeId partner(const Joints& J, int32_t entry) {
    return J.nodes[static_cast<size_t>(entry / 4)][static_cast<size_t>(3 - entry % 4)];
}

}  // namespace

void compute_node_sectors(const Model& m, std::span<const JointStatus> status,
                          std::vector<NodeId>& node_sector) {
    const Joints& J = m.joints;
    if (J.nodes.empty()) {
        node_sector.clear();
        return;
    }
    FDEM_ASSERT(status.size() == J.nodes.size(), "compute_node_sectors: one status per joint");

    // the copies facing each other across an unbroken joint are one sector
    MinUnionFind uf(static_cast<size_t>(m.num_nodes()));
    for (int32_t j = 0; j < J.num_joints(); ++j) {
        if (!intact(status, j)) continue;
        const auto& n = J.nodes[static_cast<size_t>(j)];
        uf.unite(n[0], n[3]);
        uf.unite(n[1], n[2]);
    }
    node_sector.resize(static_cast<size_t>(m.num_nodes()));
    for (NodeId i = 0; i < m.num_nodes(); ++i)
        node_sector[static_cast<size_t>(i)] = uf.find(i);
}

void update_node_sectors(const Model& m, std::span<const JointStatus> status,
                         std::span<const int32_t> broken, std::vector<NodeId>& node_sector) {
    const Joints& J = m.joints;
    if (J.nodes.empty() || broken.empty()) return;
    FDEM_ASSERT(node_sector.size() == static_cast<size_t>(m.num_nodes()),
                "update_node_sectors: node_sector is not the full form's array");
    FDEM_ASSERT(J.gather_begin.size() == J.gather_node.size() + 1,
                "update_node_sectors: joints not finalized (finalize_joints)");
    std::unordered_set<NodeId> done;
    std::vector<NodeId> fan, queue;
    std::vector<uint8_t> assigned;
    for (const int32_t j : broken) {
        for (const NodeId start : J.nodes[static_cast<size_t>(j)]) {
            if (done.count(start) != 0) continue;

            // 1. every copy of start's vertex: the copies linked by any joint, broken or not
            //    (around a vertex the fan is cut only at jointed edges, all of which have joints)
            fan.assign(1, start);
            done.insert(start);
            for (size_t q = 0; q < fan.size(); ++q) {
                for (const int32_t e : node_entries(J, fan[q])) {
                    const NodeId p = partner(J, e);
                    if (done.insert(p).second) fan.push_back(p);
                }
            }
            std::sort(fan.begin(), fan.end());

            // 2. the sectors among them: runs linked by unbroken joints; visiting the copies
            //    in ascending order, the first unassigned one is its run's smallest id
            assigned.assign(fan.size(), 0);
            auto slot = [&](NodeId n) {
                return static_cast<size_t>(std::lower_bound(fan.begin(), fan.end(), n) -
                                           fan.begin());
            };
            for (size_t k = 0; k < fan.size(); ++k) {
                if (assigned[k]) continue;
                const NodeId rep = fan[k];
                assigned[k] = 1;
                queue.assign(1, rep);
                for (size_t q = 0; q < queue.size(); ++q) {
                    node_sector[static_cast<size_t>(queue[q])] = rep;
                    for (const int32_t e : node_entries(J, queue[q])) {
                        if (!intact(status, e / 4)) continue;
                        const size_t s = slot(partner(J, e));
                        if (!assigned[s]) {
                            assigned[s] = 1;
                            queue.push_back(fan[s]);
                        }
                    }
                }
            }
        }
    }
}

namespace {

// fragments of fracture body b by union-find over its triangles: through shared nodes and
// through the unbroken joints of its nodes (gather lists). Local ids (t - tri_begin, n -
// node_begin) keep the scratch the size of the body; the smallest local id is the smallest id.
void body_fragments(const Model& m, std::span<const JointStatus> status, BodyId b,
                    std::vector<int32_t>& first, std::vector<TriId>& tri_fragment) {
    const Body& body = m.bodies[static_cast<size_t>(b)];
    const TriId t0 = body.tri_begin;
    const NodeId n0 = body.node_begin;
    MinUnionFind uf(static_cast<size_t>(body.tri_end - t0));
    first.assign(static_cast<size_t>(body.node_end - n0), kNone);
    for (TriId t = t0; t < body.tri_end; ++t) {
        for (const NodeId n : m.tri_nodes[static_cast<size_t>(t)]) {
            int32_t& f = first[static_cast<size_t>(n - n0)];
            if (f == kNone) {
                f = t - t0;
            } else {
                uf.unite(f, t - t0);
            }
        }
    }
    const Joints& J = m.joints;
    if (!J.nodes.empty()) {
        // the body's nodes with joints are one run of the ascending gather_node: walk it (the
        // same nodes and entries in the same order as node_entries per node, without a binary
        // search per node, which was most of the cost of a break in a large body)
        const auto begin = std::lower_bound(J.gather_node.begin(), J.gather_node.end(), n0);
        for (auto g = static_cast<size_t>(begin - J.gather_node.begin());
             g < J.gather_node.size() && J.gather_node[g] < body.node_end; ++g) {
            for (int32_t q = J.gather_begin[g]; q < J.gather_begin[g + 1]; ++q) {
                const int32_t e = J.gather_entry[static_cast<size_t>(q)];
                if (e % 4 != 0 || !intact(status, e / 4)) continue;  // once per joint, at node 0
                const auto& jn = J.nodes[static_cast<size_t>(e / 4)];
                uf.unite(first[static_cast<size_t>(jn[0] - n0)],
                         first[static_cast<size_t>(jn[3] - n0)]);
            }
        }
    }
    for (TriId t = t0; t < body.tri_end; ++t)
        tri_fragment[static_cast<size_t>(t)] = t0 + uf.find(t - t0);
}

}  // namespace

void compute_fragments(const Model& m, std::span<const JointStatus> status,
                       std::vector<TriId>& tri_fragment) {
    FDEM_ASSERT(status.size() == m.joints.nodes.size(), "compute_fragments: one status per joint");
    FDEM_ASSERT(
        m.joints.nodes.empty() || m.joints.gather_begin.size() == m.joints.gather_node.size() + 1,
        "compute_fragments: joints not finalized (finalize_joints)");
    tri_fragment.resize(static_cast<size_t>(m.num_tris()));
    std::vector<int32_t> first;
    for (BodyId b = 0; b < m.num_bodies(); ++b) {
        const Body& body = m.bodies[static_cast<size_t>(b)];
        if (body.fracture) {
            body_fragments(m, status, b, first, tri_fragment);
        } else {
            // a body is a connected component of its mesh: one fragment
            for (TriId t = body.tri_begin; t < body.tri_end; ++t)
                tri_fragment[static_cast<size_t>(t)] = body.tri_begin;
        }
    }
}

void update_fragments(const Model& m, std::span<const JointStatus> status,
                      std::span<const int32_t> broken, std::vector<TriId>& tri_fragment) {
    if (broken.empty()) return;
    FDEM_ASSERT(tri_fragment.size() == static_cast<size_t>(m.num_tris()),
                "update_fragments: tri_fragment is not the full form's array");
    std::vector<BodyId> bodies;
    bodies.reserve(broken.size());
    for (const int32_t j : broken)
        bodies.push_back(
            m.node_body[static_cast<size_t>(m.joints.nodes[static_cast<size_t>(j)][0])]);
    std::sort(bodies.begin(), bodies.end());
    bodies.erase(std::unique(bodies.begin(), bodies.end()), bodies.end());
    std::vector<int32_t> first;
    for (const BodyId b : bodies)
        body_fragments(m, status, b, first, tri_fragment);
}

Real largest_fragment_mass_fraction(const Model& m, std::span<const TriId> tri_fragment,
                                    std::span<TriId> node_fragment, std::span<Real> fragment_mass) {
    FDEM_ASSERT(tri_fragment.size() == static_cast<size_t>(m.num_tris()) &&
                    node_fragment.size() == static_cast<size_t>(m.num_nodes()) &&
                    fragment_mass.size() == static_cast<size_t>(m.num_tris()),
                "largest_fragment_mass_fraction: array sizes");
    Real total = 0, largest = 0;
    for (const Body& body : m.bodies) {
        if (!body.fracture) continue;
        for (NodeId n = body.node_begin; n < body.node_end; ++n)
            node_fragment[static_cast<size_t>(n)] = kNone;
        // a fragment's id is its smallest triangle, met first: its sum starts there
        for (TriId t = body.tri_begin; t < body.tri_end; ++t) {
            const TriId f = tri_fragment[static_cast<size_t>(t)];
            if (f == t) fragment_mass[static_cast<size_t>(f)] = 0;
            for (const NodeId n : m.tri_nodes[static_cast<size_t>(t)])
                node_fragment[static_cast<size_t>(n)] = f;
        }
        for (NodeId n = body.node_begin; n < body.node_end; ++n) {
            const TriId f = node_fragment[static_cast<size_t>(n)];
            if (f == kNone) continue;
            fragment_mass[static_cast<size_t>(f)] += m.node_mass[static_cast<size_t>(n)];
            total += m.node_mass[static_cast<size_t>(n)];
        }
        for (TriId t = body.tri_begin; t < body.tri_end; ++t) {
            if (tri_fragment[static_cast<size_t>(t)] == t)
                largest = std::max(largest, fragment_mass[static_cast<size_t>(t)]);
        }
    }
    return total > 0 ? largest / total : 0;
}

}  // namespace fdem
