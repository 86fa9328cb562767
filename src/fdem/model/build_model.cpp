// Model construction: bodies from connected components, derived geometry and masses
// (docs/theory.md §3), contact topology (docs/theory.md §6).
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
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

namespace {

/// Initial velocity of the nodes of one piece from the affine field of its entry (theory
/// eq. 5.5). Leaves node_v0 = opt.velocity (bitwise) when the field has no spin or gradient.
void set_initial_velocity(Model& m, const Body& b, const BodyOptions& opt) {
    const Mat2& G = opt.velocity_gradient;
    const Real w = opt.angular_velocity;
    if (w == 0 && G.xx == 0 && G.xy == 0 && G.yx == 0 && G.yy == 0) return;
    // mass centre of the piece: the area-weighted triangle centroids, which is also the centre
    // of the lumped masses rho A / 3 (theory eq. 3.4) for the one density of the entry
    Vec2 c{0, 0};
    Real area = 0;
    for (TriId t = b.tri_begin; t < b.tri_end; ++t) {
        const auto& n = m.tri_nodes[static_cast<size_t>(t)];
        const Vec2 p0 = m.node_x0[n[0]], p1 = m.node_x0[n[1]], p2 = m.node_x0[n[2]];
        const Real a = signed_area(p0, p1, p2);
        c += (a / 3.0) * (p0 + p1 + p2);
        area += a;
    }
    c = c / area;
    const Vec2 o = opt.origin_centroid ? c : opt.origin;
    if (opt.rigid_pieces) {
        // rigid: translation = the field at c, spin = omega + the vorticity of G
        const Vec2 vc = opt.velocity + w * perp(c - o) + G * (c - o);
        const Real spin = w + 0.5 * (G.yx - G.xy);
        for (NodeId i = b.node_begin; i < b.node_end; ++i)
            m.node_v0[static_cast<size_t>(i)] =
                vc + spin * perp(m.node_x0[static_cast<size_t>(i)] - c);
        return;
    }
    for (NodeId i = b.node_begin; i < b.node_end; ++i) {
        const Vec2 r = m.node_x0[static_cast<size_t>(i)] - o;
        m.node_v0[static_cast<size_t>(i)] = opt.velocity + w * perp(r) + G * r;
    }
}

}  // namespace

NodeId MeshNodeMap::operator[](int32_t q) const {
    const auto it = std::lower_bound(mesh_nodes.begin(), mesh_nodes.end(), q);
    if (it == mesh_nodes.end() || *it != q) return kNone;
    return model_nodes[static_cast<size_t>(it - mesh_nodes.begin())];
}

std::vector<NodeId> add_bodies(Model& m, const MeshData& mesh, const std::vector<int32_t>& tri_ids,
                               const BodyOptions& opt) {
    const MeshNodeMap sparse = add_bodies_mapped(m, mesh, tri_ids, opt);
    std::vector<NodeId> map(mesh.nodes.size(), kNone);
    for (size_t i = 0; i < sparse.mesh_nodes.size(); ++i) {
        map[static_cast<size_t>(sparse.mesh_nodes[i])] = sparse.model_nodes[i];
    }
    return map;
}

