// Smooth triangle-to-node contact of Lei et al. 2020 (docs/theory.md §6): per step, virtual-node
// kinematics, broad phase when the skin is used up, narrow phase (locate the target node in a
// contactor sub-triangle), the contact law and the reaction on the contactor (eq. 20).
//
// Pair loop order: candidate pairs sorted by (target node, contactor body), merged with the
// active-contact list of the previous step that is sorted the same way. Serial and therefore
// bitwise deterministic.
#include "contact/contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/field.hpp"
#include "contact/law.hpp"
#include "detect/broad_phase.hpp"

namespace fdem {

namespace {

constexpr Real kLocateEps = 1e-12;     // N_i >= -eps counts as inside (spec §4.5-1)
constexpr Real kLostCheckRatio = 0.1;  // depth ratio above which a lost pair is tested

inline Vec2 cpos(const ContactModel& cm, const Vec2* x, const Vec2* xv, NodeId i) {
    return i < cm.num_real_nodes ? x[i] : xv[i - cm.num_real_nodes];
}

// even-odd crossing test of p against the boundary edges of body c (handles holes)
bool inside_body(const ContactModel& cm, BodyId c, const Vec2* x, Vec2 p) {
    bool in = false;
    for (int32_t e = cm.body_bedge_begin[c]; e < cm.body_bedge_begin[c + 1]; ++e) {
        const Vec2 a = x[cm.boundary_edges[e][0]], b = x[cm.boundary_edges[e][1]];
        if ((a.y > p.y) != (b.y > p.y)) {
            const Real xc = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if (p.x < xc) in = !in;
        }
    }
    return in;
}

// force f on contact node i (virtual: to its parents with the frozen weights, spec §4.4-6)
inline void add_node_force(const ContactModel& cm, State& s, NodeId i, Vec2 f) {
    if (i < cm.num_real_nodes) {
        s.f[i] += f;
        s.f_contact[i] += f;
        return;
    }
    const size_t v = static_cast<size_t>(i - cm.num_real_nodes);
    for (int k = 0; k < 3; ++k) {
        const Vec2 fk = cm.virt_weight[v][k] * f;
        s.f[cm.virt_parent[v][k]] += fk;
        s.f_contact[cm.virt_parent[v][k]] += fk;
    }
}

}  // namespace

void init_contact_state(const Model& m, State& s) {
    const ContactModel& cm = m.contact;
    ContactState& cs = s.contact;
    cs = ContactState{};
    if (cm.algorithm == ContactAlgorithm::None) return;
    const size_t nv = static_cast<size_t>(cm.num_virtual());
    const size_t nb = cm.boundary_nodes.size();
    const size_t nt = static_cast<size_t>(cm.num_sub_tris());
    cs.xv.assign(nv, Vec2{});
    cs.vv.assign(nv, Vec2{});
    // reservations: the grow-only buffers rarely need more than this after warm-up
    cs.cand_node.reserve(4 * nb + 16);
    cs.cand_body.reserve(4 * nb + 16);
    cs.cand_begin.reserve(4 * nb + 17);
    cs.cand_tri.reserve(16 * nb + 64);
    cs.tri_center.reserve(nt);
    cs.tri_radius.reserve(nt);
    cs.tri_cell.reserve(nt);
    cs.cell_items.reserve(nt);
    cs.cell_start.reserve(4 * nt + 64);
    cs.query.reserve(4 * nt + 64);
    cs.active.reserve(2 * nb + 16);
    cs.active_next.reserve(2 * nb + 16);
}

void update_virtual_nodes(const Model& m, State& s) {
    const ContactModel& cm = m.contact;
    ContactState& cs = s.contact;
    const Vec2* x = s.x.data();
    const Vec2* v = s.v.data();
    for (int32_t k = 0; k < cm.num_virtual(); ++k) {
        const auto& p = cm.virt_parent[k];
        const auto& w = cm.virt_weight[k];
        cs.xv[k] = w[0] * x[p[0]] + w[1] * x[p[1]] + w[2] * x[p[2]];
        cs.vv[k] = w[0] * v[p[0]] + w[1] * v[p[1]] + w[2] * v[p[2]];
    }
}

void add_contact_forces(const Model& m, State& s) {
    const ContactModel& cm = m.contact;
    ContactState& cs = s.contact;
    cs.deep_penetrations = 0;
    cs.lost_inside = 0;
    cs.max_depth_ratio = 0;
    if (cm.algorithm == ContactAlgorithm::None || cm.num_sub_tris() == 0) {
        s.energy.contact = 0;
        cs.active_contacts = 0;
        return;
    }
    const Real dt = s.dt;
    const Vec2* x = s.x.data();
    const Vec2* v = s.v.data();

    // 1. virtual nodes follow their parents (spec §4.4-2)
    update_virtual_nodes(m, s);
    const Vec2* xv = cs.xv.data();
    const Vec2* vv = cs.vv.data();

    // 2. skin (spec §2.3): x^n - x^{n-1} = dt v^{n-1/2}; two objects close by at most
    //    2 dt max|v| per step, so the candidates stay complete until the sum exceeds b
    if (!cs.need_rebuild) {
        Real v2 = 0;
        for (NodeId i = 0; i < m.num_nodes(); ++i)
            v2 = std::max(v2, norm2(v[i]));
        cs.skin_used += 2.0 * dt * std::sqrt(v2);
        if (cs.skin_used > cm.buffer) cs.need_rebuild = true;
    }
    if (cs.need_rebuild) {
        find_candidates(m, x, xv, cs);
        cs.need_rebuild = false;
        cs.skin_used = 0;
        ++cs.rebuilds;
    }

    // 3. narrow phase and law, merged with the previous active list
    Real stored = 0, dissipated = 0;
    size_t ia = 0;
    cs.active_next.clear();
    auto release = [&](const ActiveContact& a) {
        const BodyId bt = m.node_body[a.node];
        const ContactParams& p =
            pair_parameters(cm, m.bodies[a.body].material, m.bodies[bt].material);
        const Real scale = m.node_mass[a.node] / cm.m_bar;
        bool lost = false;
        if (a.h.depth_ratio > kLostCheckRatio && inside_body(cm, a.body, x, x[a.node])) {
            lost = true;  // left the boundary layer inwards: penetration too deep (spec §4.6)
            ++cs.lost_inside;
        }
        dissipated += release_energy(p, a.h, scale, lost);
    };
    auto before = [](const ActiveContact& a, NodeId j, BodyId c) {
        return a.node < j || (a.node == j && a.body < c);
    };
    const int32_t npairs = static_cast<int32_t>(cs.cand_node.size());
    for (int32_t pr = 0; pr < npairs; ++pr) {
        const NodeId j = cs.cand_node[pr];
        const BodyId c = cs.cand_body[pr];
        while (ia < cs.active.size() && before(cs.active[ia], j, c))
            release(cs.active[ia++]);
        ActiveContact ac{j, c, PairHistory{}};
        bool had = false;
        if (ia < cs.active.size() && cs.active[ia].node == j && cs.active[ia].body == c) {
            ac = cs.active[ia++];
            had = true;
        }

        // locate x_j: the candidate sub-triangle with the largest min N_i >= -eps
        const Vec2 xj = x[j];
        int32_t best = -1;
        Real best_min = -kLocateEps;
        FieldSample fs;
        Vec2 pbest[3];
        for (int32_t k = cs.cand_begin[pr]; k < cs.cand_begin[pr + 1]; ++k) {
            const auto& q = cm.sub_tri[cs.cand_tri[k]];
            const Vec2 p[3] = {cpos(cm, x, xv, q[0]), cpos(cm, x, xv, q[1]), cpos(cm, x, xv, q[2])};
            Real N[3];
            if (!barycentric(p[0], p[1], p[2], xj, N)) continue;
            const Real mn = std::min({N[0], N[1], N[2]});
            if (mn >= best_min) {
                best_min = mn;
                best = cs.cand_tri[k];
                fs.N[0] = N[0];
                fs.N[1] = N[1];
                fs.N[2] = N[2];
                pbest[0] = p[0];
                pbest[1] = p[1];
                pbest[2] = p[2];
            }
        }
        if (best < 0) {
            if (had) release(ac);
            continue;
        }
        const auto& q = cm.sub_tri[best];
        const Real dist[3] = {cm.node_dist[q[0]], cm.node_dist[q[1]], cm.node_dist[q[2]]};
        evaluate_field(cm.algorithm, pbest, dist, fs);
        if (!(fs.d > 0)) {
            if (had) release(ac);
            continue;
        }

        // the law (eqs. 5-19) with v_r = v_c - v_j, v_c = sum N_i v_i (eq. 13)
        const BodyId bt = m.node_body[j];
        const ContactParams& p = pair_parameters(cm, m.bodies[c].material, m.bodies[bt].material);
        const Real scale = m.node_mass[j] / cm.m_bar;
        Vec2 vc;
        for (int k = 0; k < 3; ++k)
            vc += fs.N[k] * cpos(cm, v, vv, q[k]);
        const LawResult r = contact_law(p, fs.d, fs.grad, vc - v[j], scale, dt, ac.h);

        // f on the target, -N_i f on the contactor (eq. 20)
        s.f[j] += r.f;
        s.f_contact[j] += r.f;
        for (int k = 0; k < 3; ++k)
            add_node_force(cm, s, q[k], -fs.N[k] * r.f);

        // depth diagnostics: d relative to the local layer thickness
        const Real ratio = fs.layer > 0 ? fs.d / fs.layer : 1.0;
        ac.h.depth_ratio = ratio;
        cs.max_depth_ratio = std::max(cs.max_depth_ratio, ratio);
        if (ratio > cm.deep_ratio_limit) ++cs.deep_penetrations;

        stored += r.stored;
        dissipated += r.dissipated;
        cs.active_next.push_back(ac);
    }
    while (ia < cs.active.size())
        release(cs.active[ia++]);
    std::swap(cs.active, cs.active_next);

    s.energy.contact = stored;
    s.energy.dissipated_contact += dissipated;
    cs.active_contacts = static_cast<int32_t>(cs.active.size());
    cs.total_deep_penetrations += cs.deep_penetrations;
    cs.total_lost_inside += cs.lost_inside;
    cs.max_depth_ratio_ever = std::max(cs.max_depth_ratio_ever, cs.max_depth_ratio);
}

Real contact_stable_dt(const Model& m) {
    const ContactModel& cm = m.contact;
    Real dt = std::numeric_limits<Real>::infinity();
    if (cm.algorithm == ContactAlgorithm::None || cm.num_sub_tris() == 0 || !(cm.m_bar > 0)) {
        return dt;
    }
    // stiffness factor g' at the deepest penetration expected, d_ref = 0.1 h_min (spec §4.6);
    // the unloading branch is up to beta times stiffer than the loading one (theory eq. 6.13)
    const Real d_ref = 0.1 * cm.h_min;
    for (const ContactParams& p : cm.resolved) {
        Real gp = contact_dg(d_ref, p.alpha, p.length_scale);
        if (p.unloading == UnloadingLaw::Continuous) {
            gp = std::max(gp, p.beta * contact_g(d_ref, p.alpha, p.length_scale) / d_ref);
        } else {
            gp = std::max(gp, contact_dg(d_ref, p.beta, p.length_scale));
        }
        // omega_c = sqrt(g' k_n / mbar) * sqrt(2): the reaction on a contactor node of similar
        // mass doubles the effective stiffness (spec §3.4); damping lowers the bound
        const Real k = gp * p.penalty;
        const Real omega = std::sqrt(2.0 * k / cm.m_bar);
        const Real zeta = p.damping / (2.0 * std::sqrt(k * cm.m_bar));
        dt = std::min(dt, 2.0 / omega * (std::sqrt(1.0 + zeta * zeta) - zeta));
        if (p.friction > 0 && p.tangential_penalty > 0) {
            dt = std::min(dt, 2.0 / std::sqrt(2.0 * p.tangential_penalty / cm.m_bar));
        }
    }
    return dt;
}

}  // namespace fdem
