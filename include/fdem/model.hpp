// Model: everything that does not change during a run (mesh, materials, derived geometry,
// boundary conditions, contact parameters). Built once by build_model() and then read-only.
// The contact topology, which can change during a run, is State::topology.
//
// Layout (style guide §4.4): one flat array per field, indexed by the id named in its prefix.
// Nodes of a body are contiguous, triangles of a body are contiguous, and bodies never share nodes.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "fdem/contact_model.hpp"
#include "fdem/fracture.hpp"
#include "fdem/material.hpp"
#include "fdem/math.hpp"

namespace fdem {

/// Finite-element formulation of a body's triangles (docs/theory.md §3; spec §3.3).
enum class ElementKind : uint8_t {
    Cst,         ///< 3-node constant-strain triangle, finite strain (theory §3)
    Composite6,  ///< 6-node composite triangle (Lei et al. 2016): four CST sub-triangles with
                 ///< the volumetric part taken from the whole composite (spec §3.3)
};

/// One discrete element: a connected set of triangles with its own nodes.
///
/// Composite6 bodies: the body's triangles come in groups of four consecutive ids, one composite
/// element per group (group c = triangles tri_begin + 4c ... tri_begin + 4c + 3). With the
/// paper's perimeter numbering n1..n6 (corners n1, n3, n5; mid-edge n2 on n1-n3, n4 on n3-n5,
/// n6 on n5-n1), the four sub-triangles are, in this order (paper §2.1, spec §3.3):
///   (n1, n2, n6), (n2, n3, n4), (n6, n4, n5), (n2, n4, n6)
/// all counter-clockwise in the reference configuration. So n1 = tri[0][0], n2 = tri[0][1],
/// n6 = tri[0][2], n3 = tri[1][1], n4 = tri[1][2], n5 = tri[2][2]. Every per-triangle array of
/// the Model (dm_inv, area0, eta, ...) then describes the sub-triangles; masses are lumped per
/// sub-triangle; contact and output see the sub-triangles.
struct Body {
    std::string name;      ///< scenario body name (several bodies may share it: one per component)
    int32_t group = 0;     ///< index of the scenario [[body]] entry it came from
    int32_t material = 0;  ///< index into Model::materials
    bool fixed = false;    ///< every node held at its initial position
    ElementKind element = ElementKind::Cst;  ///< formulation of the triangles (see above)
    /// Has cohesive joints (issue #14, spec fracture.md §1.2): the triangles on either side of a
    /// jointed edge have their own node copies, Model::joints couples them; the body is one
    /// contact body whose cracks contact themselves by rule X (docs/theory.md §9)
    bool fracture = false;
    NodeId node_begin = 0, node_end = 0;  ///< nodes [begin, end)
    TriId tri_begin = 0, tri_end = 0;     ///< triangles [begin, end)
};

/// Prescribed velocity components on a node set (a "fixed" component has velocity 0).
struct BoundaryCondition {
    std::string name;           ///< node-set name, for messages
    std::vector<NodeId> nodes;  ///< sorted, unique
    bool has_x = false, has_y = false;
    Vec2 velocity;                                     ///< [m/s]
    Real start = 0;                                    ///< active from this time [s]
    Real end = std::numeric_limits<Real>::infinity();  ///< active until this time [s]
};

/// A one-time velocity assignment to whole scenario body entries at a given time
/// (used e.g. to launch a block after gravity relaxation).
struct VelocityKick {
    int32_t group = 0;  ///< scenario body entry
    Real time = 0;      ///< [s]
    bool has_x = false, has_y = false;
    Vec2 velocity;  ///< [m/s]
};

/// Time function of a load: the factor that multiplies its magnitude at time t
/// (docs/scenario.md [[load]], docs/theory.md eq. 4.6).
struct TimeFunction {
    enum class Kind : uint8_t {
        Constant,  ///< 1 for all t
        Ramp,      ///< t / ramp_time up to ramp_time, then 1
        Table,     ///< piecewise linear through table (t strictly increasing), held at the ends
    };
    Kind kind = Kind::Constant;
    Real ramp_time = 0;                      ///< [s], > 0 for Ramp
    std::vector<std::array<Real, 2>> table;  ///< (t [s], factor [-]) pairs for Table
    /// Factor at time t [s].
    Real at(Real t) const;
};

/// What a [[load]] applies (docs/scenario.md, docs/theory.md §4.1).
enum class LoadKind : uint8_t {
    Traction,  ///< dead traction [N/m^2 = Pa] per unit reference edge length (and thickness)
    Pressure,  ///< follower pressure [Pa], normal to the current edge, positive inward
    Force,     ///< resultant point force [N/m], split equally over the nodes
};

/// An external load on a boundary group of one body entry (theory eqs. 4.5-4.7).
/// Traction and pressure act on boundary edges, force on nodes; all ids are model node ids.
struct Load {
    std::string name;  ///< "body/group", for messages
    LoadKind kind = LoadKind::Traction;
    Vec2 vector;        ///< traction [Pa] or resultant force [N/m]
    Real pressure = 0;  ///< [Pa], positive compressive (pushes into the body)
    TimeFunction time_function;
    /// Traction, Pressure: boundary edges (a, b) oriented counter-clockwise around their body
    /// (the body lies to the left of a -> b, the outward normal is (b - a) rotated by -90 deg)
    std::vector<std::array<NodeId, 2>> edges;
    std::vector<Real> edge_length0;  ///< reference length of each edge [m] (Traction)
    std::vector<NodeId> nodes;       ///< Force: sorted, unique (every copy of a jointed vertex)
    /// Force: the fraction of the resultant each node of `nodes` takes. Empty: 1/nodes.size()
    /// each (no node copies). With fracture (finalize_model): F / (number of mesh vertices) per
    /// vertex, split over its copies in proportion to their masses (theory eq. 4.11), so the
    /// copies of an intact vertex get the same acceleration.
    std::vector<Real> node_share;
    /// Slots of this load in State::scratch_load: one per edge or node, from slot_begin.
    int32_t slot_begin = 0;
    int32_t num_slots() const {
        return static_cast<int32_t>(kind == LoadKind::Force ? nodes.size() : edges.size());
    }
};

/// Global damping used only to reach equilibrium: f = -c m v while t < until (spec §3.2).
struct MassDamping {
    Real coefficient = 0;  ///< c [1/s]
    Real until = 0;        ///< [s]
};

/// Parallel schedule of the element loop, derived by finalize_model() (docs/performance.md).
/// The triangles of each non-fixed body are cut into chunks of contiguous ids, and runs of
/// consecutive chunks into units (one chunk each in models under 131 072 triangles, up to 16 in
/// larger ones: a unit's triangles stream through memory in one pass). Units of one color share
/// no node, so they run concurrently, and every node sums the forces of its triangles in one
/// fixed order (color, chunk, triangle) whatever the thread count.
struct ElementSchedule {
    /// [begin, end) per chunk, sorted by (color of its unit, chunk): a unit's chunks are
    /// consecutive here and ascending in triangle ids (contiguous unless a fixed body, which has
    /// no chunk, lies between two of them)
    std::vector<std::array<TriId, 2>> chunk_tris;
    std::vector<BodyId> chunk_body;  ///< (first) body of each chunk
    /// unit u: chunks [unit_begin[u], unit_begin[u + 1]) (one more entry than units)
    std::vector<int32_t> unit_begin;
    /// units of color c: [color_units[c], color_units[c + 1]) (one more entry than colors)
    std::vector<int32_t> color_units;
    /// per chunk: 1 when it is of CST triangles whose every node belongs to that one triangle (a
    /// jointed body: fracture splits every vertex), so the serial step's element pass is the
    /// first writer of those nodes' forces and stores them (first_internal_forces())
    std::vector<uint8_t> chunk_first;
    /// the node ranges [first, end) whose force the serial step zeros before the element pass:
    /// every node but those of the chunk_first chunks (all nodes as one run when there is none)
    std::vector<std::array<NodeId, 2>> clear_runs;
    int32_t num_chunks() const { return static_cast<int32_t>(chunk_tris.size()); }
};

struct Model {
    // nodes (num_nodes())
    std::vector<Vec2> node_x0;        ///< reference position [m]
    std::vector<Vec2> node_v0;        ///< initial velocity [m/s]
    std::vector<Real> node_mass;      ///< lumped mass per unit thickness [kg/m]
    std::vector<Real> node_inv_mass;  ///< 1/mass [m/kg]; 0 for nodes of fixed bodies
    std::vector<BodyId> node_body;    ///< owning body

