// Load-time geometric checks of a contact model (docs/theory.md §6.13-6.14): bodies that overlap
// at t = 0, and thin bodies whose contact layer takes nodal distances from the opposite face.
#pragma once

#include <string>
#include <vector>

#include "fdem/contact_topology.hpp"
#include "fdem/model.hpp"

namespace fdem {

/// An overlap of two bodies in the reference configuration (find_initial_overlap()): a point of
/// `body` lies inside `other`. The point is a boundary node, the midpoint of a boundary edge or
/// the centroid of a boundary element of `body`; `node` is that node or a node of that edge or
/// element.
struct InitialOverlap {
    enum class Point { Node, EdgeMidpoint, Centroid };
    bool found = false;
    BodyId body = kNone;   ///< the body whose point lies inside the other
    BodyId other = kNone;  ///< the body it lies inside
    Point point = Point::Node;
    NodeId node = kNone;  ///< the boundary node, or the first node of the edge / element
    int32_t edge = -1;    ///< Point::EdgeMidpoint: boundary edge (ContactTopology::boundary_edges)
    TriId tri = kNone;    ///< Point::Centroid: the element
    Vec2 where;           ///< the point [m]
    Real depth = 0;       ///< its distance to the boundary of `other` [m]
    Real tolerance = 0;   ///< depths up to this count as touching [m]
};

/// Depth up to which an overlap counts as touching: kOverlapTolerance x the smallest element
/// altitude of the model (docs/theory.md §6.14).
constexpr Real kOverlapTolerance = 1e-6;

/// Deepest point of one body inside another at t = 0 (reference positions): boundary nodes and
/// centroids of boundary elements of every body, tested against every other body whose box
/// holds them (sweep over the bodies' boxes), by an even-odd test on the other body's boundary
/// edges and the distance to them; a point counts when it is inside and deeper than the
/// tolerance. Two fixed bodies are not compared (they never interact). Serial, deterministic:
/// the deepest point, the first in (body, point) order on ties. found = false when none.
InitialOverlap find_initial_overlap(const Model& m, const ContactTopology& ct);

/// An inner node counts as taking its distance from the far face when that distance is below
/// kThinLayerRatio x its distance to the faces its sub-triangle touches (docs/theory.md §6.13).
constexpr Real kThinLayerRatio = 0.99;

/// One thin-body finding (docs/theory.md §6.13): an inner node of a contactor sub-triangle takes
/// its nodal distance (eq. 6.3 or the fallback) from a boundary edge facing away from every face
/// the sub-triangle touches, and is nearer to it than to those faces.
struct ThinLayer {
    BodyId body = kNone;
    TriId tri = kNone;    ///< mesh element (sub_parent of the sub-triangle)
    NodeId node = kNone;  ///< contact node id (real, or virtual >= num_real_nodes)
    int32_t edge = -1;    ///< boundary edge that gave its distance (the far face)
    Real dist = 0;        ///< its nodal distance [m]
    Real near_dist = 0;   ///< its distance to the nearest face the sub-triangle touches [m]
    int32_t count = 0;    ///< number of such sub-triangles in the body
};

/// Every body with such sub-triangles, one entry per body (the one with the largest
/// near_dist / dist), ascending body ids.
std::vector<ThinLayer> find_thin_layers(const Model& m, const ContactTopology& ct);

/// The warning text of fdem check / fdem run for one finding.
std::string thin_layer_warning(const Model& m, const ContactTopology& ct, const ThinLayer& t);

}  // namespace fdem
