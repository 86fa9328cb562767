// Load-time geometric checks of the contact model (checks.hpp; docs/theory.md §6.13-6.14).
#include "contact/checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/format.h>

namespace fdem {

namespace {

Real point_segment_distance(Vec2 x, Vec2 a, Vec2 b) {
    const Vec2 ab = b - a;
    const Real l2 = norm2(ab);
    Real s = l2 > 0 ? dot(x - a, ab) / l2 : 0;
    s = std::clamp(s, Real(0), Real(1));
    return norm(x - (a + s * ab));
}

// outward unit normal of boundary edge e (material on its left: the normal is on its right)
Vec2 outward_normal(const Model& m, const ContactTopology& ct, int32_t e) {
    const auto& be = ct.boundary_edges[static_cast<size_t>(e)];
    const Vec2 t = m.node_x0[be[1]] - m.node_x0[be[0]];
    const Real l = norm(t);
    return l > 0 ? Vec2{t.y / l, -t.x / l} : Vec2{};
}

Vec2 contact_x0(const ContactTopology& ct, const Model& m, NodeId i) {
    if (i < ct.num_real_nodes) return m.node_x0[i];
    const size_t v = static_cast<size_t>(i - ct.num_real_nodes);
    Vec2 x;
    for (int k = 0; k < 3; ++k)
        x += ct.virt_weight[v][k] * m.node_x0[ct.virt_parent[v][k]];
    return x;
}

struct Box {
    Vec2 lo, hi;
};

// even-odd test of p against the boundary edges of body b (holes included), reference positions
bool inside(const Model& m, const ContactTopology& ct, BodyId b, Vec2 p) {
    bool in = false;
    for (int32_t e = ct.body_bedge_begin[b]; e < ct.body_bedge_begin[b + 1]; ++e) {
        const Vec2 a = m.node_x0[ct.boundary_edges[e][0]], c = m.node_x0[ct.boundary_edges[e][1]];
        if ((a.y > p.y) != (c.y > p.y)) {
            const Real xc = a.x + (p.y - a.y) * (c.x - a.x) / (c.y - a.y);
            if (p.x < xc) in = !in;
        }
    }
    return in;
}

Real boundary_distance(const Model& m, const ContactTopology& ct, BodyId b, Vec2 p) {
    Real d = std::numeric_limits<Real>::infinity();
    for (int32_t e = ct.body_bedge_begin[b]; e < ct.body_bedge_begin[b + 1]; ++e) {
        d = std::min(d, point_segment_distance(p, m.node_x0[ct.boundary_edges[e][0]],
                                               m.node_x0[ct.boundary_edges[e][1]]));
    }
    return d;
}

}  // namespace

InitialOverlap find_initial_overlap(const Model& m, const ContactTopology& ct) {
    const ContactModel& cm = m.contact;
    InitialOverlap best;
    const BodyId nb = m.num_bodies();
    if (cm.algorithm == ContactAlgorithm::None || nb < 2 ||
        ct.body_bedge_begin.size() != static_cast<size_t>(nb) + 1) {
        return best;
    }
    best.tolerance = kOverlapTolerance * cm.h_min;
    const Real tol = best.tolerance;

    // boxes of the bodies (all their nodes), widened by the tolerance
    std::vector<Box> box(static_cast<size_t>(nb));
    for (BodyId b = 0; b < nb; ++b) {
        constexpr Real inf = std::numeric_limits<Real>::infinity();
        Box x{{inf, inf}, {-inf, -inf}};
        for (NodeId i = m.bodies[b].node_begin; i < m.bodies[b].node_end; ++i) {
            const Vec2 p = m.node_x0[i];
            x.lo = {std::min(x.lo.x, p.x), std::min(x.lo.y, p.y)};
            x.hi = {std::max(x.hi.x, p.x), std::max(x.hi.y, p.y)};
        }
        box[b] = {{x.lo.x - tol, x.lo.y - tol}, {x.hi.x + tol, x.hi.y + tol}};
    }
    // boundary elements per body (boundary_tris ascending, bodies own contiguous triangles)
    std::vector<int32_t> btri_begin(static_cast<size_t>(nb) + 1, 0);
    for (TriId t : ct.boundary_tris)
        ++btri_begin[static_cast<size_t>(m.tri_body[t]) + 1];
    std::partial_sum(btri_begin.begin(), btri_begin.end(), btri_begin.begin());

    auto in_box = [](const Box& x, Vec2 p) {
        return p.x > x.lo.x && p.x < x.hi.x && p.y > x.lo.y && p.y < x.hi.y;
    };
    auto test = [&](BodyId a, BodyId b, Vec2 p, InitialOverlap::Point kind, NodeId node,
                    int32_t edge, TriId tri) {
        if (!in_box(box[b], p) || !inside(m, ct, b, p)) return;
        const Real d = boundary_distance(m, ct, b, p);
        if (!(d > tol) || (best.found && !(d > best.depth))) return;
        best.found = true;
        best.body = a;
        best.other = b;
        best.point = kind;
        best.node = node;
        best.edge = edge;
        best.tri = tri;
        best.where = p;
        best.depth = d;
    };
    // points of body a inside body b: boundary nodes, boundary-edge midpoints, centroids of
    // boundary elements (the last ones find coincident meshes, whose boundaries coincide)
    auto points_of_in = [&](BodyId a, BodyId b) {
        for (int32_t k = ct.body_bnode_begin[a]; k < ct.body_bnode_begin[a + 1]; ++k) {
            const NodeId i = ct.boundary_nodes[k];
            test(a, b, m.node_x0[i], InitialOverlap::Point::Node, i, -1, kNone);
        }
        for (int32_t e = ct.body_bedge_begin[a]; e < ct.body_bedge_begin[a + 1]; ++e) {
            const auto& be = ct.boundary_edges[e];
            test(a, b, 0.5 * (m.node_x0[be[0]] + m.node_x0[be[1]]),
                 InitialOverlap::Point::EdgeMidpoint, be[0], e, kNone);
        }
        for (int32_t k = btri_begin[a]; k < btri_begin[a + 1]; ++k) {
            const TriId t = ct.boundary_tris[k];
            const auto& n = m.tri_nodes[t];
            const Vec2 c = (m.node_x0[n[0]] + m.node_x0[n[1]] + m.node_x0[n[2]]) / 3.0;
            test(a, b, c, InitialOverlap::Point::Centroid, n[0], -1, t);
        }
    };

    // sweep over the boxes sorted by their lower x (ties: body id)
    std::vector<BodyId> order(static_cast<size_t>(nb));
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](BodyId a, BodyId b) { return box[a].lo.x < box[b].lo.x; });
    std::vector<std::pair<BodyId, BodyId>> pairs;
    for (size_t i = 0; i < order.size(); ++i) {
        const BodyId a = order[i];
        for (size_t j = i + 1; j < order.size() && box[order[j]].lo.x < box[a].hi.x; ++j) {
            const BodyId b = order[j];
            if (box[b].lo.y >= box[a].hi.y || box[a].lo.y >= box[b].hi.y) continue;
            if (ct.body_fixed[a] && ct.body_fixed[b]) continue;  // never interact
            pairs.emplace_back(std::min(a, b), std::max(a, b));
        }
    }
    std::sort(pairs.begin(), pairs.end());  // a fixed order for the tie rule
    for (const auto& [a, b] : pairs) {
        points_of_in(a, b);
        points_of_in(b, a);
    }
    return best;
}

