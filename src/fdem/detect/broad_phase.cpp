// Uniform-grid broad phase with counting sort (spec §2.5; NBS idea of Munjiza & Andrews 1998:
// cells at least as large as the search radius, so a 3x3 block of cells suffices).
#include "detect/broad_phase.hpp"

#include "detect/grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace fdem {

namespace {

inline Vec2 cpos(const ContactModel& cm, const Vec2* x, const Vec2* xv, NodeId i) {
    return i < cm.num_real_nodes ? x[i] : xv[i - cm.num_real_nodes];
}

// bounding circles of the contactor sub-triangles at the current positions; returns the largest
// radius
Real bounding_circles(const Model& m, const Vec2* x, const Vec2* xv, ContactState& cs) {
    const ContactModel& cm = m.contact;
    const int32_t nt = cm.num_sub_tris();
    cs.tri_center.resize(static_cast<size_t>(nt));
    cs.tri_radius.resize(static_cast<size_t>(nt));
    Vec2* __restrict center = cs.tri_center.data();
    Real* __restrict radius = cs.tri_radius.data();
    const std::array<NodeId, 3>* sub = cm.sub_tri.data();
    Real r_max = 0;
    for (int32_t t = 0; t < nt; ++t) {
        const auto& q = sub[t];
        const Vec2 a = cpos(cm, x, xv, q[0]), b = cpos(cm, x, xv, q[1]), c = cpos(cm, x, xv, q[2]);
        const Vec2 ctr = (a + b + c) / 3.0;
        const Real r = std::sqrt(std::max({norm2(a - ctr), norm2(b - ctr), norm2(c - ctr)}));
        center[t] = ctr;
        radius[t] = r;
        r_max = std::max(r_max, r);
    }
    return r_max;
}

// sort the n hits of one node by tri id (insertion sort: a node has a handful of hits, and
// equal ids never occur)
inline void sort_hits(int32_t* h, int32_t n) {
    for (int32_t i = 1; i < n; ++i) {
        const int32_t t = h[i];
        int32_t k = i;
        for (; k > 0 && h[k - 1] > t; --k)
            h[k] = h[k - 1];
        h[k] = t;
    }
}

// Output cursor over cs.cand_*: the vectors keep the length of the previous detection (no
// clear, so nothing is zero-filled again) and are cut to the written length at the end; the
// per-node loop writes through raw pointers (no push_back bookkeeping). When full they grow by
// 25 % within their capacity, beyond it by doubling (rare, and only before warm-up ends).
struct CandWriter {
    ContactState& cs;
    NodeId* node = nullptr;
    BodyId* body = nullptr;
    int32_t* begin = nullptr;
    int32_t* tri = nullptr;
    size_t pairs = 0, tris = 0, pair_cap = 0, tri_cap = 0;

    explicit CandWriter(ContactState& c) : cs(c) {
        resize(std::max<size_t>(cs.cand_node.size(), 64), std::max<size_t>(cs.cand_tri.size(), 64));
    }
    void resize(size_t np, size_t nt) {
        pair_cap = np;
        tri_cap = nt;
        cs.cand_node.resize(pair_cap);
        cs.cand_body.resize(pair_cap);
        cs.cand_begin.resize(pair_cap + 1);
        cs.cand_tri.resize(tri_cap);
        node = cs.cand_node.data();
        body = cs.cand_body.data();
        begin = cs.cand_begin.data();
        tri = cs.cand_tri.data();
    }
    static size_t grown(size_t need, size_t capacity) {
        const size_t target = need + need / 4 + 64;
        return target <= capacity ? target : std::max(need, 2 * capacity);
    }
    // room for n more sub-triangles (and at most n more pairs)
    void reserve(size_t n) {
        if (pairs + n > pair_cap || tris + n > tri_cap) {
            resize(std::max(pair_cap, grown(pairs + n, cs.cand_node.capacity())),
                   std::max(tri_cap, grown(tris + n, cs.cand_tri.capacity())));
        }
    }
    void finish() {
        begin[pairs] = static_cast<int32_t>(tris);
        cs.cand_node.resize(pairs);
        cs.cand_body.resize(pairs);
        cs.cand_begin.resize(pairs + 1);
        cs.cand_tri.resize(tris);
    }
};

// append the candidates of node j: its n accepted sub-triangles h, any order
void emit(const ContactModel& cm, NodeId j, int32_t* h, int32_t n, CandWriter& w) {
    sort_hits(h, n);  // tri ids ascending = bodies ascending
    w.reserve(static_cast<size_t>(n));
    BodyId prev = kNone;
    for (int32_t k = 0; k < n; ++k) {
        const int32_t t = h[k];
        const BodyId c = cm.sub_body[t];
        if (c != prev) {
            w.node[w.pairs] = j;
            w.body[w.pairs] = c;
            w.begin[w.pairs] = static_cast<int32_t>(w.tris);
            ++w.pairs;
            prev = c;
        }
        w.tri[w.tris++] = t;
    }
}

void clear_candidates(ContactState& cs) {
    cs.cand_node.clear();
    cs.cand_body.clear();
    cs.cand_begin.clear();
    cs.cand_tri.clear();
}

}  // namespace

