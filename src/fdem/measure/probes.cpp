// Probes: position, velocity and stress of chosen nodes, groups or bodies (measure.hpp,
// docs/output.md probes.csv, theory eq. 8.6).
#include <limits>

#include "fdem/measure.hpp"
#include "fdem/output.hpp"

namespace fdem {

namespace {

// p inside or on triangle (a, b, c), counter-clockwise in the reference configuration
bool contains(Vec2 a, Vec2 b, Vec2 c, Vec2 p) {
    return cross(b - a, p - a) >= 0 && cross(c - b, p - b) >= 0 && cross(a - c, p - c) >= 0;
}

Vec2 centroid0(const Model& m, TriId t) {
    const auto& n = m.tri_nodes[static_cast<size_t>(t)];
    return (m.node_x0[static_cast<size_t>(n[0])] + m.node_x0[static_cast<size_t>(n[1])] +
            m.node_x0[static_cast<size_t>(n[2])]) /
           3.0;
}

}  // namespace

void locate_probe(const Model& m, Vec2 p, int32_t entry, NodeId& node, TriId& tri) {
    node = kNone;
    tri = kNone;
    Real best = std::numeric_limits<Real>::infinity();
    for (const Body& b : m.bodies) {
        if (entry >= 0 && b.group != entry) continue;
        for (NodeId i = b.node_begin; i < b.node_end; ++i) {
            const Real d = norm2(m.node_x0[static_cast<size_t>(i)] - p);
            if (d < best) {
                best = d;
                node = i;
            }
        }
    }
    if (node == kNone) return;
    const Body& b = m.bodies[static_cast<size_t>(m.node_body[static_cast<size_t>(node)])];
    for (TriId t = b.tri_begin; t < b.tri_end; ++t) {
        const auto& n = m.tri_nodes[static_cast<size_t>(t)];
        if (contains(m.node_x0[static_cast<size_t>(n[0])], m.node_x0[static_cast<size_t>(n[1])],
                     m.node_x0[static_cast<size_t>(n[2])], p)) {
            tri = t;
            return;
        }
    }
    best = std::numeric_limits<Real>::infinity();
    for (TriId t = b.tri_begin; t < b.tri_end; ++t) {
        const auto& n = m.tri_nodes[static_cast<size_t>(t)];
        if (n[0] != node && n[1] != node && n[2] != node) continue;
        const Real d = norm2(centroid0(m, t) - p);
        if (d < best) {
            best = d;
            tri = t;
        }
    }
}

std::vector<TriId> probe_triangles(const Model& m, const std::vector<NodeId>& nodes) {
    std::vector<uint8_t> in(static_cast<size_t>(m.num_nodes()), 0);
    std::vector<uint8_t> body(static_cast<size_t>(m.num_bodies()), 0);
    for (NodeId i : nodes) {
        in[static_cast<size_t>(i)] = 1;
        body[static_cast<size_t>(m.node_body[static_cast<size_t>(i)])] = 1;
    }
    std::vector<TriId> all, any;
    for (BodyId b = 0; b < m.num_bodies(); ++b) {
        if (!body[static_cast<size_t>(b)]) continue;
        for (TriId t = m.bodies[static_cast<size_t>(b)].tri_begin;
             t < m.bodies[static_cast<size_t>(b)].tri_end; ++t) {
            const auto& n = m.tri_nodes[static_cast<size_t>(t)];
            const int k = in[static_cast<size_t>(n[0])] + in[static_cast<size_t>(n[1])] +
                          in[static_cast<size_t>(n[2])];
            if (k == 3) all.push_back(t);
            if (k > 0) any.push_back(t);
        }
    }
    return all.empty() ? any : all;
}

ProbeValues evaluate_probe(const Model& m, const State& s, const ProbeSpec& p) {
    ProbeValues o;
    if (p.kind == ProbeSpec::Kind::Node) {
        const auto i = static_cast<size_t>(p.nodes.front());
        o.x = s.x[i];
        o.v = s.v[i];
        o.stress = tri_fields(m, s, p.tris.front()).stress;
        return o;
    }
    // mass-weighted mean position and velocity, current-area-weighted mean stress (eq. 8.6)
    Vec2 mx{}, mv{};
    Real mass = 0;
    for (NodeId i : p.nodes) {
        const Real mi = m.node_mass[static_cast<size_t>(i)];
        mx += mi * s.x[static_cast<size_t>(i)];
        mv += mi * s.v[static_cast<size_t>(i)];
        mass += mi;
    }
    o.x = mass > 0 ? mx / mass : Vec2{};
    o.v = mass > 0 ? mv / mass : Vec2{};
    Mat2 sa{0, 0, 0, 0};
    Real area = 0;
    for (TriId t : p.tris) {
        const auto& n = m.tri_nodes[static_cast<size_t>(t)];
        const Real a = signed_area(s.x[static_cast<size_t>(n[0])], s.x[static_cast<size_t>(n[1])],
                                   s.x[static_cast<size_t>(n[2])]);
        sa = sa + a * tri_fields(m, s, t).stress;
        area += a;
    }
    o.stress = area > 0 ? (1.0 / area) * sa : Mat2{0, 0, 0, 0};
    return o;
}

}  // namespace fdem
