// Parameters of the cohesive joints of discrete fracture (docs/theory.md §9, spec fracture.md
// §3, §10), the joint arrays (Joints, in Model) and their history (JointState, in State). Public
// because the scenario reader, Model, State and the Python module use them; the law's arithmetic
// and the kernel are internal (src/fdem/fracture/).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "fdem/exact_sum.hpp"
#include "fdem/math.hpp"

namespace fdem {

/// Shape z(D) of the softening branch (theory eq. 9.10).
enum class SofteningCurve : uint8_t {
    EvansMarathe,  ///< Evans & Marathe 1968, a, b, c = 0.63, 1.8, 6.0 (Munjiza 2004 p. 240)
    Linear,        ///< z = 1 - D (tests: integral 1/2)
};

/// Length of the softening branch (theory eq. 9.12, spec §3.7).
enum class SofteningLength : uint8_t {
    Exact,     ///< o_r - o_p = G_I/(I_z f_t): the softening branch dissipates exactly G (default)
    Total,     ///< o_r - o_p = (G_I - 2/3 f_t o_p)/(I_z f_t): the whole curve dissipates G
    YGeo,      ///< o_r - o_p = 3 G_I/f_t (Y-Geo): dissipates 3 I_z G = 1.159 G
    Solidity,  ///< o_r - o_p = max(2 o_p, 3 G_I/f_t) (Y, Solidity)
};

/// How damage is remembered (spec §3.8). Only Frozen is implemented: per integration point
/// D_max <- max(D_max, D) and the tractions use z(D_max).
enum class Irreversibility : uint8_t { Frozen };

/// How a softening point shares its strength between the two modes (theory §9.3b).
enum class MixedMode : uint8_t {
    /// spec §3 (Y, Y-Geo, Solidity): each traction is capped by its own strength times z(D_max),
    /// sigma <= f_t z, |tau| <= f_s z, whatever the mix of the separation (eqs. 9.5, 9.8); a
    /// crack forced along inclined mesh edges dissipates up to ~1.5 G_I (eq. 9.29, theory §9.3a)
    Independent,
    /// each mode's traction is scaled by that mode's share of the damage reached, D_n,max/K and
    /// D_s,max/K (K = |(D_n,max, D_s,max)|), blended in over the first kMixOnset of K (theory eq.
    /// 9.30): pure modes as Independent, a radial separation dissipates
    /// (G_I u^2 + G_II v^2)/(u^2 + v^2), u = f_t cos(theta)/G_I, v = f_s sin(theta)/G_II
    /// (eq. 9.31); the tractions use the smallest shares reached, so none ever rises (eq. 9.32).
    /// The default since 2026-12-02 (theory §9.3d: V4, V6 on unstructured meshes, V7 on a zigzag
    /// path)
    Proportional,
};

/// Width in K = |(D_n,max, D_s,max)| over which MixedMode::Proportional's shares are blended in
/// from 1 (theory eq. 9.30): the shares are undefined at K = 0, so the tractions would jump at the
/// onset of damage without it. Over the blend a mode with no damage of its own keeps 1 - K/K_w of
/// its strength; 0.05 until 2026-12-02 locked such a mode at 0 too early (spec V4 at D/l_ch = 40
/// split the disc under a platen), 0.2 keeps 24 % of the spec law's mixed-mode premium (theory
/// §9.3d).
inline constexpr Real kMixOnset = 0.2;

/// Joint parameters of one material (spec §3.1, §10). Units: Pa, rad, J/m^2.
struct JointMaterial {
    Real tensile_strength = 0;    ///< f_t > 0
    Real cohesion = 0;            ///< c > 0
    Real friction_angle = 0;      ///< phi in [0, pi/2) [rad]
    Real fracture_energy_I = 0;   ///< G_I > 0
    Real fracture_energy_II = 0;  ///< G_II > 0
    Real penalty = 0;             ///< p > 0 (a stress; spec default 10 E)
    Real shear_penalty = 0;       ///< p_s > 0 (spec default p)
    SofteningCurve softening = SofteningCurve::EvansMarathe;
    SofteningLength softening_length = SofteningLength::Exact;
    Irreversibility irreversibility = Irreversibility::Frozen;
    MixedMode mixed_mode = MixedMode::Proportional;
    int32_t failure_points = 2;  ///< 1..3 integration points with D >= 1 break the joint
    /// Accept joints longer than h_max (theory eq. 9.14), whose softening branch is shorter than
    /// 2 o_p; false: finalize_model() rejects them (InputError naming the longest joint)
    bool allow_coarse = false;
};

/// I_z = integral of z(D) over [0, 1] (theory eq. 9.11): 0.38631 for Evans-Marathe, 1/2 linear.
Real softening_integral(SofteningCurve curve);

/// Effective Young's modulus of a jointed body, E/(1 + c_m E/p) (theory eq. 9.6); c_m = 2 for a
/// structured right-triangle mesh under uniaxial stress with nu = 0.
Real joint_effective_modulus(Real youngs_modulus, Real penalty, Real c_m = 2.0);

/// Largest joint length for which the softening branch is at least 2 o_p long with the "exact"
/// rule: h_max = p G_I / (4 I_z f_t^2) (theory eq. 9.14).
Real joint_max_length(const JointMaterial& jm);

/// Constants of one JointMaterial derived once (make_joint_law), read by the kernel.
struct JointLaw {
    Real ft = 0, c = 0, tan_phi = 0;  ///< f_t, c [Pa], tan(phi)
    Real p = 0, ps = 0;               ///< penalties p, p_s [Pa]
    Real GI = 0, GII = 0;             ///< fracture energies [J/m^2]
    Real Iz = 0;                      ///< integral of z over [0, 1] (eq. 9.11)
    Real half_p_over_ft = 0;          ///< p/(2 f_t): xi = o p/(2 h f_t) = o/o_p (eq. 9.4)
    Real half_ps = 0;                 ///< p_s/2: 1/s_p = (p_s/2)/(h f_s) (eq. 9.4)
    SofteningCurve curve = SofteningCurve::EvansMarathe;
    SofteningLength length_rule = SofteningLength::Exact;
    MixedMode mixed = MixedMode::Independent;
    int32_t failure_points = 2;
};

/// Joints per chunk of the kernel: fixed, so the energy sums do not depend on the thread count.
inline constexpr int32_t kJointChunk = 2048;

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
    /// set by renumber_spatially(): the joints are sorted by node 0 along the Morton curve, so
    /// side B's nodes (3, 2) jump through memory and joint_forces prefetches them (a large model;
    /// docs/performance.md "Stop 49"). Changes no value.
    bool sorted_by_node0 = false;
    int32_t num_joints() const { return static_cast<int32_t>(nodes.size()); }
};

