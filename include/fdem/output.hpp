// Output: VTU frames (binary appended), PVD series for ParaView, CSV energy history.
// Fields, units and how to open them: docs/output.md.
#pragma once

#include <cstdio>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "fdem/measure.hpp"
#include "fdem/model.hpp"
#include "fdem/state.hpp"

namespace fdem {

/// Derived per-triangle quantities written as cell data (docs/output.md).
struct TriFields {
    Mat2 stress;     ///< elastic Cauchy stress sigma [Pa] (spec §3.1, without the viscous eta D)
    Mat2 strain;     ///< Green-Lagrange strain E = 1/2 (F^T F - I) [-]
    Real von_mises;  ///< sqrt(sxx^2 - sxx syy + syy^2 + 3 sxy^2) [Pa] (in-plane, sigma_zz = 0)
};

/// Stress, strain and von Mises stress of triangle t in state s.
TriFields tri_fields(const Model& m, const State& s, TriId t);

/// An extra named array for write_vtu (e.g. the contact distance field). Values are tuple-major:
/// values[i * components + c]; the tuple count must be num_nodes() (point data) or num_tris()
/// (cell data). A 2-component array (an in-plane vector) is written as 3 components with z = 0
/// so ParaView's glyph filter accepts it. The span must stay valid during the call only.
struct ExtraField {
    std::string name;    ///< array name in ParaView (must not clash with a built-in one)
    int components = 1;  ///< 1 (scalar), 2 (in-plane vector, padded to 3), 3, 9, ...
    std::span<const Real> values;
};

/// Write one VTU frame: VTK XML UnstructuredGrid, raw binary appended data (UInt64 headers,
/// little endian), written atomically (temporary file then rename).
///   points: current positions x (z = 0); cells: triangles (VTK type 5).
///   point data: displacement x - X [m], velocity [m/s], force [N/m], contact_force [N/m],
///               body (int32), then extra_point.
///   cell data:  stress (9-component Cauchy tensor [Pa]), strain (9-component Green-Lagrange),
///               von_mises [Pa], body, material (int32), then extra_cell.
///   field data: TIME and TimeValue (= s.time [s]), CYCLE (= s.step).
/// Throws SimulationError (naming the file and the system error) if the file cannot be written,
/// and std::invalid_argument if an extra field has the wrong size.
void write_vtu(const std::string& path, const Model& m, const State& s,
               std::span<const ExtraField> extra_point = {},
               std::span<const ExtraField> extra_cell = {});

/// One process's piece of a frame of a distributed run (spec parallel-and-python.md D13): the
/// triangles whose first node the process owns and the nodes they use (ascending ids), with
/// the triangles' connectivity in the piece's node numbering.
struct VtuPiece {
    int32_t rank = 0;
    std::vector<int32_t> nodes;         ///< node ids (global), ascending
    std::vector<int32_t> tris;          ///< triangle ids (global), ascending
    std::vector<int32_t> connectivity;  ///< 3 per triangle: indices into nodes
};

/// The piece of process `rank`, given the owner of every node.
VtuPiece make_vtu_piece(const Model& m, const std::vector<int32_t>& node_owner, int32_t rank);

/// write_vtu() restricted to a piece: the same arrays at the piece's nodes and triangles, plus
/// point data node_id and cell data tri_id and rank (the ids of the serial frame, so tools can
/// merge the pieces: a node used by two pieces appears in both).
void write_vtu_piece(const std::string& path, const Model& m, const State& s, const VtuPiece& piece,
                     std::span<const ExtraField> extra_point = {},
                     std::span<const ExtraField> extra_cell = {});

/// The .pvtu (VTK XML PUnstructuredGrid) that lists the pieces `sources` (paths relative to
/// the .pvtu) with the arrays write_vtu_piece() writes. ParaView opens it as one data set.
void write_pvtu(const std::string& path, const Model& m, const State& s,
                const std::vector<std::string>& sources,
                std::span<const ExtraField> extra_point = {},
                std::span<const ExtraField> extra_cell = {});

/// ParaView time series: collects (time, file) and rewrites the .pvd atomically after each
/// frame, so a killed run still leaves a valid series of the frames written so far.
class PvdSeries {
public:
    /// path: the .pvd file; frame files are given relative to its directory.
    explicit PvdSeries(std::string path) : path_(std::move(path)) {}
    /// Append frame (time [s], file name relative to the .pvd) and rewrite the .pvd.
    void add(Real time, const std::string& relative_file);
    const std::vector<std::pair<Real, std::string>>& frames() const { return frames_; }

private:
    std::string path_;
    std::vector<std::pair<Real, std::string>> frames_;
};

/// CSV history of energies and counters, one row per call, flushed after each row.
/// Columns (energies in J/m, per unit thickness):
///   step,time,kinetic,strain,contact,work_gravity,work_external,dissipated_viscous,
///   dissipated_contact,total,energy_error,active_contacts
/// total = Energy::total(); energy_error = total - total of the first row written (absolute,
/// J/m; 0 on the first row). Values use %.17g, so they read back bit-exact.
/// write() reads s.energy as it is: call update_energy() first.
class HistoryWriter {
public:
    /// Creates (truncates) path and writes the header. Throws SimulationError if it cannot.
    /// fracture: the model has cohesive joints; the header gets the columns energy.joint,
    /// energy.fracture, joints.softening, joints.broken, crack_length, fragments,
    /// largest_fragment_mass_fraction (write() fills
    /// them when the Model has joints: construct with fracture = !m.joints.nodes.empty()).
    explicit HistoryWriter(const std::string& path, bool fracture = false);
    /// Restart: keeps the header and the rows of an existing file with step <= resume_step
    /// (later rows came from the interrupted run and will be written again), takes the
    /// energy_error reference from its first row, and appends from there. A missing file is
    /// created as by the other constructor. Throws SimulationError if it cannot.
    HistoryWriter(const std::string& path, int64_t resume_step, bool fracture = false);
    ~HistoryWriter();
    HistoryWriter(const HistoryWriter&) = delete;
    HistoryWriter& operator=(const HistoryWriter&) = delete;
    /// Sizes the scratch of the fracture columns for m (no allocation in write() afterwards;
    /// write() sizes it itself at its first call otherwise).
    void prepare(const Model& m);
    void write(const Model& m, const State& s);

private:
    std::string path_;
    std::FILE* file_ = nullptr;
    bool has_reference_ = false;
    Real total0_ = 0;               ///< total energy of the first row [J/m]
    std::vector<TriId> node_frag_;  ///< scratch of largest_fragment_mass_fraction (per node)
    std::vector<Real> frag_mass_;   ///< scratch of largest_fragment_mass_fraction (per fragment)
};

/// A CSV time series (bodies.csv, probes.csv): one header line, then one row per call, each
/// row starting with the step number and flushed at once, so a killed run keeps every complete
/// row. Numbers are written by the callers with %.17g (bit-exact when read back).
class CsvSeries {
public:
    /// Creates (truncates) path and writes header (one line, without the newline). Throws
    /// SimulationError naming the file if it cannot.
    CsvSeries(std::string path, const std::string& header);
    /// Restart: keeps the rows of an existing file with step <= resume_step (later rows came
    /// from the interrupted run and will be written again) and appends from there. A missing
    /// file, or one whose header differs from header (other columns: the output settings
    /// changed), is started afresh; header_changed() then says whether old rows were dropped.
    CsvSeries(std::string path, const std::string& header, int64_t resume_step);
    ~CsvSeries();
    CsvSeries(const CsvSeries&) = delete;
    CsvSeries& operator=(const CsvSeries&) = delete;

