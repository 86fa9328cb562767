// Scene builders shared by tests, benchmarks and examples (like Box2D's shared/).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
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

/// Renumber the nodes and triangles of a mesh by a random permutation (same geometry), so that
/// consecutive ids are far apart in space: the worst case for memory locality.
inline void shuffle_mesh(MeshData& mesh, uint32_t seed = 12345) {
    std::mt19937 rng(seed);
    std::vector<int32_t> perm(mesh.nodes.size());  // old node -> new node
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), rng);
    std::vector<Vec2> nodes(mesh.nodes.size());
    for (size_t i = 0; i < perm.size(); ++i) nodes[static_cast<size_t>(perm[i])] = mesh.nodes[i];
    mesh.nodes = std::move(nodes);
    for (auto& t : mesh.tris) {
        for (auto& n : t) n = perm[static_cast<size_t>(n)];
    }
    for (auto& l : mesh.lines) {
        for (auto& n : l) n = perm[static_cast<size_t>(n)];
    }
    for (auto& p : mesh.points) p = perm[static_cast<size_t>(p)];
    std::shuffle(mesh.tris.begin(), mesh.tris.end(), rng);  // every triangle has tag 1 here
}

/// Options of the continuum block scene used by the benchmarks and the determinism test.
struct BlockOptions {
    int64_t num_tris = 1 << 14;  ///< about this many triangles (n x n cells, 2 per cell)
    bool gravity = false;        ///< g = (0, -9.81) m/s^2
    bool clamp = false;          ///< bottom edge held by a zero-velocity support
    bool shuffled = false;       ///< random node and triangle numbering (see shuffle_mesh)
    Real viscosity = 0;          ///< material viscosity eta [Pa s]
};

/// A 1 m x 1 m elastic block (paper material, nu = 0.25) vibrating in its first modes: initial
/// velocity v = 0.1 m/s (sin(pi y), sin(pi x)) sin(pi x) sin(pi y) gives strains ~1e-4, so every
/// triangle is stressed from the first steps on.
inline Model make_block(const BlockOptions& o) {
    const int n = std::max(1, static_cast<int>(std::lround(std::sqrt(o.num_tris / 2.0))));
    Model m;
    Material mat = paper_material("block", 1e9, 0.25, 1000.0);
    mat.viscosity = o.viscosity;
    m.materials.push_back(mat);
    if (o.gravity) m.gravity = {0, -9.81};
    MeshData mesh = make_rectangle_mesh(0, 0, 1, 1, n, n, true);
    if (o.shuffled) shuffle_mesh(mesh);
    std::vector<int32_t> all(mesh.tris.size());
    std::iota(all.begin(), all.end(), 0);
    BodyOptions opt;
    opt.name = "block";
    add_bodies(m, mesh, all, opt);
    const Real pi = std::acos(-1.0);
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        const Vec2 p = m.node_x0[i];
        const Real s = 0.1 * std::sin(pi * p.x) * std::sin(pi * p.y);
        m.node_v0[i] = {s * std::sin(pi * p.y), s * std::sin(pi * p.x)};
    }
    if (o.clamp) {
        BoundaryCondition bc;
        bc.name = "bottom";
        bc.nodes = select_nodes(m, 0, [](Vec2 p) { return p.y < 1e-12; });
        bc.has_x = bc.has_y = true;
        for (NodeId i : bc.nodes) m.node_v0[i] = {};
        m.bcs.push_back(bc);
    }
    finalize_model(m);
    return m;
}

}  // namespace fdem::scenes
