// Model construction: bodies from connected components, derived geometry and masses
// (docs/theory.md §3), contact topology (docs/theory.md §6).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/format.h>

#include "contact/contact.hpp"
#include "element/cst.hpp"
#include "fdem/build.hpp"
#include "fdem/error.hpp"
#include "model/renumber.hpp"

namespace fdem {

namespace {

// Union-find over mesh nodes, used to split a triangle set into connected components.
struct DisjointSets {
    std::vector<int32_t> parent;
    explicit DisjointSets(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
    int32_t find(int32_t a) {
        while (parent[a] != a) {
            parent[a] = parent[parent[a]];
            a = parent[a];
        }
        return a;
    }
    void unite(int32_t a, int32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
};

}  // namespace

void compute_lame(Material& mat) {
    const Real E = mat.youngs_modulus, nu = mat.poisson_ratio;
    // theory eq. 2.5: plane strain uses the 3-D Lame constants; plane stress the reduced lambda
    mat.mu = E / (2.0 * (1.0 + nu));
    if (mat.plane == PlaneMode::Strain) {
        mat.lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    } else {
        mat.lambda = E * nu / (1.0 - nu * nu);
    }
}

std::vector<NodeId> add_bodies(Model& m, const MeshData& mesh, const std::vector<int32_t>& tri_ids,
                               const BodyOptions& opt) {
    const int32_t n_mesh_nodes = static_cast<int32_t>(mesh.nodes.size());
    std::vector<NodeId> map(static_cast<size_t>(n_mesh_nodes), kNone);

    // reject degenerate triangles before anything else (tolerance relative to edge length^2)
    for (int32_t t : tri_ids) {
        const auto& n = mesh.tris[static_cast<size_t>(t)];
        const Vec2 a = mesh.nodes[n[0]], b = mesh.nodes[n[1]], c = mesh.nodes[n[2]];
        const Real area = signed_area(a, b, c);
        const Real l2 = std::max({norm2(b - a), norm2(c - b), norm2(a - c)});
        if (!(std::abs(area) > 1e-12 * l2)) {
            throw InputError(
                {mesh.file, 0, 0}, fmt::format("triangle {}", t + 1),
                fmt::format(
                    "triangle {} (nodes {}, {}, {}) of body \"{}\" is degenerate (area {:.3g} "
                    "m^2); remove it or fix the mesh (e.g. remesh with gmsh)",
                    t + 1, n[0] + 1, n[1] + 1, n[2] + 1, opt.name, area));
        }
    }

    // connected components: triangles sharing a node belong to the same body
    DisjointSets sets(static_cast<size_t>(n_mesh_nodes));
    for (int32_t t : tri_ids) {
        const auto& n = mesh.tris[static_cast<size_t>(t)];
        sets.unite(n[0], n[1]);
        sets.unite(n[0], n[2]);
    }
    // group triangles by component root, components ordered by their first triangle (file order)
    std::vector<int32_t> sorted = tri_ids;
    std::sort(sorted.begin(), sorted.end());
    std::vector<int32_t> roots;
    std::vector<std::vector<int32_t>> comp_tris;
    {
        std::vector<int32_t> root_to_comp(static_cast<size_t>(n_mesh_nodes), -1);
        for (int32_t t : sorted) {
            const int32_t r = sets.find(mesh.tris[static_cast<size_t>(t)][0]);
            if (root_to_comp[r] < 0) {
                root_to_comp[r] = static_cast<int32_t>(comp_tris.size());
                comp_tris.emplace_back();
            }
            comp_tris[static_cast<size_t>(root_to_comp[r])].push_back(t);
        }
    }

    const int32_t group = static_cast<int32_t>(m.group_names.size());
    m.group_names.push_back(opt.name);
    for (const auto& tris : comp_tris) {
        Body body;
        body.name = opt.name;
        body.group = group;
        body.material = opt.material;
        body.fixed = opt.fixed;
        body.node_begin = m.num_nodes();
        body.tri_begin = m.num_tris();
        const BodyId bid = m.num_bodies();
        for (int32_t t : tris) {
            auto n = mesh.tris[static_cast<size_t>(t)];
            std::array<NodeId, 3> ids{};
            for (int k = 0; k < 3; ++k) {
                if (map[n[k]] == kNone) {
                    map[n[k]] = m.num_nodes();
                    m.node_x0.push_back(mesh.nodes[n[k]]);
                    m.node_v0.push_back(opt.velocity);
                    m.node_body.push_back(bid);
                }
                ids[k] = map[n[k]];
            }
            // re-orient counter-clockwise
            if (signed_area(m.node_x0[ids[0]], m.node_x0[ids[1]], m.node_x0[ids[2]]) < 0) {
                std::swap(ids[1], ids[2]);
            }
            m.tri_nodes.push_back(ids);
            m.tri_body.push_back(bid);
            m.tri_material.push_back(opt.material);
        }
        body.node_end = m.num_nodes();
        body.tri_end = m.num_tris();
        m.bodies.push_back(body);
    }
    return map;
}

void finalize_model(Model& m) {
    for (Material& mat : m.materials)
        compute_lame(mat);
    renumber_spatially(m);  // first: everything below is derived from the final numbering

    const size_t nn = static_cast<size_t>(m.num_nodes());
    const size_t nt = static_cast<size_t>(m.num_tris());
    m.node_mass.assign(nn, 0.0);
    m.node_inv_mass.assign(nn, 0.0);
    m.tri_dm_inv.resize(nt);
    m.tri_area0.resize(nt);
    m.tri_eta.resize(nt);

    for (TriId t = 0; t < m.num_tris(); ++t) {
        const auto& n = m.tri_nodes[t];
        const Vec2 X0 = m.node_x0[n[0]], X1 = m.node_x0[n[1]], X2 = m.node_x0[n[2]];
        const Mat2 Dm = columns(X1 - X0, X2 - X0);
        m.tri_dm_inv[t] = inverse(Dm);
        m.tri_area0[t] = 0.5 * det(Dm);
        const Material& mat = m.materials[m.tri_material[t]];

        // lumped mass: rho A0 / 3 to each node (theory eq. 3.4)
        for (int k = 0; k < 3; ++k)
            m.node_mass[n[k]] += mat.density * m.tri_area0[t] / 3.0;

        // element viscosity: eta + 2 h xi sqrt(E rho), h = smallest altitude (theory eq. 2.6)
        const Real lmax = std::max({norm(X1 - X0), norm(X2 - X1), norm(X0 - X2)});
        const Real h = 2.0 * m.tri_area0[t] / lmax;
        m.tri_eta[t] = mat.viscosity +
                       2.0 * h * mat.damping_ratio * std::sqrt(mat.youngs_modulus * mat.density);
    }
    for (size_t i = 0; i < nn; ++i) {
        const bool fixed = m.bodies[m.node_body[i]].fixed;
        m.node_inv_mass[i] = (fixed || m.node_mass[i] <= 0) ? 0.0 : 1.0 / m.node_mass[i];
    }
    std::stable_sort(m.kicks.begin(), m.kicks.end(),
                     [](const VelocityKick& a, const VelocityKick& b) { return a.time < b.time; });

    build_contact_topology(m);
    m.element_schedule = build_element_schedule(m);
}

Real stable_time_step(const Model& m, TriId* limiting_tri) {
    Real dt = std::numeric_limits<Real>::infinity();
    TriId arg = kNone;
    for (TriId t = 0; t < m.num_tris(); ++t) {
        if (m.bodies[m.tri_body[t]].fixed) continue;
        const Real dte = element_critical_dt(m, t);
        if (dte < dt) {
            dt = dte;
            arg = t;
        }
    }
    const Real dtc = contact_stable_dt(m);
    if (dtc < dt) {
        dt = dtc;
        arg = kNone;
    }
    if (limiting_tri) *limiting_tri = arg;
    return dt;
}

}  // namespace fdem
