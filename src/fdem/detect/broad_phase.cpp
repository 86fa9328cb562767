// Uniform-grid broad phase with counting sort (spec §2.5; NBS idea of Munjiza & Andrews 1998:
// cells at least as large as the search radius, so a 3x3 block of cells suffices).
#include "detect/broad_phase.hpp"

#include <algorithm>
#include <cmath>

namespace fdem {

namespace {

inline Vec2 cpos(const ContactModel& cm, const Vec2* x, const Vec2* xv, NodeId i) {
    return i < cm.num_real_nodes ? x[i] : xv[i - cm.num_real_nodes];
}

// bounding circles of the contactor sub-triangles at the current positions
Real bounding_circles(const Model& m, const Vec2* x, const Vec2* xv, ContactState& cs) {
    const ContactModel& cm = m.contact;
    const int32_t nt = cm.num_sub_tris();
    cs.tri_center.resize(static_cast<size_t>(nt));
    cs.tri_radius.resize(static_cast<size_t>(nt));
    Real r_max = 0;
    for (int32_t t = 0; t < nt; ++t) {
        const auto& q = cm.sub_tri[t];
        const Vec2 a = cpos(cm, x, xv, q[0]), b = cpos(cm, x, xv, q[1]), c = cpos(cm, x, xv, q[2]);
        const Vec2 ctr = (a + b + c) / 3.0;
        const Real r = std::sqrt(std::max({norm2(a - ctr), norm2(b - ctr), norm2(c - ctr)}));
        cs.tri_center[t] = ctr;
        cs.tri_radius[t] = r;
        r_max = std::max(r_max, r);
    }
    return r_max;
}

// append the candidates of node j (cs.query holds its accepted sub-triangles, any order)
void emit(const ContactModel& cm, NodeId j, ContactState& cs) {
    std::sort(cs.query.begin(), cs.query.end());  // tri ids ascending = bodies ascending
    for (size_t k = 0; k < cs.query.size(); ++k) {
        const int32_t t = cs.query[k];
        const BodyId c = cm.sub_body[t];
        if (k == 0 || cm.sub_body[cs.query[k - 1]] != c) {
            cs.cand_node.push_back(j);
            cs.cand_body.push_back(c);
            cs.cand_begin.push_back(static_cast<int32_t>(cs.cand_tri.size()));
        }
        cs.cand_tri.push_back(t);
    }
}

void clear_candidates(ContactState& cs) {
    cs.cand_node.clear();
    cs.cand_body.clear();
    cs.cand_begin.clear();
    cs.cand_tri.clear();
}

}  // namespace

void find_candidates(const Model& m, const Vec2* x, const Vec2* xv, ContactState& cs) {
    const ContactModel& cm = m.contact;
    const Real b = cm.buffer;
    clear_candidates(cs);
    const int32_t nt = cm.num_sub_tris();
    if (nt == 0) {
        cs.cand_begin.push_back(0);
        return;
    }
    const Real r_max = bounding_circles(m, x, xv, cs);

    // grid over the centroids; cell >= r_max + b, so every accepted centroid lies in the 3x3
    // block around the node's cell
    Vec2 lo = cs.tri_center[0], hi = lo;
    for (int32_t t = 1; t < nt; ++t) {
        lo.x = std::min(lo.x, cs.tri_center[t].x);
        lo.y = std::min(lo.y, cs.tri_center[t].y);
        hi.x = std::max(hi.x, cs.tri_center[t].x);
        hi.y = std::max(hi.y, cs.tri_center[t].y);
    }
    Real cell = r_max + b;
    // cap the number of cells at ~4 per sub-triangle (sparse layouts): larger cells stay correct
    const Real max_cells = 4.0 * nt + 16.0;
    const Real area_cells = ((hi.x - lo.x) / cell + 1) * ((hi.y - lo.y) / cell + 1);
    if (area_cells > max_cells) cell *= std::sqrt(area_cells / max_cells) * 1.01;
    const int32_t nx = static_cast<int32_t>((hi.x - lo.x) / cell) + 1;
    const int32_t ny = static_cast<int32_t>((hi.y - lo.y) / cell) + 1;
    const Real inv = 1.0 / cell;

    // counting sort of the sub-triangles by cell (stable: ascending tri id within a cell)
    const size_t ncell = static_cast<size_t>(nx) * static_cast<size_t>(ny);
    cs.cell_start.assign(ncell + 1, 0);
    cs.tri_cell.resize(static_cast<size_t>(nt));
    for (int32_t t = 0; t < nt; ++t) {
        const int32_t ix =
            std::min(nx - 1, static_cast<int32_t>((cs.tri_center[t].x - lo.x) * inv));
        const int32_t iy =
            std::min(ny - 1, static_cast<int32_t>((cs.tri_center[t].y - lo.y) * inv));
        cs.tri_cell[t] = iy * nx + ix;
        ++cs.cell_start[static_cast<size_t>(cs.tri_cell[t]) + 1];
    }
    for (size_t c = 0; c < ncell; ++c)
        cs.cell_start[c + 1] += cs.cell_start[c];
    cs.cell_items.resize(static_cast<size_t>(nt));
    cs.query.assign(cs.cell_start.begin(), cs.cell_start.end() - 1);  // fill cursor
    for (int32_t t = 0; t < nt; ++t) {
        cs.cell_items[static_cast<size_t>(cs.query[static_cast<size_t>(cs.tri_cell[t])]++)] = t;
    }

    // query every target boundary node against its 3x3 block
    for (NodeId j : cm.boundary_nodes) {
        const BodyId bj = m.node_body[j];
        const Vec2 xj = x[j];
        const Real fx = std::floor((xj.x - lo.x) * inv), fy = std::floor((xj.y - lo.y) * inv);
        if (!(fx >= -1 && fy >= -1 && fx <= nx && fy <= ny)) continue;  // also NaN
        const int32_t ix = static_cast<int32_t>(fx), iy = static_cast<int32_t>(fy);
        cs.query.clear();
        for (int32_t cy = std::max(0, iy - 1); cy <= std::min(ny - 1, iy + 1); ++cy) {
            for (int32_t cx = std::max(0, ix - 1); cx <= std::min(nx - 1, ix + 1); ++cx) {
                const size_t c = static_cast<size_t>(cy * nx + cx);
                for (int32_t k = cs.cell_start[c]; k < cs.cell_start[c + 1]; ++k) {
                    const int32_t t = cs.cell_items[static_cast<size_t>(k)];
                    const Real reach = cs.tri_radius[t] + b;
                    if (norm2(xj - cs.tri_center[t]) >= reach * reach) continue;
                    if (!is_contactor_for(cm, cm.sub_body[t], bj)) continue;
                    cs.query.push_back(t);
                }
            }
        }
        if (!cs.query.empty()) emit(cm, j, cs);
    }
    cs.cand_begin.push_back(static_cast<int32_t>(cs.cand_tri.size()));
}

void find_candidates_brute_force(const Model& m, const Vec2* x, const Vec2* xv, ContactState& cs) {
    const ContactModel& cm = m.contact;
    clear_candidates(cs);
    bounding_circles(m, x, xv, cs);
    for (NodeId j : cm.boundary_nodes) {
        cs.query.clear();
        for (int32_t t = 0; t < cm.num_sub_tris(); ++t) {
            const Real reach = cs.tri_radius[t] + cm.buffer;
            if (norm2(x[j] - cs.tri_center[t]) >= reach * reach) continue;
            if (!is_contactor_for(cm, cm.sub_body[t], m.node_body[j])) continue;
            cs.query.push_back(t);
        }
        if (!cs.query.empty()) emit(cm, j, cs);
    }
    cs.cand_begin.push_back(static_cast<int32_t>(cs.cand_tri.size()));
}

}  // namespace fdem
