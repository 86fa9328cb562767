// Validator of the contact topology: every invariant listed in validate.hpp, checked from the
// mesh (Model) and the topology arrays alone. Sizes and ranges are checked first; the checks
// that index arrays run only when those passed, so a corrupted topology gives messages, never
// an out-of-bounds read.
#include "contact/validate.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

namespace fdem {

namespace {

using Key = std::array<NodeId, 2>;
Key key(NodeId a, NodeId b) {
    return a < b ? Key{a, b} : Key{b, a};
}

class Validator {
public:
    Validator(const Model& m, const ContactTopology& t, size_t max_messages)
        : m_(m), t_(t), max_(max_messages) {}

    std::vector<std::string> run() {
        if (!sizes()) return out_;
        if (m_.contact.algorithm == ContactAlgorithm::None) return out_;
        if (!ranges()) return out_;
        for (BodyId b = 0; b < m_.num_bodies(); ++b)
            body_edges(b);
        boundary_nodes();
        chords();
        boundary_tris();
        virtual_nodes();
        sub_triangles();
        contact_node_lists();
        distances();
        scales();
        return out_;
    }

private:
    template <typename... A>
    void fail(fmt::format_string<A...> f, A&&... a) {
        if (out_.size() < max_) out_.push_back(fmt::format(f, std::forward<A>(a)...));
    }
    size_t nb() const { return static_cast<size_t>(m_.num_bodies()); }
    bool is_real(NodeId i) const { return i >= 0 && i < t_.num_real_nodes; }
    bool is_contact(NodeId i) const { return i >= 0 && i < t_.num_contact_nodes(); }
    // sector of real node i: the weld in a body with fracture (welded form), else i
    NodeId W(NodeId i) const {
        return t_.node_weld.empty() || !m_.bodies[m_.node_body[i]].fracture ? i : t_.node_weld[i];
    }
    bool in_body(NodeId i, BodyId b) const {
        return i >= m_.bodies[b].node_begin && i < m_.bodies[b].node_end;
    }
    Vec2 x0(NodeId i) const {
        if (i < t_.num_real_nodes) return m_.node_x0[i];
        const size_t v = static_cast<size_t>(i - t_.num_real_nodes);
        Vec2 x;
        for (int k = 0; k < 3; ++k)
            x += t_.virt_weight[v][k] * m_.node_x0[t_.virt_parent[v][k]];
        return x;
    }
    // body of contact node i (real: node_body; virtual: its first parent's)
    BodyId body_of(NodeId i) const {
        if (i < t_.num_real_nodes) return m_.node_body[i];
        return m_.node_body[t_.virt_parent[static_cast<size_t>(i - t_.num_real_nodes)][0]];
    }

    bool sizes() {
        const size_t before = out_.size();
        auto eq = [&](const char* name, size_t got, size_t want) {
            if (got != want) fail("sizes: {} has {} entries, expected {}", name, got, want);
        };
        if (t_.num_real_nodes != m_.num_nodes())
            fail("sizes: num_real_nodes = {}, the model has {} nodes", t_.num_real_nodes,
                 m_.num_nodes());
        if (t_.edge_target_base != t_.num_contact_nodes())
            fail("sizes: edge_target_base = {}, expected num_contact_nodes() = {}",
                 t_.edge_target_base, t_.num_contact_nodes());
        if (m_.contact.algorithm == ContactAlgorithm::None) {
            if (!t_.sub_tri.empty() || !t_.boundary_edges.empty() || t_.num_virtual() != 0)
                fail("sizes: contact is off but the topology is not empty");
            return out_.size() == before;
        }
        const size_t nn = static_cast<size_t>(m_.num_nodes());
        const size_t nc = static_cast<size_t>(std::max(t_.num_contact_nodes(), 0));
        const size_t ns = t_.sub_tri.size();
        eq("node_on_boundary", t_.node_on_boundary.size(), nn);
        eq("node_scale", t_.node_scale.size(), nn);
        eq("node_dist", t_.node_dist.size(), nc);
        eq("node_dist_edge", t_.node_dist_edge.size(), nc);
        eq("virt_weight", t_.virt_weight.size(), t_.virt_parent.size());
        eq("sub_body", t_.sub_body.size(), ns);
        eq("sub_parent", t_.sub_parent.size(), ns);
        eq("sub_local", t_.sub_local.size(), ns);
        eq("body_fixed", t_.body_fixed.size(), nb());
        eq("body_bnode_begin", t_.body_bnode_begin.size(), nb() + 1);
        eq("body_bedge_begin", t_.body_bedge_begin.size(), nb() + 1);
        eq("body_sub_begin", t_.body_sub_begin.size(), nb() + 1);
        eq("body_cnode_begin", t_.body_cnode_begin.size(), nb() + 1);
        eq("body_cnode_nreal", t_.body_cnode_nreal.size(), nb());
        eq("body_virt_begin", t_.body_virt_begin.size(), nb() + 1);
        eq("body_chord_begin", t_.body_chord_begin.size(), nb() + 1);
        eq("body_btri_begin", t_.body_btri_begin.size(), nb() + 1);
        eq("body_fallback", t_.body_fallback.size(), nb());
        eq("body_self", t_.body_self.size(), nb());
        if (!t_.node_weld.empty()) eq("node_weld", t_.node_weld.size(), nn);
        const bool edge_targets =
            m_.contact.edge_targets && m_.contact.algorithm == ContactAlgorithm::Smooth;
        eq("edge_scale", t_.edge_scale.size(), edge_targets ? t_.boundary_edges.size() : 0);
        eq("sub_legacy_b", t_.sub_legacy_b.size(),
           m_.contact.algorithm == ContactAlgorithm::LegacyBoundary ? ns : 0);
        return out_.size() == before;
    }

