// Jointed (fracture) bodies for the tests, built by hand from a MeshData (spec fracture.md §1.2,
// include/fdem/build.hpp BodyOptions::fracture): around every mesh vertex the fan of triangles is
// cut at the jointed edges and every run gets its own node copy; every jointed internal edge gets
// a joint in the node order of add_edge_joints (fracture/joint_mesh.hpp: A = the lower triangle,
// nodes 0, 1 its edge in its own order, 2 facing 1, 3 facing 0). Model::node_vertex maps every
// copy to the smallest copy of its vertex. Stands in for add_bodies(opt.fracture) until the model
// build has it.
#pragma once

#include <algorithm>
#include <array>
#include <functional>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include "fdem/build.hpp"
#include "fdem/mesh.hpp"
#include "fdem/model.hpp"
#include "fracture/joint_law.hpp"
#include "fracture/joints.hpp"

namespace fdem::testing {

/// Is the mesh edge between mesh vertices a and b jointed?
using JointedEdge = std::function<bool(int32_t a, int32_t b)>;

/// Every internal edge jointed (every triangle its own three nodes).
inline bool all_edges(int32_t, int32_t) {
    return true;
}

/// Append all triangles of mesh (one connected piece, re-oriented counter-clockwise) as one body
/// with fracture. Returns its id. Call finalize_jointed() after the last body.
inline BodyId add_jointed_body(Model& m, const MeshData& mesh, const JointedEdge& jointed,
                               int32_t material = 0, bool fixed = false, Vec2 velocity = {}) {
    const int32_t nt = static_cast<int32_t>(mesh.tris.size());
    std::vector<std::array<int32_t, 3>> tris = mesh.tris;
    for (auto& t : tris) {
        if (signed_area(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]]) < 0)
            std::swap(t[1], t[2]);
    }

    // corners 3 t + k; corners of one vertex across a non-jointed edge share a node
    std::vector<int32_t> parent(static_cast<size_t>(3 * nt));
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int32_t c) {
        while (parent[c] != c)
            c = parent[c] = parent[parent[c]];
        return c;
    };
    auto corner = [&](int32_t t, int32_t v) {
        for (int k = 0; k < 3; ++k) {
            if (tris[t][k] == v) return 3 * t + k;
        }
        return -1;
    };
    std::map<std::array<int32_t, 2>, std::vector<std::array<int32_t, 2>>> edges;  // (t, slot)
    for (int32_t t = 0; t < nt; ++t) {
        for (int32_t k = 0; k < 3; ++k) {
            const int32_t a = tris[t][k], b = tris[t][(k + 1) % 3];
            edges[{std::min(a, b), std::max(a, b)}].push_back({t, k});
        }
    }
    for (const auto& [e, uses] : edges) {
        if (uses.size() != 2 || jointed(e[0], e[1])) continue;
        for (const int32_t v : e) {
            const int32_t c1 = find(corner(uses[0][0], v)), c2 = find(corner(uses[1][0], v));
            if (c1 != c2) parent[std::max(c1, c2)] = std::min(c1, c2);
        }
    }

    // one node per class, numbered in corner order
    const NodeId base = m.num_nodes();
    const BodyId bid = m.num_bodies();
    if (m.node_vertex.size() < static_cast<size_t>(base)) {
        m.node_vertex.resize(static_cast<size_t>(base));
        std::iota(m.node_vertex.begin(), m.node_vertex.end(), 0);
    }
    std::vector<NodeId> node_of(static_cast<size_t>(3 * nt), kNone);
    std::map<int32_t, NodeId> first_copy;  // mesh vertex -> smallest copy
    for (int32_t c = 0; c < 3 * nt; ++c) {
        const int32_t r = find(c);
        if (node_of[r] == kNone) {
            node_of[r] = m.num_nodes();
            const int32_t v = tris[c / 3][c % 3];
            m.node_x0.push_back(mesh.nodes[v]);
            m.node_v0.push_back(velocity);
            m.node_body.push_back(bid);
            first_copy.emplace(v, node_of[r]);
            m.node_vertex.push_back(first_copy.at(v));
        }
        node_of[c] = node_of[r];
    }
    for (int32_t t = 0; t < nt; ++t) {
        m.tri_nodes.push_back({node_of[3 * t], node_of[3 * t + 1], node_of[3 * t + 2]});
        m.tri_body.push_back(bid);
        m.tri_material.push_back(material);
    }

    // joints on the jointed internal edges, ordered by (A, slot)
    std::vector<std::array<int32_t, 4>> found;  // A, slot A, B, slot B
    for (const auto& [e, uses] : edges) {
        if (uses.size() == 2 && jointed(e[0], e[1]))
            found.push_back({uses[0][0], uses[0][1], uses[1][0], uses[1][1]});
    }
    std::sort(found.begin(), found.end());
    for (const auto& [ta, ka, tb, kb] : found) {
        const NodeId a0 = node_of[3 * ta + ka], a1 = node_of[3 * ta + (ka + 1) % 3];
        const NodeId b0 = node_of[corner(tb, tris[ta][(ka + 1) % 3])];
        const NodeId b1 = node_of[corner(tb, tris[ta][ka])];
        (void)kb;
        m.joints.nodes.push_back({a0, a1, b0, b1});
        m.joints.length0.push_back(norm(m.node_x0[a1] - m.node_x0[a0]));
        m.joints.law.push_back(0);
    }

    Body body;
    body.name = "jointed" + std::to_string(bid);
    body.group = static_cast<int32_t>(m.group_names.size());
    m.group_names.push_back(body.name);
    body.material = material;
    body.fixed = fixed;
    body.fracture = true;
    body.node_begin = base;
    body.node_end = m.num_nodes();
    body.tri_begin = m.num_tris() - nt;
    body.tri_end = m.num_tris();
    m.bodies.push_back(body);
    return bid;
}

/// A joint material with the given penalty [Pa] (strength and energies only need to be valid).
inline JointMaterial test_joint_material(Real penalty) {
    JointMaterial jm;
    jm.tensile_strength = 1e6;
    jm.cohesion = 2e6;
    jm.friction_angle = 0.5;
    jm.fracture_energy_I = 100;
    jm.fracture_energy_II = 200;
    jm.penalty = penalty;
    jm.shear_penalty = penalty;
    return jm;
}

/// After the last body: node_vertex for every node, the joint law (one material) and gather
/// lists, then finalize_model() (meshes below the renumbering threshold keep their numbering).
inline Model& finalize_jointed(Model& m, const JointMaterial& jm) {
    const size_t nn = static_cast<size_t>(m.num_nodes());
    const size_t old = m.node_vertex.size();
    m.node_vertex.resize(nn);
    for (size_t i = old; i < nn; ++i)
        m.node_vertex[i] = static_cast<NodeId>(i);
    m.joints.laws.assign(1, make_joint_law(jm));
    finalize_joints(m.joints, m.num_nodes());
    finalize_model(m);
    return m;
}

/// Joint statuses: all intact, then the listed joints broken.
inline std::vector<JointStatus> statuses(const Model& m, const std::vector<int32_t>& broken = {}) {
    std::vector<JointStatus> s(static_cast<size_t>(m.joints.num_joints()), JointStatus::Intact);
    for (const int32_t j : broken)
        s[static_cast<size_t>(j)] = JointStatus::Broken;
    return s;
}

}  // namespace fdem::testing
