// Fracture output (spec fracture.md §8, docs/output.md "Fracture output"): the joint frames
// joints_NNNNNN.vtu + joints.pvd, the crack event catalogue cracks.csv, the fragment table
// fragments.csv, and the per-triangle fragment / damage arrays of the frame VTU. Written by
// Simulation (run/simulation.cpp) for models with joints; models without joints write none of it.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "fdem/model.hpp"
#include "fdem/output.hpp"
#include "fdem/scenario.hpp"
#include "fdem/state.hpp"

namespace fdem {

/// The two triangles of every joint: [0] = A (the triangle with joint nodes 0, 1), [1] = B
/// (nodes 3, 2), theory eq. 9.1; kNone if not found (cannot happen for joints made by
/// add_bodies). One pass over the triangles and the joints; allocates.
std::vector<std::array<TriId, 2>> joint_triangles(const Model& m);

/// Per triangle the largest frozen damage max_k D_max,k over the joints on its edges (spec §3.8),
/// 0 for a triangle without joints. out.size() == num_tris().
void triangle_damage(const Model& m, const State& s,
                     std::span<const std::array<TriId, 2>> joint_tris, std::span<Real> out);

/// Write one joint frame: VTK XML UnstructuredGrid (raw appended binary, like write_vtu), one
/// VTK_LINE per selected joint from the midpoint of its node pair 0-3 to that of 1-2 (the joint's
/// mid-line in the current configuration). Cell data: joint (id), state (0 intact, 1 softening,
/// 2 broken), damage (max D_max), mode (0 none, 1 I, 2 II, 3 mixed), break_time [s] (n dt of the
/// step n that broke it; -1 if not broken, 0 if broken at t = 0), opening and slip [m] at the
/// mid-point (eq. 9.2), dissipated W_J [J/m] (eq. 9.17), length h_0 [m]. all = false: softening
/// and broken joints only. Throws SimulationError naming the file if it cannot be written.
/// Returns the number of joints written.
int32_t write_joints_vtu(const std::string& path, const Model& m, const State& s, bool all);

/// cracks.csv (acoustic-emission catalogue): one row per joint break, in joint-id order within a
/// step: step (n of the step that broke it, JointState::break_step), time (t^n) [s], joint,
/// x, y (mid-point of the joint's 4 nodes after the step) [m], h (h_0) [m], mode (1 I, 2 II,
/// 3 mixed), work (W_J) [J/m].
class CracksWriter {
public:
    /// Fresh file (restart = false), or continue one whose rows up to the state's breaks are
    /// kept (rows with step <= s.step - 1: the breaks the restored state contains).
    CracksWriter(const std::string& path, const Model& m, const State& s, bool restart);
    /// After a step: rows for the joints the step just taken broke. step_before, time_before: n
    /// and t^n of that step. O(joints) bytes scanned; no allocation unless a row is written.
    void after_step(const Model& m, const State& s, int64_t step_before, Real time_before);
    bool header_changed() const { return csv_.header_changed(); }

private:
    CsvSeries csv_;
    int64_t broken_seen_ = 0;
    std::string line_;
};

/// fragments.csv: per output time a summary row (fragment = -1: the whole model) and one row per
/// fragment in fragment-id order: step, time, fragment (State::tri_fragment id), triangles,
/// mass [kg/m], area (reference) [m^2], diameter sqrt(4 A/pi) [m], x, y (centre of mass) [m],
/// vx, vy (mean velocity v^{n+1/2}) [m/s], kinetic (sum 1/2 m |v|^2) [J/m], fragments (count at
/// this time), largest_fraction (mass of the largest fragment / total mass). Scratch sized once.
class FragmentsWriter {
public:
    FragmentsWriter(const std::string& path, const Model& m, int64_t resume_step = -1);
    /// One block of rows for the state. One pass over the triangles and one over the nodes.
    void write(const Model& m, const State& s);
    bool header_changed() const { return csv_.header_changed(); }

private:
    struct Acc {
        int64_t tris = 0;
        Real mass = 0, area = 0, mx = 0, my = 0, px = 0, py = 0, ke = 0;
    };
    CsvSeries csv_;
    std::vector<Acc> acc_;          ///< per fragment id (a triangle id)
    std::vector<TriId> node_frag_;  ///< fragment of every node (kNone: in no triangle)
    std::string block_;
};

/// The fracture files of one run (Simulation): cracks.csv always, fragments.csv per
/// FractureSettings::fragments, joints_NNNNNN.vtu + joints.pvd per output_joints (with
/// [output] vtu).
class FractureOutput {
public:
    /// dir: output folder; restart: continue the files of the run the state came from; frames:
    /// the frame series so far (RunProgress::frames), whose joint frames joints.pvd lists again.
    FractureOutput(const std::string& dir, const Model& m, const State& s,
                   const FractureSettings& settings, bool vtu, bool restart,
                   const std::vector<std::pair<Real, std::string>>& frames);
    void after_step(const Model& m, const State& s, int64_t step_before, Real time_before) {
        cracks_.after_step(m, s, step_before, time_before);
    }
    /// At an output time: the joint frame for frame number `frame` and fragments.csv (every
    /// output, or only when last with fragments = "end").
    void write_output(const Model& m, const State& s, int64_t frame, bool last);
    /// Files whose earlier rows a restart dropped (other columns), for a notice.
    std::vector<std::string> changed_headers() const;
    /// joints_NNNNNN.vtu belonging to frame file name `frame_file` (frame_NNNNNN.vtu, possibly
    /// with a folder): the same folder and number.
    static std::string joint_file_of(const std::string& frame_file);

private:
    std::string dir_;
    FractureSettings settings_;
    bool vtu_ = true;
    CracksWriter cracks_;
    std::unique_ptr<FragmentsWriter> fragments_;
    std::unique_ptr<PvdSeries> joints_pvd_;
};

}  // namespace fdem