    bool ranges() {
        const size_t before = out_.size();
        auto range = [&](const char* name, const std::vector<int32_t>& r, size_t end) {
            if (r.front() != 0) fail("ranges: {}[0] = {}, expected 0", name, r.front());
            for (size_t b = 0; b + 1 < r.size(); ++b) {
                if (r[b + 1] < r[b])
                    fail("ranges: {} decreases at body {} ({} -> {})", name, b, r[b], r[b + 1]);
            }
            if (static_cast<size_t>(r.back()) != end)
                fail("ranges: {} ends at {}, the array has {} entries", name, r.back(), end);
        };
        range("body_bnode_begin", t_.body_bnode_begin, t_.boundary_nodes.size());
        range("body_bedge_begin", t_.body_bedge_begin, t_.boundary_edges.size());
        range("body_sub_begin", t_.body_sub_begin, t_.sub_tri.size());
        range("body_cnode_begin", t_.body_cnode_begin, t_.body_cnode.size());
        range("body_virt_begin", t_.body_virt_begin, t_.virt_parent.size());
        range("body_chord_begin", t_.body_chord_begin, t_.chords.size());
        range("body_btri_begin", t_.body_btri_begin, t_.boundary_tris.size());
        int32_t fallback = 0;
        for (const int32_t n : t_.body_fallback)
            fallback += n;
        if (fallback != t_.num_fallback_nodes)
            fail("body_fallback: the bodies' counts add up to {}, num_fallback_nodes = {}",
                 fallback, t_.num_fallback_nodes);
        for (BodyId b = 0; b < m_.num_bodies(); ++b) {
            if ((t_.body_fixed[b] != 0) != m_.bodies[b].fixed)
                fail("body_fixed: body {} has {}, Body::fixed is {}", b, t_.body_fixed[b],
                     m_.bodies[b].fixed);
        }
        for (BodyId b = 0; b < m_.num_bodies(); ++b) {
            if ((t_.body_self[b] != 0) != m_.bodies[b].fracture)
                fail("body_self: body {} has {}, Body::fracture is {}", b, t_.body_self[b],
                     m_.bodies[b].fracture);
        }
        // a weld maps every node to the smallest node of its sector, in its body, at the same
        // reference position (copies of one mesh vertex)
        for (size_t i = 0; i < t_.node_weld.size(); ++i) {
            const NodeId w = t_.node_weld[i];
            const NodeId n = static_cast<NodeId>(i);
            if (w < 0 || w > n || t_.node_weld[static_cast<size_t>(w)] != w ||
                m_.node_body[w] != m_.node_body[n] || !(m_.node_x0[w] == m_.node_x0[n]))
                fail("node_weld: node {} has sector {}", n, w);
        }
        for (size_t v = 0; v < t_.virt_parent.size(); ++v) {
            for (NodeId p : t_.virt_parent[v]) {
                if (!is_real(p)) fail("virtual nodes: virtual node {} has parent {}", v, p);
            }
        }
        for (size_t s = 0; s < t_.sub_tri.size(); ++s) {
            for (NodeId i : t_.sub_tri[s]) {
                if (!is_contact(i)) fail("sub_tri: sub-triangle {} has contact node {}", s, i);
            }
        }
        for (size_t k = 0; k < t_.body_cnode.size(); ++k) {
            if (!is_contact(t_.body_cnode[k]))
                fail("body_cnode: entry {} is contact node {}", k, t_.body_cnode[k]);
        }
        for (const auto& e : t_.boundary_edges) {
            if (!is_real(e[0]) || !is_real(e[1]))
                fail("boundary_edges: edge ({}, {}) has a node outside the model", e[0], e[1]);
        }
        for (NodeId i : t_.boundary_nodes) {
            if (!is_real(i)) fail("boundary_nodes: node {} outside the model", i);
        }
        for (const auto& c : t_.chords) {
            if (!is_real(c[0]) || !is_real(c[1]))
                fail("chords: chord ({}, {}) has a node outside the model", c[0], c[1]);
        }
        for (size_t s = 0; s < t_.sub_parent.size(); ++s) {
            if (t_.sub_parent[s] < 0 || t_.sub_parent[s] >= m_.num_tris())
                fail("sub_parent: sub-triangle {} has parent {}", s, t_.sub_parent[s]);
        }
        for (TriId t : t_.boundary_tris) {
            if (t < 0 || t >= m_.num_tris()) fail("boundary_tris: triangle {} outside", t);
        }
        for (size_t e = 0; e < t_.node_dist_edge.size(); ++e) {
            const int32_t k = t_.node_dist_edge[e];
            if (k < -1 || k >= static_cast<int32_t>(t_.boundary_edges.size()))
                fail("node_dist_edge: contact node {} has edge {}", e, k);
        }
        return out_.size() == before;
    }

