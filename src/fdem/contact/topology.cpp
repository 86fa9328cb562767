// Contact topology of the smooth contact (paper §2, spec §4.1-4.4, docs/theory.md §6.1-6.2):
// boundary edges/nodes/elements per body, chord splitting with virtual mid-nodes, incenter fan
// of single-triangle bodies, the special cases of the 6-node composite element (paper §2.4,
// docs/theory.md §6.1.1), contactor sub-triangles and frozen nodal contact distances.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "contact/contact.hpp"
#include "contact/legacy_boundary.hpp"
#include "contact/validate.hpp"
#include "fdem/assert.hpp"
#include "fdem/build.hpp"
#include "fdem/error.hpp"

namespace fdem {

namespace {

struct EdgeRec {
    NodeId a, b;  // a < b
    TriId tri;
    int8_t local;  // edge local -> local+1 of the triangle
};

bool edge_less(const EdgeRec& x, const EdgeRec& y) {
    if (x.a != y.a) return x.a < y.a;
    if (x.b != y.b) return x.b < y.b;
    return x.tri < y.tri;
}

using Key = std::array<NodeId, 2>;
Key key(NodeId a, NodeId b) {
    return a < b ? Key{a, b} : Key{b, a};
}

bool has_key(const std::vector<Key>& sorted, NodeId a, NodeId b) {
    return std::binary_search(sorted.begin(), sorted.end(), key(a, b));
}

// distance from point x to segment [a, b]
Real point_segment_distance(Vec2 x, Vec2 a, Vec2 b) {
    const Vec2 ab = b - a;
    const Real l2 = norm2(ab);
    Real s = l2 > 0 ? dot(x - a, ab) / l2 : 0;
    s = std::clamp(s, Real(0), Real(1));
    return norm(x - (a + s * ab));
}

void check_params(const ContactParams& p, const std::string& where) {
    auto bad = [&](const char* k, Real v, const char* expected) {
        throw InputError(
            SourceLocation{}, std::string("contact.") + k,
            fmt::format("contact parameters{}: {} must be {}, got {}", where, k, expected, v));
    };
    if (!(p.penalty > 0)) bad("penalty", p.penalty, "> 0");
    if (!(p.alpha >= 1)) bad("alpha", p.alpha, ">= 1");
    if (!(p.beta >= p.alpha)) bad("beta", p.beta, ">= alpha");
    if (!(p.length_scale > 0)) bad("length_scale", p.length_scale, "> 0");
    if (!(p.damping >= 0)) bad("damping", p.damping, ">= 0");
    if (!(p.friction >= 0)) bad("friction", p.friction, ">= 0");
    if (!(p.tangential_penalty >= 0)) bad("tangential_penalty", p.tangential_penalty, ">= 0");
}

// defaults of spec §4.5, resolved once here and never at use time
void resolve_params(Model& m) {
    ContactModel& cm = m.contact;
    const int32_t nm = static_cast<int32_t>(m.materials.size());
    cm.num_materials = nm;
    for (const ContactModel::PairOverride& o : cm.pair_overrides) {
        if (o.a < 0 || o.a >= nm || o.b < 0 || o.b >= nm) {
            throw InputError(SourceLocation{}, "contact.pair_overrides",
                             fmt::format("contact pair override ({}, {}): material index outside "
                                         "0 .. {}",
                                         o.a, o.b, nm - 1));
        }
    }
    Real e_min = std::numeric_limits<Real>::infinity();
    for (const Material& mat : m.materials)
        e_min = std::min(e_min, mat.youngs_modulus);
    auto resolve = [](ContactParams p, Real e) {
        if (p.penalty == 0) p.penalty = 5.0 * e;  // k_n = 5 E (spec §4.5)
        if (p.tangential_penalty < 0) p.tangential_penalty = 0.1 * p.penalty;  // Y practice
        return p;
    };
    if (nm > 0) {
        cm.params = resolve(cm.params, e_min);
        check_params(cm.params, "");
    }
    // classes: 0 for materials in no override, 1.. in order of first appearance
    cm.material_class.assign(static_cast<size_t>(nm), 0);
    std::vector<int32_t> class_material = {-1};
    for (const ContactModel::PairOverride& o : cm.pair_overrides) {
        for (const int32_t mat : {o.a, o.b}) {
            if (cm.material_class[static_cast<size_t>(mat)] == 0) {
                cm.material_class[static_cast<size_t>(mat)] =
                    static_cast<int32_t>(class_material.size());
                class_material.push_back(mat);
            }
        }
    }
    const int32_t nc = static_cast<int32_t>(class_material.size());
    if (static_cast<int64_t>(nc) * nc > 10'000'000) {
        throw InputError(SourceLocation{}, "contact.pair",
                         fmt::format("[[contact.pair]] entries name {} different materials; the "
                                     "resolved table would need {}^2 entries; expected at most "
                                     "3161 materials in contact pairs",
                                     nc - 1, nc));
    }
    cm.num_classes = nc;
    cm.resolved.assign(static_cast<size_t>(nc) * static_cast<size_t>(nc), cm.params);
    for (const ContactModel::PairOverride& o : cm.pair_overrides) {
        const size_t k = static_cast<size_t>(cm.material_class[static_cast<size_t>(o.a)]) *
                             static_cast<size_t>(nc) +
                         static_cast<size_t>(cm.material_class[static_cast<size_t>(o.b)]);
        const Real e = std::min(m.materials[static_cast<size_t>(o.a)].youngs_modulus,
                                m.materials[static_cast<size_t>(o.b)].youngs_modulus);
        cm.resolved[k] = resolve(o.params, e);
        check_params(cm.resolved[k], fmt::format(" of materials \"{}\" / \"{}\"",
                                                 m.materials[static_cast<size_t>(o.a)].name,
                                                 m.materials[static_cast<size_t>(o.b)].name));
    }
}

class TopologyBuilder {
public:
    TopologyBuilder(const Model& m, ContactTopology& t) : m_(m), cm_(t) {}

