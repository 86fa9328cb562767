// Baseline B field (spec §1.3, docs/theory.md §7.4): per contactor sub-triangle the terms of
// phi_B of its parent mesh triangle, and the amplitude H_ref per body.
#include "contact/legacy_boundary.hpp"

#include <algorithm>

namespace fdem {

namespace {

using Key = std::array<NodeId, 2>;
Key key(NodeId a, NodeId b) {
    return a < b ? Key{a, b} : Key{b, a};
}

}  // namespace

LegacyBoundaryField build_legacy_boundary_field(const Model& m, const ContactTopology& cm) {
    LegacyBoundaryField lb;

    // boundary edges as sorted undirected keys
    std::vector<Key> bkeys;
    bkeys.reserve(cm.boundary_edges.size());
    for (const auto& e : cm.boundary_edges)
        bkeys.push_back(key(e[0], e[1]));
    std::sort(bkeys.begin(), bkeys.end());
    auto is_boundary = [&](NodeId a, NodeId b) {
        return std::binary_search(bkeys.begin(), bkeys.end(), key(a, b));
    };

    // H_ref: mean height 2A/l of the triangles over their boundary edges (theory eq. 7.8)
    lb.body_h_ref.assign(static_cast<size_t>(m.num_bodies()), 0.0);
    for (BodyId b = 0; b < m.num_bodies(); ++b) {
        Real sum = 0;
        int32_t count = 0;
        for (TriId t = m.bodies[b].tri_begin; t < m.bodies[b].tri_end; ++t) {
            const auto& n = m.tri_nodes[t];
            const Real a2 = std::abs(
                cross(m.node_x0[n[1]] - m.node_x0[n[0]], m.node_x0[n[2]] - m.node_x0[n[0]]));
            for (int k = 0; k < 3; ++k) {
                const NodeId p = n[k], q = n[(k + 1) % 3];
                if (!is_boundary(p, q)) continue;
                sum += a2 / norm(m.node_x0[q] - m.node_x0[p]);
                ++count;
            }
        }
        if (count > 0) lb.body_h_ref[static_cast<size_t>(b)] = sum / count;
    }

    // value of the parent's shape function N_o at a contact node (real or virtual)
    auto parent_N = [&](NodeId i, NodeId o) -> Real {
        if (i < cm.num_real_nodes) return i == o ? 1.0 : 0.0;
        const size_t v = static_cast<size_t>(i - cm.num_real_nodes);
        Real w = 0;
        for (int k = 0; k < 3; ++k) {
            if (cm.virt_parent[v][k] == o) w += cm.virt_weight[v][k];
        }
        return w;
    };

    // per sub-triangle: one term N_o per boundary edge of the parent (o opposite that edge)
    lb.sub.resize(static_cast<size_t>(cm.num_sub_tris()));
    for (int32_t s = 0; s < cm.num_sub_tris(); ++s) {
        LegacyBoundaryTri& c = lb.sub[static_cast<size_t>(s)];
        const TriId t = cm.sub_parent[static_cast<size_t>(s)];
        const auto& n = m.tri_nodes[t];
        const auto& q = cm.sub_tri[static_cast<size_t>(s)];
        c.h_ref = lb.body_h_ref[static_cast<size_t>(m.tri_body[t])];
        for (int k = 0; k < 3; ++k) {
            if (!is_boundary(n[k], n[(k + 1) % 3])) continue;
            const NodeId o = n[(k + 2) % 3];
            for (int i = 0; i < 3; ++i)
                c.coef[c.terms][i] = parent_N(q[i], o);
            ++c.terms;
        }
    }
    return lb;
}

}  // namespace fdem