/// Mutable part: per-joint history (state side) and the kernel's scratch.
struct JointState {
    std::vector<std::array<Real, 3>> d_max;  ///< frozen damage per point (spec §3.8)
    /// z(D_max) per point (theory eq. 9.10) where D_max > 0: a cache of a pure function of d_max,
    /// recomputed only where D_max rises (theory §9.4); not saved, rebuilt from d_max by
    /// refresh_softening_cache() after a restore
    std::vector<std::array<Real, 3>> z_max;
    /// largest D_n and D_s reached per point (eq. 9.9, not clamped), the history of
    /// MixedMode::Proportional's shares (theory eq. 9.30); empty unless a law of the model has
    /// that rule (make_joint_state)
    std::vector<std::array<Real, 3>> dn_max, ds_max;
    /// smallest shares a_n, a_s of eq. 9.30 reached per point (1 at the start), which the
    /// tractions use: the shares never rise (theory eq. 9.32); sized with dn_max
    std::vector<std::array<Real, 3>> an_min, as_min;
    std::vector<JointStatus> status;
    std::vector<uint8_t> mode_bits;  ///< 1: a point reached D_n >= 1, 2: D_s >= 1, 4: neither alone
    std::vector<JointMode> mode;     ///< mode at breaking (None while not broken)
    std::vector<int64_t> break_step;          ///< step argument of the call that broke it, -1
    std::vector<Real> work;                   ///< W_J: work done on the joint (eq. 9.17) [J/m]
    std::vector<std::array<Real, 4>> f_prev;  ///< forces on nodes 0, 1 of the last call
    std::vector<std::array<Real, 4>> d_prev;  ///< end separations delta_a, delta_b of the last call
    Real total_work = 0;                      ///< sum over all calls of the work increments
    ExactSum total_work_sum;  ///< its exact running sum (theory §4.4); total_work is it rounded
    // scratch (chunk_sums sized once by make_joint_state, jf by the first call with 2+ threads)
    /// per-joint forces on nodes 0, 1 (parallel path; empty until the first call with 2+ threads)
    std::vector<std::array<Vec2, 2>> jf;
    std::vector<Real> chunk_sums;
    /// per block of 8 joints: steps to go joint by joint after its softening or broken joints
    /// failed as a block (a damage grew); which path computes a block changes no bit
    std::vector<uint8_t> block_wait;
};

}  // namespace fdem