std::vector<ThinLayer> find_thin_layers(const Model& m, const ContactTopology& ct) {
    const ContactModel& cm = m.contact;
    std::vector<ThinLayer> out;
    if (cm.algorithm != ContactAlgorithm::Smooth || ct.node_dist_edge.empty()) return out;
    // boundary edges at each real node (CSR)
    const size_t nn = static_cast<size_t>(m.num_nodes());
    std::vector<int32_t> begin(nn + 1, 0), edges;
    for (const auto& be : ct.boundary_edges) {
        ++begin[static_cast<size_t>(be[0]) + 1];
        ++begin[static_cast<size_t>(be[1]) + 1];
    }
    std::partial_sum(begin.begin(), begin.end(), begin.begin());
    edges.resize(static_cast<size_t>(begin[nn]));
    {
        std::vector<int32_t> cur(begin.begin(), begin.end() - 1);
        for (int32_t e = 0; e < static_cast<int32_t>(ct.boundary_edges.size()); ++e) {
            for (NodeId i : ct.boundary_edges[e])
                edges[static_cast<size_t>(cur[i]++)] = e;
        }
    }
    for (BodyId b = 0; b < m.num_bodies(); ++b) {
        ThinLayer worst;
        worst.body = b;
        for (int32_t s = ct.body_sub_begin[b]; s < ct.body_sub_begin[b + 1]; ++s) {
            const auto& q = ct.sub_tri[s];
            for (NodeId o : q) {
                const bool bnode = o < ct.num_real_nodes && ct.node_on_boundary[o];
                const int32_t src = ct.node_dist_edge[static_cast<size_t>(o)];
                if (bnode || src < 0) continue;
                const Vec2 n_src = outward_normal(m, ct, src);
                const Vec2 xo = contact_x0(ct, m, o);
                // the faces the sub-triangle touches: boundary edges at its boundary vertices
                bool any = false, opposite = true;
                Real near = std::numeric_limits<Real>::infinity();
                for (NodeId v : q) {
                    if (v >= ct.num_real_nodes || !ct.node_on_boundary[v]) continue;
                    for (int32_t k = begin[v]; k < begin[v + 1]; ++k) {
                        const int32_t e = edges[static_cast<size_t>(k)];
                        any = true;
                        // more than 120 degrees apart: a corner (90 degrees) is not "opposite"
                        if (dot(outward_normal(m, ct, e), n_src) >= -0.5) opposite = false;
                        const auto& be = ct.boundary_edges[e];
                        near = std::min(
                            near, point_segment_distance(xo, m.node_x0[be[0]], m.node_x0[be[1]]));
                    }
                }
                const Real d = ct.node_dist[static_cast<size_t>(o)];
                // only where the far face gives a clearly smaller distance (a tie tilts nothing)
                if (!any || !opposite || !(d < kThinLayerRatio * near)) continue;
                ++worst.count;
                if (worst.tri == kNone || near / d > worst.near_dist / worst.dist) {
                    worst.tri = ct.sub_parent[s];
                    worst.node = o;
                    worst.edge = src;
                    worst.dist = d;
                    worst.near_dist = near;
                }
            }
        }
        if (worst.count > 0) out.push_back(worst);
    }
    return out;
}

std::string thin_layer_warning(const Model& m, const ContactTopology& ct, const ThinLayer& t) {
    const auto& be = ct.boundary_edges[static_cast<size_t>(t.edge)];
    const std::string node = t.node < ct.num_real_nodes
                                 ? fmt::format("node {}", t.node)
                                 : fmt::format("virtual node {} (chord midpoint or incenter)",
                                               t.node - ct.num_real_nodes);
    return fmt::format(
        "warning: body {} \"{}\" is too thin for its contact layer: in {} boundary "
        "sub-triangle(s) an inner node takes its contact distance from the opposite face, e.g. "
        "{} of element {}: {:.4g} m from boundary edge {}-{} on the far side instead of "
        "{:.4g} m from the face element {} lies on; the contact normal there tilts towards the "
        "far face (docs/theory.md §6.13). Remedy: make the body thicker (at least three elements "
        "through its thickness) or refine the mesh there",
        t.body, m.bodies[t.body].name, t.count, node, t.tri, t.dist, be[0], be[1], t.near_dist,
        t.tri);
}

}  // namespace fdem