    // Directed edges of body b's triangles: (welded) key -> (uses, the triangle's own nodes
    // a->b as in the triangle)
    void body_edges(BodyId b) {
        const Body& body = m_.bodies[b];
        std::map<Key, std::pair<int, Key>> uses;
        for (TriId t = body.tri_begin; t < body.tri_end; ++t) {
            const auto& n = m_.tri_nodes[t];
            for (int k = 0; k < 3; ++k) {
                auto& u = uses[key(W(n[k]), W(n[(k + 1) % 3]))];
                ++u.first;
                u.second = {n[k], n[(k + 1) % 3]};
            }
        }
        size_t once = 0;
        for (const auto& [k, u] : uses) {
            if (u.first == 1) ++once;
            if (u.first == 2 && t_.node_on_boundary[k[0]] && t_.node_on_boundary[k[1]])
                interior_bb_.push_back(k);
        }
        const int32_t e0 = t_.body_bedge_begin[b], e1 = t_.body_bedge_begin[b + 1];
        if (static_cast<size_t>(e1 - e0) != once)
            fail("boundary_edges: body {} lists {} edges, its triangles have {} boundary edges", b,
                 e1 - e0, once);
        for (int32_t e = e0; e < e1; ++e) {
            const auto& be = t_.boundary_edges[e];
            if (!in_body(be[0], b) || !in_body(be[1], b)) {
                fail("boundary_edges: edge {} ({}, {}) is not in body {}", e, be[0], be[1], b);
                continue;
            }
            const auto& bp = t_.boundary_edges[e - (e > e0 ? 1 : 0)];
            if (e > e0 && !(key(W(bp[0]), W(bp[1])) < key(W(be[0]), W(be[1]))))
                fail("boundary_edges: edge {} ({}, {}) is not after edge {} in (min, max) order", e,
                     be[0], be[1], e - 1);
            const auto it = uses.find(key(W(be[0]), W(be[1])));
            if (it == uses.end() || it->second.first != 1) {
                fail("boundary_edges: edge {} ({}, {}) is used by {} triangles of body {}, not 1",
                     e, be[0], be[1], it == uses.end() ? 0 : it->second.first, b);
            } else if (it->second.second != be) {
                fail("boundary_edges: edge {} ({}, {}) is oriented against its triangle", e, be[0],
                     be[1]);
            }
        }
    }

