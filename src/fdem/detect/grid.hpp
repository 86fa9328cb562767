// Uniform grid filled by a counting sort (NBS idea of Munjiza & Andrews 1998, spec §2.5): the one
// cell structure of the smooth-contact broad phase (broad_phase.cpp) and the couple search of
// baseline A (contact/legacy_triangle.cpp). Linear time, stable (ascending item index within a
// cell), so the order does not depend on anything but the input.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "fdem/math.hpp"

namespace fdem {

/// Geometry of a grid built by build_grid(): cell (ix, iy) is item range
/// [cell_start[iy * nx + ix], cell_start[iy * nx + ix + 1]) of cell_items.
struct GridDims {
    Vec2 lo;       ///< lower corner (smallest point coordinates) [m]
    Real inv = 0;  ///< 1 / cell size [1/m]
    int32_t nx = 0, ny = 0;
};

/// Sort the n > 0 points p by uniform cells of size >= min_cell (larger for sparse layouts: at
/// most ~4 cells per point). Writes cell[i] (cell of point i), cell_start (ncell + 1 prefix
/// sums), cell_items (point indices in cell order, ascending within a cell); cursor is scratch.
/// The vectors only grow (no allocation once they are large enough).
inline GridDims build_grid(const Vec2* p, int32_t n, Real min_cell, std::vector<int32_t>& cell,
                           std::vector<int32_t>& cell_start, std::vector<int32_t>& cell_items,
                           std::vector<int32_t>& cursor) {
    GridDims g;
    Vec2 lo = p[0], hi = lo;
    for (int32_t i = 1; i < n; ++i) {
        lo.x = std::min(lo.x, p[i].x);
        lo.y = std::min(lo.y, p[i].y);
        hi.x = std::max(hi.x, p[i].x);
        hi.y = std::max(hi.y, p[i].y);
    }
    Real size = min_cell;
    // cap the number of cells at ~4 per point (sparse layouts): larger cells stay correct
    const Real max_cells = 4.0 * n + 16.0;
    const Real area_cells = ((hi.x - lo.x) / size + 1) * ((hi.y - lo.y) / size + 1);
    if (area_cells > max_cells) size *= std::sqrt(area_cells / max_cells) * 1.01;
    g.lo = lo;
    g.nx = static_cast<int32_t>((hi.x - lo.x) / size) + 1;
    g.ny = static_cast<int32_t>((hi.y - lo.y) / size) + 1;
    g.inv = 1.0 / size;

    const size_t ncell = static_cast<size_t>(g.nx) * static_cast<size_t>(g.ny);
    cell_start.assign(ncell + 1, 0);
    cell.resize(static_cast<size_t>(n));
    cell_items.resize(static_cast<size_t>(n));
    cursor.resize(ncell);
    int32_t* __restrict c = cell.data();
    int32_t* __restrict start = cell_start.data();
    for (int32_t i = 0; i < n; ++i) {
        const int32_t ix = std::min(g.nx - 1, static_cast<int32_t>((p[i].x - lo.x) * g.inv));
        const int32_t iy = std::min(g.ny - 1, static_cast<int32_t>((p[i].y - lo.y) * g.inv));
        c[i] = iy * g.nx + ix;
        ++start[c[i] + 1];
    }
    for (size_t k = 0; k < ncell; ++k)
        start[k + 1] += start[k];
    int32_t* __restrict cur = cursor.data();
    std::copy(start, start + ncell, cur);
    int32_t* __restrict items = cell_items.data();
    for (int32_t i = 0; i < n; ++i)
        items[cur[c[i]]++] = i;
    return g;
}

}  // namespace fdem