    void body(BodyId b);

private:
    NodeId add_virtual(std::array<NodeId, 3> parent, std::array<Real, 3> w) {
        cm_.virt_parent.push_back(parent);
        cm_.virt_weight.push_back(w);
        return cm_.num_real_nodes + cm_.num_virtual() - 1;
    }
    Vec2 x0(NodeId i) const {
        if (i < cm_.num_real_nodes) return m_.node_x0[i];
        const size_t v = static_cast<size_t>(i - cm_.num_real_nodes);
        Vec2 x;
        for (int k = 0; k < 3; ++k)
            x += cm_.virt_weight[v][k] * m_.node_x0[cm_.virt_parent[v][k]];
        return x;
    }
    void add_sub(BodyId b, TriId t, NodeId p, NodeId q, NodeId r) {
        cm_.sub_tri.push_back({p, q, r});
        cm_.sub_body.push_back(b);
        cm_.sub_parent.push_back(t);
    }
    bool is_boundary_node(NodeId i) const { return cm_.node_on_boundary[i] != 0; }
    // sector of real node i in the body being built (i itself unless the body is welded)
    NodeId W(NodeId i) const { return weld_ != nullptr ? weld_[i] : i; }
    // the id a nodal distance is computed on: the sector of a real node, a virtual node itself
    NodeId R(NodeId i) const { return i < cm_.num_real_nodes ? W(i) : i; }
    // welded key of the edge between real nodes p and q
    Key wkey(NodeId p, NodeId q) const { return key(W(p), W(q)); }
    // virtual mid-node of chord p-q (p, q: the calling triangle's own copies), created on first
    // use (composite bodies) or up front (CST); in a welded body the second triangle of a chord
    // has its own mid-node when its copies differ (a chord across an intact joint)
    NodeId chord_mid(NodeId p, NodeId q) {
        const auto it = std::lower_bound(ckeys_.begin(), ckeys_.end(), wkey(p, q));
        const size_t c = static_cast<size_t>(it - ckeys_.begin());
        if (cvirt2_[c] != kNone && key(p, q) != ccopy_[c]) return cvirt2_[c];
        NodeId& v = cvirt_[c];
        if (v == kNone) v = add_virtual({p, q, p}, {0.5, 0.5, 0.0});
        return v;
    }
    void split_mesh_triangle(BodyId b, TriId t);
    void composite(BodyId b, TriId t0);
    void nodal_distances(BodyId b, size_t sub_begin);