    /// Append one line (without the newline) and flush. Throws SimulationError on failure.
    void write_line(const std::string& line, int64_t step, Real time);
    /// The restart found rows under another header and dropped them.
    bool header_changed() const { return header_changed_; }
    const std::string& path() const { return path_; }

private:
    void open_append(int64_t step);
    std::string path_;
    std::FILE* file_ = nullptr;
    bool header_changed_ = false;
};

/// Quote a CSV field if it needs it (RFC 4180: a comma, quote, CR or LF inside, or leading or
/// trailing blanks): "a,b" -> "\"a,b\"" with inner quotes doubled.
std::string csv_field(const std::string& text);

/// bodies.csv (docs/output.md): per row step, time, then for every set of Resultants (body
/// entries, then boundary groups) 12 columns NAME.ux, NAME.uy, NAME.vx, NAME.vy,
/// NAME.contact_x, NAME.contact_y, NAME.contact_avg_x, NAME.contact_avg_y, NAME.reaction_x,
/// NAME.reaction_y, NAME.reaction_avg_x, NAME.reaction_avg_y (SetValues).
class BodiesWriter {
public:
    /// Fresh file (resume_step < 0) or restart from resume_step (CsvSeries).
    BodiesWriter(const std::string& path, const Resultants& r, int64_t resume_step = -1);
    /// One row of the state after a step; acc: impulses since the last row (the caller resets
    /// them afterwards). Throws SimulationError if the row cannot be written.
    void write(const Model& m, const State& s, const IntervalImpulses& acc);
    bool header_changed() const { return csv_.header_changed(); }

private:
    static std::string header(const Resultants& r);
    const Resultants& r_;
    CsvSeries csv_;
    std::vector<SetValues> values_;
    std::string line_;
};

/// probes.csv (docs/output.md): per row step, time, then for every probe 7 columns NAME.x,
/// NAME.y, NAME.vx, NAME.vy, NAME.sxx, NAME.syy, NAME.sxy (ProbeValues).
class ProbesWriter {
public:
    /// Fresh file (resume_step < 0) or restart from resume_step (CsvSeries). probes must outlive
    /// the writer.
    ProbesWriter(const std::string& path, const std::vector<ProbeSpec>& probes,
                 int64_t resume_step = -1);
    /// One row of the state after a step. Throws SimulationError if it cannot be written.
    void write(const Model& m, const State& s);
    bool header_changed() const { return csv_.header_changed(); }

private:
    static std::string header(const std::vector<ProbeSpec>& probes);
    const std::vector<ProbeSpec>& probes_;
    CsvSeries csv_;
    std::string line_;
};

}  // namespace fdem
