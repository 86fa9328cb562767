// Discrete fracture in the time step (docs/theory.md §9, spec fracture.md §4, §7).
#include "integrate/fracture_update.hpp"

#include <algorithm>
#include <numeric>
#include <span>
#include <vector>

#include "contact/contact.hpp"
#include "fdem/build.hpp"
#include "fracture/joints.hpp"

namespace fdem {

namespace {

int32_t find_root(std::vector<int32_t>& parent, int32_t a) {
    while (parent[static_cast<size_t>(a)] != a) {
        parent[static_cast<size_t>(a)] =
            parent[static_cast<size_t>(parent[static_cast<size_t>(a)])];
        a = parent[static_cast<size_t>(a)];
    }
    return a;
}

void unite(std::vector<int32_t>& parent, int32_t a, int32_t b) {
    a = find_root(parent, a);
    b = find_root(parent, b);
    if (a != b) parent[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
}

// Sectors (spec fracture.md §4.2): copies of one vertex joined by an unbroken joint face pair
// (nodes 0-3, 1-2, theory eq. 9.1) are one contact vertex; its representative is the smallest
// copy id (the union-find keeps the smallest id as root).
std::vector<NodeId> node_sectors(const Model& m, std::span<const JointStatus> status) {
    std::vector<int32_t> parent(static_cast<size_t>(m.num_nodes()));
    std::iota(parent.begin(), parent.end(), 0);
    for (int32_t j = 0; j < m.joints.num_joints(); ++j) {
        if (status[static_cast<size_t>(j)] == JointStatus::Broken) continue;
        const auto& n = m.joints.nodes[static_cast<size_t>(j)];
        unite(parent, n[0], n[3]);
        unite(parent, n[1], n[2]);
    }
    std::vector<NodeId> sector(parent.size());
    for (size_t i = 0; i < parent.size(); ++i)
        sector[i] = find_root(parent, static_cast<int32_t>(i));
    return sector;
}

// Fragments (spec fracture.md §4.1): triangles connected through shared nodes and unbroken
// joints; each is labelled with its smallest triangle id.
std::vector<TriId> fragments(const Model& m, std::span<const NodeId> sector) {
    std::vector<int32_t> parent(static_cast<size_t>(m.num_nodes()));
    std::iota(parent.begin(), parent.end(), 0);
    for (TriId t = 0; t < m.num_tris(); ++t) {
        const auto& n = m.tri_nodes[static_cast<size_t>(t)];
        unite(parent, sector[static_cast<size_t>(n[0])], sector[static_cast<size_t>(n[1])]);
        unite(parent, sector[static_cast<size_t>(n[0])], sector[static_cast<size_t>(n[2])]);
    }
    std::vector<TriId> first(parent.size(), kNone);  // smallest triangle per root
    std::vector<TriId> frag(static_cast<size_t>(m.num_tris()));
    for (TriId t = 0; t < m.num_tris(); ++t) {
        const auto r = static_cast<size_t>(
            find_root(parent, sector[static_cast<size_t>(m.tri_nodes[static_cast<size_t>(t)][0])]));
        if (first[r] == kNone) first[r] = t;
        frag[static_cast<size_t>(t)] = first[r];
    }
    return frag;
}

void update_views(const Model& m, State& s) {
    s.node_sector = node_sectors(m, s.joints.status);
    s.tri_fragment = fragments(m, s.node_sector);
}

// The contact state's arrays sized by the topology follow it; the broad phase runs next step.
void topology_changed(State& s) {
    ContactState& cs = s.contact;
    const size_t nv = static_cast<size_t>(s.topology.num_virtual());
    if (cs.xv.size() != nv) {
        cs.xv.assign(nv, Vec2{});
        cs.vv.assign(nv, Vec2{});
    }
    cs.need_rebuild = true;
    cs.legacy.need_rebuild = true;
}

}  // namespace

void init_fracture_state(const Model& m, State& s) {
    if (m.joints.nodes.empty()) return;
    s.joints = make_joint_state(m.joints);
    // pre-broken joints (notches, DFN): broken before the first step, no work, no mode
    for (const int32_t j : m.prebroken_joints)
        s.joints.status[static_cast<size_t>(j)] = JointStatus::Broken;
    update_views(m, s);
}

void process_breaks(const Model& m, State& s) {
    update_views(m, s);
    std::vector<BodyId> dirty;
    for (int32_t j = 0; j < m.joints.num_joints(); ++j) {
        if (s.joints.break_step[static_cast<size_t>(j)] != s.step) continue;
        dirty.push_back(
            m.node_body[static_cast<size_t>(m.joints.nodes[static_cast<size_t>(j)][0])]);
    }
    std::sort(dirty.begin(), dirty.end());
    dirty.erase(std::unique(dirty.begin(), dirty.end()), dirty.end());
    // welded topology with the new sectors; edge-target histories follow their edges
    rebuild_contact_topology(m, s, dirty);
    topology_changed(s);
}

void rebuild_fracture_views(const Model& m, State& s) {
    if (m.joints.nodes.empty()) return;
    update_views(m, s);
    std::vector<BodyId> dirty;
    for (BodyId b = 0; b < m.num_bodies(); ++b) {
        if (m.bodies[static_cast<size_t>(b)].fracture) dirty.push_back(b);
    }
    rebuild_topology(m, dirty, s.node_sector, s.topology);
    const size_t nv = static_cast<size_t>(s.topology.num_virtual());
    if (s.contact.xv.size() != nv) {  // restored below from the file; only the size matters
        s.contact.xv.assign(nv, Vec2{});
        s.contact.vv.assign(nv, Vec2{});
    }
}

}  // namespace fdem
