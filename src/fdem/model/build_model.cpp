// Model construction: bodies from connected components, derived geometry and masses
// (docs/theory.md §3), contact topology (docs/theory.md §6).
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <span>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>

#include "contact/contact.hpp"
#include "core/huge_pages.hpp"
#include "element/cst.hpp"
#include "fdem/build.hpp"
#include "fdem/error.hpp"
#include "fracture/joint_law.hpp"
#include "fracture/joint_mesh.hpp"
#include "fracture/joints.hpp"
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

namespace {

/// The nodes, triangles and joints of one connected component `tris` (mesh triangle ids) of a
/// body with fracture (BodyOptions::fracture, spec fracture.md §1.2). Jointed edges: the internal
/// edges between two triangles of opt.fracture_tris (every triangle when both fracture_tris and
/// joint_edges are empty), the edges opt.joint_edges and opt.prebroken_edges. Around every mesh
/// vertex the fan of triangles is cut at the jointed edges; each run (corners connected through
/// unjointed edges) gets its own node copy, created in order of first use by the triangles, so
/// the first copy of a vertex has the smallest id (Model::node_vertex). map[local vertex] = that
/// first copy. Joints: add_edge_joints on the jointed edges (ordered by triangle A, edge slot),
/// law index = material index (finalize_model() makes Joints::laws per material).
template <class SubTriangles, class Local>
void add_jointed_nodes(Model& m, const MeshData& mesh, const std::vector<int32_t>& tris,
                       const BodyOptions& opt, BodyId bid, SubTriangles&& sub_triangles,
                       Local&& local, std::vector<NodeId>& map) {
    using Edge = std::array<int32_t, 2>;  // (smaller, larger) mesh node ids
    auto key = [](int32_t a, int32_t b) { return Edge{std::min(a, b), std::max(a, b)}; };
    auto sorted_keys = [&](const std::vector<std::array<int32_t, 2>>& in) {
        std::vector<Edge> out;
        out.reserve(in.size());
        for (const auto& e : in)
            out.push_back(key(e[0], e[1]));
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
        return out;
    };
    const std::vector<Edge> listed = sorted_keys(opt.joint_edges);
    const std::vector<Edge> prebroken = sorted_keys(opt.prebroken_edges);
    std::vector<int32_t> region = opt.fracture_tris;
    std::sort(region.begin(), region.end());
    const bool all_tris = region.empty() && listed.empty();
    auto in_region = [&](int32_t t) {
        return all_tris || std::binary_search(region.begin(), region.end(), t);
    };

    // model triangles of the component (mesh node ids) and their mesh triangle
    std::vector<std::array<int32_t, 3>> ctri;
    std::vector<int32_t> cparent;
    ctri.reserve(tris.size());
    cparent.reserve(tris.size());
    for (int32_t t : tris) {
        std::array<std::array<int32_t, 3>, 4> sub{};
        const int ns = sub_triangles(t, sub);
        for (int k = 0; k < ns; ++k) {
            ctri.push_back(sub[static_cast<size_t>(k)]);
            cparent.push_back(t);
        }
    }
    // edges (key, triangle, slot) sorted: a shared edge is a run of two
    std::vector<std::tuple<Edge, int32_t, int32_t>> edges;
    edges.reserve(3 * ctri.size());
    for (size_t i = 0; i < ctri.size(); ++i) {
        for (int k = 0; k < 3; ++k)
            edges.emplace_back(
                key(ctri[i][static_cast<size_t>(k)], ctri[i][static_cast<size_t>((k + 1) % 3)]),
                static_cast<int32_t>(i), k);
    }
    std::sort(edges.begin(), edges.end());
    DisjointSets corners(3 * ctri.size());       // corner 3 i + k
    std::vector<std::array<NodeId, 2>> jointed;  // (smaller, larger) local vertex ids
    for (size_t i = 0; i < edges.size();) {
        size_t r = i + 1;
        while (r < edges.size() && std::get<0>(edges[r]) == std::get<0>(edges[i]))
            ++r;
        if (r - i == 2) {
            const Edge e = std::get<0>(edges[i]);
            const int32_t ta = std::get<1>(edges[i]), tb = std::get<1>(edges[i + 1]);
            const int32_t pa = cparent[static_cast<size_t>(ta)];
            const int32_t pb = cparent[static_cast<size_t>(tb)];
            const bool joint = (pa != pb && in_region(pa) && in_region(pb)) ||
                               std::binary_search(listed.begin(), listed.end(), e) ||
                               std::binary_search(prebroken.begin(), prebroken.end(), e);
            if (joint) {
                jointed.push_back({local(e[0]), local(e[1])});
            } else {
                // unjointed: the two triangles share their copies of both end vertices
                for (const int32_t q : e) {
                    int32_t ca = -1, cb = -1;
                    for (int k = 0; k < 3; ++k) {
                        if (ctri[static_cast<size_t>(ta)][static_cast<size_t>(k)] == q)
                            ca = 3 * ta + k;
                        if (ctri[static_cast<size_t>(tb)][static_cast<size_t>(k)] == q)
                            cb = 3 * tb + k;
                    }
                    corners.unite(ca, cb);
                }
            }
        }
        // r - i > 2 (an edge of three triangles): left to build_topology's InputError
        i = r;
    }
    std::sort(jointed.begin(), jointed.end());

    // node copies: one per run, in order of first use; the first copy of a vertex represents it
    if (m.node_vertex.size() < static_cast<size_t>(m.num_nodes())) {
        for (NodeId i = static_cast<NodeId>(m.node_vertex.size()); i < m.num_nodes(); ++i)
            m.node_vertex.push_back(i);
    }
    const NodeId node_begin = m.num_nodes();
    const TriId tri_begin = m.num_tris();
    std::vector<NodeId> copy_of_root(3 * ctri.size(), kNone);
    std::vector<NodeId> lvertex;   // local vertex id of every new node (for add_edge_joints)
    std::vector<int32_t> mvertex;  // its mesh node
    for (size_t i = 0; i < ctri.size(); ++i) {
        std::array<NodeId, 3> ids{};
        for (int k = 0; k < 3; ++k) {
            const int32_t q = ctri[i][static_cast<size_t>(k)];
            const auto root = static_cast<size_t>(corners.find(static_cast<int32_t>(3 * i) + k));
            if (copy_of_root[root] == kNone) {
                const auto l = static_cast<size_t>(local(q));
                copy_of_root[root] = m.num_nodes();
                if (map[l] == kNone) map[l] = m.num_nodes();
                m.node_x0.push_back(mesh.nodes[q]);
                m.node_v0.push_back(opt.velocity);
                m.node_body.push_back(bid);
                m.node_vertex.push_back(map[l]);
                lvertex.push_back(static_cast<NodeId>(l));
                mvertex.push_back(q);
            }
            ids[static_cast<size_t>(k)] = copy_of_root[root];
        }
        m.tri_nodes.push_back(ids);
        m.tri_body.push_back(bid);
        m.tri_material.push_back(opt.material);
    }

    // joints (theory eq. 9.1) on the jointed edges, in the component's local node ids
    const size_t nn = static_cast<size_t>(m.num_nodes() - node_begin);
    std::vector<std::array<NodeId, 3>> ltris(ctri.size());
    for (size_t i = 0; i < ctri.size(); ++i) {
        for (int k = 0; k < 3; ++k)
            ltris[i][static_cast<size_t>(k)] =
                m.tri_nodes[static_cast<size_t>(tri_begin) + i][static_cast<size_t>(k)] -
                node_begin;
    }
    const std::span<const Vec2> lx0(m.node_x0.data() + node_begin, nn);
    const size_t j0 = m.joints.nodes.size();
    add_edge_joints(m.joints, lx0, ltris, lvertex, opt.material, &jointed);
    for (size_t j = j0; j < m.joints.nodes.size(); ++j) {
        auto& n = m.joints.nodes[j];
        const Edge e = key(mvertex[static_cast<size_t>(n[0])], mvertex[static_cast<size_t>(n[1])]);
        if (std::binary_search(prebroken.begin(), prebroken.end(), e))
            m.prebroken_joints.push_back(static_cast<int32_t>(j));
        for (NodeId& id : n)
            id += node_begin;
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
    if (opt.fracture) {
        // spec fracture.md §12.12: the composite's sub-triangles share the volumetric part of the
        // whole element, a joint between them would cut a single element
        if (kind == ElementKind::Composite6) {
            throw InputError({mesh.file, 0, 0}, "fracture",
                             fmt::format("body \"{}\": fracture is not available for the "
                                         "composite (6-node) element; use element = \"cst\" "
                                         "or a mesh of 3-node triangles",
                                         opt.name));
        }
        if (opt.material < 0 || opt.material >= static_cast<int32_t>(m.materials.size()) ||
            !m.materials[static_cast<size_t>(opt.material)].has_fracture) {
            throw InputError({mesh.file, 0, 0}, "fracture",
                             fmt::format("body \"{}\" has fracture, but its material has no "
                                         "[material.fracture] table (the joint parameters)",
                                         opt.name));
        }
    }
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
        if (opt.fracture) {
            body.fracture = true;
            add_jointed_nodes(m, mesh, tris, opt, bid, sub_triangles, local, map);
            body.node_end = m.num_nodes();
            body.tri_end = m.num_tris();
            m.bodies.push_back(body);
            set_initial_velocity(m, body, opt);
            continue;
        }
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
    // Model::node_vertex: identity for every unsplit node once some body has fracture
    if (!m.node_vertex.empty()) {
        for (NodeId i = static_cast<NodeId>(m.node_vertex.size()); i < m.num_nodes(); ++i)
            m.node_vertex.push_back(i);
    }
    return out;
}

namespace {

/// Joint laws, gather lists and the h_max check of the cohesive joints (theory §9).
void finalize_fracture(Model& m) {
    Joints& J = m.joints;
    if (J.nodes.empty()) return;
    // one law per material (index = material id, Joints::law), made for the materials with
    // fracture only (the others are never referenced)
    J.laws.assign(m.materials.size(), JointLaw{});
    for (size_t k = 0; k < m.materials.size(); ++k) {
        const Material& mat = m.materials[k];
        if (!mat.has_fracture) continue;
        try {
            J.laws[k] = make_joint_law(mat.fracture);
        } catch (const std::invalid_argument& e) {
            throw InputError({}, "material.fracture",
                             fmt::format("material \"{}\": {}", mat.name, e.what()));
        }
    }
    // theory eq. 9.14: a joint longer than h_max = p G_I / (4 I_z f_t^2) has a softening branch
    // shorter than 2 o_p (its snap-back would dissipate more than G_I); report the longest
    std::vector<int32_t> worst(m.materials.size(), -1);
    for (int32_t j = 0; j < J.num_joints(); ++j) {
        const auto k = static_cast<size_t>(J.law[static_cast<size_t>(j)]);
        if (worst[k] < 0 ||
            J.length0[static_cast<size_t>(j)] > J.length0[static_cast<size_t>(worst[k])])
            worst[k] = j;
    }
    for (size_t k = 0; k < m.materials.size(); ++k) {
        if (worst[k] < 0) continue;
        const Material& mat = m.materials[k];
        const Real h = J.length0[static_cast<size_t>(worst[k])];
        const Real h_max = joint_max_length(mat.fracture);
        // eq. 9.14 is the well-posedness of the "exact" rule (the others set their own lengths)
        if (mat.fracture.softening_length == SofteningLength::Exact && h > h_max &&
            !mat.fracture.allow_coarse) {
            const auto& n = J.nodes[static_cast<size_t>(worst[k])];
            const Vec2 a = m.node_x0[static_cast<size_t>(n[0])];
            const Vec2 b = m.node_x0[static_cast<size_t>(n[1])];
            throw InputError(
                {}, "material.fracture",
                fmt::format("material \"{}\": joint {} from ({:.6g}, {:.6g}) to ({:.6g}, {:.6g}) "
                            "is {:.4g} m long, more than h_max = p G_I / (4 I_z f_t^2) = {:.4g} m "
                            "(theory eq. 9.14): its softening branch would be shorter than twice "
                            "the elastic opening; refine the mesh, raise the penalty or set "
                            "allow_coarse = true",
                            mat.name, worst[k], a.x, a.y, b.x, b.y, h, h_max));
        }
    }
    finalize_joints(J, m.num_nodes());
}

}  // namespace

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

    // point forces on jointed vertices: F / (number of vertices) per vertex, split over its
    // node copies by mass (theory eq. 4.11); no shares (equal split) when no vertex has copies
    if (m.node_vertex.size() == nn) {
        for (Load& ld : m.loads) {
            ld.node_share.clear();
            if (ld.kind != LoadKind::Force) continue;
            std::vector<NodeId> reps;
            for (const NodeId i : ld.nodes)
                reps.push_back(m.node_vertex[static_cast<size_t>(i)]);
            std::vector<NodeId> vertices = reps;
            std::sort(vertices.begin(), vertices.end());
            vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
            if (vertices.size() == ld.nodes.size()) continue;  // one node per vertex
            std::vector<Real> vertex_mass(vertices.size(), 0.0);
            const auto vid = [&](NodeId r) {
                return static_cast<size_t>(std::lower_bound(vertices.begin(), vertices.end(), r) -
                                           vertices.begin());
            };
            for (size_t k = 0; k < ld.nodes.size(); ++k)
                vertex_mass[vid(reps[k])] += m.node_mass[static_cast<size_t>(ld.nodes[k])];
            const Real per_vertex = 1.0 / static_cast<Real>(vertices.size());
            ld.node_share.resize(ld.nodes.size());
            for (size_t k = 0; k < ld.nodes.size(); ++k)
                ld.node_share[k] = per_vertex * m.node_mass[static_cast<size_t>(ld.nodes[k])] /
                                   vertex_mass[vid(reps[k])];
        }
    }

    int32_t slot = 0;  // State::scratch_load slots of each load
    for (Load& ld : m.loads) {
        ld.slot_begin = slot;
        slot += ld.num_slots();
    }

    finalize_fracture(m);
    resolve_contact_params(m);
    m.element_schedule = build_element_schedule(m);
    // the per-node, per-triangle and per-joint arrays the step streams, on huge pages where the
    // kernel allows (no result changes: docs/performance.md "Huge pages")
    for (const auto* a : {&m.node_x0, &m.node_v0})
        prefer_huge_pages(*a);
    for (const auto* a : {&m.node_mass, &m.node_inv_mass, &m.tri_area0, &m.tri_eta})
        prefer_huge_pages(*a);
    prefer_huge_pages(m.tri_nodes);
    prefer_huge_pages(m.tri_dm_inv);
    prefer_huge_pages(m.tri_material);
    prefer_huge_pages(m.node_body);
    prefer_huge_pages(m.tri_body);
    prefer_huge_pages(m.joints.nodes);
    prefer_huge_pages(m.joints.length0);
    prefer_huge_pages(m.joints.law);
    prefer_huge_pages(m.joints.gather_node);
    prefer_huge_pages(m.joints.gather_begin);
    prefer_huge_pages(m.joints.gather_entry);
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
    // cohesive joints: the Gershgorin bound of M^-1 K_joint (theory eq. 9.16)
    const Real dtj = joint_critical_dt(m.joints, m.node_mass);
    if (std::min(dtc, dtj) < dte) arg = kNone;
    if (limiting_tri) *limiting_tri = arg;
    // element, contact and joint stiffness act on the same nodes: the largest eigenvalue of
    // M^-1 (K_e + K_c + K_j) is at most the sum of theirs (Weyl), so
    // (2/dt)^2 <= (2/dte)^2 + (2/dtc)^2 + (2/dtj)^2 (theory eqs. 6.17, 9.21); an infinite bound
    // (no contact, no joints) adds nothing
    Real inv2 = 0;
    int finite = 0;
    for (const Real d : {dte, dtc, dtj}) {
        if (!std::isfinite(d)) continue;
        inv2 += 1.0 / (d * d);
        ++finite;
    }
    // one finite bound: itself (bitwise what it was before joints existed)
    if (finite <= 1) return std::min({dte, dtc, dtj});
    return 1.0 / std::sqrt(inv2);
}

}  // namespace fdem
