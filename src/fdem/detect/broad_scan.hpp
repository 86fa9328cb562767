// The inner loop of the smooth-contact broad phase (detect/broad_phase.cpp): one target node
// against the sub-triangles of its 3x3 block of grid cells, in a portable and an AVX-512 version
// (detect/broad_scan_avx512.cpp, runtime dispatch like element/cst_simd.cpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "fdem/candidates.hpp"
#include "fdem/contact_topology.hpp"
#include "fdem/math.hpp"
#include "fdem/model.hpp"

namespace fdem::detail {

// Output cursor over a Candidates list: the vectors keep the length of the previous detection (no
// clear, so nothing is zero-filled again) and are cut to the written length at the end; the
// per-node loop writes through raw pointers (no push_back bookkeeping). When full they grow by
// 25 % within their capacity, beyond it by doubling (rare, and only before warm-up ends).
struct CandWriter {
    Candidates& out;
    NodeId* node = nullptr;
    BodyId* body = nullptr;
    int32_t* begin = nullptr;
    int32_t* tri = nullptr;
    size_t pairs = 0, tris = 0, pair_cap = 0, tri_cap = 0;

    explicit CandWriter(Candidates& c) : out(c) {
        resize(std::max<size_t>(out.node.size(), 64), std::max<size_t>(out.tri.size(), 64));
    }
    void resize(size_t np, size_t nt) {
        pair_cap = np;
        tri_cap = nt;
        out.node.resize(pair_cap);
        out.body.resize(pair_cap);
        out.begin.resize(pair_cap + 1);
        out.tri.resize(tri_cap);
        node = out.node.data();
        body = out.body.data();
        begin = out.begin.data();
        tri = out.tri.data();
    }
    static size_t grown(size_t need, size_t capacity) {
        const size_t target = need + need / 4 + 64;
        return target <= capacity ? target : std::max(need, 2 * capacity);
    }
    // room for n more sub-triangles (and at most n more pairs)
    void reserve(size_t n) {
        if (pairs + n > pair_cap || tris + n > tri_cap) {
            resize(std::max(pair_cap, grown(pairs + n, out.node.capacity())),
                   std::max(tri_cap, grown(tris + n, out.tri.capacity())));
        }
    }
    void finish() {
        begin[pairs] = static_cast<int32_t>(tris);
        out.node.resize(pairs);
        out.body.resize(pairs);
        out.begin.resize(pairs + 1);
        out.tri.resize(tris);
    }
};

/// Role key of a contactor body c: c, plus kFixedKey when c is fixed (body ids < kFixedKey).
constexpr int32_t kFixedKey = int32_t{1} << 30;

/// The role rule is_contactor_for(c, t) for one target body t as a test on the key of c:
/// key != t and (key < lo or key >= hi). two-way: t free: (lo, hi) = (INT32_MAX, INT32_MAX),
/// t fixed: (kFixedKey, INT32_MAX); one-way: t free: (t, kFixedKey) (a free contactor needs
/// c < t, a fixed one always acts), t fixed: no contactor at all (the caller skips the node).
struct RoleTest {
    int32_t t = 0, lo = 0, hi = 0;
};

/// Sub-triangles in grid-cell order (structure of arrays, entry k = sub-triangle item[k]):
/// centroid (cx, cy), squared reach r2 = (r + b)^2 of the bounding circle grown by the buffer,
/// role key of its body; cell (ix, iy) holds entries [start[iy * nx + ix], start[iy * nx + ix +
/// 1]).
struct CellTris {
    const Real* cx = nullptr;
    const Real* cy = nullptr;
    const Real* r2 = nullptr;
    const int32_t* key = nullptr;
    const int32_t* item = nullptr;
    const int32_t* start = nullptr;
    int32_t nx = 0;
};

/// Grid of find_candidates: cell (ix, iy) = floor((x - lo) * inv), 0 <= ix < nx, 0 <= iy < ny.
struct NodeGrid {
    Vec2 lo;
    Real inv = 0;
    int32_t nx = 0, ny = 0;
};

/// The query of one target node: position, role test, block of cells [cx0, cx1] x [cy0, cy1];
/// self = the node's body contacts itself (ContactTopology::body_self): the role test lets its
/// own sub-triangles through and the caller filters them by rule X (filter_rule_x()).
struct Block {
    Vec2 xj;
    RoleTest role;
    bool self = false;
    BodyId role_body = 0;  ///< the node's body
    int32_t cx0 = 0, cx1 = -1, cy0 = 0, cy1 = -1;
};

/// Set up the query of target node j at xj; false when it has no contactor (a fixed target of
/// a one-way model) or lies outside the grid by more than a cell (or is NaN).
inline bool node_block(const Model& m, const ContactTopology& ct, const NodeGrid& g, NodeId j,
                       Vec2 xj, Block& q) {
    const ContactModel& cm = m.contact;
    const BodyId bj = m.node_body[target_node(ct, j)];
    const bool fixed_j = ct.body_fixed[static_cast<size_t>(bj)] != 0;
    if (!cm.two_way && fixed_j) return false;  // one-way: a fixed body is never a target
    q.xj = xj;
    q.role.t = bj;  // is_contactor_for(., bj) as a test on the key
    q.role.lo = cm.two_way ? (fixed_j ? kFixedKey : INT32_MAX) : bj;
    q.role.hi = cm.two_way ? INT32_MAX : kFixedKey;
    q.self = ct.body_self[static_cast<size_t>(bj)] != 0;
    q.role_body = bj;
    if (q.self) {
        // own sub-triangles pass (key bj): no key equals -1; one-way, key < bj + 1 admits bj
        // (the role rule orders different bodies; within one body every pair is evaluated,
        // each crack face as target of the other: the two-way evaluation of theory §6.7)
        q.role.t = -1;
        if (!cm.two_way) q.role.lo = bj + 1;
    }
    const Real vx = (xj.x - g.lo.x) * g.inv, vy = (xj.y - g.lo.y) * g.inv;
    if (!(vx >= -1 && vy >= -1 && vx < g.nx + 1 && vy < g.ny + 1)) return false;  // also NaN
    // floor without a libm call: truncation, minus 1 below it (|v| < 2^31 here)
    int32_t ix = static_cast<int32_t>(vx), iy = static_cast<int32_t>(vy);
    ix -= vx < ix ? 1 : 0;
    iy -= vy < iy ? 1 : 0;
    q.cx0 = std::max(0, ix - 1);
    q.cx1 = std::min(g.nx - 1, ix + 1);
    q.cy0 = std::max(0, iy - 1);
    q.cy1 = std::min(g.ny - 1, iy + 1);
    return true;
}

/// Extra slots the caller leaves behind the hit list: the AVX-512 scan stores 4 ids at a time.
constexpr int32_t kScanSlack = 4;

/// Write to hits (returns the count) the sub-triangles of cells [cx0, cx1] x [cy0, cy1] that
/// pass the role test and whose circle holds xj: (xj.x - cx)^2 + (xj.y - cy)^2 < r2, evaluated
/// as dx * dx + dy * dy. Order: cell rows, then entries. hits needs room for the block's
/// entries + kScanSlack. kAnyRole = false: only key != t (two-way, free target: the usual case).
///
/// The (up to) three row runs are scanned as one loop over their concatenation, the entry index
/// picked branch-free: one loop exit per node instead of one per row, whose varying trip counts
/// (a few entries each) the branch predictor misses.
template <bool kAnyRole>
inline int32_t scan_rows(const CellTris& a, const Block& q, int32_t* __restrict hits) {
    int32_t s[3], len[3];
    for (int32_t r = 0; r < 3; ++r) {
        const int32_t cy = std::min(q.cy0 + r, q.cy1);
        const int32_t k0 = a.start[cy * a.nx + q.cx0];
        s[r] = k0;
        len[r] = q.cy0 + r <= q.cy1 ? a.start[cy * a.nx + q.cx1 + 1] - k0 : 0;
    }
    const int32_t e0 = len[0], e1 = e0 + len[1], total = e1 + len[2];
    const int32_t d0 = s[0], d1 = s[1] - e0, d2 = s[2] - e1;
    const Real x = q.xj.x, y = q.xj.y;
    const RoleTest role = q.role;
    const Real* __restrict cx = a.cx;
    const Real* __restrict cy = a.cy;
    const Real* __restrict r2 = a.r2;
    const int32_t* __restrict keys = a.key;
    const int32_t* __restrict item = a.item;
    int32_t n = 0;
    for (int32_t i = 0; i < total; ++i) {
        const int32_t k = i + (i < e0 ? d0 : (i < e1 ? d1 : d2));
        const Real dx = x - cx[k], dy = y - cy[k];
        const int32_t key = keys[k];
        bool ok = key != role.t;
        if constexpr (kAnyRole) ok = ok & ((key < role.lo) | (key >= role.hi));
        // branch-free append: the slot is overwritten unless the circle is hit by a
        // contactor of the node
        hits[n] = item[k];
        n += (dx * dx + dy * dy < r2[k]) & ok;
    }
    return n;
}

/// scan_rows for the node's role test.
inline int32_t scan_block(const CellTris& a, const Block& q, int32_t* __restrict hits) {
    return q.role.lo == INT32_MAX ? scan_rows<false>(a, q, hits) : scan_rows<true>(a, q, hits);
}

/// Rule X on the hits h[0 .. n) of target j of a self-contact body bj: drop own sub-triangles
/// whose parent mesh triangle touches j's sector (rule_x_allows()); returns the count kept, in
/// the same order.
inline int32_t filter_rule_x(const Model& m, const ContactTopology& ct, NodeId j, BodyId bj,
                             int32_t* h, int32_t n) {
    int32_t kept = 0;
    for (int32_t k = 0; k < n; ++k) {
        const int32_t s = h[k];
        h[kept] = s;
        kept += ct.sub_body[static_cast<size_t>(s)] != bj ||
                rule_x_allows(ct, m.tri_nodes.data(), j, s);
    }
    return kept;
}

/// Sort the n distinct ids h ascending (insertion sort: a few, nearly in order).
inline void sort_hits(int32_t* h, int32_t n) {
    for (int32_t i = 1; i < n; ++i) {
        const int32_t t = h[i];
        int32_t k = i;
        for (; k > 0 && h[k - 1] > t; --k)
            h[k] = h[k - 1];
        h[k] = t;
    }
}

/// scan_block, then sort_hits: the hits of one node in ascending id order; returns their count.
inline int32_t scan_sorted(const CellTris& a, const Block& q, int32_t* __restrict hits) {
    const int32_t n = scan_block(a, q, hits);
    sort_hits(hits, n);
    return n;
}

// append the candidates of node j: its n sub-triangles h, ascending ids, all of contactor bodies
// of j. A pair starts where the body changes; branch-free: the pair slot at the cursor is written
// for every sub-triangle and kept (cursor advanced) only when the body is new (reserve(n) leaves
// room for the extra slot, finish() writes the last cand_begin).
inline void emit(const ContactTopology& ct, NodeId j, const int32_t* h, int32_t n,
                 detail::CandWriter& w) {
    w.reserve(static_cast<size_t>(n));
    const BodyId* __restrict sub_body = ct.sub_body.data();
    NodeId* __restrict node = w.node;
    BodyId* __restrict body = w.body;
    int32_t* __restrict begin = w.begin;
    int32_t* __restrict tri = w.tri + w.tris;
    const int32_t t0 = static_cast<int32_t>(w.tris);
    size_t p = w.pairs;
    BodyId prev = kNone;
    for (int32_t k = 0; k < n; ++k) {
        const int32_t t = h[k];
        const BodyId c = sub_body[t];
        node[p] = j;
        body[p] = c;
        begin[p] = t0 + k;
        p += c != prev ? 1 : 0;
        prev = c;
        tri[k] = t;
    }
    w.pairs = p;
    w.tris += static_cast<size_t>(n);
}

/// true when the CPU runs scan_block_avx512 (checked once, __builtin_cpu_supports).
bool scan_avx512_supported();

/// scan_block with 4 entries per instruction (256-bit registers, AVX-512VL masks and compress):
/// the same IEEE operations on the same operands (-ffp-contract=off: no fused multiply-add), so
/// the same hits in the same order. Only call when scan_avx512_supported().
int32_t scan_block_avx512(const CellTris& a, const Block& q, int32_t* hits);

}  // namespace fdem::detail