MeshNodeMap add_bodies_mapped(Model& m, const MeshData& mesh, const std::vector<int32_t>& tri_ids,
                              const BodyOptions& opt) {
    const bool second = mesh.second_order();
    const ElementKind kind =
        opt.element.value_or(second ? ElementKind::Composite6 : ElementKind::Cst);
    if (kind == ElementKind::Composite6 && !second) {
        throw InputError({mesh.file, 0, 0}, "element",
                         fmt::format("body \"{}\": the composite element needs a mesh of 6-node "
                                     "triangles (Gmsh type 9), but mesh '{}' has 3-node "
                                     "triangles; mesh it at order 2 (gmsh -order 2) or use "
                                     "element = \"cst\"",
                                     opt.name, mesh.file));
    }

    // Element t of the mesh as the triangles of the model, counter-clockwise: itself for a
    // 3-node triangle; for a 6-node triangle its four sub-triangles in the order of the Body
    // contract (model.hpp), with the paper's perimeter numbering n1..n6 (spec §3.3)
    auto sub_triangles = [&](int32_t t, std::array<std::array<int32_t, 3>, 4>& out) -> int {
        std::array<int32_t, 3> c = mesh.tris[static_cast<size_t>(t)];
        if (!second) {
            if (signed_area(mesh.nodes[c[0]], mesh.nodes[c[1]], mesh.nodes[c[2]]) < 0) {
                std::swap(c[1], c[2]);
            }
            out[0] = c;
            return 1;
        }
        std::array<int32_t, 3> mid = mesh.tri_mid[static_cast<size_t>(t)];  // on c0c1, c1c2, c2c0
        if (signed_area(mesh.nodes[c[0]], mesh.nodes[c[1]], mesh.nodes[c[2]]) < 0) {
            // corners (c0, c2, c1): edges c0c2, c2c1, c1c0 carry mid[2], mid[1], mid[0]
            std::swap(c[1], c[2]);
            std::swap(mid[0], mid[2]);
        }
        const int32_t n1 = c[0], n2 = mid[0], n3 = c[1], n4 = mid[1], n5 = c[2], n6 = mid[2];
        out = {{{n1, n2, n6}, {n2, n3, n4}, {n6, n4, n5}, {n2, n4, n6}}};
        return 4;
    };

    // reject degenerate triangles before anything else (tolerance relative to edge length^2);
    // for a 6-node triangle each sub-triangle must be counter-clockwise too, else a mid-edge
    // node sits on the wrong side of the chord between its neighbours (a badly curved edge)
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
        if (second) {
            std::array<std::array<int32_t, 3>, 4> sub{};
            sub_triangles(t, sub);
            for (int k = 0; k < 4; ++k) {
                const auto& q = sub[static_cast<size_t>(k)];
                const Vec2 p0 = mesh.nodes[q[0]], p1 = mesh.nodes[q[1]], p2 = mesh.nodes[q[2]];
                const Real sa = signed_area(p0, p1, p2);
                const Real sl2 = std::max({norm2(p1 - p0), norm2(p2 - p1), norm2(p0 - p2)});
                if (!(sa > 1e-12 * sl2)) {
                    throw InputError(
                        {mesh.file, 0, 0}, fmt::format("triangle {}", t + 1),
                        fmt::format("6-node triangle {} (corner nodes {}, {}, {}) of body \"{}\" "
                                    "has a degenerate or inverted sub-triangle {} (nodes {}, {}, "
                                    "{}, area {:.3g} m^2): a mid-edge node is far from its "
                                    "edge; straighten the edges or refine the mesh",
                                    t + 1, n[0] + 1, n[1] + 1, n[2] + 1, opt.name, k + 1, q[0] + 1,
                                    q[1] + 1, q[2] + 1, sa));
                }
            }
        }
    }

    // a triangle inverted relative to a neighbour folds the mesh over itself (the reorientation
    // above hides it): across every shared edge the two opposite corners must lie on opposite
    // sides (for 6-node triangles the corners decide; their sub-triangles are checked above)
    {
        std::map<std::pair<int32_t, int32_t>, std::pair<int32_t, int32_t>> first_on_edge;
        for (int32_t t : tri_ids) {
            const auto& n = mesh.tris[static_cast<size_t>(t)];
            for (int e = 0; e < 3; ++e) {
                const int32_t a = n[e], b = n[(e + 1) % 3], c = n[(e + 2) % 3];
                const auto [it, added] =
                    first_on_edge.try_emplace({std::min(a, b), std::max(a, b)}, t, c);
                if (added) continue;
                const auto [u, d] = it->second;
                const Vec2 pa = mesh.nodes[a], pb = mesh.nodes[b];
                if (signed_area(pa, pb, mesh.nodes[c]) * signed_area(pa, pb, mesh.nodes[d]) > 0) {
                    throw InputError(
                        {mesh.file, 0, 0}, fmt::format("triangle {}", t + 1),
                        fmt::format("triangles {} and {} of body \"{}\" overlap: they share the "
                                    "edge of nodes {} and {} and lie on the same side of it, so "
                                    "one of them is inverted (the mesh folds over itself); fix "
                                    "the node positions or remesh (e.g. with gmsh)",
                                    u + 1, t + 1, opt.name, std::min(a, b) + 1,
                                    std::max(a, b) + 1));
                }
            }
        }
    }

    // the mesh nodes these triangles use, ascending; local index = position in this list (an
    // order-preserving renumbering, so the union-find below links the same nodes as one over
    // the whole mesh would, at a cost independent of the mesh size)
    MeshNodeMap out;
    std::vector<int32_t>& used = out.mesh_nodes;
    used.reserve(tri_ids.size() * (second ? 6 : 3));
    for (int32_t t : tri_ids) {
        const auto& n = mesh.tris[static_cast<size_t>(t)];
        used.insert(used.end(), n.begin(), n.end());
        if (second) {
            const auto& q = mesh.tri_mid[static_cast<size_t>(t)];
            used.insert(used.end(), q.begin(), q.end());
        }
    }
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    const auto local = [&used](int32_t q) {
        return static_cast<int32_t>(std::lower_bound(used.begin(), used.end(), q) - used.begin());
    };

    // connected components: triangles sharing a node belong to the same body
    DisjointSets sets(used.size());
    for (int32_t t : tri_ids) {
        const auto& n = mesh.tris[static_cast<size_t>(t)];
        const int32_t n0 = local(n[0]);
        sets.unite(n0, local(n[1]));
        sets.unite(n0, local(n[2]));
        if (second) {
            for (const int32_t q : mesh.tri_mid[static_cast<size_t>(t)])
                sets.unite(n0, local(q));
        }
    }
    // group triangles by component root, components ordered by their first triangle (file order)
    std::vector<int32_t> sorted = tri_ids;
    std::sort(sorted.begin(), sorted.end());
    std::vector<std::vector<int32_t>> comp_tris;
    {
        std::vector<int32_t> root_to_comp(used.size(), -1);
        for (int32_t t : sorted) {
            const int32_t r = sets.find(local(mesh.tris[static_cast<size_t>(t)][0]));
            if (root_to_comp[r] < 0) {
                root_to_comp[r] = static_cast<int32_t>(comp_tris.size());
                comp_tris.emplace_back();
            }
            comp_tris[static_cast<size_t>(root_to_comp[r])].push_back(t);
        }
    }

    std::vector<NodeId>& map = out.model_nodes;  // by local index
    map.assign(used.size(), kNone);
    const int32_t group = static_cast<int32_t>(m.group_names.size());
    m.group_names.push_back(opt.name);
    for (const auto& tris : comp_tris) {
        Body body;
        body.name = opt.name;
        body.group = group;
        body.material = opt.material;
        body.fixed = opt.fixed;
        body.element = kind;
        body.node_begin = m.num_nodes();
        body.tri_begin = m.num_tris();
        const BodyId bid = m.num_bodies();
        for (int32_t t : tris) {
            std::array<std::array<int32_t, 3>, 4> sub{};
            const int ns = sub_triangles(t, sub);
            for (int s = 0; s < ns; ++s) {
                std::array<NodeId, 3> ids{};
                for (int k = 0; k < 3; ++k) {
                    const int32_t q = sub[static_cast<size_t>(s)][static_cast<size_t>(k)];
                    const auto l = static_cast<size_t>(local(q));
                    if (map[l] == kNone) {
                        map[l] = m.num_nodes();
                        m.node_x0.push_back(mesh.nodes[q]);
                        m.node_v0.push_back(opt.velocity);
                        m.node_body.push_back(bid);
                    }
                    ids[static_cast<size_t>(k)] = map[l];
                }
                m.tri_nodes.push_back(ids);
                m.tri_body.push_back(bid);
                m.tri_material.push_back(opt.material);
            }
        }
        body.node_end = m.num_nodes();
        body.tri_end = m.num_tris();
        m.bodies.push_back(body);
        set_initial_velocity(m, body, opt);
    }
    return out;
}

