// Discrete fracture in the time step (docs/theory.md §9, spec fracture.md §4, §7).
#include "integrate/fracture_update.hpp"

#include <algorithm>
#include <vector>

#include "contact/contact.hpp"
#include "fdem/build.hpp"
#include "fracture/joints.hpp"
#include "fracture/sectors.hpp"

namespace fdem {

namespace {

// Sectors and fragments of the whole model (spec fracture.md §4.1-4.2, fracture/sectors.hpp).
void update_views(const Model& m, State& s) {
    compute_node_sectors(m, s.joints.status, s.node_sector);
    compute_fragments(m, s.joints.status, s.tri_fragment);
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
    std::vector<int32_t> broken;  // this step's breaks, ascending
    std::vector<BodyId> dirty;
    for (int32_t j = 0; j < m.joints.num_joints(); ++j) {
        if (s.joints.break_step[static_cast<size_t>(j)] != s.step) continue;
        broken.push_back(j);
        dirty.push_back(
            m.node_body[static_cast<size_t>(m.joints.nodes[static_cast<size_t>(j)][0])]);
    }
    std::sort(dirty.begin(), dirty.end());
    dirty.erase(std::unique(dirty.begin(), dirty.end()), dirty.end());
    // only the vertices of the broken joints and the fragments of their bodies (the incremental
    // forms give the full forms' arrays, fracture/sectors.hpp)
    update_node_sectors(m, s.joints.status, broken, s.node_sector);
    update_fragments(m, s.joints.status, broken, s.tri_fragment);
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
