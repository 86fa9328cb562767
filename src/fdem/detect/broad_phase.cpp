// Uniform-grid broad phase with counting sort (spec §2.5; NBS idea of Munjiza & Andrews 1998:
// cells at least as large as the search radius, so a 3x3 block of cells suffices).
#include "detect/broad_phase.hpp"

#include "detect/broad_scan.hpp"
#include "detect/grid.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <stdexcept>

namespace fdem {

namespace {

inline Vec2 cpos(const ContactTopology& ct, const Vec2* x, const Vec2* xv, NodeId i) {
    return i < ct.num_real_nodes ? x[i] : xv[i - ct.num_real_nodes];
}

// bounding circles of the contactor sub-triangles at the current positions; returns the largest
// radius
Real bounding_circles(const ContactTopology& ct, const Vec2* x, const Vec2* xv,
                      BroadPhaseScratch& g) {
    const int32_t nt = ct.num_sub_tris();
    // grow-only: find_candidates keeps cell-ordered copies behind the first nt entries
    if (g.tri_center.size() < static_cast<size_t>(nt)) g.tri_center.resize(static_cast<size_t>(nt));
    if (g.tri_radius.size() < static_cast<size_t>(nt)) g.tri_radius.resize(static_cast<size_t>(nt));
    Vec2* __restrict center = g.tri_center.data();
    Real* __restrict radius = g.tri_radius.data();
    const std::array<NodeId, 3>* sub = ct.sub_tri.data();
    Real r_max = 0;
    for (int32_t t = 0; t < nt; ++t) {
        const auto& q = sub[t];
        const Vec2 a = cpos(ct, x, xv, q[0]), b = cpos(ct, x, xv, q[1]), c = cpos(ct, x, xv, q[2]);
        const Vec2 ctr = (a + b + c) / 3.0;
        const Real r = std::sqrt(std::max({norm2(a - ctr), norm2(b - ctr), norm2(c - ctr)}));
        center[t] = ctr;
        radius[t] = r;
        r_max = std::max(r_max, r);
    }
    return r_max;
}

void clear_candidates(Candidates& out) {
    out.node.clear();
    out.body.clear();
    out.begin.clear();
    out.tri.clear();
}

}  // namespace

// Layout for speed (docs/performance.md): after the counting sort (stable: ascending sub-triangle
// id within a cell) the centres, squared reaches (r + b)^2 and role keys (body, + kFixedKey if
// fixed) of the sub-triangles are gathered into cell order (row-major cells, structure of
// arrays), so the 3x3 block of a node is three contiguous runs (columns ix-1 .. ix+1 of a row are
// adjacent cells) scanned without indirection (detect/broad_scan.hpp; 8 entries per instruction
// and a sorting network with AVX-512). The scan appends branch-free and applies the whole role
// rule is_contactor_for there (a comparison of keys, detail::RoleTest), so the node's own body
// never reaches the hit list, unless the body contacts itself (fracture: its own sub-triangles
// pass the key test and filter_rule_x() applies rule X, a per-node branch that bodies without
// fracture never take); the hits are put in ascending id order (= body order) and emitted
// branch-free. Output order = (node ascending, tri ascending) as before, independent of the grid.
void find_candidates(const Model& m, const ContactTopology& ct, const Vec2* x, const Vec2* xv,
                     Candidates& out, BroadPhaseScratch& g, BroadKernel kernel) {
    find_candidates(m, ct, x, x, xv, out, g, kernel);
}

void find_candidates(const Model& m, const ContactTopology& ct, const Vec2* x, const Vec2* xc,
                     const Vec2* xv, Candidates& out, BroadPhaseScratch& g, BroadKernel kernel) {
    find_candidates(m, ct, x, xc, xv, out, g, TargetOwner{}, kernel);
}

void find_candidates(const Model& m, const ContactTopology& ct, const Vec2* x, const Vec2* xc,
                     const Vec2* xv, Candidates& out, BroadPhaseScratch& g, TargetOwner own,
                     BroadKernel kernel) {
    const ContactModel& cm = m.contact;
    const Real b = cm.buffer;
    const int32_t nt = ct.num_sub_tris();
    if (nt == 0) {
        clear_candidates(out);
        out.begin.push_back(0);
        return;
    }
    if (m.num_bodies() >= detail::kFixedKey)
        throw std::length_error("find_candidates: too many bodies");
    const Real r_max = bounding_circles(ct, xc, xv, g);

    // grid over the centroids (detect/grid.hpp); cell >= r_max + b, so every accepted centroid
    // lies in the 3x3 block around the node's cell. g.query is the fill cursor here, then the
    // hit list of one node (at most nt + slack)
    const GridDims gd = build_grid(g.tri_center.data(), nt, r_max + b, g.tri_cell, g.cell_start,
                                   g.cell_items, g.query);
    const Vec2 lo = gd.lo;
    const int32_t nx = gd.nx, ny = gd.ny;
    const Real inv = gd.inv;
    const size_t n = static_cast<size_t>(nt);
    g.query.resize(std::max(g.query.size(), n + detail::kScanSlack));
    // cell-ordered x, y and (r + b)^2 behind the id-ordered radii (grow-only scratch); the
    // grid's cell per item (tri_cell) is not needed any more and takes the role keys
    if (g.tri_radius.size() < 4 * n) g.tri_radius.resize(4 * n);
    const Vec2* __restrict center_id = g.tri_center.data();
    const Real* __restrict radius_id = g.tri_radius.data();
    Real* __restrict cx = g.tri_radius.data() + n;
    Real* __restrict cy = cx + n;
    Real* __restrict reach2 = cy + n;
    int32_t* __restrict key = g.tri_cell.data();
    const int32_t* __restrict items = g.cell_items.data();
    const BodyId* __restrict sub_body = ct.sub_body.data();
    for (size_t k = 0; k < n; ++k) {
        const int32_t t = items[k];
        cx[k] = center_id[t].x;
        cy[k] = center_id[t].y;
        const Real reach = radius_id[t] + b;
        reach2[k] = reach * reach;
        const BodyId c = sub_body[t];
        key[k] = c + (ct.body_fixed[static_cast<size_t>(c)] != 0 ? detail::kFixedKey : 0);
    }
    detail::CellTris a;
    a.cx = cx;
    a.cy = cy;
    a.r2 = reach2;
    a.key = key;
    a.item = items;
    a.start = g.cell_start.data();
    a.nx = nx;
    detail::NodeGrid ng;
    ng.lo = lo;
    ng.inv = inv;
    ng.nx = nx;
    ng.ny = ny;

    // query every target boundary node against its 3x3 block
    detail::CandWriter w(out);
    const bool simd = kernel == BroadKernel::Auto && detail::scan_avx512_supported();
    int32_t* __restrict hits = g.query.data();
    // (boundary nodes, then the edge targets of docs/theory.md §6.12: ascending target ids)
    auto query = [&](NodeId j) {
        detail::Block blk;
        if (!detail::node_block(m, ct, ng, j, target_point(ct, x, j), blk)) return;
        int32_t nh =
            simd ? detail::scan_block_avx512(a, blk, hits) : detail::scan_block(a, blk, hits);
        if (blk.self) nh = detail::filter_rule_x(m, ct, j, blk.role_body, hits, nh);
        detail::sort_hits(hits, nh);
        if (nh > 0) detail::emit(ct, j, hits, nh, w);
    };
    // (a distributed run: this process's targets only, same order)
    auto mine = [&](NodeId j) {
        return own.owner == nullptr || own.owner[target_node(ct, j)] == own.rank;
    };
    for (NodeId j : ct.boundary_nodes) {
        if (mine(j)) query(j);
    }
    for (NodeId j = ct.edge_target_base; j < ct.target_end(); ++j) {
        if (mine(j)) query(j);
    }
    w.finish();
}

void find_candidates_brute_force(const Model& m, const ContactTopology& ct, const Vec2* x,
                                 const Vec2* xv, Candidates& out, BroadPhaseScratch& g) {
    find_candidates_brute_force(m, ct, x, x, xv, out, g);
}

void find_candidates_brute_force(const Model& m, const ContactTopology& ct, const Vec2* x,
                                 const Vec2* xc, const Vec2* xv, Candidates& out,
                                 BroadPhaseScratch& g) {
    const ContactModel& cm = m.contact;
    bounding_circles(ct, xc, xv, g);
    detail::CandWriter w(out);
    auto query = [&](NodeId j) {
        g.query.clear();
        const Vec2 xj = target_point(ct, x, j);
        for (int32_t t = 0; t < ct.num_sub_tris(); ++t) {
            const Real reach = g.tri_radius[t] + cm.buffer;
            if (norm2(xj - g.tri_center[t]) >= reach * reach) continue;
            const BodyId bj = m.node_body[target_node(ct, j)];
            const bool self_pair = ct.sub_body[t] == bj && ct.body_self[static_cast<size_t>(bj)] &&
                                   rule_x_allows(ct, m.tri_nodes.data(), j, t);
            if (!self_pair && !is_contactor_for(cm, ct, ct.sub_body[t], bj)) continue;
            g.query.push_back(t);
        }
        if (!g.query.empty()) {
            detail::emit(ct, j, g.query.data(), static_cast<int32_t>(g.query.size()), w);
        }
    };
    for (NodeId j : ct.boundary_nodes)
        query(j);
    for (NodeId j = ct.edge_target_base; j < ct.target_end(); ++j)
        query(j);
    w.finish();
}

}  // namespace fdem
