// What the broad phase (detect/broad_phase.hpp) writes: the candidate list it hands to the
// narrow phase and its own grid scratch. Separate from ContactState (contact_state.hpp) so the
// broad phase depends on these two structs only and never on contact's pair history.
#pragma once

#include <cstdint>
#include <vector>

#include "fdem/math.hpp"

namespace fdem {

/// Candidate pairs (target node, contactor body), sorted by (node, body); the candidate
/// sub-triangles of pair p are tri[begin[p] .. begin[p+1]), ascending. Grows only.
struct Candidates {
    std::vector<NodeId> node;
    std::vector<BodyId> body;
    std::vector<int32_t> begin;
    std::vector<int32_t> tri;
};

/// Grid scratch of the broad phase (contents meaningless outside find_candidates; grows only).
struct BroadPhaseScratch {
    /// sub-triangle centroid at the last rebuild [m]; find_candidates() leaves it in cell
    /// order (k-th entry: sub-triangle cell_items[k]), the brute force in sub-triangle order
    std::vector<Vec2> tri_center;
    /// bounding-circle radius about the centroid [m], ordered like tri_center
    std::vector<Real> tri_radius;
    std::vector<int32_t> tri_cell;  ///< grid cell of each sub-triangle
    std::vector<int32_t> cell_start;
    std::vector<int32_t> cell_items;
    std::vector<int32_t> query;  ///< fill cursor of the grid, then the hit list of one node
    /// queries on 2+ threads (from 4 096 targets): each thread's list and hit list
    std::vector<Candidates> part;
    std::vector<std::vector<int32_t>> part_hits;
};

}  // namespace fdem
