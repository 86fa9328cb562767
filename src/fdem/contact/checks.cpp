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

// whether boundary edge e crosses the ray from p to +x (the even-odd rule's term)
bool crosses(const Model& m, const ContactTopology& ct, int32_t e, Vec2 p) {
    const Vec2 a = m.node_x0[ct.boundary_edges[e][0]], c = m.node_x0[ct.boundary_edges[e][1]];
    if ((a.y > p.y) != (c.y > p.y)) {
        const Real xc = a.x + (p.y - a.y) * (c.x - a.x) / (c.y - a.y);
        return p.x < xc;
    }
    return false;
}

// even-odd test of p against the boundary edges of body b (holes included), reference positions
bool inside(const Model& m, const ContactTopology& ct, BodyId b, Vec2 p) {
    bool in = false;
    for (int32_t e = ct.body_bedge_begin[b]; e < ct.body_bedge_begin[b + 1]; ++e)
        in = in != crosses(m, ct, e, p);
    return in;
}

// Horizontal strips of one large body (a wall ring around a raster of 10^6 particles has 10^4
// boundary edges and is a neighbour of every particle): its boundary edges by the strips their
// y-range meets, and its test points by strip. strip(y) is non-decreasing in y (a subtraction
// and a division by h > 0, then floor), so an edge whose y-range holds p.y is in p's strip, and
// a point in a box is in a strip the box's y-range meets: the tests below skip only what could
// not count.
struct Strips {
    Real y0 = 0, h = 1;
    int32_t n = 1;
    std::vector<int32_t> edge_begin, edges;    // CSR: boundary edges meeting strip s
    std::vector<int32_t> point_begin, points;  // CSR: point sequence numbers in strip s
    int32_t strip(Real y) const {
        const Real s = std::floor((y - y0) / h);
        return s < 0 ? 0 : (s >= n ? n - 1 : static_cast<int32_t>(s));
    }
};

// bodies with more boundary edges than this get strips (smaller ones: the plain loops)
constexpr int32_t kStripEdges = 256;

