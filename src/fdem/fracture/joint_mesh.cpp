// Jointed meshes (spec fracture.md §1.2, §7).
#include "fracture/joint_mesh.hpp"

#include <algorithm>
#include <stdexcept>
#include <tuple>

namespace fdem {

SplitMesh split_mesh(std::span<const Vec2> x, std::span<const std::array<NodeId, 3>> tris) {
    SplitMesh m;
    m.x0.reserve(3 * tris.size());
    m.tris.reserve(tris.size());
    m.vertex.reserve(3 * tris.size());
    for (size_t t = 0; t < tris.size(); ++t) {
        const NodeId base = static_cast<NodeId>(3 * t);
        for (int k = 0; k < 3; ++k) {
            m.x0.push_back(x[static_cast<size_t>(tris[t][k])]);
            m.vertex.push_back(tris[t][k]);
        }
        m.tris.push_back({base, base + 1, base + 2});
    }
    return m;
}

void add_edge_joints(Joints& J, std::span<const Vec2> x0,
                     std::span<const std::array<NodeId, 3>> tris, std::span<const NodeId> vertex,
                     int32_t law, const std::vector<std::array<NodeId, 2>>* only) {
    // (smaller vertex, larger vertex, triangle, slot) per edge, sorted: a shared edge is a run
    std::vector<std::tuple<NodeId, NodeId, int32_t, int32_t>> edges;
    edges.reserve(3 * tris.size());
    for (size_t t = 0; t < tris.size(); ++t) {
        for (int k = 0; k < 3; ++k) {
            const NodeId a = vertex[static_cast<size_t>(tris[t][k])];
            const NodeId b = vertex[static_cast<size_t>(tris[t][(k + 1) % 3])];
            edges.emplace_back(std::min(a, b), std::max(a, b), static_cast<int32_t>(t), k);
        }
    }
    std::sort(edges.begin(), edges.end());
    std::vector<std::array<int32_t, 4>> found;  // A, slot A, B, slot B
    for (size_t i = 0; i + 1 < edges.size();) {
        size_t r = i + 1;
        while (r < edges.size() && std::get<0>(edges[r]) == std::get<0>(edges[i]) &&
               std::get<1>(edges[r]) == std::get<1>(edges[i]))
            ++r;
        if (r - i > 2)
            throw std::invalid_argument("add_edge_joints: edge of more than 2 triangles");
        const std::array<NodeId, 2> key{std::get<0>(edges[i]), std::get<1>(edges[i])};
        if (r - i == 2 && (!only || std::binary_search(only->begin(), only->end(), key)))
            found.push_back({std::get<2>(edges[i]), std::get<3>(edges[i]),
                             std::get<2>(edges[i + 1]), std::get<3>(edges[i + 1])});
        i = r;
    }
    std::sort(found.begin(), found.end());
    for (const auto& [ta, ka, tb, kb] : found) {
        const NodeId a0 = tris[static_cast<size_t>(ta)][static_cast<size_t>(ka)];
        const NodeId a1 = tris[static_cast<size_t>(ta)][static_cast<size_t>((ka + 1) % 3)];
        const NodeId b0 = tris[static_cast<size_t>(tb)][static_cast<size_t>(kb)];
        const NodeId b1 = tris[static_cast<size_t>(tb)][static_cast<size_t>((kb + 1) % 3)];
        if (vertex[static_cast<size_t>(b0)] != vertex[static_cast<size_t>(a1)])
            throw std::invalid_argument("add_edge_joints: neighbours of opposite orientation");
        // node 2 faces node 1 (a1), node 3 faces node 0 (a0)
        J.nodes.push_back({a0, a1, b0, b1});
        J.length0.push_back(norm(x0[static_cast<size_t>(a1)] - x0[static_cast<size_t>(a0)]));
        J.law.push_back(law);
    }
}

}  // namespace fdem
