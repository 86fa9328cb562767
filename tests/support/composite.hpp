// Hand-built bodies of 6-node composite triangles (issue #7) for the contact tests and the
// distance-field pictures: nodes and sub-triangles appended to a Model exactly as the Body
// contract of include/fdem/model.hpp lays them out, independent of the mesh reader.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fdem/model.hpp"

namespace fdem::scenes {

/// Nodes and composite elements in the paper's perimeter numbering: elems[e] = (n1, ..., n6),
/// corners n1, n3, n5 counter-clockwise, n2 on n1-n3, n4 on n3-n5, n6 on n5-n1.
struct CompositeMesh {
    std::vector<Vec2> nodes;
    std::vector<std::array<int32_t, 6>> elems;
};

/// Straight-sided composite elements on the corner triangles tris (any orientation) of the
/// corner nodes: one mid-edge node per mesh edge, at its midpoint, shared by both neighbours.
inline CompositeMesh composite_mesh(const std::vector<Vec2>& corners,
                                    const std::vector<std::array<int32_t, 3>>& tris) {
    CompositeMesh cm;
    cm.nodes = corners;
    std::map<std::pair<int32_t, int32_t>, int32_t> mid;
    auto mid_node = [&](int32_t a, int32_t b) {
        const auto k = a < b ? std::pair{a, b} : std::pair{b, a};
        const auto it = mid.find(k);
        if (it != mid.end()) return it->second;
        cm.nodes.push_back(0.5 * (corners[a] + corners[b]));
        const int32_t id = static_cast<int32_t>(cm.nodes.size()) - 1;
        mid[k] = id;
        return id;
    };
    for (auto t : tris) {
        if (signed_area(corners[t[0]], corners[t[1]], corners[t[2]]) < 0) std::swap(t[1], t[2]);
        cm.elems.push_back(
            {t[0], mid_node(t[0], t[1]), t[1], mid_node(t[1], t[2]), t[2], mid_node(t[2], t[0])});
    }
    return cm;
}

/// Append mesh as one Composite6 body (Body contract of model.hpp: per element the sub-triangles
/// (n1,n2,n6), (n2,n3,n4), (n6,n4,n5), (n2,n4,n6), counter-clockwise). Nodes unused by the
/// elements are not created. The caller adds materials first and calls finalize_model() last.
inline BodyId add_composite_body(Model& m, const CompositeMesh& mesh, int32_t material = 0,
                                 bool fixed = false, Vec2 velocity = {},
                                 std::string name = "composite") {
    const BodyId bid = m.num_bodies();
    Body body;
    body.name = name;
    body.group = static_cast<int32_t>(m.group_names.size());
    body.material = material;
    body.fixed = fixed;
    body.element = ElementKind::Composite6;
    body.node_begin = m.num_nodes();
    body.tri_begin = m.num_tris();
    m.group_names.push_back(std::move(name));
    std::vector<NodeId> map(mesh.nodes.size(), kNone);
    for (const auto& e : mesh.elems) {
        NodeId n[6];
        for (int k = 0; k < 6; ++k) {
            if (map[e[k]] == kNone) {
                map[e[k]] = m.num_nodes();
                m.node_x0.push_back(mesh.nodes[e[k]]);
                m.node_v0.push_back(velocity);
                m.node_body.push_back(bid);
            }
            n[k] = map[e[k]];
        }
        const std::array<std::array<NodeId, 3>, 4> sub = {
            {{n[0], n[1], n[5]}, {n[1], n[2], n[3]}, {n[5], n[3], n[4]}, {n[1], n[3], n[5]}}};
        for (const auto& s : sub) {
            if (!(signed_area(m.node_x0[s[0]], m.node_x0[s[1]], m.node_x0[s[2]]) > 0)) {
                throw std::invalid_argument("add_composite_body: element not counter-clockwise");
            }
            m.tri_nodes.push_back(s);
            m.tri_body.push_back(bid);
            m.tri_material.push_back(material);
        }
    }
    body.node_end = m.num_nodes();
    body.tri_end = m.num_tris();
    m.bodies.push_back(body);
    return bid;
}

}  // namespace fdem::scenes
