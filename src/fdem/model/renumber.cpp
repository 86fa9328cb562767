// Morton-order renumbering of nodes and triangles (docs/performance.md: the element loop gathers
// x and scatters f through tri_nodes, so neighbouring ids should be neighbours in space).
#include "model/renumber.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <utility>

namespace fdem {

namespace {

// Spread the low 21 bits of v to the even bits (2-D Morton code = spread(x) | spread(y) << 1).
uint64_t spread_bits(uint64_t v) {
    v &= 0x1fffff;
    v = (v | (v << 16)) & 0x0000ffff0000ffffull;
    v = (v | (v << 8)) & 0x00ff00ff00ff00ffull;
    v = (v | (v << 4)) & 0x0f0f0f0f0f0f0f0full;
    v = (v | (v << 2)) & 0x3333333333333333ull;
    v = (v | (v << 1)) & 0x5555555555555555ull;
    return v;
}

template <class T>
void permute(std::vector<T>& a, const std::vector<int32_t>& new_of_old, size_t lo, size_t hi) {
    std::vector<T> tmp(a.begin() + static_cast<std::ptrdiff_t>(lo),
                       a.begin() + static_cast<std::ptrdiff_t>(hi));
    for (size_t i = lo; i < hi; ++i)
        a[static_cast<size_t>(new_of_old[i])] = tmp[i - lo];
}

}  // namespace

bool renumber_spatially(Model& m, std::vector<int32_t>* node_new_out) {
    const size_t nn = static_cast<size_t>(m.num_nodes());
    std::vector<int32_t> node_new(nn);  // old node id -> new node id
    std::iota(node_new.begin(), node_new.end(), 0);
    bool changed = false;

    for (const Body& body : m.bodies) {
        const TriId nt = body.tri_end - body.tri_begin;
        if (nt < kRenumberMinTris) continue;
        changed = true;

        // Morton key of each centroid on a 2^21 x 2^21 grid over the body's bounding box
        Vec2 lo = m.node_x0[body.node_begin], hi = lo;
        for (NodeId i = body.node_begin; i < body.node_end; ++i) {
            lo = {std::min(lo.x, m.node_x0[i].x), std::min(lo.y, m.node_x0[i].y)};
            hi = {std::max(hi.x, m.node_x0[i].x), std::max(hi.y, m.node_x0[i].y)};
        }
        const Real cells = static_cast<Real>((1 << 21) - 1);
        const Real sx = hi.x > lo.x ? cells / (hi.x - lo.x) : 0;
        const Real sy = hi.y > lo.y ? cells / (hi.y - lo.y) : 0;

        // units that move together: a triangle, or the four sub-triangles of a composite
        // element (model.hpp: they must stay consecutive and in their order)
        const TriId unit = body.element == ElementKind::Composite6 ? 4 : 1;
        const TriId nu = nt / unit;
        std::vector<std::pair<uint64_t, TriId>> order(static_cast<size_t>(nu));
        for (TriId u = 0; u < nu; ++u) {
            Vec2 c{0, 0};
            for (TriId t = body.tri_begin + u * unit; t < body.tri_begin + (u + 1) * unit; ++t) {
                const auto& n = m.tri_nodes[t];
                c += m.node_x0[n[0]] + m.node_x0[n[1]] + m.node_x0[n[2]];
            }
            c = c / static_cast<Real>(3 * unit);
            const auto qx = static_cast<uint64_t>((c.x - lo.x) * sx);
            const auto qy = static_cast<uint64_t>((c.y - lo.y) * sy);
            order[static_cast<size_t>(u)] = {spread_bits(qx) | (spread_bits(qy) << 1),
                                             body.tri_begin + u * unit};
        }
        std::sort(order.begin(), order.end());  // ties broken by the old id: deterministic

        // nodes in order of first use by the sorted triangles
        NodeId next = body.node_begin;
        std::vector<bool> seen(static_cast<size_t>(body.node_end - body.node_begin), false);
        std::vector<std::array<NodeId, 3>> tris(static_cast<size_t>(nt));
        std::vector<int32_t> mats(static_cast<size_t>(nt));
        for (size_t k = 0; k < static_cast<size_t>(nt); ++k) {
            const TriId old = order[k / static_cast<size_t>(unit)].second +
                              static_cast<TriId>(k % static_cast<size_t>(unit));
            tris[k] = m.tri_nodes[old];
            mats[k] = m.tri_material[old];
            for (NodeId n : tris[k]) {
                const size_t local = static_cast<size_t>(n - body.node_begin);
                if (!seen[local]) {
                    seen[local] = true;
                    node_new[static_cast<size_t>(n)] = next++;
                }
            }
        }
        // triangles (tri_body is uniform within the body)
        for (size_t k = 0; k < tris.size(); ++k) {
            for (NodeId& n : tris[k])
                n = node_new[static_cast<size_t>(n)];
            m.tri_nodes[static_cast<size_t>(body.tri_begin) + k] = tris[k];
            m.tri_material[static_cast<size_t>(body.tri_begin) + k] = mats[k];
        }
        // per-node arrays of the body (node_body is uniform within the body)
        permute(m.node_x0, node_new, static_cast<size_t>(body.node_begin),
                static_cast<size_t>(body.node_end));
        permute(m.node_v0, node_new, static_cast<size_t>(body.node_begin),
                static_cast<size_t>(body.node_end));
    }
    if (node_new_out) *node_new_out = node_new;
    if (!changed) return false;

    // fracture: joint node ids follow; a vertex's representative is again its smallest copy
    if (!m.node_vertex.empty()) {
        std::vector<NodeId> best(nn, kNone);
        for (size_t i = 0; i < nn; ++i) {
            const auto r = static_cast<size_t>(m.node_vertex[i]);
            const NodeId ni = node_new[i];
            if (best[r] == kNone || ni < best[r]) best[r] = ni;
        }
        std::vector<NodeId> vertex(nn);
        for (size_t i = 0; i < nn; ++i)
            vertex[static_cast<size_t>(node_new[i])] = best[static_cast<size_t>(m.node_vertex[i])];
        m.node_vertex = std::move(vertex);
    }
    for (auto& jn : m.joints.nodes) {
        for (NodeId& n : jn)
            n = node_new[static_cast<size_t>(n)];
    }
    // the joints in the order of their node 0 (a node of triangle A at the joint's edge, whose
    // id now follows the Morton curve): chunks of consecutive joints lie in one region (the
    // kernel's gathers stay local, and a distributed run's processes share few chunks,
    // docs/parallel.md "Joints"); they were in the order of the mesh's triangle ids
    if (!m.joints.nodes.empty()) {
        Joints& J = m.joints;
        const size_t nj = J.nodes.size();
        std::vector<int32_t> order(nj);  // new joint k = old joint order[k]
        std::iota(order.begin(), order.end(), 0);
        std::stable_sort(order.begin(), order.end(), [&](int32_t a, int32_t b) {
            return J.nodes[static_cast<size_t>(a)][0] < J.nodes[static_cast<size_t>(b)][0];
        });
        std::vector<int32_t> joint_new(nj);
        for (size_t k = 0; k < nj; ++k)
            joint_new[static_cast<size_t>(order[k])] = static_cast<int32_t>(k);
        const auto apply = [&](auto& a) {
            auto old = a;
            for (size_t k = 0; k < nj; ++k)
                a[k] = old[static_cast<size_t>(order[k])];
        };
        apply(J.nodes);
        apply(J.length0);
        apply(J.law);
        J.sorted_by_node0 = true;
        for (int32_t& j : m.prebroken_joints)
            j = joint_new[static_cast<size_t>(j)];
        std::sort(m.prebroken_joints.begin(), m.prebroken_joints.end());
    }
    for (BoundaryCondition& bc : m.bcs) {
        for (NodeId& n : bc.nodes)
            n = node_new[static_cast<size_t>(n)];
        std::sort(bc.nodes.begin(), bc.nodes.end());
    }
    for (Load& ld : m.loads) {
        for (auto& e : ld.edges) {
            for (NodeId& n : e)
                n = node_new[static_cast<size_t>(n)];
        }
        for (NodeId& n : ld.nodes)
            n = node_new[static_cast<size_t>(n)];
        std::sort(ld.nodes.begin(), ld.nodes.end());
    }
    return true;
}

}  // namespace fdem