    // triangles (num_tris()), reference orientation counter-clockwise
    std::vector<std::array<NodeId, 3>> tri_nodes;
    std::vector<BodyId> tri_body;
    std::vector<int32_t> tri_material;
    std::vector<Mat2> tri_dm_inv;  ///< inverse reference edge matrix [X1-X0, X2-X0]^-1 [1/m]
    std::vector<Real> tri_area0;   ///< reference area [m^2]
    std::vector<Real> tri_eta;     ///< viscosity eta of the element [Pa s]

    std::vector<Body> bodies;
    std::vector<Material> materials;
    std::vector<std::string> group_names;  ///< scenario [[body]] names, indexed by Body::group

    std::vector<BoundaryCondition> bcs;
    std::vector<VelocityKick> kicks;
    std::vector<Load> loads;  ///< external loads (finalize_model() sets their slot_begin)
    MassDamping mass_damping;
    Vec2 gravity;  ///< [m/s^2]

    /// Discrete fracture (docs/theory.md §9, spec fracture.md): the cohesive joints (4 node
    /// copies each, reference length, law; empty without fracture) and, per node, the node that
    /// represents its original mesh vertex (the smallest copy id of that vertex; node_vertex[n]
    /// == n for a node that was never split). Empty when no body has fracture.
    Joints joints;
    std::vector<NodeId> node_vertex;
    /// Joints broken at t = 0 (pre-broken curves: notches, DFN), ascending ids; make_state() marks
    /// them broken with zero dissipation.
    std::vector<int32_t> prebroken_joints;

    ContactModel contact;              ///< contact parameters (contact_model.hpp)
    ElementSchedule element_schedule;  ///< derived: parallel element loop (element/cst.hpp)

    int32_t num_nodes() const { return static_cast<int32_t>(node_x0.size()); }
    int32_t num_tris() const { return static_cast<int32_t>(tri_nodes.size()); }
    int32_t num_bodies() const { return static_cast<int32_t>(bodies.size()); }
};

}  // namespace fdem