    const Model& m_;
    ContactTopology& cm_;
    std::vector<EdgeRec> edges_;
    std::vector<Key> bkeys_, ckeys_;
    std::vector<NodeId> cvirt_;  // virtual node of chord ckeys_[i]
    // welded bodies: the first triangle's copies of chord i (min, max) and the second
    // triangle's mid-node when its copies differ (else kNone)
    std::vector<Key> ccopy_;
    std::vector<NodeId> cvirt2_;
    std::vector<size_t> interior_;  // first record (in edges_) of each interior edge
    std::vector<uint8_t> in_sub_;   // welded bodies: real node is a vertex of a sub-triangle
    const NodeId* weld_ = nullptr;  // sectors of the body being built (null: not welded)
};

void TopologyBuilder::body(BodyId b) {
    const Body& body = m_.bodies[b];
    // a body with fracture is built on its welded mesh (docs/theory.md §6.15): node copies of
    // one sector are one vertex for the edge classification, the chords and the distances
    weld_ = body.fracture && !cm_.node_weld.empty() ? cm_.node_weld.data() : nullptr;

    // 1. edges of the body, grouped by (welded) node pair: used once = boundary (an external
    //    edge or a face of a broken joint), twice = interior
    edges_.clear();
    for (TriId t = body.tri_begin; t < body.tri_end; ++t) {
        const auto& n = m_.tri_nodes[t];
        for (int8_t k = 0; k < 3; ++k) {
            const Key e = wkey(n[k], n[(k + 1) % 3]);
            edges_.push_back({e[0], e[1], t, k});
        }
    }
    std::sort(edges_.begin(), edges_.end(), edge_less);
    bkeys_.clear();
    interior_.clear();
    for (size_t i = 0; i < edges_.size();) {
        size_t j = i;
        while (j < edges_.size() && edges_[j].a == edges_[i].a && edges_[j].b == edges_[i].b)
            ++j;
        if (j - i == 1) {
            const auto& n = m_.tri_nodes[edges_[i].tri];
            cm_.boundary_edges.push_back({n[edges_[i].local], n[(edges_[i].local + 1) % 3]});
            bkeys_.push_back({edges_[i].a, edges_[i].b});
            cm_.node_on_boundary[edges_[i].a] = 1;
            cm_.node_on_boundary[edges_[i].b] = 1;
        } else if (j - i == 2) {
            interior_.push_back(i);
        } else {
            throw InputError(SourceLocation{}, "mesh",
                             fmt::format("body {} (\"{}\"): edge between nodes {} and {} is shared "
                                         "by {} triangles; a 2-D mesh edge may have at most 2",
                                         b, body.name, edges_[i].a, edges_[i].b, j - i));
        }
        i = j;
    }
    cm_.body_bedge_begin.push_back(static_cast<int32_t>(cm_.boundary_edges.size()));
    if (weld_ != nullptr) {
        // every copy of a boundary sector is a boundary node (a target with its own mass);
        // the representative (smallest copy) was marked above and comes first
        for (NodeId i = body.node_begin; i < body.node_end; ++i)
            cm_.node_on_boundary[i] = cm_.node_on_boundary[weld_[i]];
    }
    for (NodeId i = body.node_begin; i < body.node_end; ++i) {
        if (cm_.node_on_boundary[i]) cm_.boundary_nodes.push_back(i);
    }
    cm_.body_bnode_begin.push_back(static_cast<int32_t>(cm_.boundary_nodes.size()));

    // 2. chords: interior edges joining two boundary nodes get a virtual mid-node (spec §4.4).
    //    CST bodies create them all here; in composite bodies the chords are the central
    //    sub-triangle edges of the special cases, whose mid-nodes composite() creates if its
    //    layout uses them (theory §6.1.1)
    const bool composite_body = body.element == ElementKind::Composite6;
    ckeys_.clear();
    cvirt_.clear();
    ccopy_.clear();
    cvirt2_.clear();
    for (const size_t i : interior_) {
        const Key e = {edges_[i].a, edges_[i].b};
        if (cm_.node_on_boundary[e[0]] && cm_.node_on_boundary[e[1]]) {
            // the two triangles' own copies of the edge (the same nodes unless welded)
            auto copies = [&](const EdgeRec& r) {
                const auto& n = m_.tri_nodes[r.tri];
                return key(n[r.local], n[(r.local + 1) % 3]);
            };
            const Key c1 = copies(edges_[i]), c2 = copies(edges_[i + 1]);
            cm_.chords.push_back(e);
            ckeys_.push_back(e);
            ccopy_.push_back(c1);
            cvirt_.push_back(composite_body ? kNone
                                            : add_virtual({c1[0], c1[1], c1[0]}, {0.5, 0.5, 0.0}));
            cvirt2_.push_back(composite_body || c2 == c1
                                  ? kNone
                                  : add_virtual({c2[0], c2[1], c2[0]}, {0.5, 0.5, 0.0}));
        }
    }

    // 3. boundary elements -> contactor sub-triangles (all counter-clockwise)
    if (composite_body) {
        if ((body.tri_end - body.tri_begin) % 4 != 0) {
            throw InputError(SourceLocation{}, "mesh",
                             fmt::format("body {} (\"{}\"): a composite body needs 4 sub-triangles "
                                         "per element, got {} triangles",
                                         b, body.name, body.tri_end - body.tri_begin));
        }
        for (TriId t = body.tri_begin; t < body.tri_end; t += 4)
            composite(b, t);
    } else {
        for (TriId t = body.tri_begin; t < body.tri_end; ++t)
            split_mesh_triangle(b, t);
    }
    const size_t sub_begin = static_cast<size_t>(cm_.body_sub_begin.back());
    cm_.body_sub_begin.push_back(static_cast<int32_t>(cm_.sub_tri.size()));
    nodal_distances(b, sub_begin);
}

// Contactor sub-triangles of mesh triangle t if it is a boundary element (theory eqs. 6.1-6.2).
void TopologyBuilder::split_mesh_triangle(BodyId b, TriId t) {
    const auto& n = m_.tri_nodes[t];
    if (!cm_.node_on_boundary[n[0]] && !cm_.node_on_boundary[n[1]] && !cm_.node_on_boundary[n[2]]) {
        return;
    }
    cm_.boundary_tris.push_back(t);
    int nb = 0, nc = 0;
    bool is_chord[3];
    for (int k = 0; k < 3; ++k) {
        const NodeId p = W(n[k]), q = W(n[(k + 1) % 3]);
        nb += has_key(bkeys_, p, q) ? 1 : 0;
        is_chord[k] = has_key(ckeys_, p, q);
        nc += is_chord[k] ? 1 : 0;
    }
    if (nb == 3) {
        // single-triangle body (paper case 2): fan from the incenter, weights = opposite
        // edge lengths (spec §4.4-4), which makes the field exact (spec §6.5)
        const Real la = norm(m_.node_x0[n[1]] - m_.node_x0[n[2]]);
        const Real lb = norm(m_.node_x0[n[2]] - m_.node_x0[n[0]]);
        const Real lc = norm(m_.node_x0[n[0]] - m_.node_x0[n[1]]);
        const Real per = la + lb + lc;
        const NodeId c = add_virtual(n, {la / per, lb / per, lc / per});
        add_sub(b, t, n[0], n[1], c);
        add_sub(b, t, n[1], n[2], c);
        add_sub(b, t, n[2], n[0], c);
    } else if (nc == 0) {
        add_sub(b, t, n[0], n[1], n[2]);
    } else if (nc == 1) {
        // chord B-C opposite A: (A, B, M), (A, M, C)
        int k = 0;
        while (!is_chord[k])
            ++k;
        const NodeId B = n[k], C = n[(k + 1) % 3], A = n[(k + 2) % 3];
        const NodeId M = chord_mid(B, C);
        add_sub(b, t, A, B, M);
        add_sub(b, t, A, M, C);
    } else if (nc == 2) {
        // chords P0-P1 and P0-P2: (P0, M1, M2), (M1, P1, P2), (M1, P2, M2)
        int k = 0;
        while (is_chord[k])
            ++k;
        const NodeId P1 = n[k], P2 = n[(k + 1) % 3], P0 = n[(k + 2) % 3];
        const NodeId M1 = chord_mid(P0, P1), M2 = chord_mid(P0, P2);
        add_sub(b, t, P0, M1, M2);
        add_sub(b, t, M1, P1, P2);
        add_sub(b, t, M1, P2, M2);
    } else {
        // 1 -> 4 midpoint subdivision
        const NodeId mab = chord_mid(n[0], n[1]), mbc = chord_mid(n[1], n[2]),
                     mca = chord_mid(n[2], n[0]);
        add_sub(b, t, n[0], mab, mca);
        add_sub(b, t, mab, n[1], mbc);
        add_sub(b, t, mca, mbc, n[2]);
        add_sub(b, t, mab, mbc, mca);
    }
}

// Contact sub-triangles of the composite element whose four mesh sub-triangles start at t0
// (layout of model.hpp Body; paper §2.4, docs/theory.md §6.1.1). Perimeter numbering of the
// paper: P = n1..n6, corners n1, n3, n5; macro edge k = P[2k] - P[2k+1] - P[2k+2].
void TopologyBuilder::composite(BodyId b, TriId t0) {
    const auto& s0 = m_.tri_nodes[t0];
    const auto& s1 = m_.tri_nodes[t0 + 1];
    const auto& s2 = m_.tri_nodes[t0 + 2];
    const auto& s3 = m_.tri_nodes[t0 + 3];
    const NodeId P[6] = {s0[0], s0[1], s1[1], s1[2], s2[2], s0[2]};
    if (s1[0] != P[1] || s2[0] != P[5] || s2[1] != P[3] ||
        !(s3 == std::array<NodeId, 3>{P[1], P[3], P[5]})) {
        const Body& body = m_.bodies[b];
        throw InputError(SourceLocation{}, "mesh",
                         fmt::format("body {} (\"{}\"): composite element {} does not follow the "
                                     "sub-triangle layout (n1,n2,n6), (n2,n3,n4), (n6,n4,n5), "
                                     "(n2,n4,n6) (include/fdem/model.hpp)",
                                     b, body.name, (t0 - body.tri_begin) / 4));
    }
    int n_bedges = 0, inner = -1;
    for (int k = 0; k < 3; ++k) {
        const bool on = has_key(bkeys_, P[2 * k], P[2 * k + 1]) &&
                        has_key(bkeys_, P[2 * k + 1], P[(2 * k + 2) % 6]);
        n_bedges += on ? 1 : 0;
        if (!on) inner = k;
    }
    if (n_bedges < 2) {
        // no sub-triangle without an inner node: the sub-triangles as they are (no chords)
        for (TriId t = t0; t < t0 + 4; ++t)
            split_mesh_triangle(b, t);
        return;
    }
    for (TriId t = t0; t < t0 + 4; ++t)
        cm_.boundary_tris.push_back(t);

    // baseline B evaluates phi_B of the mesh sub-triangle holding each contact sub-triangle
    // (legacy_boundary.cpp), so it needs the nested option (a) layout
    const CompositeSpecialCase mode = m_.contact.algorithm == ContactAlgorithm::LegacyBoundary
                                          ? CompositeSpecialCase::Split
                                          : m_.contact.composite_special_case;
    if (mode == CompositeSpecialCase::Split) {
        // option (a), Figs. 8a/10a: n7, n8, n9 at the midpoints of the central sub-triangle's
        // edges; each corner sub-triangle is halved, the central one cut 1 -> 4 (10 in all)
        auto mid = [&](NodeId p, NodeId q) {
            return is_boundary_node(p) && is_boundary_node(q)
                       ? chord_mid(p, q)
                       : add_virtual({p, q, p}, {0.5, 0.5, 0.0});
        };
        const NodeId m24 = mid(P[1], P[3]), m46 = mid(P[3], P[5]), m62 = mid(P[5], P[1]);
        add_sub(b, t0, P[0], P[1], m62);  // (n1, n2, n6) halved at n7 = mid(n2, n6)
        add_sub(b, t0, P[0], m62, P[5]);
        add_sub(b, t0 + 1, P[2], P[3], m24);  // (n2, n3, n4) halved at n8 = mid(n2, n4)
        add_sub(b, t0 + 1, P[2], m24, P[1]);
        add_sub(b, t0 + 2, P[4], P[5], m46);  // (n6, n4, n5) halved at n9 = mid(n4, n6)
        add_sub(b, t0 + 2, P[4], m46, P[3]);
        add_sub(b, t0 + 3, P[1], m24, m62);  // (n2, n4, n6): 1 -> 4
        add_sub(b, t0 + 3, m24, P[3], m46);
        add_sub(b, t0 + 3, m62, m46, P[5]);
        add_sub(b, t0 + 3, m24, m46, m62);
        return;
    }

    // option (b): a fan, one triangle per boundary half-edge h = P[h] - P[h+1]; its mesh parent
    // is the corner sub-triangle holding that half-edge
    constexpr int kHalfEdgeTri[6] = {0, 1, 1, 2, 2, 0};
    NodeId apex;
    int h0, nh;
    if (n_bedges == 2) {
        // case 1, Fig. 8b: fan of four around the mid-node of the inner edge (an inner node)
        apex = P[2 * inner + 1];
        h0 = 2 * inner + 2;
        nh = 4;
    } else {
        // case 2, Fig. 10b: fan of six around n7 at the incenter of the corner triangle
        // (n1, n3, n5), weights = opposite side lengths (theory eq. 6.2): for a straight-sided
        // element every fan triangle is then the region nearest to its base, so d is exact
        const Real l1 = norm(m_.node_x0[P[2]] - m_.node_x0[P[4]]);
        const Real l3 = norm(m_.node_x0[P[4]] - m_.node_x0[P[0]]);
        const Real l5 = norm(m_.node_x0[P[0]] - m_.node_x0[P[2]]);
        const Real per = l1 + l3 + l5;
        apex = add_virtual({P[0], P[2], P[4]}, {l1 / per, l3 / per, l5 / per});
        h0 = 0;
        nh = 6;
    }
    for (int j = 0; j < nh; ++j) {
        const int h = (h0 + j) % 6;
        const NodeId p = P[h], q = P[(h + 1) % 6];
        if (!(signed_area(x0(p), x0(q), x0(apex)) > 0)) {
            const Body& body = m_.bodies[b];
            throw InputError(
                SourceLocation{}, "contact.composite_special_case",
                fmt::format("body {} (\"{}\"): composite element {} is too distorted for the "
                            "contact fan of paper §2.4 option (b) (fan triangle on nodes {}, {} "
                            "not counter-clockwise); use composite_special_case = \"split\"",
                            b, body.name, (t0 - body.tri_begin) / 4, p, q));
        }
        add_sub(b, t0 + kHalfEdgeTri[h], p, q, apex);
    }
}

void TopologyBuilder::nodal_distances(BodyId b, size_t sub_begin) {
    // 4. nodal distances, eqs. 1-2: height 2A/l over every boundary edge of a sub-triangle,
    //    minimum over the sub-triangles (reference configuration, frozen)
    constexpr Real kUnset = std::numeric_limits<Real>::infinity();
    cm_.node_dist.resize(static_cast<size_t>(cm_.num_contact_nodes()), 0.0);
    cm_.node_dist_edge.resize(static_cast<size_t>(cm_.num_contact_nodes()), -1);
    // (on sector ids R(i) in a welded body: a sector's distance is the minimum over the
    // sub-triangles opposite any of its copies, given to its copies at the end)
    for (size_t s = sub_begin; s < cm_.sub_tri.size(); ++s) {
        for (NodeId i : cm_.sub_tri[s]) {
            const bool bnode = i < cm_.num_real_nodes && cm_.node_on_boundary[i];
            if (!bnode) cm_.node_dist[R(i)] = kUnset;
        }
    }
    const int32_t e_first = cm_.body_bedge_begin[b];  // bkeys_[k] is boundary edge e_first + k
    for (size_t s = sub_begin; s < cm_.sub_tri.size(); ++s) {
        const auto& q = cm_.sub_tri[s];
        const Real a2 = cross(x0(q[1]) - x0(q[0]), x0(q[2]) - x0(q[0]));  // 2A
        for (int k = 0; k < 3; ++k) {
            const NodeId p = q[k], r = q[(k + 1) % 3], o = q[(k + 2) % 3];
            if (p >= cm_.num_real_nodes || r >= cm_.num_real_nodes) continue;
            if (!has_key(bkeys_, W(p), W(r))) continue;
            if (o < cm_.num_real_nodes && cm_.node_on_boundary[o]) continue;
            const Real h = a2 / norm(x0(r) - x0(p));
            const NodeId ro = R(o);
            if (h < cm_.node_dist[ro]) {
                cm_.node_dist[ro] = h;
                const auto it = std::lower_bound(bkeys_.begin(), bkeys_.end(), wkey(p, r));
                cm_.node_dist_edge[ro] = e_first + static_cast<int32_t>(it - bkeys_.begin());
            }
        }
    }

    // 5. fallback (spec §4.2): true distance to the body boundary for nodes eq. 1 missed
    const size_t e0 = static_cast<size_t>(cm_.body_bedge_begin[b]);
    const size_t e1 = static_cast<size_t>(cm_.body_bedge_begin[b + 1]);
    for (size_t s = sub_begin; s < cm_.sub_tri.size(); ++s) {
        for (const NodeId c : cm_.sub_tri[s]) {
            const NodeId i = R(c);  // copies of a sector coincide in the reference
            if (cm_.node_dist[i] != kUnset) continue;
            Real dmin = kUnset;
            const Vec2 xi = x0(i);
            for (size_t e = e0; e < e1; ++e) {
                const auto& be = cm_.boundary_edges[e];
                const Real d = point_segment_distance(xi, m_.node_x0[be[0]], m_.node_x0[be[1]]);
                if (d < dmin) {
                    dmin = d;
                    cm_.node_dist_edge[i] = static_cast<int32_t>(e);
                }
            }
            cm_.node_dist[i] = dmin;
            ++cm_.num_fallback_nodes;
            ++cm_.body_fallback.back();
        }
    }

    // 6. welded body: the sector's distance to every copy that is a sub-triangle vertex; a
    //    representative that is in no sub-triangle keeps 0 (never read by the field)
    if (weld_ != nullptr) {
        const Body& body = m_.bodies[b];
        in_sub_.resize(static_cast<size_t>(cm_.num_real_nodes), 0);
        for (size_t s = sub_begin; s < cm_.sub_tri.size(); ++s) {
            for (const NodeId i : cm_.sub_tri[s]) {
                if (i < cm_.num_real_nodes) in_sub_[i] = 1;
            }
        }
        for (NodeId i = body.node_begin; i < body.node_end; ++i) {
            if (weld_[i] != i && in_sub_[i]) {
                cm_.node_dist[i] = cm_.node_dist[weld_[i]];
                cm_.node_dist_edge[i] = cm_.node_dist_edge[weld_[i]];
            }
        }
        for (NodeId i = body.node_begin; i < body.node_end; ++i) {
            if (weld_[i] == i && !in_sub_[i]) {
                cm_.node_dist[i] = 0;
                cm_.node_dist_edge[i] = -1;
            }
            in_sub_[i] = 0;
        }
    }
}

// Edge targets (docs/theory.md §6.12): the midpoint of every boundary edge becomes a target.
// The force scale s_j of each boundary node (eq. 19 or 6.16) is shared out as the weights of
// the three-point Gauss-Lobatto (Simpson) rule on each of its edges: node j's part on edge e is
// sigma_je = s_j l_e / L_j (L_j = the lengths of its boundary edges); the node keeps 1/3 of
// every part and the midpoint of e gets 2/3 (sigma_ae + sigma_be) (eq. 6.19), so the total scale
// of a body is unchanged. With length scaling this is Simpson's rule on every edge exactly.
// target_dt_factor: the target stiffness is no longer diagonal (a midpoint moves with both end
// nodes); its largest row sum per node mass bounds the target-side term of eq. 6.15 (Gershgorin).
//
// Welded form (docs/theory.md §6.15): the sharing is per sector, not per copy: the sector's scale
// (the sum over its copies) is shared over the boundary edges of all its copies (L_j = their
// lengths), since a copy whose triangle touches the boundary only at the vertex has no edge of
// its own; so the sector's total scale is kept, as eq. 19 requires. Without a weld w(i) = i and
// the sums are the per-node values themselves.
void add_edge_targets(const Model& m, ContactTopology& cm) {
    const size_t ne = cm.boundary_edges.size();
    std::vector<Real> len(ne), tributary(static_cast<size_t>(m.num_nodes()), 0.0);
    for (size_t e = 0; e < ne; ++e) {
        const auto& be = cm.boundary_edges[e];
        len[e] = norm(m.node_x0[be[1]] - m.node_x0[be[0]]);
        tributary[cm.weld(be[0])] += len[e];
        tributary[cm.weld(be[1])] += len[e];
    }
    const std::vector<Real>* sector_scale = &cm.node_scale;
    std::vector<Real> welded;
    if (!cm.node_weld.empty()) {
        welded.assign(static_cast<size_t>(m.num_nodes()), 0.0);
        for (NodeId i : cm.boundary_nodes)
            welded[cm.weld(i)] += cm.node_scale[i];
        sector_scale = &welded;
    }
    cm.edge_scale.assign(ne, 0.0);
    for (size_t e = 0; e < ne; ++e) {
        Real w = 0;
        for (NodeId c : cm.boundary_edges[e]) {
            const NodeId i = cm.weld(c);
            if (tributary[i] > 0) w += (*sector_scale)[i] * (len[e] / tributary[i]);
        }
        cm.edge_scale[e] = (2.0 / 3.0) * w;
    }
    for (NodeId i : cm.boundary_nodes)
        cm.node_scale[i] *= 1.0 / 3.0;

    // row sums of the target stiffness (units k): own share + half of each adjacent midpoint's
    std::vector<Real> row(static_cast<size_t>(m.num_nodes()), 0.0);
    for (NodeId i : cm.boundary_nodes)
        row[i] = cm.node_scale[i];
    for (size_t e = 0; e < ne; ++e) {
        for (NodeId i : cm.boundary_edges[e])
            row[i] += 0.5 * cm.edge_scale[e];
    }
    Real factor = 1;  // never below the node-only bound
    for (NodeId i : cm.boundary_nodes) {
        if (m.node_inv_mass[i] > 0 && m.node_mass[i] > 0)
            factor = std::max(factor, row[i] * cm.m_dt / m.node_mass[i]);
    }
    cm.target_dt_factor = factor;
}

// Welded contactor positions (docs/theory.md §6.15, eq. 6.23): the copies of every sector of a
// fracture body that the contactor geometry references (a copy that is a sub-triangle vertex or a
// virtual node's parent), with their mass shares m_c / M_S, as groups; the other referenced real
// nodes (bodies without fracture, sectors of one copy) are listed as standing for themselves.
// All copies of a grouped sector are in the group, referenced or not (the mean is the sector's).
void build_weld_groups(const Model& m, ContactTopology& cm) {
    const size_t n = static_cast<size_t>(m.num_nodes());
    std::vector<uint8_t> referenced(n, 0);
    for (const auto& q : cm.sub_tri) {
        for (const NodeId i : q) {
            if (i < cm.num_real_nodes) referenced[static_cast<size_t>(i)] = 1;
        }
    }
    for (const auto& p : cm.virt_parent) {
        for (const NodeId i : p)
            referenced[static_cast<size_t>(i)] = 1;
    }
    // copies per sector (a sector's copies are in one body; node_weld is the identity elsewhere)
    std::vector<int32_t> copies(n, 0);
    std::vector<uint8_t> sector_used(n, 0);
    for (size_t i = 0; i < n; ++i) {
        ++copies[static_cast<size_t>(cm.node_weld[i])];
        if (referenced[i]) sector_used[static_cast<size_t>(cm.node_weld[i])] = 1;
    }
    cm.weld_group.assign(n, -1);
    std::vector<int32_t> group_of_sector(n, -1);
    int32_t ng = 0;
    for (size_t s = 0; s < n; ++s) {
        if (sector_used[s] && copies[s] > 1) group_of_sector[s] = ng++;
    }
    cm.weld_group_begin.assign(static_cast<size_t>(ng) + 1, 0);
    for (size_t i = 0; i < n; ++i) {
        const int32_t g = group_of_sector[static_cast<size_t>(cm.node_weld[i])];
        cm.weld_group[i] = g;
        if (g >= 0) ++cm.weld_group_begin[static_cast<size_t>(g) + 1];
        if (g < 0 && referenced[i]) cm.weld_plain.push_back(static_cast<NodeId>(i));
    }
    for (int32_t g = 0; g < ng; ++g)
        cm.weld_group_begin[static_cast<size_t>(g) + 1] +=
            cm.weld_group_begin[static_cast<size_t>(g)];
    cm.weld_copy.assign(static_cast<size_t>(cm.weld_group_begin.back()), kNone);
    cm.weld_share.assign(cm.weld_copy.size(), 0.0);
    std::vector<int32_t> fill(cm.weld_group_begin.begin(), cm.weld_group_begin.end() - 1);
    for (size_t i = 0; i < n; ++i) {  // ascending copies within each group
        const int32_t g = cm.weld_group[i];
        if (g >= 0)
            cm.weld_copy[static_cast<size_t>(fill[static_cast<size_t>(g)]++)] =
                static_cast<NodeId>(i);
    }
    for (int32_t g = 0; g < ng; ++g) {
        const int32_t b = cm.weld_group_begin[static_cast<size_t>(g)],
                      e = cm.weld_group_begin[static_cast<size_t>(g) + 1];
        Real mass = 0;
        for (int32_t k = b; k < e; ++k)
            mass += m.node_mass[cm.weld_copy[static_cast<size_t>(k)]];
        for (int32_t k = b; k < e; ++k) {
            // massless copies (not expected: every element has a density) share equally
            cm.weld_share[static_cast<size_t>(k)] =
                mass > 0 ? m.node_mass[cm.weld_copy[static_cast<size_t>(k)]] / mass
                         : 1.0 / static_cast<Real>(e - b);
        }
    }
}

// Body b of the old topology o, appended to t unchanged but for the ids that depend on what
// comes before it: virtual node ids and boundary edge ids (node_dist_edge). Real node ids,
// triangle ids and body ids do not move. Gives the arrays TopologyBuilder::body(b) would append
// for the same mesh of body b (rebuild_topology()).
void splice_body(const Model& m, const ContactTopology& o, BodyId b, ContactTopology& t) {
    const Body& body = m.bodies[b];
    const int32_t nr = t.num_real_nodes;
    const int32_t vshift = t.num_virtual() - o.body_virt_begin[b];
    const int32_t eshift = static_cast<int32_t>(t.boundary_edges.size()) - o.body_bedge_begin[b];
    auto append = [](auto& dst, const auto& src, int32_t begin, int32_t end) {
        dst.insert(dst.end(), src.begin() + begin, src.begin() + end);
    };
    append(t.boundary_edges, o.boundary_edges, o.body_bedge_begin[b], o.body_bedge_begin[b + 1]);
    t.body_bedge_begin.push_back(static_cast<int32_t>(t.boundary_edges.size()));
    append(t.boundary_nodes, o.boundary_nodes, o.body_bnode_begin[b], o.body_bnode_begin[b + 1]);
    t.body_bnode_begin.push_back(static_cast<int32_t>(t.boundary_nodes.size()));
    for (NodeId i = body.node_begin; i < body.node_end; ++i) {
        t.node_on_boundary[i] = o.node_on_boundary[i];
        t.node_dist[i] = o.node_dist[i];
        t.node_dist_edge[i] = o.node_dist_edge[i] < 0 ? -1 : o.node_dist_edge[i] + eshift;
    }
    append(t.chords, o.chords, o.body_chord_begin[b], o.body_chord_begin[b + 1]);
    append(t.boundary_tris, o.boundary_tris, o.body_btri_begin[b], o.body_btri_begin[b + 1]);
    append(t.virt_parent, o.virt_parent, o.body_virt_begin[b], o.body_virt_begin[b + 1]);
    append(t.virt_weight, o.virt_weight, o.body_virt_begin[b], o.body_virt_begin[b + 1]);
    for (int32_t s = o.body_sub_begin[b]; s < o.body_sub_begin[b + 1]; ++s) {
        std::array<NodeId, 3> q = o.sub_tri[s];
        for (NodeId& i : q)
            i = i < nr ? i : i + vshift;
        t.sub_tri.push_back(q);
        t.sub_body.push_back(b);
        t.sub_parent.push_back(o.sub_parent[s]);
    }
    t.body_sub_begin.push_back(static_cast<int32_t>(t.sub_tri.size()));
    t.node_dist.resize(static_cast<size_t>(t.num_contact_nodes()), 0.0);
    t.node_dist_edge.resize(static_cast<size_t>(t.num_contact_nodes()), -1);
    for (int32_t v = o.body_virt_begin[b]; v < o.body_virt_begin[b + 1]; ++v) {
        const size_t from = static_cast<size_t>(nr + v), to = static_cast<size_t>(nr + v + vshift);
        t.node_dist[to] = o.node_dist[from];
        t.node_dist_edge[to] = o.node_dist_edge[from] < 0 ? -1 : o.node_dist_edge[from] + eshift;
    }
    t.num_fallback_nodes += o.body_fallback[b];
    t.body_fallback.back() = o.body_fallback[b];
}

// Build t for m: bodies with dirty[b] (or every body when old is null) by TopologyBuilder, the
// others spliced from old; then the passes over all bodies (contact node lists, target scales,
// edge targets, baseline B field).
void assemble(const Model& m, const ContactTopology* old, const std::vector<uint8_t>* dirty,
              std::span<const NodeId> node_sector, ContactTopology& cm) {
    cm = ContactTopology{};
    cm.num_real_nodes = m.num_nodes();
    cm.edge_target_base = cm.num_real_nodes;
    if (m.contact.algorithm == ContactAlgorithm::None) return;

    cm.body_fixed.resize(static_cast<size_t>(m.num_bodies()));
    cm.body_self.resize(static_cast<size_t>(m.num_bodies()));
    bool any_fracture = false;
    for (BodyId b = 0; b < m.num_bodies(); ++b) {
        cm.body_fixed[b] = m.bodies[b].fixed ? 1 : 0;
        cm.body_self[b] = m.bodies[b].fracture ? 1 : 0;
        any_fracture = any_fracture || m.bodies[b].fracture;
    }
    // the weld only where it can differ from the identity: bodies with fracture
    if (any_fracture && !node_sector.empty())
        cm.node_weld.assign(node_sector.begin(), node_sector.end());
    cm.node_on_boundary.assign(static_cast<size_t>(m.num_nodes()), 0);
    cm.node_dist.assign(static_cast<size_t>(m.num_nodes()), 0.0);
    cm.node_dist_edge.assign(static_cast<size_t>(m.num_nodes()), -1);
    cm.body_bnode_begin.push_back(0);
    cm.body_bedge_begin.push_back(0);
    cm.body_sub_begin.push_back(0);
    cm.body_virt_begin.push_back(0);
    cm.body_chord_begin.push_back(0);
    cm.body_btri_begin.push_back(0);
    TopologyBuilder tb(m, cm);
    for (BodyId b = 0; b < m.num_bodies(); ++b) {
        cm.body_fallback.push_back(0);
        if (old != nullptr && (*dirty)[static_cast<size_t>(b)] == 0) {
            splice_body(m, *old, b, cm);
        } else {
            tb.body(b);
        }
        cm.body_virt_begin.push_back(cm.num_virtual());
        cm.body_chord_begin.push_back(static_cast<int32_t>(cm.chords.size()));
        cm.body_btri_begin.push_back(static_cast<int32_t>(cm.boundary_tris.size()));
    }
    cm.node_dist.resize(static_cast<size_t>(cm.num_contact_nodes()), 0.0);
    cm.node_dist_edge.resize(static_cast<size_t>(cm.num_contact_nodes()), -1);
    build_body_contact_nodes(cm);

    // scale of the force on a target node (docs/theory.md §6.11): m_j / mbar (eq. 19) or
    // l_j / lbar with l_j = half the lengths of the node's boundary edges (its tributary
    // length), lbar = the smallest boundary edge; m_dt is the mass of the stable-dt bound
    const Real m_bar = m.contact.m_bar;
    cm.node_scale.assign(static_cast<size_t>(m.num_nodes()), 0.0);
    cm.l_bar = 0;
    cm.m_dt = m_bar;
    if (m.contact.scaling == ContactScaling::Mass) {
        for (NodeId i = 0; i < m.num_nodes(); ++i)
            cm.node_scale[i] = m.node_mass[i] / m_bar;
    } else {
        Real l_bar = std::numeric_limits<Real>::infinity();
        for (const auto& e : cm.boundary_edges) {
            const Real len = norm(m.node_x0[e[1]] - m.node_x0[e[0]]);
            l_bar = std::min(l_bar, len);
            cm.node_scale[e[0]] += 0.5 * len;
            cm.node_scale[e[1]] += 0.5 * len;
        }
        if (!(l_bar > 0) || !std::isfinite(l_bar)) l_bar = 0;
        cm.l_bar = l_bar;
        Real m_dt = std::numeric_limits<Real>::infinity();
        for (NodeId i = 0; i < m.num_nodes(); ++i) {
            if (cm.node_scale[i] == 0) continue;
            cm.node_scale[i] /= l_bar;
            if (m.node_inv_mass[i] > 0) m_dt = std::min(m_dt, m.node_mass[i] / cm.node_scale[i]);
        }
        cm.m_dt = std::isfinite(m_dt) ? m_dt : m_bar;
    }

    cm.edge_target_base = cm.num_contact_nodes();
    if (m.contact.edge_targets && m.contact.algorithm == ContactAlgorithm::Smooth)
        add_edge_targets(m, cm);
    if (!cm.node_weld.empty()) build_weld_groups(m, cm);

    // baseline B: phi_B per contactor sub-triangle (spec §1.3, docs/theory.md §7.4)
    if (m.contact.algorithm == ContactAlgorithm::LegacyBoundary) {
        cm.sub_legacy_b = build_legacy_boundary_field(m, cm).sub;
    }
}

}  // namespace

void build_body_contact_nodes(ContactTopology& cm) {
    cm.body_cnode.clear();
    cm.body_cnode_begin.assign(1, 0);
    cm.body_cnode_nreal.clear();
    cm.sub_local.assign(cm.sub_tri.size(), {0, 0, 0});
    const int32_t nbodies =
        cm.body_sub_begin.empty() ? 0 : static_cast<int32_t>(cm.body_sub_begin.size()) - 1;
    std::vector<NodeId> ids;
    for (BodyId b = 0; b < nbodies; ++b) {
        ids.clear();
        for (int32_t t = cm.body_sub_begin[b]; t < cm.body_sub_begin[b + 1]; ++t)
            ids.insert(ids.end(), cm.sub_tri[t].begin(), cm.sub_tri[t].end());
        // ascending contact ids: the real nodes [0, num_real_nodes) come first
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        const auto nreal =
            std::lower_bound(ids.begin(), ids.end(), cm.num_real_nodes) - ids.begin();
        cm.body_cnode_nreal.push_back(static_cast<int32_t>(nreal));
        for (int32_t t = cm.body_sub_begin[b]; t < cm.body_sub_begin[b + 1]; ++t) {
            for (int k = 0; k < 3; ++k) {
                const auto it = std::lower_bound(ids.begin(), ids.end(), cm.sub_tri[t][k]);
                cm.sub_local[t][k] = static_cast<int32_t>(it - ids.begin());
            }
        }
        cm.body_cnode.insert(cm.body_cnode.end(), ids.begin(), ids.end());
        cm.body_cnode_begin.push_back(static_cast<int32_t>(cm.body_cnode.size()));
    }
}

void resolve_contact_params(Model& m) {
    ContactModel& cm = m.contact;
    cm.resolved.clear();
    if (cm.algorithm == ContactAlgorithm::None) return;
    // the legacy potentials (docs/theory.md §7) use the same topology: baseline A its
    // boundary_tris, parameters and buffer, baseline B also the sub-triangles
    resolve_params(m);

    // m_bar = smallest element mass over all bodies, fixed ones included (eq. 19, spec §4.5-7);
    // h_min = smallest altitude (buffer default and depth diagnostics)
    cm.h_min = std::numeric_limits<Real>::infinity();
    Real m_bar = std::numeric_limits<Real>::infinity();
    for (TriId t = 0; t < m.num_tris(); ++t) {
        const auto& n = m.tri_nodes[t];
        const Vec2 a = m.node_x0[n[0]], b = m.node_x0[n[1]], c = m.node_x0[n[2]];
        const Real area = std::abs(signed_area(a, b, c));
        const Real lmax = std::max({norm(b - a), norm(c - b), norm(a - c)});
        cm.h_min = std::min(cm.h_min, 2.0 * area / lmax);
        m_bar = std::min(m_bar, m.materials[m.tri_material[t]].density * area);
    }
    if (m.num_tris() == 0) cm.h_min = 0;
    if (cm.m_bar == 0) cm.m_bar = m.num_tris() > 0 ? m_bar : 0;
    if (cm.buffer == 0) cm.buffer = 0.2 * cm.h_min;  // spec §2.5
    if (!(cm.buffer > 0) && m.num_tris() > 0) {
        throw InputError(SourceLocation{}, "contact.buffer",
                         fmt::format("contact buffer must be > 0, got {}", cm.buffer));
    }
    if (!(cm.m_bar > 0) && m.num_tris() > 0) {
        throw InputError(SourceLocation{}, "density",
                         fmt::format("contact needs the smallest element mass > 0 (eq. 19), got "
                                     "{}; every body, fixed ones included, needs a density",
                                     cm.m_bar));
    }
}

namespace {

void check_sectors(const Model& m, std::span<const NodeId> node_sector, const char* who) {
    if (!node_sector.empty() && node_sector.size() != static_cast<size_t>(m.num_nodes())) {
        throw std::invalid_argument(
            fmt::format("{}: node_sector has {} entries, the model {} nodes", who,
                        node_sector.size(), m.num_nodes()));
    }
}

}  // namespace

void build_topology(const Model& m, ContactTopology& t) {
    build_topology(m, {}, t);
}

void build_topology(const Model& m, std::span<const NodeId> node_sector, ContactTopology& t) {
    check_sectors(m, node_sector, "build_topology");
    assemble(m, nullptr, nullptr, node_sector, t);
    if constexpr (kAssertsEnabled) {
        const std::vector<std::string> bad = validate_topology(m, t, 1);
        FDEM_ASSERT(bad.empty(), bad.front().c_str());
    }
}

ContactTopology build_topology(const Model& m) {
    ContactTopology t;
    build_topology(m, t);
    return t;
}

void rebuild_topology(const Model& m, std::span<const BodyId> dirty, ContactTopology& t) {
    rebuild_topology(m, dirty, {}, t);
}

void rebuild_topology(const Model& m, std::span<const BodyId> dirty,
                      std::span<const NodeId> node_sector, ContactTopology& t) {
    check_sectors(m, node_sector, "rebuild_topology");
    if (m.contact.algorithm == ContactAlgorithm::None) {
        assemble(m, nullptr, nullptr, node_sector, t);
        return;
    }
    FDEM_ASSERT(t.body_virt_begin.size() == static_cast<size_t>(m.num_bodies()) + 1,
                "rebuild_topology: t is not a topology of this model's bodies");
    std::vector<uint8_t> flag(static_cast<size_t>(m.num_bodies()), 0);
    for (const BodyId b : dirty) {
        if (b < 0 || b >= m.num_bodies()) {
            throw std::invalid_argument(
                fmt::format("rebuild_topology: body {} outside 0 .. {}", b, m.num_bodies() - 1));
        }
        flag[static_cast<size_t>(b)] = 1;
    }
    ContactTopology next;
    assemble(m, &t, &flag, node_sector, next);
    t = std::move(next);
    if constexpr (kAssertsEnabled) {
        const std::vector<std::string> bad = validate_topology(m, t, 1);
        FDEM_ASSERT(bad.empty(), bad.front().c_str());
    }
}

}  // namespace fdem
