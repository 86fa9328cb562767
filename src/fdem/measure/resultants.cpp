// Force resultants, support reactions and mean motion of body entries and boundary groups
// (measure.hpp, docs/output.md bodies.csv, theory §8).
#include <algorithm>
#include <map>

#include "fdem/build.hpp"
#include "fdem/measure.hpp"

namespace fdem {

namespace {

// forces(): the listed nodes (ContactState::fc_nodes) are searched in a set's nodes when they
// are fewer than 1 in kListedSumRatio of them (a binary search each against one add each)
constexpr size_t kListedSumRatio = 32;

// Nodes that can receive a contact force (a superset: summing f_contact over them in ascending
// order gives the same bits as summing over every node of the body, zeros add nothing).
std::vector<uint8_t> contact_force_nodes(const Model& m, const ContactTopology& ct) {
    const ContactModel& cm = m.contact;
    std::vector<uint8_t> flag(static_cast<size_t>(m.num_nodes()), 0);
    if (cm.algorithm == ContactAlgorithm::None) return flag;
    for (NodeId j : ct.boundary_nodes)  // targets
        flag[static_cast<size_t>(j)] = 1;
    for (const auto& t : ct.sub_tri) {  // contactor vertices, virtual ones via their parents
        for (NodeId i : t) {
            if (i < ct.num_real_nodes) {
                flag[static_cast<size_t>(i)] = 1;
            } else {
                for (NodeId p : ct.virt_parent[static_cast<size_t>(i - ct.num_real_nodes)])
                    flag[static_cast<size_t>(p)] = 1;
            }
        }
    }
    for (TriId t : ct.boundary_tris) {  // baseline A couples
        for (NodeId i : m.tri_nodes[static_cast<size_t>(t)])
            flag[static_cast<size_t>(i)] = 1;
    }
    return flag;
}

// Nodes where a contact force or an external load ([[load]]) can act: a fixed body's reaction
// (eq. 8.2) sums f over them.
std::vector<uint8_t> force_nodes(const Model& m, const ContactTopology& ct) {
    std::vector<uint8_t> flag = contact_force_nodes(m, ct);
    for (const Load& ld : m.loads) {
        for (NodeId i : ld.nodes)
            flag[static_cast<size_t>(i)] = 1;
        for (const auto& e : ld.edges) {
            flag[static_cast<size_t>(e[0])] = 1;
            flag[static_cast<size_t>(e[1])] = 1;
        }
    }
    return flag;
}

}  // namespace

Resultants::Resultants(const Model& m) : Resultants(m, build_topology(m)) {}

Resultants::Resultants(const Model& m, const ContactTopology& ct) {
    const std::vector<uint8_t> carries = contact_force_nodes(m, ct);
    const std::vector<uint8_t> loaded = force_nodes(m, ct);
    const int32_t n_entries = static_cast<int32_t>(m.group_names.size());
    num_entries_ = n_entries;
    sets_.resize(static_cast<size_t>(n_entries));
    for (int32_t e = 0; e < n_entries; ++e)
        sets_[static_cast<size_t>(e)].name = m.group_names[static_cast<size_t>(e)];
    for (BodyId b = 0; b < m.num_bodies(); ++b) {
        const Body& body = m.bodies[static_cast<size_t>(b)];
        Set& set = sets_[static_cast<size_t>(body.group)];
        set.bodies.push_back(b);
        for (NodeId i = body.node_begin; i < body.node_end; ++i) {
            if (carries[static_cast<size_t>(i)]) set.force_nodes.push_back(i);
            if (body.fixed && loaded[static_cast<size_t>(i)]) set.fixed_nodes.push_back(i);
        }
        if (body.fixed) {
            set.fixed_bodies.push_back(b);
            for (NodeId i = body.node_begin; i < body.node_end; ++i)
                set.fixed_mass += m.node_mass[static_cast<size_t>(i)];
        }
    }
    // boundary groups: one set per support name, in order of first appearance
    std::map<std::string, size_t> group_of;
    int32_t slot = 0;
    for (const BoundaryCondition& bc : m.bcs) {
        auto it = group_of.find(bc.name);
        if (it == group_of.end()) {
            it = group_of.emplace(bc.name, sets_.size()).first;
            sets_.emplace_back();
            sets_.back().name = bc.name;
        }
        Set& g = sets_[it->second];
        for (NodeId i : bc.nodes) {
            g.nodes.push_back(i);
            g.slots.push_back(slot);
            const Body& body = m.bodies[static_cast<size_t>(m.node_body[static_cast<size_t>(i)])];
            sets_[static_cast<size_t>(body.group)].slots.push_back(slot);
            ++slot;
        }
    }
    for (Set& set : sets_) {
        std::sort(set.slots.begin(), set.slots.end());
        if (set.nodes.empty()) continue;
        std::sort(set.nodes.begin(), set.nodes.end());
        set.nodes.erase(std::unique(set.nodes.begin(), set.nodes.end()), set.nodes.end());
        for (NodeId i : set.nodes) {
            if (carries[static_cast<size_t>(i)]) set.force_nodes.push_back(i);
        }
    }
}

IntervalImpulses Resultants::make_impulses() const {
    IntervalImpulses acc;
    acc.contact.assign(sets_.size(), Vec2{});
    acc.reaction.assign(sets_.size(), Vec2{});
    return acc;
}

void Resultants::forces(const Model& m, const State& s, int32_t set, Vec2& contact,
                        Vec2& reaction) const {
    const Set& st = sets_[static_cast<size_t>(set)];
    // resultant contact force: the nodal contact forces of the last step, in node order (eq. 8.3)
    contact = {};
    const ContactState& cs = s.contact;
    if (cs.fc_sparse && cs.fc_nodes.size() * kListedSumRatio < st.force_nodes.size()) {
        // few nodes can carry a contact force (ContactState::fc_nodes): the same sum without its
        // zero terms, the same bits (from +0, adding +-0 changes no partial sum)
        auto it = st.force_nodes.begin();
        for (const NodeId i : cs.fc_nodes) {
            it = std::lower_bound(it, st.force_nodes.end(), i);
            if (it == st.force_nodes.end()) break;
            if (*it == i) contact += s.f_contact[static_cast<size_t>(i)];
        }
    } else {
        for (NodeId i : st.force_nodes)
            contact += s.f_contact[static_cast<size_t>(i)];
    }
    // reaction of the supports (eq. 8.1, computed by step()), in slot order
    reaction = {};
    for (int32_t k : st.slots)
        reaction += s.bc_reaction[static_cast<size_t>(k)];
    // fixed bodies hold every node still: the ground balances the force on them and their
    // weight (eq. 8.2). Their nodes carry no internal force (fixed bodies are not in the element
    // loop), so f there is the contact force plus any [[load]].
    if (!st.fixed_bodies.empty()) {
        Vec2 f{};
        for (NodeId i : st.fixed_nodes)
            f += s.f[static_cast<size_t>(i)];
        reaction -= f + st.fixed_mass * m.gravity;
    }
}

void Resultants::accumulate(const Model& m, const State& s, IntervalImpulses& acc) const {
    accumulate_sets(m, s, acc, nullptr);
}

void Resultants::accumulate(const Model& m, const State& s, IntervalImpulses& acc,
                            const std::vector<uint8_t>& mine) const {
    accumulate_sets(m, s, acc, mine.data());
}

void Resultants::accumulate_sets(const Model& m, const State& s, IntervalImpulses& acc,
                                 const uint8_t* mine) const {
    // the step just taken advanced v by dt_v (f / m): dt/2 on the first step (theory eq. 5.1)
    const Real dt_v = s.step == 1 ? 0.5 * s.dt : s.dt;
    for (int32_t k = 0; k < num_sets(); ++k) {
        if (mine != nullptr && !mine[k]) continue;
        Vec2 c, r;
        forces(m, s, k, c, r);
        acc.contact[static_cast<size_t>(k)] += dt_v * c;
        acc.reaction[static_cast<size_t>(k)] += dt_v * r;
    }
    acc.time += dt_v;
}

std::vector<NodeId> Resultants::read_nodes(int32_t set) const {
    const Set& st = sets_[static_cast<size_t>(set)];
    std::vector<NodeId> nodes = st.force_nodes;
    nodes.insert(nodes.end(), st.fixed_nodes.begin(), st.fixed_nodes.end());
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    return nodes;
}

std::vector<int32_t> Resultants::set_ranks(int32_t procs,
                                           std::span<const int32_t> node_owner) const {
    const int32_t n = num_sets();
    std::vector<int32_t> order(static_cast<size_t>(n));
    for (int32_t k = 0; k < n; ++k)
        order[static_cast<size_t>(k)] = k;
    std::stable_sort(order.begin(), order.end(),
                     [&](int32_t a, int32_t b) { return set_cost(a) > set_cost(b); });
    const size_t np = static_cast<size_t>(std::max(procs, 1));
    std::vector<int64_t> load(np, 0);
    std::vector<int32_t> rank(static_cast<size_t>(n), 0);
    std::vector<int64_t> owned(np, 0);  // read nodes of the set per process (touched ones only)
    std::vector<int32_t> touched;
    for (const int32_t k : order) {
        touched.clear();
        for (const NodeId i : read_nodes(k)) {
            const int32_t o = node_owner[static_cast<size_t>(i)];
            if (owned[static_cast<size_t>(o)]++ == 0) touched.push_back(o);
        }
        int32_t best = -1;
        for (const int32_t o : touched) {
            const size_t u = static_cast<size_t>(o);
            if (best < 0) {
                best = o;
                continue;
            }
            const size_t b = static_cast<size_t>(best);
            if (owned[u] > owned[b] || (owned[u] == owned[b] && load[u] < load[b]) ||
                (owned[u] == owned[b] && load[u] == load[b] && o < best))
                best = o;
        }
        for (const int32_t o : touched)
            owned[static_cast<size_t>(o)] = 0;
        if (best < 0)  // no read nodes: the least loaded process (the first of equals)
            best = static_cast<int32_t>(std::min_element(load.begin(), load.end()) - load.begin());
        load[static_cast<size_t>(best)] += set_cost(k);
        rank[static_cast<size_t>(k)] = best;
    }
    return rank;
}

int64_t Resultants::set_cost(int32_t set) const {
    const Set& st = sets_[static_cast<size_t>(set)];
    return static_cast<int64_t>(st.force_nodes.size() + st.slots.size() + st.fixed_nodes.size()) +
           1;
}

void Resultants::evaluate(const Model& m, const State& s, const IntervalImpulses& acc,
                          SetValues* out) const {
    for (int32_t k = 0; k < num_sets(); ++k) {
        const Set& st = sets_[static_cast<size_t>(k)];
        SetValues& o = out[k];
        // mass-weighted means (eq. 8.5): a body entry's centre of mass
        Vec2 mu{}, mv{};
        Real mass = 0;
        auto add = [&](NodeId i) {
            const Real mi = m.node_mass[static_cast<size_t>(i)];
            mu += mi * (s.x[static_cast<size_t>(i)] - m.node_x0[static_cast<size_t>(i)]);
            mv += mi * s.v[static_cast<size_t>(i)];
            mass += mi;
        };
        if (k < num_entries_) {
            for (BodyId b : st.bodies) {
                const Body& body = m.bodies[static_cast<size_t>(b)];
                for (NodeId i = body.node_begin; i < body.node_end; ++i)
                    add(i);
            }
        } else {
            for (NodeId i : st.nodes)
                add(i);
        }
        o.u = mass > 0 ? mu / mass : Vec2{};
        o.v = mass > 0 ? mv / mass : Vec2{};
        forces(m, s, k, o.contact, o.reaction);
        const bool has = acc.time > 0 && acc.contact.size() == sets_.size();
        o.contact_avg = has ? acc.contact[static_cast<size_t>(k)] / acc.time : o.contact;
        o.reaction_avg = has ? acc.reaction[static_cast<size_t>(k)] / acc.time : o.reaction;
    }
}

}  // namespace fdem
