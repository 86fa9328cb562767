// Building a Model from meshes: bodies from connected components, derived geometry,
// lumped masses, boundary-condition node arrays and contact topology.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fdem/contact_topology.hpp"
#include "fdem/mesh.hpp"
#include "fdem/model.hpp"

namespace fdem {

/// Options shared by all bodies created from one scenario [[body]] entry.
struct BodyOptions {
    std::string name;      ///< scenario body name
    int32_t material = 0;  ///< index into Model::materials (must exist)
    bool fixed = false;    ///< all nodes held fixed
    /// Initial velocity field (docs/theory.md eq. 5.5), per connected piece:
    /// v(x) = velocity + angular_velocity e_z x (x - o) + velocity_gradient (x - o), with
    /// o = origin, or the piece's own mass centre when origin_centroid.
    Vec2 velocity;                ///< v0 [m/s]
    Real angular_velocity = 0;    ///< omega [rad/s], counter-clockwise positive
    Mat2 velocity_gradient;       ///< G [1/s], row-major [[dvx/dx, dvx/dy], [dvy/dx, dvy/dy]]
    bool origin_centroid = true;  ///< o = each piece's mass centre (else origin)
    Vec2 origin;                  ///< o [m] when !origin_centroid
    /// true: every piece moves rigidly, with the field's velocity at its mass centre c and the
    /// spin omega + (G_yx - G_xy)/2 about c; false: the field is evaluated at every node
    bool rigid_pieces = false;
    /// Element formulation; nullopt takes it from the mesh: Composite6 for 6-node triangles,
    /// Cst for 3-node ones. Cst on a 6-node mesh splits every 6-node triangle into its four
    /// sub-triangles as plain CSTs; Composite6 on a 3-node mesh is an InputError.
    std::optional<ElementKind> element;
    /// Discrete fracture (spec fracture.md §1.2, §10; docs/theory.md §9). With fracture, the
    /// jointed edges are: the internal edges between two triangles of fracture_tris (mesh
    /// triangle ids; empty = every triangle of the entry, unless joint_edges is given), plus the
    /// mesh edges joint_edges (mesh node pairs, e.g. of a curve group), plus prebroken_edges.
    /// Around every mesh vertex the fan of triangles is cut at jointed edges; each run gets its
    /// own node copy (Model::node_vertex maps copies to the vertex), each jointed edge a joint
    /// with the material's law (Material::fracture). prebroken_edges are broken at t = 0
    /// (Model::prebroken_joints). Connected components (bodies) are those of the mesh.
    bool fracture = false;
    std::vector<int32_t> fracture_tris;
    std::vector<std::array<int32_t, 2>> joint_edges;
    std::vector<std::array<int32_t, 2>> prebroken_edges;
};

/// Append the triangles tri_ids of mesh (indices into mesh.tris) as one or more bodies: every
/// connected component (triangles sharing an edge or a node) becomes its own body with its own
/// nodes. Triangles are re-oriented counter-clockwise. A 6-node triangle of a second-order mesh
/// becomes four sub-triangles in the order and numbering of the Body contract (model.hpp), for
/// either element kind. Returns, per mesh node, the model node created for it (kNone if these
/// triangles do not use it).
/// Throws InputError naming mesh.file and the element for a degenerate (zero-area) triangle or
/// sub-triangle (a misplaced mid-edge node), and for Composite6 requested on a 3-node mesh.
std::vector<NodeId> add_bodies(Model& m, const MeshData& mesh, const std::vector<int32_t>& tri_ids,
                               const BodyOptions& opt);

/// The mesh nodes one add_bodies_mapped() call used and the model node made for each: a map
/// whose size is that of the selected triangles, not of the whole mesh (a mesh of 10^4 blocks
/// loaded one block per [[body]] entry would otherwise cost entries x mesh nodes; issue #16).
struct MeshNodeMap {
    std::vector<int32_t> mesh_nodes;  ///< ascending mesh node ids
    std::vector<NodeId> model_nodes;  ///< the model node of each, parallel to mesh_nodes
    /// The model node made for mesh node q; kNone if the triangles do not use it.
    NodeId operator[](int32_t q) const;
};

/// add_bodies() with the node map returned sparse; the work is O(k log k) in the k selected
/// triangles, independent of the size of the mesh. Same bodies, nodes and errors.
MeshNodeMap add_bodies_mapped(Model& m, const MeshData& mesh, const std::vector<int32_t>& tri_ids,
                              const BodyOptions& opt);

/// Compute everything derived: reference geometry, lumped masses, element viscosity and the
/// resolved contact parameters (m_bar, buffer, pair laws). Call once after all bodies, materials
/// and BCs are added. The contact topology is not part of the Model: build_topology().
void finalize_model(Model& m);

/// The contact topology of m's bodies (fdem/contact_topology.hpp; docs/theory.md §6.1-6.2,
/// §6.11-6.12): make_state() stores it in State::topology. Throws InputError for a mesh the
/// contact cannot use (an edge shared by three triangles, a composite element off the layout or
/// too distorted for the fan of option (b)).
ContactTopology build_topology(const Model& m);
/// The same into t.
void build_topology(const Model& m, ContactTopology& t);
/// Rebuild t, a topology of m's bodies, for the bodies `dirty` whose mesh changed (e.g. broken
/// joints): those are built anew, the others are copied with their virtual node and boundary
/// edge ids renumbered, then the passes over all bodies (contact node lists, target scales,
/// edge targets) run again. Gives bitwise the arrays build_topology(m) gives (tested). Throws
/// std::invalid_argument for a body id out of range.
void rebuild_topology(const Model& m, std::span<const BodyId> dirty, ContactTopology& t);
/// build_topology / rebuild_topology of the welded form (docs/theory.md §6.15): node_sector =
/// State::node_sector (the sector representative of every node, compute_node_sectors()), used
/// by the bodies with fracture; empty = identity, which gives the forms above bitwise. Bodies
/// spliced by the rebuild must have the sectors they had. Throws std::invalid_argument for a
/// node_sector that is neither empty nor one entry per node.
void build_topology(const Model& m, std::span<const NodeId> node_sector, ContactTopology& t);
void rebuild_topology(const Model& m, std::span<const BodyId> dirty,
                      std::span<const NodeId> node_sector, ContactTopology& t);

/// Effective 2-D Lame constants of a material (docs/theory.md eq. 2.5).
void compute_lame(Material& mat);

/// Stable central-difference time step [s] (docs/theory.md §5, §6.9): the element limit
/// dt_e (below) and, with contact, the contact frequency bound dt_c combined as
/// 1 / sqrt(1/dt_e^2 + 1/dt_c^2) (eq. 6.17: both stiffnesses act on the boundary nodes).
/// limiting_tri receives the element that sets dt_e when dt_e <= dt_c, kNone when the contact
/// bound governs.
Real stable_time_step(const Model& m, const ContactTopology& t, TriId* limiting_tri = nullptr);
/// The same with the topology built here (build_topology(m)).
Real stable_time_step(const Model& m, TriId* limiting_tri = nullptr);

/// The element part of stable_time_step(): min over the movable triangles of h_min / c_p
/// (eq. 5.3, 5.4) and the triangle that sets it (kNone: no movable triangle).
Real element_stable_time_step(const Model& m, TriId* limiting_tri = nullptr);

}  // namespace fdem