void finalize_model(Model& m) {
    std::vector<int32_t> node_new;
    finalize_model(m, node_new);
}

void finalize_model(Model& m, std::vector<int32_t>& node_new) {
    for (Material& mat : m.materials)
        compute_lame(mat);
    // first: everything below is derived from the final numbering
    renumber_spatially(m, &node_new);

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

    int32_t slot = 0;  // State::scratch_load slots of each load
    for (Load& ld : m.loads) {
        ld.slot_begin = slot;
        slot += ld.num_slots();
    }

    resolve_contact_params(m);
    m.element_schedule = build_element_schedule(m);
}

Real element_stable_time_step(const Model& m, TriId* limiting_tri) {
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
    if (limiting_tri) *limiting_tri = arg;
    return dt;
}

Real stable_time_step(const Model& m, TriId* limiting_tri) {
    return stable_time_step(m, build_topology(m), limiting_tri);
}

Real stable_time_step(const Model& m, const ContactTopology& t, TriId* limiting_tri) {
    TriId arg = kNone;
    const Real dte = element_stable_time_step(m, &arg);
    const Real dtc = contact_stable_dt(m, t);
    if (dtc < dte) arg = kNone;
    if (limiting_tri) *limiting_tri = arg;
    if (!std::isfinite(dte) || !std::isfinite(dtc)) return std::min(dte, dtc);
    // element and contact stiffness act on the same boundary nodes: the largest eigenvalue of
    // M^-1 (K_e + K_c) is at most the sum of theirs (Weyl), (2/dt)^2 <= (2/dte)^2 + (2/dtc)^2
    // (theory eq. 6.17)
    return 1.0 / std::sqrt(1.0 / (dte * dte) + 1.0 / (dtc * dtc));
}

}  // namespace fdem
