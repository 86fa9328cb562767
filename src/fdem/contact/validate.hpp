// Validator of the contact topology (issue #14 item 3): checks every invariant the contact code
// relies on, independently of how the topology was built, so that a rebuilt topology (fracture,
// fragments) can be checked after every rebuild in tests and, with FDEM_ASSERT, in Debug and
// sanitizer builds.
#pragma once

#include <string>
#include <vector>

#include "fdem/contact_topology.hpp"
#include "fdem/model.hpp"

namespace fdem {

/// Every violated invariant of t as the contact topology of m (empty: valid). Each message starts
/// with the name of the array or invariant it concerns ("boundary_edges: ...", tests match on
/// it), then the entity ids. At most max_messages are returned. The invariants:
///  * sizes: per-node, per-contact-node, per-sub-triangle, per-virtual-node and per-body arrays
///    have the sizes of what they index; edge_target_base = num_contact_nodes()
///  * ranges: body_bnode_begin, body_bedge_begin, body_sub_begin, body_cnode_begin,
///    body_virt_begin, body_chord_begin, body_btri_begin start at 0, never decrease and end at
///    the size of their array (one entry per body + 1); what each body's range holds belongs to
///    the body; body_fallback adds up to num_fallback_nodes
///  * boundary_edges: per body in strictly ascending (min, max) node order (the binary searches
///    of the builder rely on it), both nodes in the body, used by exactly one triangle of the
///    body (really on the boundary) and oriented as in that triangle (material on the left);
///    every edge used once in the body is listed
///  * boundary_nodes: strictly ascending, in their body's node range, = the end nodes of the
///    boundary edges = node_on_boundary
///  * chords: strictly ascending (min, max) keys of interior edges (two triangles) joining two
///    boundary nodes; every such edge of the model is one
///  * boundary_tris: strictly ascending, = the triangles with a boundary node
///  * virtual nodes: parents are real nodes of one body, weights in [0, 1] summing to 1, each
///    virtual node is a vertex of some sub-triangle of that body
///  * sub-triangles: valid contact ids, counter-clockwise in the reference configuration,
///    sub_body / sub_parent / vertices in the body of their range; per body the areas add up to
///    those of its boundary elements; every boundary edge is a directed edge of exactly one
///    sub-triangle of its body (the distance field covers the whole boundary)
///  * body_cnode / sub_local: per body the distinct vertices of its sub-triangles, ascending,
///    body_cnode_nreal real ones first; sub_local points at each vertex
///  * nodal distances: 0 and edge -1 on boundary nodes and on nodes in no sub-triangle; on the
///    other vertices of sub-triangles > 0, finite, the recorded edge is a boundary edge of the
///    node's body, and the distance is the node's distance to that edge's line (eq. 6.3) or
///    segment (fallback, eq. 6.4)
///  * scales: node_scale finite, >= 0, > 0 on boundary nodes (with length scaling: on those that
///    end a boundary edge); edge_scale (edge targets) finite and > 0; body_fixed = Body::fixed;
///    body_self = Body::fracture; sub_legacy_b parallel to sub_tri for baseline B only
///  * welded form (node_weld not empty, docs/theory.md §6.15): node_weld maps every node to the
///    smallest node of its sector, in its body, at the same reference position; in bodies with
///    fracture the edge keys, the boundary / chord classification and the boundary nodes above
///    are those of the welded ids (every copy of a boundary sector is a boundary node), while
///    boundary edges hold (and are oriented as in) their triangle's own copies
std::vector<std::string> validate_topology(const Model& m, const ContactTopology& t,
                                           size_t max_messages = 20);

}  // namespace fdem
