// Scene builders shared by tests, benchmarks and examples (like Box2D's shared/).
#pragma once

#include <string>
#include <vector>

#include "fdem/build.hpp"
#include "fdem/mesh.hpp"
#include "fdem/model.hpp"

namespace fdem::scenes {

/// A material with the paper's defaults (E = 1 GPa, nu = 0, rho = 1000 kg/m^3, plane strain).
inline Material paper_material(std::string name = "paper", Real E = 1e9, Real nu = 0.0,
                               Real rho = 1000.0) {
    Material mat;
    mat.name = std::move(name);
    mat.density = rho;
    mat.youngs_modulus = E;
    mat.poisson_ratio = nu;
    return mat;
}

/// Add a structured rectangle body; returns the mesh-node -> model-node map.
inline std::vector<NodeId> add_rectangle(Model& m, Real x0, Real y0, Real w, Real h, int nx, int ny,
                                         int32_t material, bool fixed = false, Vec2 velocity = {},
                                         bool alternate = false, std::string name = "rect") {
    const MeshData mesh = make_rectangle_mesh(x0, y0, w, h, nx, ny, alternate);
    std::vector<int32_t> all(mesh.tris.size());
    for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int32_t>(i);
    BodyOptions opt;
    opt.name = std::move(name);
    opt.material = material;
    opt.fixed = fixed;
    opt.velocity = velocity;
    return add_bodies(m, mesh, all, opt);
}

/// Nodes of body b whose reference position satisfies pred.
template <class Pred>
std::vector<NodeId> select_nodes(const Model& m, BodyId b, Pred pred) {
    std::vector<NodeId> out;
    for (NodeId i = m.bodies[b].node_begin; i < m.bodies[b].node_end; ++i) {
        if (pred(m.node_x0[i])) out.push_back(i);
    }
    return out;
}

}  // namespace fdem::scenes
