// The force kernel of the cohesive 4-node joints (docs/theory.md §9, spec fracture.md §2-§7);
// the joint arrays themselves (Joints in Model, JointState in State) are public: fdem/fracture.hpp.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "fracture/joint_law.hpp"

namespace fdem {

/// Build the gather lists from nodes (call after filling nodes; num_nodes >= every id + 1).
void finalize_joints(Joints& J, int32_t num_nodes);

/// State of the joints in the reference configuration (separations 0, no force, no damage).
JointState make_joint_state(const Joints& J);

/// JointState::z_max from d_max (after anything that sets d_max other than the kernel: a
/// checkpoint restore).
void refresh_softening_cache(const Joints& J, JointState& s);

/// Result of one kernel call.
struct JointPass {
    Real elastic_energy = 0;  ///< E_joint = sum w_k (psi_n + psi_s) (eq. 9.18), when need_energy
    Real work = 0;            ///< work done on all joints so far, = JointState::total_work
    Real fracture = 0;        ///< W_frac = work - E_joint (eq. 9.19), when need_energy
    int32_t newly_broken = 0;
    int32_t softening = 0;  ///< joints softening (not broken) after the call
    int32_t blocked = 0;    ///< joints computed by the blocked path (diagnostic; same results)
};

/// Add the forces of every non-broken joint at positions x to f (theory eq. 9.3), update damage,
/// status, mode and the work W_J (eq. 9.17), and mark joints broken (eq. 9.15). Bitwise identical
/// for every OpenMP thread count: with one thread the forces are scattered in joint order, with
/// more each joint writes its two forces to JointState::jf and every node gathers its joints in
/// joint order (the same additions in the same order); sums go per chunk of kJointChunk joints,
/// then over chunks in chunk order. No allocation after the first call with 2+ threads (which sizes
/// JointState::jf). A joint shorter than 1e-9 h_0 or non-finite throws SimulationError(step, time,
/// "joint J").
JointPass joint_forces(const Joints& J, JointState& s, std::span<const Vec2> x, std::span<Vec2> f,
                       bool need_energy, int64_t step = 0, double time = 0);

/// The SimulationError of a joint shorter than 1e-9 h_0 or not finite (joint_forces()).
[[noreturn]] void throw_joint_failure(int32_t j, int64_t step, double time);

/// One process's share of the joints in a distributed run (parallel/distributed.hpp, theory
/// §9 and docs/parallel.md "Joints"): the chunks of kJointChunk joints it runs, ascending. A
/// chunk whose first joint's node 0 the process owns it runs whole and sums (its partial sums
/// are the serial chunk's, and exactly one process sums each chunk); of the other chunks it runs
/// the ranges of joints with a node it owns. So every owned node gets the forces of all its
/// joints in joint order (the serial bits); joints run by several processes are updated alike
/// by each (the same positions in, the same history out).
struct JointSubset {
    std::vector<int32_t> chunks;       ///< ascending
    std::vector<uint8_t> counts;       ///< per entry: 1 = runs the chunk whole and sums it
    std::vector<int32_t> range_begin;  ///< per entry: its ranges [range_begin[k], [k + 1])
    std::vector<std::array<int32_t, 2>> ranges;  ///< [first, end) joints (entries not counted)
    std::vector<int32_t> gather;  ///< indices into Joints::gather_node of the owned nodes
};

/// fn(first, end) for every range of joints `sub` runs, ascending: its chunks run whole, then
/// the ranges of the others (num_joints: of the model, for the last chunk's end).
template <class Fn>
void for_each_joint_range(const JointSubset& sub, int32_t num_joints, Fn&& fn) {
    for (size_t k = 0; k < sub.chunks.size(); ++k) {
        if (sub.counts[k]) {
            const int32_t b = sub.chunks[k] * kJointChunk;
            fn(b, std::min(num_joints, b + kJointChunk));
        } else {
            for (int32_t r = sub.range_begin[k]; r < sub.range_begin[k + 1]; ++r)
                fn(sub.ranges[static_cast<size_t>(r)][0], sub.ranges[static_cast<size_t>(r)][1]);
        }
    }
}

/// The subset of process `rank` for node_owner[n] in [0, processes).
JointSubset joint_subset(const Joints& J, std::span<const int32_t> node_owner, int32_t rank);

/// What a process's subset pass reports, over the chunks it counts: exact sums, so that the sums
/// of all processes (Comm::sum) are the serial pass's bits (theory §4.4).
struct JointSubsetPass {
    ExactSum work;             ///< the work increments of this call (eq. 9.17)
    ExactSum elastic;          ///< E_joint (eq. 9.18), with need_energy
    int32_t newly_broken = 0;  ///< joints broken by this call
    int32_t bad = -1;          ///< the smallest joint too short or not finite, else -1
};

/// joint_forces() over the joints of `sub` only: forces added to f (complete on the owned nodes;
/// with one thread also on the other nodes of the joints run), history updated for every joint
/// run. JointState::total_work is not updated (the caller adds the work of every process). Does
/// not throw for a bad joint: it reports it.
JointSubsetPass joint_forces(const Joints& J, JointState& s, std::span<const Vec2> x,
                             std::span<Vec2> f, bool need_energy, const JointSubset& sub,
                             int64_t step);

namespace detail {

/// Which code computes blocks of 8 intact elastic joints in joint_forces (same bits on every
/// path): Auto (the default) picks Avx512 when the CPU has AVX-512F, else Avx2 when it has AVX2,
/// else Portable (baseline SSE2); Scalar turns the blocked path off. For tests and benchmarks; not
/// thread-safe against a running kernel.
enum class JointPath { Auto, Scalar, Portable, Avx512, Avx2 };
void set_joint_path(JointPath p);
/// true when this build has the AVX-512 variant and the CPU runs it.
bool joint_avx512_supported();
/// true when this build has the AVX2 variant and the CPU runs it.
bool joint_avx2_supported();

/// Blocks that hold softening or broken joints (computed on the chosen path on steps without
/// the energy, when none of their joints' damage grows) on (the default) or off: for tests that
/// compare both.
void set_damaged_blocks(bool on);

/// The path joint_forces uses for blocks of intact joints: "avx512", "avx2", "portable" or
/// "scalar" (printed by `fdem run`).
const char* joint_path_name();

}  // namespace detail

/// Per-node Gershgorin row sum of the joint stiffness, sum over joints of max(p, p_s) (theory eq.
/// 9.16), added to k (size >= num_nodes).
void add_joint_row_sums(const Joints& J, std::span<Real> k);

/// Stable time step of the joints alone: 2 / sqrt(max_i k_i / m_i) (theory eq. 9.16); +inf
/// without joints. Combine with the element and contact bounds by min, or add the row sums.
Real joint_critical_dt(const Joints& J, std::span<const Real> node_mass);

}  // namespace fdem
