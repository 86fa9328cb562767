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
    for (size_t i = 0; i < all.size(); ++i)
        all[i] = static_cast<int32_t>(i);
    BodyOptions opt;
    opt.name = std::move(name);
    opt.material = material;
    opt.fixed = fixed;
    opt.velocity = velocity;
    return add_bodies(m, mesh, all, opt);
}

/// Add a structured rectangle body of 6-node triangles (make_rectangle_mesh_order2, same
/// corners and diagonals as add_rectangle) as composite elements, or as four CSTs per 6-node
/// triangle with element = ElementKind::Cst (issue #7). Returns the mesh-node -> model-node map.
inline std::vector<NodeId> add_rectangle_order2(Model& m, Real x0, Real y0, Real w, Real h, int nx,
                                                int ny, int32_t material,
                                                ElementKind element = ElementKind::Composite6,
                                                bool fixed = false, Vec2 velocity = {},
                                                bool alternate = false, std::string name = "rect") {
    const MeshData mesh = make_rectangle_mesh_order2(x0, y0, w, h, nx, ny, alternate);
    std::vector<int32_t> all(mesh.tris.size());
    for (size_t i = 0; i < all.size(); ++i)
        all[i] = static_cast<int32_t>(i);
    BodyOptions opt;
    opt.name = std::move(name);
    opt.material = material;
    opt.fixed = fixed;
    opt.velocity = velocity;
    opt.element = element;
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
    for (size_t i = 0; i < perm.size(); ++i)
        nodes[static_cast<size_t>(perm[i])] = mesh.nodes[i];
    mesh.nodes = std::move(nodes);
    for (auto& t : mesh.tris) {
        for (auto& n : t)
            n = perm[static_cast<size_t>(n)];
    }
    for (auto& l : mesh.lines) {
        for (auto& n : l)
            n = perm[static_cast<size_t>(n)];
    }
    for (auto& p : mesh.points)
        p = perm[static_cast<size_t>(p)];
    std::shuffle(mesh.tris.begin(), mesh.tris.end(), rng);  // every triangle has tag 1 here
}

/// Options of the continuum block scene used by the benchmarks and the determinism test.
struct BlockOptions {
    int64_t num_tris = 1 << 14;  ///< about this many triangles (n x n cells, 2 per cell)
    bool gravity = false;        ///< g = (0, -9.81) m/s^2
    bool clamp = false;          ///< bottom edge held by a zero-velocity support
    bool shuffled = false;       ///< random node and triangle numbering (see shuffle_mesh)
    Real viscosity = 0;          ///< material viscosity eta [Pa s]
    /// every internal edge an intact cohesive joint (every triangle its own three nodes, spec
    /// fracture.md §1.2) with strengths far above the block's stresses (~1e5 Pa): f_t = 1 MPa,
    /// c = 2 MPa, p = p_s = 10 E, so no joint softens
    bool jointed = false;
};

/// A 1 m x 1 m elastic block (paper material, nu = 0.25) vibrating in its first modes: initial
/// velocity v = 0.1 m/s (sin(pi y), sin(pi x)) sin(pi x) sin(pi y) gives strains ~1e-4, so every
/// triangle is stressed from the first steps on.
inline Model make_block(const BlockOptions& o) {
    const int n = std::max(1, static_cast<int>(std::lround(std::sqrt(o.num_tris / 2.0))));
    Model m;
    Material mat = paper_material("block", 1e9, 0.25, 1000.0);
    mat.viscosity = o.viscosity;
    if (o.jointed) {
        mat.has_fracture = true;
        mat.fracture.tensile_strength = 1e6;
        mat.fracture.cohesion = 2e6;
        mat.fracture.friction_angle = 0.5;
        mat.fracture.fracture_energy_I = 100;
        mat.fracture.fracture_energy_II = 200;
        mat.fracture.penalty = mat.fracture.shear_penalty = 10 * mat.youngs_modulus;
    }
    m.materials.push_back(mat);
    if (o.gravity) m.gravity = {0, -9.81};
    MeshData mesh = make_rectangle_mesh(0, 0, 1, 1, n, n, true);
    if (o.shuffled) shuffle_mesh(mesh);
    std::vector<int32_t> all(mesh.tris.size());
    std::iota(all.begin(), all.end(), 0);
    BodyOptions opt;
    opt.name = "block";
    opt.fracture = o.jointed;
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
        for (NodeId i : bc.nodes)
            m.node_v0[i] = {};
        m.bcs.push_back(bc);
    }
    finalize_model(m);
    return m;
}

