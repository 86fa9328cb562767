// Jointed (fracture) bodies for the tests (spec fracture.md §1.2, include/fdem/build.hpp
// BodyOptions::fracture): add_bodies with fracture, the jointed and pre-broken edges chosen by
// predicates on mesh vertex pairs, and the joint material set on the body's material.
#pragma once

#include <algorithm>
#include <array>
#include <functional>
#include <numeric>
#include <string>
#include <vector>

#include "fdem/build.hpp"
#include "fdem/mesh.hpp"
#include "fdem/model.hpp"

namespace fdem::testing {

/// Is the mesh edge between mesh vertices a and b selected?
using JointedEdge = std::function<bool(int32_t a, int32_t b)>;

/// Every internal edge jointed (every triangle its own three nodes).
inline bool all_edges(int32_t, int32_t) {
    return true;
}

/// A joint material with the given penalty [Pa]; strength and energies valid, allow_coarse so
/// that unit-size test meshes pass the h_max check (eq. 9.14; these tests never soften).
inline JointMaterial test_joint_material(Real penalty) {
    JointMaterial jm;
    jm.tensile_strength = 1e6;
    jm.cohesion = 2e6;
    jm.friction_angle = 0.5;
    jm.fracture_energy_I = 100;
    jm.fracture_energy_II = 200;
    jm.penalty = penalty;
    jm.shear_penalty = penalty;
    jm.allow_coarse = true;
    return jm;
}

/// the internal edges of mesh (mesh vertex pairs, min first) for which pick(a, b)
inline std::vector<std::array<int32_t, 2>> internal_edges(const MeshData& mesh,
                                                          const JointedEdge& pick) {
    std::vector<std::array<int32_t, 2>> all, out;
    for (const auto& t : mesh.tris) {
        for (int k = 0; k < 3; ++k)
            all.push_back({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
    }
    std::sort(all.begin(), all.end());
    for (size_t i = 0; i + 1 < all.size(); ++i) {
        if (all[i] == all[i + 1] && pick(all[i][0], all[i][1])) out.push_back(all[i]);
    }
    return out;
}

/// Append all triangles of mesh (one connected piece) as one body with fracture, jointed on the
/// internal edges `jointed` selects (all_edges: every internal edge), of which those `prebroken`
/// selects are broken at t = 0. The material gets test_joint_material(10 E) unless it has a
/// joint material already. Returns the body id; finalize_model() after the last body.
inline BodyId add_jointed_body(Model& m, const MeshData& mesh, const JointedEdge& jointed,
                               int32_t material = 0, bool fixed = false, Vec2 velocity = {},
                               const JointedEdge& prebroken = nullptr) {
    Material& mat = m.materials[static_cast<size_t>(material)];
    if (!mat.has_fracture) {
        mat.has_fracture = true;
        mat.fracture = test_joint_material(10 * mat.youngs_modulus);
    }
    BodyOptions opt;
    opt.name = "jointed" + std::to_string(m.num_bodies());
    opt.material = material;
    opt.fixed = fixed;
    opt.velocity = velocity;
    opt.fracture = true;
    bool every = true;
    for (const auto& e : internal_edges(mesh, [](int32_t, int32_t) { return true; }))
        every = every && jointed(e[0], e[1]);
    if (!every) opt.joint_edges = internal_edges(mesh, jointed);
    if (prebroken) opt.prebroken_edges = internal_edges(mesh, prebroken);
    std::vector<int32_t> ids(mesh.tris.size());
    std::iota(ids.begin(), ids.end(), 0);
    const BodyId bid = m.num_bodies();
    add_bodies(m, mesh, ids, opt);
    return bid;
}

/// Joint statuses: all intact, then the listed joints broken.
inline std::vector<JointStatus> statuses(const Model& m, const std::vector<int32_t>& broken = {}) {
    std::vector<JointStatus> s(static_cast<size_t>(m.joints.num_joints()), JointStatus::Intact);
    for (const int32_t j : broken)
        s[static_cast<size_t>(j)] = JointStatus::Broken;
    return s;
}

}  // namespace fdem::testing
