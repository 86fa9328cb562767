// External loads (docs/theory.md §4.1): time functions, nodal forces and their power.
#include "integrate/loads.hpp"

#include "fdem/exact_sum.hpp"

#include <algorithm>

namespace fdem {

Real TimeFunction::at(Real t) const {
    switch (kind) {
        case Kind::Constant:
            return 1.0;
        case Kind::Ramp:
            // theory eq. 4.8: linear from 0 at t = 0 to 1 at ramp_time, then held
            return t >= ramp_time ? 1.0 : std::max(t, 0.0) / ramp_time;
        case Kind::Table: {
            // piecewise linear through (t_k, f_k), held at the first and last values (eq. 4.8)
            if (t <= table.front()[0]) return table.front()[1];
            if (t >= table.back()[0]) return table.back()[1];
            const auto it =
                std::upper_bound(table.begin(), table.end(), t,
                                 [](Real v, const std::array<Real, 2>& p) { return v < p[0]; });
            const std::array<Real, 2>& b = *it;
            const std::array<Real, 2>& a = *(it - 1);
            const Real s = (t - a[0]) / (b[0] - a[0]);
            return a[1] + s * (b[1] - a[1]);
        }
    }
    return 0.0;
}

void evaluate_loads(const Model& m, Real t, const Vec2* x, Vec2* slot_f) {
    for (const Load& ld : m.loads) {
        const Real k = ld.time_function.at(t);
        Vec2* out = slot_f + ld.slot_begin;
        switch (ld.kind) {
            case LoadKind::Traction: {
                // dead traction: ½ k tr L0 on each node of the edge (theory eq. 4.5)
                const Vec2 tr = k * ld.vector;
                for (size_t e = 0; e < ld.edges.size(); ++e)
                    out[e] = (0.5 * ld.edge_length0[e]) * tr;
                break;
            }
            case LoadKind::Pressure: {
                // follower pressure on the current edge: -½ k p L n_out = ½ k p (-d.y, d.x)
                // with d = x_b - x_a, the body to the left of a -> b (theory eq. 4.6)
                const Real hp = 0.5 * k * ld.pressure;
                for (size_t e = 0; e < ld.edges.size(); ++e) {
                    const Vec2 d = x[ld.edges[e][1]] - x[ld.edges[e][0]];
                    out[e] = Vec2{-hp * d.y, hp * d.x};
                }
                break;
            }
            case LoadKind::Force: {
                if (!ld.node_share.empty()) {
                    // node copies of jointed vertices: mass shares (theory eq. 4.11)
                    const Vec2 f = k * ld.vector;
                    for (size_t i = 0; i < ld.nodes.size(); ++i)
                        out[i] = ld.node_share[i] * f;
                    break;
                }
                const Vec2 share = (k / static_cast<Real>(ld.nodes.size())) * ld.vector;
                for (size_t i = 0; i < ld.nodes.size(); ++i)
                    out[i] = share;
                break;
            }
        }
    }
}

void add_load_forces(const Model& m, const Vec2* slot_f, Vec2* f) {
    for (const Load& ld : m.loads) {
        const Vec2* in = slot_f + ld.slot_begin;
        if (ld.kind == LoadKind::Force) {
            for (size_t i = 0; i < ld.nodes.size(); ++i)
                f[ld.nodes[i]] += in[i];
        } else {
            for (size_t e = 0; e < ld.edges.size(); ++e) {
                f[ld.edges[e][0]] += in[e];
                f[ld.edges[e][1]] += in[e];
            }
        }
    }
}

Real load_power(const Model& m, const Vec2* slot_f, const Vec2* v) {
    ExactSum p;  // exact (theory §4.4): independent of how the slots are grouped
    for (const Load& ld : m.loads) {
        const Vec2* in = slot_f + ld.slot_begin;
        if (ld.kind == LoadKind::Force) {
            for (size_t i = 0; i < ld.nodes.size(); ++i)
                p.add(dot(in[i], v[ld.nodes[i]]));
        } else {
            for (size_t e = 0; e < ld.edges.size(); ++e)
                p.add(dot(in[e], v[ld.edges[e][0]] + v[ld.edges[e][1]]));
        }
    }
    return p.value();
}

}  // namespace fdem