    void boundary_nodes() {
        // welded form: every copy of a sector that ends a boundary edge
        std::vector<uint8_t> end_node(static_cast<size_t>(m_.num_nodes()), 0);
        for (const auto& e : t_.boundary_edges) {
            end_node[W(e[0])] = 1;
            end_node[W(e[1])] = 1;
        }
        for (NodeId i = 0; i < m_.num_nodes(); ++i)
            end_node[i] = end_node[W(i)];
        for (NodeId i = 0; i < m_.num_nodes(); ++i) {
            if ((t_.node_on_boundary[i] != 0) != (end_node[i] != 0))
                fail("node_on_boundary: node {} has {}, but it is {}an end of a boundary edge", i,
                     t_.node_on_boundary[i], end_node[i] ? "" : "not ");
        }
        size_t listed = 0;
        for (BodyId b = 0; b < m_.num_bodies(); ++b) {
            for (int32_t k = t_.body_bnode_begin[b]; k < t_.body_bnode_begin[b + 1]; ++k) {
                const NodeId i = t_.boundary_nodes[k];
                if (!in_body(i, b)) fail("boundary_nodes: node {} is not in body {}", i, b);
                if (k > 0 && !(t_.boundary_nodes[k - 1] < i))
                    fail("boundary_nodes: not strictly ascending at entry {} (node {})", k, i);
                if (!end_node[i]) fail("boundary_nodes: node {} ends no boundary edge", i);
                ++listed;
            }
        }
        const size_t want =
            static_cast<size_t>(std::count(end_node.begin(), end_node.end(), uint8_t{1}));
        if (listed != want)
            fail("boundary_nodes: {} listed, {} nodes end a boundary edge", listed, want);
    }

    void chords() {
        std::sort(interior_bb_.begin(), interior_bb_.end());
        for (size_t c = 0; c < t_.chords.size(); ++c) {
            const Key k = t_.chords[c];
            if (!(k[0] < k[1])) fail("chords: chord {} ({}, {}) is not (min, max)", c, k[0], k[1]);
            if (c > 0 && !(t_.chords[c - 1] < k))
                fail("chords: not strictly ascending at chord {} ({}, {})", c, k[0], k[1]);
            if (!std::binary_search(interior_bb_.begin(), interior_bb_.end(), key(k[0], k[1])))
                fail(
                    "chords: chord {} ({}, {}) is not an interior edge joining two boundary "
                    "nodes",
                    c, k[0], k[1]);
        }
        if (t_.chords.size() != interior_bb_.size())
            fail("chords: {} listed, the mesh has {} interior edges joining boundary nodes",
                 t_.chords.size(), interior_bb_.size());
    }

    void boundary_tris() {
        std::vector<TriId> want;
        for (TriId t = 0; t < m_.num_tris(); ++t) {
            const auto& n = m_.tri_nodes[t];
            if (t_.node_on_boundary[n[0]] || t_.node_on_boundary[n[1]] || t_.node_on_boundary[n[2]])
                want.push_back(t);
        }
        for (size_t k = 1; k < t_.boundary_tris.size(); ++k) {
            if (!(t_.boundary_tris[k - 1] < t_.boundary_tris[k]))
                fail("boundary_tris: not strictly ascending at entry {} (triangle {})", k,
                     t_.boundary_tris[k]);
        }
        if (t_.boundary_tris != want)
            fail("boundary_tris: {} listed, {} triangles have a boundary node (or other ids)",
                 t_.boundary_tris.size(), want.size());
    }

    void virtual_nodes() {
        std::vector<uint8_t> used(t_.virt_parent.size(), 0);
        for (BodyId b = 0; b < m_.num_bodies(); ++b) {
            for (int32_t s = t_.body_sub_begin[b]; s < t_.body_sub_begin[b + 1]; ++s) {
                for (NodeId i : t_.sub_tri[s]) {
                    if (i >= t_.num_real_nodes)
                        used[static_cast<size_t>(i - t_.num_real_nodes)] = 1;
                }
            }
        }
        for (BodyId b = 0; b < m_.num_bodies(); ++b) {
            for (int32_t v = t_.body_virt_begin[b]; v < t_.body_virt_begin[b + 1]; ++v) {
                if (m_.node_body[t_.virt_parent[v][0]] != b)
                    fail(
                        "body_virt_begin: virtual node {} in the range of body {} has parents in "
                        "body {}",
                        v, b, m_.node_body[t_.virt_parent[v][0]]);
            }
            for (int32_t c = t_.body_chord_begin[b]; c < t_.body_chord_begin[b + 1]; ++c) {
                if (!in_body(t_.chords[c][0], b))
                    fail("body_chord_begin: chord {} in the range of body {} is not in it", c, b);
            }
            for (int32_t k = t_.body_btri_begin[b]; k < t_.body_btri_begin[b + 1]; ++k) {
                const TriId tri = t_.boundary_tris[k];
                if (tri < m_.bodies[b].tri_begin || tri >= m_.bodies[b].tri_end)
                    fail(
                        "body_btri_begin: boundary element {} in the range of body {} is not in "
                        "it",
                        tri, b);
            }
        }
        for (size_t v = 0; v < t_.virt_parent.size(); ++v) {
            const auto& p = t_.virt_parent[v];
            const auto& w = t_.virt_weight[v];
            const BodyId b = m_.node_body[p[0]];
            Real sum = 0;
            for (int k = 0; k < 3; ++k) {
                if (m_.node_body[p[k]] != b)
                    fail("virtual nodes: virtual node {} has parents in bodies {} and {}", v, b,
                         m_.node_body[p[k]]);
                if (!(w[k] >= 0 && w[k] <= 1))
                    fail("virtual nodes: virtual node {} has weight {}", v, w[k]);
                sum += w[k];
            }
            if (!(std::abs(sum - 1) <= 1e-12))
                fail("virtual nodes: weights of virtual node {} sum to {}", v, sum);
            if (!used[v]) fail("virtual nodes: virtual node {} is in no sub-triangle", v);
        }
    }

