// Uniform-grid broad phase with counting sort (spec §2.5; NBS idea of Munjiza & Andrews 1998:
// cells at least as large as the search radius, so a 3x3 block of cells suffices).
#include "detect/broad_phase.hpp"

#include "detect/broad_scan.hpp"
#include "detect/grid.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <stdexcept>

namespace fdem {

namespace {

// from this many targets on, the queries run on all threads (each a contiguous range of
// targets into its own list, concatenated in order: the same list for any thread count)
constexpr int32_t kMinParallelTargets = 4096;

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

const char* broad_scan_kernel_name() {
    return detail::scan_avx512_supported() ? "avx512" : "portable";
}

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
    const bool simd = kernel == BroadKernel::Auto && detail::scan_avx512_supported();
    // (boundary nodes, then the edge targets of docs/theory.md §6.12: ascending target ids)
    auto query = [&](NodeId j, detail::CandWriter& w, int32_t* __restrict hits) {
        detail::Block blk;
        if (!detail::node_block(m, ct, ng, j, target_point(ct, x, j), blk)) return;
        int32_t nh =
            simd ? detail::scan_block_avx512(a, blk, hits) : detail::scan_block(a, blk, hits);
        if (blk.self) nh = detail::filter_rule_x(m, ct, j, blk.role_body, hits, nh);
        detail::sort_hits(hits, nh);
        if (nh > 0) detail::emit(ct, j, hits, nh, w);
    };
    // the targets [i0, i1) in ascending ids (a distributed run: this process's only, same order)
    const int32_t n_bn = static_cast<int32_t>(ct.boundary_nodes.size());
    const int32_t n_targets = n_bn + (ct.target_end() - ct.edge_target_base);
    auto query_range = [&](int32_t i0, int32_t i1, detail::CandWriter& w, int32_t* hits) {
        for (int32_t i = i0; i < i1; ++i) {
            const NodeId j = i < n_bn ? ct.boundary_nodes[static_cast<size_t>(i)]
                                      : ct.edge_target_base + (i - n_bn);
            if (own.owner == nullptr || own.owner[target_node(ct, j)] == own.rank)
                query(j, w, hits);
        }
    };
    const int max_threads = n_targets >= kMinParallelTargets ? omp_get_max_threads() : 1;
    if (max_threads <= 1) {
        detail::CandWriter w(out);
        query_range(0, n_targets, w, g.query.data());
        w.finish();
        return;
    }
    // thread t: the targets [n t / T, n (t + 1) / T) into its own list part[t], then its part
    // copied to its place in out (after the parts before it)
    if (g.part.size() < static_cast<size_t>(max_threads)) {
        g.part.resize(static_cast<size_t>(max_threads));
        g.part_hits.resize(static_cast<size_t>(max_threads));
    }
#pragma omp parallel num_threads(max_threads)
    {
        const int nthr = omp_get_num_threads(), t = omp_get_thread_num();
        Candidates& part = g.part[static_cast<size_t>(t)];
        std::vector<int32_t>& hv = g.part_hits[static_cast<size_t>(t)];
        if (hv.size() < n + detail::kScanSlack) hv.resize(n + detail::kScanSlack);  // (grows only)
        {
            detail::CandWriter w(part);
            const auto at = [&](int r) {
                return static_cast<int32_t>(static_cast<int64_t>(n_targets) * r / nthr);
            };
            query_range(at(t), at(t + 1), w, hv.data());
            w.finish();
        }
#pragma omp barrier
        size_t p0 = 0, t0 = 0, np = 0, ntri = 0;
        for (int r = 0; r < nthr; ++r) {
            const Candidates& c = g.part[static_cast<size_t>(r)];
            if (r < t) {
                p0 += c.node.size();
                t0 += c.tri.size();
            }
            np += c.node.size();
            ntri += c.tri.size();
        }
#pragma omp single
        {
            out.node.resize(np);
            out.body.resize(np);
            out.begin.resize(np + 1);
            out.tri.resize(ntri);
            out.begin[np] = static_cast<int32_t>(ntri);
        }
        // (implicit barrier of single)
        std::copy(part.node.begin(), part.node.end(),
                  out.node.begin() + static_cast<std::ptrdiff_t>(p0));
        std::copy(part.body.begin(), part.body.end(),
                  out.body.begin() + static_cast<std::ptrdiff_t>(p0));
        std::copy(part.tri.begin(), part.tri.end(),
                  out.tri.begin() + static_cast<std::ptrdiff_t>(t0));
        const int32_t shift = static_cast<int32_t>(t0);
        for (size_t p = 0; p < part.node.size(); ++p)
            out.begin[p0 + p] = part.begin[p] + shift;
    }
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