/// Options of the contact-heavy pack (issue "performance", scene b).
struct PackOptions {
    int blocks_x = 100;     ///< blocks per row
    int blocks_y = 100;     ///< rows: blocks_x * blocks_y bodies of two triangles each
    Real size = 0.01;       ///< block edge [m]
    Real gap = 0.001;       ///< nominal gap between neighbours [m] (< the default contact skin)
    Real speed = 20;        ///< each half moves towards the other at this speed [m/s]
    bool shuffled = false;  ///< bodies added in random order (ids far apart in space)
    uint32_t seed = 2024;   ///< position and velocity jitter
    /// brick bond: every odd row is shifted by half a pitch (masonry), so each block touches
    /// two blocks above and two below
    bool brick_bond = false;
    /// converging field instead of two halves: v = -speed (p - c) / (half extent) per axis (c
    /// the pack centre), so every gap closes at about the same time (a contact-saturated pack,
    /// issue #16); the jitter is the same as for the halves
    bool converge = false;
    /// resting blocks added before the pack, in a row far from it (no contact): their nodes take
    /// the first ids, so the pairs in contact lie in the later ids only
    int idle_blocks = 0;
};

/// Contact-heavy pack: blocks_x x blocks_y square blocks (two triangles each, so every node is
/// a boundary node and the diagonal is a chord) on a raster with small gaps. The left half
/// moves at +speed, the right half at -speed in x; every block gets a seeded jitter of
/// +-gap/4 in position and +-speed/20 in velocity so that the whole pack is in relative motion.
/// Smooth contact, paper material (E = 1 GPa, nu = 0.25, rho = 1000 kg/m^3).
inline Model make_contact_pack(const PackOptions& o) {
    Model m;
    m.materials.push_back(paper_material("block", 1e9, 0.25, 1000.0));
    std::mt19937 rng(o.seed);
    std::uniform_real_distribution<Real> u(-1.0, 1.0);
    const int n = o.blocks_x * o.blocks_y;
    std::vector<int> order(static_cast<size_t>(n));
    std::iota(order.begin(), order.end(), 0);
    if (o.shuffled) std::shuffle(order.begin(), order.end(), rng);
    MeshData mesh;
    mesh.nodes.reserve(4 * static_cast<size_t>(n));
    mesh.tris.reserve(2 * static_cast<size_t>(n));
    std::vector<Vec2> body_v;  // velocity per block, in the order the blocks are added
    body_v.reserve(static_cast<size_t>(n));
    const Real pitch = o.size + o.gap;
    const Real half_w = 0.5 * (o.blocks_x * pitch + (o.brick_bond ? 0.5 * pitch : 0.0));
    const Real half_h = 0.5 * o.blocks_y * pitch;
    // a square block of two triangles with its lower left corner at (x0, y0)
    const auto add_block = [&](Real x0, Real y0) {
        const int32_t b = static_cast<int32_t>(mesh.nodes.size());
        mesh.nodes.push_back({x0, y0});
        mesh.nodes.push_back({x0 + o.size, y0});
        mesh.nodes.push_back({x0 + o.size, y0 + o.size});
        mesh.nodes.push_back({x0, y0 + o.size});
        mesh.tris.push_back({b, b + 1, b + 2});
        mesh.tris.push_back({b, b + 2, b + 3});
    };
    for (int k = 0; k < o.idle_blocks; ++k) {
        add_block(k * 2 * pitch, -10 * (o.blocks_y * pitch + o.size));
        body_v.push_back({0, 0});
    }
    for (int k : order) {
        const int i = k % o.blocks_x, j = k / o.blocks_x;
        const Real shift = o.brick_bond && j % 2 == 1 ? 0.5 * pitch : 0.0;
        const Real x0 = i * pitch + shift + 0.25 * o.gap * u(rng);
        const Real y0 = j * pitch + 0.25 * o.gap * u(rng);
        add_block(x0, y0);
        if (o.converge) {
            // jitter: 5 % of the closing speed of neighbours, speed x pitch / half extent
            const Real jit = 0.05 * o.speed * pitch / half_w;
            const Real cx = x0 + 0.5 * o.size - half_w, cy = y0 + 0.5 * o.size - half_h;
            const Real vx = -o.speed * cx / half_w + jit * u(rng);
            body_v.push_back({vx, -o.speed * cy / half_h + jit * u(rng)});
        } else {
            const Real vx = (2 * i < o.blocks_x ? o.speed : -o.speed) + 0.05 * o.speed * u(rng);
            body_v.push_back({vx, 0.05 * o.speed * u(rng)});
        }
    }
    mesh.tri_tag.assign(mesh.tris.size(), 1);
    std::vector<int32_t> all(mesh.tris.size());
    std::iota(all.begin(), all.end(), 0);
    BodyOptions opt;
    opt.name = "blocks";
    add_bodies(m, mesh, all, opt);  // one body per block, in mesh order
    for (BodyId b = 0; b < m.num_bodies(); ++b) {
        for (NodeId i = m.bodies[b].node_begin; i < m.bodies[b].node_end; ++i)
            m.node_v0[i] = body_v[static_cast<size_t>(b)];
    }
    m.contact.algorithm = ContactAlgorithm::Smooth;
    finalize_model(m);
    return m;
}

/// Options of the particle raster in a box (the paper's Fig. 1, scene c).
struct ParticleOptions {
    int nx = 100;          ///< particles per row
    int ny = 100;          ///< rows
    Real spacing = 0.01;   ///< raster pitch [m]
    Real radius = 0.0045;  ///< largest vertex distance from the particle centre [m]
    int min_vertices = 5;  ///< polygon vertices, uniform in [min_vertices, max_vertices]
    int max_vertices = 8;
    Real v_max = 5;             ///< initial velocity components uniform in [-v_max, v_max] [m/s]
    Real wall = 0.02;           ///< wall thickness [m]
    Real youngs_modulus = 1e8;  ///< particles [Pa] (walls: the same material, but fixed)
    uint32_t seed = 7;
};