    void sub_triangles() {
        for (BodyId b = 0; b < m_.num_bodies(); ++b) {
            const Body& body = m_.bodies[b];
            Real sub_area = 0, tri_area = 0;
            std::map<Key, int> directed;  // directed real-node edges of the body's sub-triangles
            for (int32_t s = t_.body_sub_begin[b]; s < t_.body_sub_begin[b + 1]; ++s) {
                const auto& q = t_.sub_tri[s];
                if (t_.sub_body[s] != b)
                    fail("sub_body: sub-triangle {} of body {} says {}", s, b, t_.sub_body[s]);
                if (t_.sub_parent[s] < body.tri_begin || t_.sub_parent[s] >= body.tri_end)
                    fail("sub_parent: sub-triangle {} of body {} has parent {} of another body", s,
                         b, t_.sub_parent[s]);
                bool ok = true;
                for (NodeId i : q) {
                    if (body_of(i) != b) {
                        fail("sub_tri: sub-triangle {} of body {} has node {} of body {}", s, b, i,
                             body_of(i));
                        ok = false;
                    }
                }
                if (!ok) continue;
                const Real a = signed_area(x0(q[0]), x0(q[1]), x0(q[2]));
                if (!(a > 0)) fail("sub_tri: sub-triangle {} is not counter-clockwise", s);
                sub_area += a;
                for (int k = 0; k < 3; ++k) {
                    if (is_real(q[k]) && is_real(q[(k + 1) % 3]))
                        ++directed[{q[k], q[(k + 1) % 3]}];
                }
            }
            for (TriId t : t_.boundary_tris) {
                if (t >= body.tri_begin && t < body.tri_end) {
                    const auto& n = m_.tri_nodes[t];
                    tri_area += signed_area(m_.node_x0[n[0]], m_.node_x0[n[1]], m_.node_x0[n[2]]);
                }
            }
            if (!(std::abs(sub_area - tri_area) <= 1e-9 * std::abs(tri_area)))
                fail(
                    "sub_tri: the sub-triangles of body {} cover {} m^2, its boundary elements "
                    "{} m^2",
                    b, sub_area, tri_area);
            for (int32_t e = t_.body_bedge_begin[b]; e < t_.body_bedge_begin[b + 1]; ++e) {
                const auto it = directed.find(t_.boundary_edges[e]);
                const int n = it == directed.end() ? 0 : it->second;
                if (n != 1)
                    fail(
                        "sub_tri: boundary edge {} ({}, {}) is a side of {} sub-triangles of body "
                        "{}, not 1",
                        e, t_.boundary_edges[e][0], t_.boundary_edges[e][1], n, b);
            }
        }
    }