bool inside_strips(const Model& m, const ContactTopology& ct, const Strips& st, Vec2 p) {
    bool in = false;
    const int32_t s = st.strip(p.y);
    for (int32_t k = st.edge_begin[s]; k < st.edge_begin[s + 1]; ++k)
        in = in != crosses(m, ct, st.edges[k], p);
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
    // strips of the bodies with many boundary edges (else empty)
    std::vector<Strips> strips(static_cast<size_t>(nb));
    auto num_points = [&](BodyId a) {
        return (ct.body_bnode_begin[a + 1] - ct.body_bnode_begin[a]) +
               (ct.body_bedge_begin[a + 1] - ct.body_bedge_begin[a]) +
               (btri_begin[a + 1] - btri_begin[a]);
    };
    // test point q of body a (in the order of points_of_in(): boundary nodes, boundary-edge
    // midpoints, centroids of boundary elements)
    struct TestPoint {
        Vec2 p;
        InitialOverlap::Point kind;
        NodeId node;
        int32_t edge;
        TriId tri;
    };
    auto point = [&](BodyId a, int32_t q) -> TestPoint {
        const int32_t nn = ct.body_bnode_begin[a + 1] - ct.body_bnode_begin[a];
        const int32_t ne = ct.body_bedge_begin[a + 1] - ct.body_bedge_begin[a];
        if (q < nn) {
            const NodeId i = ct.boundary_nodes[ct.body_bnode_begin[a] + q];
            return {m.node_x0[i], InitialOverlap::Point::Node, i, -1, kNone};
        }
        if (q < nn + ne) {
            const int32_t e = ct.body_bedge_begin[a] + q - nn;
            const auto& be = ct.boundary_edges[e];
            return {0.5 * (m.node_x0[be[0]] + m.node_x0[be[1]]),
                    InitialOverlap::Point::EdgeMidpoint, be[0], e, kNone};
        }
        const TriId t = ct.boundary_tris[btri_begin[a] + q - nn - ne];
        const auto& n = m.tri_nodes[t];
        return {(m.node_x0[n[0]] + m.node_x0[n[1]] + m.node_x0[n[2]]) / 3.0,
                InitialOverlap::Point::Centroid, n[0], -1, t};
    };
    for (BodyId b = 0; b < nb; ++b) {
        const int32_t E = ct.body_bedge_begin[b + 1] - ct.body_bedge_begin[b];
        if (E <= kStripEdges) continue;
        Strips& st = strips[static_cast<size_t>(b)];
        st.y0 = box[b].lo.y;
        st.n = std::min<int32_t>(E / 4, 1 << 16);
        st.h = (box[b].hi.y - box[b].lo.y) / st.n;
        if (!(st.h > 0) || !std::isfinite(st.h)) {
            st.n = 1;
            st.h = 1;
        }
        st.edge_begin.assign(static_cast<size_t>(st.n) + 1, 0);
        auto edge_strips = [&](int32_t e) {
            const Real ya = m.node_x0[ct.boundary_edges[e][0]].y;
            const Real yc = m.node_x0[ct.boundary_edges[e][1]].y;
            return std::pair<int32_t, int32_t>{st.strip(std::min(ya, yc)),
                                               st.strip(std::max(ya, yc))};
        };
        for (int32_t e = ct.body_bedge_begin[b]; e < ct.body_bedge_begin[b + 1]; ++e) {
            const auto [s0, s1] = edge_strips(e);
            for (int32_t k = s0; k <= s1; ++k)
                ++st.edge_begin[static_cast<size_t>(k) + 1];
        }
        std::partial_sum(st.edge_begin.begin(), st.edge_begin.end(), st.edge_begin.begin());
        st.edges.resize(static_cast<size_t>(st.edge_begin.back()));
        std::vector<int32_t> at(st.edge_begin.begin(), st.edge_begin.end() - 1);
        for (int32_t e = ct.body_bedge_begin[b]; e < ct.body_bedge_begin[b + 1]; ++e) {
            const auto [s0, s1] = edge_strips(e);
            for (int32_t k = s0; k <= s1; ++k)
                st.edges[static_cast<size_t>(at[static_cast<size_t>(k)]++)] = e;
        }
        const int32_t np = num_points(b);
        st.point_begin.assign(static_cast<size_t>(st.n) + 1, 0);
        for (int32_t q = 0; q < np; ++q)
            ++st.point_begin[static_cast<size_t>(st.strip(point(b, q).p.y)) + 1];
        std::partial_sum(st.point_begin.begin(), st.point_begin.end(), st.point_begin.begin());
        st.points.resize(static_cast<size_t>(np));
        at.assign(st.point_begin.begin(), st.point_begin.end() - 1);
        for (int32_t q = 0; q < np; ++q)  // ascending within each strip
            st.points[static_cast<size_t>(at[static_cast<size_t>(st.strip(point(b, q).p.y))]++)] =
                q;
    }

    auto test = [&](BodyId a, BodyId b, Vec2 p, InitialOverlap::Point kind, NodeId node,
                    int32_t edge, TriId tri) {
        if (!in_box(box[b], p)) return;
        const Strips& sb = strips[static_cast<size_t>(b)];
        if (!(sb.edge_begin.empty() ? inside(m, ct, b, p) : inside_strips(m, ct, sb, p))) return;
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
    std::vector<int32_t> picked;  // points of a large body in the strips of another's box
    auto points_of_in = [&](BodyId a, BodyId b) {
        const Strips& sa = strips[static_cast<size_t>(a)];
        if (sa.point_begin.empty()) {
            for (int32_t q = 0, np = num_points(a); q < np; ++q) {
                const TestPoint t = point(a, q);
                test(a, b, t.p, t.kind, t.node, t.edge, t.tri);
            }
            return;
        }
        // only points in b's box can count: those of the strips b's box meets, in their order
        picked.clear();
        for (int32_t k = sa.strip(box[b].lo.y); k <= sa.strip(box[b].hi.y); ++k) {
            for (int32_t j = sa.point_begin[k]; j < sa.point_begin[k + 1]; ++j) {
                const int32_t q = sa.points[static_cast<size_t>(j)];
                if (in_box(box[b], point(a, q).p)) picked.push_back(q);
            }
        }
        std::sort(picked.begin(), picked.end());
        for (const int32_t q : picked) {
            const TestPoint t = point(a, q);
            test(a, b, t.p, t.kind, t.node, t.edge, t.tri);
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
