// Cohesive 4-node joints as flat arrays and their force kernel (docs/theory.md §9, spec
// fracture.md §2-§7). Not yet part of the step: the step, Model and State do not know joints.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "fracture/joint_law.hpp"

namespace fdem {

/// Joint status (spec §0).
enum class JointStatus : uint8_t { Intact = 0, Softening = 1, Broken = 2 };

/// Mode label at breaking (spec §3.9): I if only D_n reached 1, II if only D_s, mixed otherwise.
enum class JointMode : uint8_t { None = 0, I = 1, II = 2, Mixed = 3 };

/// Immutable part: topology and parameters of N joints (model side).
/// Node order (theory eq. 9.1): 0, 1 on triangle A in A's counter-clockwise order, 3, 2 on B;
/// 0 faces 3 and 1 faces 2 in the reference configuration.
struct Joints {
    std::vector<std::array<NodeId, 4>> nodes;
    std::vector<Real> length0;   ///< reference length h_0 [m]
    std::vector<int32_t> law;    ///< index into laws
    std::vector<JointLaw> laws;  ///< one per joint material
    // gather lists (finalize_joints): for every node with joints, in node order, its entries
    // 4 j + k (joint j, local node k), ascending in j
    std::vector<NodeId> gather_node;
    std::vector<int32_t> gather_begin;  ///< gather_node.size() + 1 offsets into gather_entry
    std::vector<int32_t> gather_entry;
    int32_t num_joints() const { return static_cast<int32_t>(nodes.size()); }
};

/// Build the gather lists from nodes (call after filling nodes; num_nodes >= every id + 1).
void finalize_joints(Joints& J, int32_t num_nodes);

/// Mutable part: per-joint history (state side) and the kernel's scratch.
struct JointState {
    std::vector<std::array<Real, 3>> d_max;  ///< frozen damage per point (spec §3.8)
    std::vector<JointStatus> status;
    std::vector<uint8_t> mode_bits;  ///< 1: a point reached D_n >= 1, 2: D_s >= 1, 4: neither alone
    std::vector<JointMode> mode;     ///< mode at breaking (None while not broken)
    std::vector<int64_t> break_step;          ///< step argument of the call that broke it, -1
    std::vector<Real> work;                   ///< W_J: work done on the joint (eq. 9.17) [J/m]
    std::vector<std::array<Real, 4>> f_prev;  ///< forces on nodes 0, 1 of the last call
    std::vector<std::array<Real, 4>> d_prev;  ///< end separations delta_a, delta_b of the last call
    Real total_work = 0;                      ///< sum over all calls of the work increments
    // scratch (sized once by make_joint_state)
    std::vector<std::array<Vec2, 2>> jf;  ///< per-joint forces on nodes 0, 1 (parallel path)
    std::vector<Real> chunk_sums;
};

/// State of the joints in the reference configuration (separations 0, no force, no damage).
JointState make_joint_state(const Joints& J);

/// Result of one kernel call.
struct JointPass {
    Real elastic_energy = 0;  ///< E_joint = sum w_k (psi_n + psi_s) (eq. 9.18), when need_energy
    Real work = 0;            ///< work done on all joints so far, = JointState::total_work
    Real fracture = 0;        ///< W_frac = work - E_joint (eq. 9.19), when need_energy
    int32_t newly_broken = 0;
    int32_t softening = 0;  ///< joints softening (not broken) after the call
    int32_t blocked = 0;    ///< joints computed by the blocked path (diagnostic; same results)
};

/// Joints per chunk of the kernel: fixed, so the energy sums do not depend on the thread count.
inline constexpr int32_t kJointChunk = 2048;

/// Add the forces of every non-broken joint at positions x to f (theory eq. 9.3), update damage,
/// status, mode and the work W_J (eq. 9.17), and mark joints broken (eq. 9.15). Bitwise identical
/// for every OpenMP thread count: with one thread the forces are scattered in joint order, with
/// more each joint writes its two forces to JointState::jf and every node gathers its joints in
/// joint order (the same additions in the same order); sums go per chunk of kJointChunk joints,
/// then over chunks in chunk order. No allocation. A joint shorter than 1e-9 h_0 or non-finite
/// throws SimulationError(step, time, "joint J").
JointPass joint_forces(const Joints& J, JointState& s, std::span<const Vec2> x, std::span<Vec2> f,
                       bool need_energy, int64_t step = 0, double time = 0);

namespace detail {

/// Which code computes blocks of 8 intact elastic joints in joint_forces (same bits on every
/// path): Auto (the default) picks Avx512 when the CPU has AVX-512F, else Portable; Scalar turns
/// the blocked path off. For tests and benchmarks; not thread-safe against a running kernel.
enum class JointPath { Auto, Scalar, Portable, Avx512 };
void set_joint_path(JointPath p);
/// true when this build has the AVX-512 variant and the CPU runs it.
bool joint_avx512_supported();

}  // namespace detail

/// Per-node Gershgorin row sum of the joint stiffness, sum over joints of max(p, p_s) (theory eq.
/// 9.16), added to k (size >= num_nodes).
void add_joint_row_sums(const Joints& J, std::span<Real> k);

/// Stable time step of the joints alone: 2 / sqrt(max_i k_i / m_i) (theory eq. 9.16); +inf
/// without joints. Combine with the element and contact bounds by min, or add the row sums.
Real joint_critical_dt(const Joints& J, std::span<const Real> node_mass);

}  // namespace fdem