    void contact_node_lists() {
        for (BodyId b = 0; b < m_.num_bodies(); ++b) {
            std::vector<NodeId> ids;
            for (int32_t s = t_.body_sub_begin[b]; s < t_.body_sub_begin[b + 1]; ++s)
                ids.insert(ids.end(), t_.sub_tri[s].begin(), t_.sub_tri[s].end());
            std::sort(ids.begin(), ids.end());
            ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
            const int32_t c0 = t_.body_cnode_begin[b], c1 = t_.body_cnode_begin[b + 1];
            const std::vector<NodeId> listed(t_.body_cnode.begin() + c0,
                                             t_.body_cnode.begin() + c1);
            if (listed != ids) {
                fail(
                    "body_cnode: body {} lists {} contact nodes, its sub-triangles have {} "
                    "distinct ones (or in another order)",
                    b, listed.size(), ids.size());
                continue;
            }
            const auto nreal =
                std::lower_bound(ids.begin(), ids.end(), t_.num_real_nodes) - ids.begin();
            if (t_.body_cnode_nreal[b] != nreal)
                fail("body_cnode_nreal: body {} has {}, expected {}", b, t_.body_cnode_nreal[b],
                     nreal);
            for (int32_t s = t_.body_sub_begin[b]; s < t_.body_sub_begin[b + 1]; ++s) {
                for (int k = 0; k < 3; ++k) {
                    const int32_t l = t_.sub_local[s][k];
                    if (l < 0 || l >= c1 - c0 || t_.body_cnode[c0 + l] != t_.sub_tri[s][k])
                        fail("sub_local: vertex {} of sub-triangle {} points at local {}", k, s, l);
                }
            }
        }
    }

    void distances() {
        std::vector<uint8_t> in_sub(static_cast<size_t>(t_.num_contact_nodes()), 0);
        for (const auto& q : t_.sub_tri) {
            for (NodeId i : q)
                in_sub[i] = 1;
        }
        for (NodeId i = 0; i < t_.num_contact_nodes(); ++i) {
            const Real d = t_.node_dist[i];
            const int32_t e = t_.node_dist_edge[i];
            const bool bnode = i < t_.num_real_nodes && t_.node_on_boundary[i];
            if (bnode || !in_sub[i]) {
                if (d != 0 || e != -1)
                    fail(
                        "node_dist: contact node {} ({}) has distance {} from edge {}, expected "
                        "0 and -1",
                        i, bnode ? "boundary node" : "in no sub-triangle", d, e);
                continue;
            }
            if (!(d > 0) || !std::isfinite(d) || e < 0) {
                fail("node_dist: contact node {} has distance {} from edge {}", i, d, e);
                continue;
            }
            const auto& be = t_.boundary_edges[static_cast<size_t>(e)];
            const BodyId b = body_of(i);
            if (e < t_.body_bedge_begin[b] || e >= t_.body_bedge_begin[b + 1]) {
                fail("node_dist_edge: contact node {} of body {} has edge {} of another body", i, b,
                     e);
                continue;
            }
            // eq. 6.3: distance to the edge's line; fallback eq. 6.4: to the segment
            const Vec2 a = m_.node_x0[be[0]], c = m_.node_x0[be[1]], x = x0(i);
            const Real l = norm(c - a);
            const Real line = std::abs(cross(c - a, x - a)) / l;
            const Real s = std::clamp(dot(x - a, c - a) / (l * l), Real(0), Real(1));
            const Real seg = norm(x - (a + s * (c - a)));
            const Real tol = 1e-9 * (d + l);
            if (!(std::abs(d - line) <= tol || std::abs(d - seg) <= tol))
                fail(
                    "node_dist: contact node {} has distance {}, its distance to boundary edge {} "
                    "is {} (line) / {} (segment)",
                    i, d, e, line, seg);
        }
    }

    void scales() {
        // length scaling: a copy's share of its sector's boundary length, 0 for a copy that
        // ends no boundary edge of its own (welded form); > 0 on every other boundary node
        std::vector<uint8_t> own_end(static_cast<size_t>(m_.num_nodes()), 0);
        for (const auto& e : t_.boundary_edges) {
            own_end[e[0]] = 1;
            own_end[e[1]] = 1;
        }
        const bool length = m_.contact.scaling == ContactScaling::Length;
        for (NodeId i = 0; i < m_.num_nodes(); ++i) {
            const Real s = t_.node_scale[i];
            const bool need = t_.node_on_boundary[i] && (!length || own_end[i]);
            if (!std::isfinite(s) || s < 0 || (need && !(s > 0)))
                fail("node_scale: node {} has {}", i, s);
        }
        for (size_t e = 0; e < t_.edge_scale.size(); ++e) {
            if (!std::isfinite(t_.edge_scale[e]) || !(t_.edge_scale[e] > 0))
                fail("edge_scale: boundary edge {} has {}", e, t_.edge_scale[e]);
        }
    }

    const Model& m_;
    const ContactTopology& t_;
    size_t max_;
    std::vector<std::string> out_;
    std::vector<Key> interior_bb_;  // interior edges joining two boundary nodes, all bodies
};

}  // namespace

std::vector<std::string> validate_topology(const Model& m, const ContactTopology& t,
                                           size_t max_messages) {
    return Validator(m, t, max_messages).run();
}

}  // namespace fdem