// Layout for speed (docs/performance.md): after the counting sort, centres and radii of the
// sub-triangles are permuted into cell order (row-major cells), so the 3x3 block of a node is three
// contiguous runs (columns ix-1 .. ix+1 of a row are adjacent cells); the circle test then streams
// through memory without indirection. Hits are sorted per node by an insertion sort (a few per
// node). Output order = (node ascending, tri ascending) as before, independent of the grid.
void find_candidates(const Model& m, const Vec2* x, const Vec2* xv, ContactState& cs) {
    const ContactModel& cm = m.contact;
    const Real b = cm.buffer;
    const int32_t nt = cm.num_sub_tris();
    if (nt == 0) {
        clear_candidates(cs);
        cs.cand_begin.push_back(0);
        return;
    }
    const Real r_max = bounding_circles(m, x, xv, cs);

    // grid over the centroids (detect/grid.hpp); cell >= r_max + b, so every accepted centroid
    // lies in the 3x3 block around the node's cell. cs.query is the fill cursor here, then the
    // hit list of one node (at most nt)
    const GridDims g = build_grid(cs.tri_center.data(), nt, r_max + b, cs.tri_cell, cs.cell_start,
                                  cs.cell_items, cs.query);
    const Vec2 lo = g.lo;
    const int32_t nx = g.nx, ny = g.ny;
    const Real inv = g.inv;
    cs.query.resize(std::max(cs.query.size(), static_cast<size_t>(nt)));
    Vec2* __restrict center = cs.tri_center.data();
    Real* __restrict radius = cs.tri_radius.data();
    int32_t* __restrict tri_cell = cs.tri_cell.data();
    const int32_t* __restrict start = cs.cell_start.data();
    const int32_t* __restrict items = cs.cell_items.data();

    // centres and radii into cell order, in place along the cycles of the permutation
    // (entry k takes sub-triangle items[k]; tri_cell, no longer needed, marks done entries)
    for (int32_t k = 0; k < nt; ++k) {
        if (tri_cell[k] < 0) continue;
        const Vec2 c0 = center[k];
        const Real r0 = radius[k];
        int32_t cur = k;
        for (;;) {
            tri_cell[cur] = -1;
            const int32_t nxt = items[cur];
            if (nxt == k) {
                center[cur] = c0;
                radius[cur] = r0;
                break;
            }
            center[cur] = center[nxt];
            radius[cur] = radius[nxt];
            cur = nxt;
        }
    }

    // query every target boundary node against its 3x3 block
    int32_t* __restrict hits = cs.query.data();
    const BodyId* sub_body = cm.sub_body.data();
    CandWriter w(cs);
    for (NodeId j : cm.boundary_nodes) {
        const BodyId bj = m.node_body[j];
        const Vec2 xj = x[j];
        const Real fx = std::floor((xj.x - lo.x) * inv), fy = std::floor((xj.y - lo.y) * inv);
        if (!(fx >= -1 && fy >= -1 && fx <= nx && fy <= ny)) continue;  // also NaN
        const int32_t ix = static_cast<int32_t>(fx), iy = static_cast<int32_t>(fy);
        const int32_t cx0 = std::max(0, ix - 1), cx1 = std::min(nx - 1, ix + 1);
        int32_t n = 0;
        for (int32_t cy = std::max(0, iy - 1); cy <= std::min(ny - 1, iy + 1); ++cy) {
            const int32_t k1 = start[cy * nx + cx1 + 1];
            for (int32_t k = start[cy * nx + cx0]; k < k1; ++k) {
                const Real dx = xj.x - center[k].x, dy = xj.y - center[k].y;
                const Real reach = radius[k] + b;
                // branch-free append: the slot is overwritten unless the circle is hit
                hits[n] = items[k];
                n += dx * dx + dy * dy < reach * reach ? 1 : 0;
            }
        }
        // role rule (rarely rejects: same body or fixed pairs), keeping the order
        int32_t kept = 0;
        for (int32_t k = 0; k < n; ++k) {
            if (is_contactor_for(cm, sub_body[hits[k]], bj)) hits[kept++] = hits[k];
        }
        if (kept > 0) emit(cm, j, hits, kept, w);
    }
    w.finish();
}

void find_candidates_brute_force(const Model& m, const Vec2* x, const Vec2* xv, ContactState& cs) {
    const ContactModel& cm = m.contact;
    bounding_circles(m, x, xv, cs);
    CandWriter w(cs);
    for (NodeId j : cm.boundary_nodes) {
        cs.query.clear();
        for (int32_t t = 0; t < cm.num_sub_tris(); ++t) {
            const Real reach = cs.tri_radius[t] + cm.buffer;
            if (norm2(x[j] - cs.tri_center[t]) >= reach * reach) continue;
            if (!is_contactor_for(cm, cm.sub_body[t], m.node_body[j])) continue;
            cs.query.push_back(t);
        }
        if (!cs.query.empty()) {
            emit(cm, j, cs.query.data(), static_cast<int32_t>(cs.query.size()), w);
        }
    }
    w.finish();
}

}  // namespace fdem
