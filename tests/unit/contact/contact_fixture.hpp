// Shared helpers of the contact tests: models built from hand-made or structured meshes, and a
// brute-force evaluation of a body's distance field at a point.
#pragma once

#include <algorithm>
#include <random>
#include <vector>

#include "contact/field.hpp"
#include "fdem/build.hpp"
#include "fdem/mesh.hpp"
#include "fdem/model.hpp"

namespace fdem::testing {

inline MeshData mesh_of(std::vector<Vec2> nodes, std::vector<std::array<int32_t, 3>> tris) {
    MeshData m;
    m.file = "test";
    m.nodes = std::move(nodes);
    m.tris = std::move(tris);
    m.tri_tag.assign(m.tris.size(), 1);
    return m;
}

inline std::vector<int32_t> all_tris(const MeshData& mesh) {
    std::vector<int32_t> ids(mesh.tris.size());
    for (size_t i = 0; i < ids.size(); ++i)
        ids[i] = static_cast<int32_t>(i);
    return ids;
}

/// Perturb the nodes of a structured mesh that are not on its bounding box by up to
/// +-amp in each direction (boundary nodes stay on the faces).
inline void perturb_interior(MeshData& mesh, Real amp, unsigned seed) {
    Vec2 lo = mesh.nodes[0], hi = lo;
    for (const Vec2& p : mesh.nodes) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> u(-amp, amp);
    for (Vec2& p : mesh.nodes) {
        if (p.x == lo.x || p.x == hi.x || p.y == lo.y || p.y == hi.y) continue;
        p.x += u(rng);
        p.y += u(rng);
    }
}

/// A model with one material (E, rho, nu = 0) and contact enabled; bodies are added by the
/// caller with add_body() and then finalize() is called.
struct ModelBuilder {
    Model m;
    explicit ModelBuilder(Real E = 1e9, Real rho = 1000) {
        Material mat;
        mat.name = "rock";
        mat.density = rho;
        mat.youngs_modulus = E;
        mat.poisson_ratio = 0;
        m.materials.push_back(mat);
        m.contact.algorithm = ContactAlgorithm::Smooth;
    }
    int32_t add_material(Real E, Real rho) {
        Material mat = m.materials[0];
        mat.name = "mat" + std::to_string(m.materials.size());
        mat.youngs_modulus = E;
        mat.density = rho;
        m.materials.push_back(mat);
        return static_cast<int32_t>(m.materials.size()) - 1;
    }
    void add_body(const MeshData& mesh, bool fixed = false, Vec2 velocity = {},
                  int32_t material = 0) {
        BodyOptions opt;
        opt.material = material;
        // (append, not "b" + std::string&&: GCC 12 warns -Wrestrict on that inlined insert,
        // a false positive, GCC bug 105329)
        opt.name = "b";
        opt.name += std::to_string(m.num_bodies());
        opt.fixed = fixed;
        opt.velocity = velocity;
        add_bodies(m, mesh, all_tris(mesh), opt);
    }
    Model& finalize() {
        finalize_model(m);
        topo = build_topology(m);
        return m;
    }
    ContactTopology topo;  ///< contact topology of m, built by finalize()
};

/// Rigidly rotate (by angle a about c) and translate (by t) a mesh.
inline MeshData moved(MeshData mesh, Real a, Vec2 c, Vec2 t) {
    for (Vec2& p : mesh.nodes) {
        const Vec2 r = p - c;
        p = c + Vec2{std::cos(a) * r.x - std::sin(a) * r.y, std::sin(a) * r.x + std::cos(a) * r.y} +
            t;
    }
    return mesh;
}

/// Reference position of contact node i (real or virtual).
inline Vec2 contact_node_x0(const Model& m, const ContactTopology& cm, NodeId i) {
    if (i < cm.num_real_nodes) return m.node_x0[i];
    const auto v = static_cast<size_t>(i - cm.num_real_nodes);
    Vec2 x;
    for (int k = 0; k < 3; ++k)
        x += cm.virt_weight[v][k] * m.node_x0[cm.virt_parent[v][k]];
    return x;
}

/// Field of body b at point x in the reference configuration: scans all contactor
/// sub-triangles of b and uses the one with the largest min N_i. Returns false if x is in none.
inline bool field_at(const Model& m, const ContactTopology& cm, BodyId b, Vec2 x, FieldSample& out,
                     int32_t* tri = nullptr) {
    Real best = -1e-12;
    bool found = false;
    for (int32_t t = cm.body_sub_begin[b]; t < cm.body_sub_begin[b + 1]; ++t) {
        const auto& q = cm.sub_tri[t];
        const Vec2 p[3] = {contact_node_x0(m, cm, q[0]), contact_node_x0(m, cm, q[1]),
                           contact_node_x0(m, cm, q[2])};
        FieldSample fs;
        if (!barycentric(p[0], p[1], p[2], x, fs.N)) continue;
        const Real mn = std::min({fs.N[0], fs.N[1], fs.N[2]});
        if (mn < best) continue;
        best = mn;
        const Real dist[3] = {cm.node_dist[q[0]], cm.node_dist[q[1]], cm.node_dist[q[2]]};
        smooth_field(p, dist, fs);
        out = fs;
        if (tri) *tri = t;
        found = true;
    }
    return found;
}

/// Exact distance from x to the closed polygon poly (counter-clockwise vertices).
inline Real polygon_distance(const std::vector<Vec2>& poly, Vec2 x) {
    Real d = 1e300;
    for (size_t i = 0; i < poly.size(); ++i) {
        const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
        const Vec2 ab = b - a;
        const Real s = std::clamp(dot(x - a, ab) / norm2(ab), Real(0), Real(1));
        d = std::min(d, norm(x - (a + s * ab)));
    }
    return d;
}

}  // namespace fdem::testing