/// Raster of nx x ny irregular deformable particles in a closed box. Each particle is a random
/// star-shaped polygon (min..max vertices at jittered angles and radii 0.6..1 x radius) fanned
/// from its centre: one triangle per edge, one interior node. Random initial velocity per
/// particle (seeded). Four fixed wall bodies (structured rectangles) enclose the raster with a
/// clearance of half a pitch. Smooth contact; rho = 1000 kg/m^3, nu = 0.25.
inline Model make_particle_box(const ParticleOptions& o) {
    Model m;
    m.materials.push_back(paper_material("particle", o.youngs_modulus, 0.25, 1000.0));
    std::mt19937 rng(o.seed);
    std::uniform_real_distribution<Real> u(0.0, 1.0);
    const Real pi = std::acos(-1.0);
    MeshData mesh;
    std::vector<Vec2> body_v;
    for (int j = 0; j < o.ny; ++j) {
        for (int i = 0; i < o.nx; ++i) {
            const Vec2 c = {(i + 0.5) * o.spacing, (j + 0.5) * o.spacing};
            const int k =
                o.min_vertices +
                static_cast<int>(u(rng) * (o.max_vertices - o.min_vertices + 1) * 0.999999);
            const int32_t centre = static_cast<int32_t>(mesh.nodes.size());
            mesh.nodes.push_back(c);
            const Real a0 = 2 * pi * u(rng);
            for (int q = 0; q < k; ++q) {
                // angles stay increasing (jitter < half a sector), so the fan is valid
                const Real a = a0 + 2 * pi * (q + 0.4 * (u(rng) - 0.5)) / k;
                const Real r = o.radius * (0.6 + 0.4 * u(rng));
                mesh.nodes.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
            }
            for (int q = 0; q < k; ++q)
                mesh.tris.push_back({centre, centre + 1 + q, centre + 1 + (q + 1) % k});
            body_v.push_back({o.v_max * (2 * u(rng) - 1), o.v_max * (2 * u(rng) - 1)});
        }
    }
    mesh.tri_tag.assign(mesh.tris.size(), 1);
    std::vector<int32_t> all(mesh.tris.size());
    std::iota(all.begin(), all.end(), 0);
    BodyOptions opt;
    opt.name = "particles";
    add_bodies(m, mesh, all, opt);
    for (BodyId b = 0; b < m.num_bodies(); ++b) {
        for (NodeId i = m.bodies[b].node_begin; i < m.bodies[b].node_end; ++i)
            m.node_v0[i] = body_v[static_cast<size_t>(b)];
    }
    // walls: bottom, top (full width incl. corners), left, right; clearance half a pitch
    const Real w = o.nx * o.spacing, h = o.ny * o.spacing, t = o.wall;
    const int cells = std::max(1, static_cast<int>(std::lround(t / o.spacing * 2)));
    auto cells_along = [&](Real len) {
        return std::max(1, static_cast<int>(len / (0.5 * o.spacing)));
    };
    add_rectangle(m, -t, -t, w + 2 * t, t, cells_along(w + 2 * t), cells, 0, true, {}, false,
                  "wall_bottom");
    add_rectangle(m, -t, h, w + 2 * t, t, cells_along(w + 2 * t), cells, 0, true, {}, false,
                  "wall_top");
    add_rectangle(m, -t, 0, t, h, cells, cells_along(h), 0, true, {}, false, "wall_left");
    add_rectangle(m, w, 0, t, h, cells, cells_along(h), 0, true, {}, false, "wall_right");
    m.contact.algorithm = ContactAlgorithm::Smooth;
    finalize_model(m);
    return m;
}

/// A mix for the parallel element pass tests: one 40 x 40 composite body (12800 sub-triangles,
/// 50 chunks of 256, so the pass runs in parallel) and 30 small bodies alternating kinds (CST,
/// composite, order-2 CST) and two materials, which the chunk merging must respect. Finalized.
inline Model make_mixed_element_model() {
    Model m;
    m.materials.push_back(paper_material("p", 1e9, 0.45));
    m.materials.push_back(paper_material("q", 2e9, 0.3));
    add_rectangle_order2(m, 0, 0, 1, 1, 40, 40, 0);
    for (int k = 0; k < 30; ++k) {
        const Real x0 = 2.0 + 0.3 * k;
        if (k % 3 == 0) {
            add_rectangle(m, x0, 0, 0.2, 0.2, 2, 2, k % 2);
        } else {
            add_rectangle_order2(m, x0, 0, 0.2, 0.2, 2, 1, k % 2,
                                 k % 3 == 1 ? ElementKind::Composite6 : ElementKind::Cst);
        }
    }
    finalize_model(m);
    return m;
}

}  // namespace fdem::scenes
