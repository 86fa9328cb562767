// Cohesive joint kernel (docs/theory.md §9; spec fracture.md §2, §3, §5, §6, §7).
#include "fracture/joints.hpp"

#include <omp.h>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <limits>
#include <string>

#include "fdem/assert.hpp"
#include "fdem/error.hpp"

namespace fdem {

namespace {

inline constexpr Real kMinLengthRatio = 1e-9;  // spec §2 guard: h < 1e-9 h_0 is an error
// per-chunk sums: work increment, elastic energy, newly broken, softening, first bad joint,
// joints done by the blocked path
inline constexpr size_t kSlots = 6;
inline constexpr Real kInf = std::numeric_limits<Real>::infinity();
// From this many joints on, the blocked loop prefetches the far-side nodes of the block
// kPrefetchBlocks ahead when the joints are in Morton order (Joints::sorted_by_node0; run_range(),
// docs/performance.md "Stop 49": -33 % of the jointed step at 131 k and 1 M triangles; +2 ... +9 %
// at 16 k, whose ~8 MB stay in cache, hence the threshold; +15 % on the row-ordered joints of
// bench_joints, whose regular strides the hardware prefetchers follow, hence the order test)
inline constexpr int32_t kPrefetchJoints = 1 << 16;
inline constexpr int32_t kPrefetchBlocks = 3;

}  // namespace

void finalize_joints(Joints& J, int32_t num_nodes) {
    const int32_t nj = J.num_joints();
    std::vector<int32_t> count(static_cast<size_t>(num_nodes) + 1, 0);
    for (int32_t j = 0; j < nj; ++j)
        for (NodeId n : J.nodes[j])
            ++count[static_cast<size_t>(n) + 1];
    J.gather_node.clear();
    J.gather_begin.assign(1, 0);
    for (NodeId n = 0; n < num_nodes; ++n) {
        if (count[static_cast<size_t>(n) + 1] == 0) continue;
        J.gather_node.push_back(n);
        J.gather_begin.push_back(J.gather_begin.back() + count[static_cast<size_t>(n) + 1]);
    }
    // slot of node n in gather_node, then fill entries in joint order (ascending j per node)
    std::vector<int32_t> next(static_cast<size_t>(num_nodes), -1);
    for (size_t g = 0; g < J.gather_node.size(); ++g)
        next[static_cast<size_t>(J.gather_node[g])] = J.gather_begin[g];
    J.gather_entry.assign(static_cast<size_t>(J.gather_begin.back()), 0);
    for (int32_t j = 0; j < nj; ++j)
        for (int k = 0; k < 4; ++k)
            J.gather_entry[static_cast<size_t>(next[static_cast<size_t>(J.nodes[j][k])]++)] =
                4 * j + k;
}

void refresh_softening_cache(const Joints& J, JointState& s) {
    const size_t n = s.d_max.size();
    s.z_max.resize(n);
    for (size_t j = 0; j < n; ++j) {
        const SofteningCurve curve = J.laws[static_cast<size_t>(J.law[j])].curve;
        for (int k = 0; k < 3; ++k)
            s.z_max[j][k] = s.d_max[j][k] > 0 ? softening_z(curve, s.d_max[j][k]) : 1.0;
    }
}

JointState make_joint_state(const Joints& J) {
    const size_t n = static_cast<size_t>(J.num_joints());
    JointState s;
    s.d_max.assign(n, {0, 0, 0});
    s.z_max.assign(n, {1, 1, 1});
    // the per-mode history of MixedMode::Proportional (theory eq. 9.30), only where a law has it
    const bool proportional = std::any_of(J.laws.begin(), J.laws.end(), [](const JointLaw& L) {
        return L.mixed == MixedMode::Proportional;
    });
    if (proportional) {
        s.dn_max.assign(n, {0, 0, 0});
        s.ds_max.assign(n, {0, 0, 0});
        s.an_min.assign(n, {1, 1, 1});
        s.as_min.assign(n, {1, 1, 1});
    }
    s.status.assign(n, JointStatus::Intact);
    s.mode_bits.assign(n, 0);
    s.mode.assign(n, JointMode::None);
    s.break_step.assign(n, -1);
    s.work.assign(n, 0);
    s.f_prev.assign(n, {0, 0, 0, 0});
    s.d_prev.assign(n, {0, 0, 0, 0});
    // jf: sized by the first call with 2+ threads (joint_forces), 32 B per joint not held by
    // single-threaded runs
    const size_t nc = (n + kJointChunk - 1) / kJointChunk;
    s.chunk_sums.assign(kSlots * nc, 0);
    s.block_wait.assign(n / 8 + 1, 0);
    return s;
}

namespace {

struct ChunkOut {
    Real work = 0, energy = 0;
    int32_t broken = 0, softening = 0, bad = -1, blocked = 0;
};

// One joint: tractions at the three Simpson points, forces f0, f1 on nodes 0, 1 (eq. 9.3; nodes
// 3, 2 get -f0, -f1), damage and status, the work increment (eq. 9.17) and, with kEnergy, the
// stored energy (eq. 9.18). Returns false when the joint carries no force (broken, or bad).
// kMixed: the model has a MixedMode::Proportional law (JointState::dn_max sized); without one the
// code is that of the independent law alone.
template <bool kEnergy, bool kMixed>
[[gnu::always_inline]] inline bool one_joint(const Joints& J, JointState& s,
                                             const Vec2* __restrict x, int32_t j, int64_t step,
                                             Vec2& f0, Vec2& f1, ChunkOut& out) {
    if (s.status[j] == JointStatus::Broken) return false;
    const auto& nd = J.nodes[j];
    const Vec2 x0 = x[nd[0]], x1 = x[nd[1]], x2 = x[nd[2]], x3 = x[nd[3]];
    // eq. 9.1: mean of both faces; n points into A
    const Vec2 eb = 0.5 * ((x1 - x0) + (x2 - x3));
    const Real h = norm(eb);
    if (!(h >= kMinLengthRatio * J.length0[j]) || !std::isfinite(h)) {
        if (out.bad < 0) out.bad = j;
        return false;
    }
    const Real inv_h = 1.0 / h;
    const Vec2 e = inv_h * eb;
    const Vec2 n = perp(e);
    // eq. 9.2: end separations; the middle point is their mean (Simpson, eq. 9.3)
    const Vec2 da = x0 - x3, db = x1 - x2;
    const Vec2 dm = 0.5 * (da + db);
    const Real oa = dot(n, da), sa = dot(e, da);
    const Real om = dot(n, dm), sm = dot(e, dm);
    const Real ob = dot(n, db), sb = dot(e, db);
    const JointLaw& L = J.laws[static_cast<size_t>(J.law[j])];
    auto& dmax = s.d_max[j];
    auto& zmax = s.z_max[j];  // z(dmax), kept by joint_point()
    JointPoint pa, pm, pb;
    bool elastic = false;
    if (s.status[j] == JointStatus::Intact) {
        // intact joint in its elastic range: branch-free, the same bits as joint_point
        elastic = std::max({joint_point_intact(L, inv_h, oa, sa, pa),
                            joint_point_intact(L, inv_h, om, sm, pm),
                            joint_point_intact(L, inv_h, ob, sb, pb)}) <= 1.0;
    }
    if (!elastic) {
        if constexpr (kAssertsEnabled) {
            for (int k = 0; k < 3; ++k)
                FDEM_ASSERT(!(dmax[k] > 0) || zmax[k] == softening_z(L.curve, dmax[k]),
                            "the cached z(D_max) of a joint point is not z of its D_max");
        }
        if (kMixed && L.mixed == MixedMode::Proportional) {
            // eq. 9.30: each mode's largest damage per point scales that mode's traction
            // (eq. 9.32: the tractions use the smallest shares so far)
            auto& dn = s.dn_max[j];
            auto& ds = s.ds_max[j];
            auto& an = s.an_min[j];
            auto& as = s.as_min[j];
            pa = joint_point(L, h, inv_h, oa, sa, dmax[0], zmax[0], &dn[0], &ds[0], &an[0], &as[0]);
            pm = joint_point(L, h, inv_h, om, sm, dmax[1], zmax[1], &dn[1], &ds[1], &an[1], &as[1]);
            pb = joint_point(L, h, inv_h, ob, sb, dmax[2], zmax[2], &dn[2], &ds[2], &an[2], &as[2]);
        } else {
            pa = joint_point(L, h, inv_h, oa, sa, dmax[0], zmax[0]);
            pm = joint_point(L, h, inv_h, om, sm, dmax[1], zmax[1]);
            pb = joint_point(L, h, inv_h, ob, sb, dmax[2], zmax[2]);
        }
    }
    bool broken = false;
    if (!elastic && (dmax[0] > 0 || dmax[1] > 0 || dmax[2] > 0)) {
        // eq. 9.15: points at D >= 1 (frozen) and the mode they reached it in (spec §3.9)
        int failed = 0;
        const JointPoint* pts[3] = {&pa, &pm, &pb};
        for (int k = 0; k < 3; ++k) {
            if (dmax[k] < 1.0) continue;
            ++failed;
            const JointPoint& p = *pts[k];
            if (p.Dn * p.Dn + p.Ds * p.Ds >= 1.0) {
                const bool n1 = p.Dn >= 1.0, s1 = p.Ds >= 1.0;
                s.mode_bits[j] |=
                    static_cast<uint8_t>((n1 ? 1 : 0) | (s1 ? 2 : 0) | (!n1 && !s1 ? 4 : 0));
            }
        }
        if (failed >= L.failure_points) {
            broken = true;
            s.status[j] = JointStatus::Broken;
            const uint8_t b = s.mode_bits[j];
            s.mode[j] = b == 1 ? JointMode::I : b == 2 ? JointMode::II : JointMode::Mixed;
            s.break_step[j] = step;
            ++out.broken;
        } else {
            s.status[j] = JointStatus::Softening;
            ++out.softening;
        }
    }
    if (broken) {
        f0 = f1 = Vec2{0, 0};
    } else {
        // eq. 9.3: t = sigma n + tau e; Simpson weights h/6, 4h/6, h/6, the middle split
        const Vec2 ta = pa.sigma * n + pa.tau * e;
        const Vec2 tm = pm.sigma * n + pm.tau * e;
        const Vec2 tb = pb.sigma * n + pb.tau * e;
        const Real w = h / 6.0;
        f0 = -w * (ta + 2.0 * tm);
        f1 = -w * (tb + 2.0 * tm);
        if constexpr (kEnergy) {
            // eq. 9.18
            out.energy += w * (joint_point_energy(L, h, oa, sa, pa) +
                               4.0 * joint_point_energy(L, h, om, sm, pm) +
                               joint_point_energy(L, h, ob, sb, pb));
        }
    }
    // eq. 9.17: trapezoidal work of the joint forces over the step, on all four nodes
    // (f3 = -f0, f2 = -f1 make it (f0 . d delta_a + f1 . d delta_b))
    auto& fp = s.f_prev[j];
    auto& dp = s.d_prev[j];
    const Real dw = -0.5 * (((fp[0] + f0.x) * (da.x - dp[0]) + (fp[1] + f0.y) * (da.y - dp[1])) +
                            ((fp[2] + f1.x) * (db.x - dp[2]) + (fp[3] + f1.y) * (db.y - dp[3])));
    s.work[j] += dw;
    out.work += dw;
    fp = {f0.x, f0.y, f1.x, f1.y};
    dp = {da.x, da.y, db.x, db.y};
    return !broken;
}

// ---- blocked path: 8 intact joints in their elastic range at a time -----------------------
//
// Why (docs/performance.md "Fracture joints"): the scalar per-joint body runs at ~100 cycles per
// joint. Most joints of a run are intact and elastic, where the law (joint_point_intact) has no
// branch; 8 such joints are computed lane by lane in plain loops the compiler vectorises (SSE2
// in the baseline build, AVX-512 in the variant below, chosen at run time as the CST kernel).
// Bitwise the same as the scalar path: every lane does the same IEEE operations in the same
// order as one_joint + joint_point_intact (-ffp-contract=off, no fused multiply-add; sqrt and
// division are correctly rounded in every width); the work, the energy and the forces are then
// summed and scattered joint by joint in joint order, as there. A block with any joint that is
// not intact, not of the block's law, too short or not elastic is redone by the scalar path
// (nothing is written before the whole block qualifies). tests/unit/fracture/joints_test.cpp
// (Joints.BlockedPathSameBits) compares all paths.

inline constexpr int kLanes = 8;

struct Block {
    alignas(64) Real f0x[kLanes], f0y[kLanes], f1x[kLanes], f1y[kLanes];
    alignas(64) Real dax[kLanes], day[kLanes], dbx[kLanes], dby[kLanes];
    alignas(64) Real dw[kLanes];  ///< work increment (eq. 9.17)
    alignas(64) Real en[kLanes];  ///< w (psi_a + 4 psi_m + psi_b) (eq. 9.18), kEnergy only
    // a block with damaged joints (kDamaged): which joints are not broken, and how many soften
    alignas(64) Real live[kLanes];
    int32_t softening = 0;
};

// joint_point_energy for an intact point (z = 1) lane-wise, both branches evaluated and one
// selected (same expressions, same bits).
[[gnu::always_inline]] inline Real intact_energy_lane(const JointLaw& L, Real h, Real o, Real s,
                                                      Real fs) {
    const Real z = 1.0;
    const Real psi_c = 0.5 * L.p * o * o / h;
    const Real op = 2.0 * h * L.ft / L.p;
    const Real xi = o / op;
    const Real psi_t = xi <= 1.0 ? z * L.ft * op * (xi * xi - xi * xi * xi / 3.0)
                                 : z * L.ft * ((2.0 / 3.0) * op + (o - op));
    Real psi = o < 0 ? psi_c : psi_t;
    const Real sp = 2.0 * h * fs / L.ps;
    const Real abs_s = std::fabs(s);
    const Real eta = abs_s / sp;
    psi += eta <= 1.0 ? z * fs * sp * (eta * eta - eta * eta * eta / 3.0)
                      : z * fs * ((2.0 / 3.0) * sp + (abs_s - sp));
    return psi;
}

// The law of an intact elastic point, lane-wise (joint_point_intact, same expressions).
[[gnu::always_inline]] inline void intact_lane(const JointLaw& L, Real inv_h, Real o, Real s,
                                               Real& sigma, Real& tau, Real& fs, Real& m) {
    const Real sigma_c = L.p * std::min(o, Real(0)) * inv_h;  // eq. 9.5
    fs = L.c - sigma_c * L.tan_phi;                           // eq. 9.7
    const Real inv_sp = (L.half_ps * inv_h) / fs;             // eq. 9.4
    const Real xi = std::max(o, Real(0)) * L.half_p_over_ft * inv_h;
    const Real eta = std::fabs(s) * inv_sp;
    sigma = sigma_c + L.ft * (xi * (2.0 - xi));        // eq. 9.5
    tau = std::copysign(fs * (eta * (2.0 - eta)), s);  // eq. 9.8, z = 1
    m = std::max(xi, eta);
}

// The law of a point in its elastic range whose damage does not grow (xi, eta <= 1), lane-wise,
// softened by z = z(D_max) and scaled by the kept shares a_n, a_s of eq. 9.32 (1 with
// MixedMode::Independent): joint_point's expressions for that case (sigma_c of the compressive
// branch, the parabola times z and a_n, eq. 9.8 times z and a_s). With z = a_n = a_s = 1 (an
// intact point) the same bits as intact_lane: x * 1 is x, and sigma_c + ft q of intact_lane is
// sigma_c where o < 0 (q = +0) and +0 + ft q = ft q where o >= 0.
[[gnu::always_inline]] inline void damaged_lane(const JointLaw& L, Real inv_h, Real o, Real s,
                                                Real z, Real an, Real as, Real& sigma, Real& tau,
                                                Real& m) {
    const Real sigma_c = L.p * std::min(o, Real(0)) * inv_h;  // eq. 9.5
    const Real fs = L.c - sigma_c * L.tan_phi;                // eq. 9.7
    const Real inv_sp = (L.half_ps * inv_h) / fs;             // eq. 9.4
    const Real xi = std::max(o, Real(0)) * L.half_p_over_ft * inv_h;
    const Real eta = std::fabs(s) * inv_sp;
    const Real st = L.ft * z * (xi * (2.0 - xi)) * an;  // eq. 9.5, times z(D_max) and a_n
    sigma = o < 0 ? sigma_c : st;
    tau = std::copysign(fs * z * (eta * (2.0 - eta)) * as, s);  // eq. 9.8
    m = std::max(xi, eta);
}

// The law of joints j0 .. j0 + 7, all intact: true when all are of one law (its index in law).
[[gnu::always_inline]] inline bool block_qualifies(const Joints& J, const JointState& s, int32_t j0,
                                                   int32_t& law) {
    law = J.law[j0];
    bool ok = true;
    for (int l = 0; l < kLanes; ++l)
        ok &= (s.status[j0 + l] == JointStatus::Intact) & (J.law[j0 + l] == law);
    return ok;
}

// The law of joints j0 .. j0 + 7, none broken or some (kDamaged blocks): true when all are of
// one law (its index in law).
[[gnu::always_inline]] inline bool block_qualifies_damaged(const Joints& J, int32_t j0,
                                                           int32_t& law) {
    law = J.law[j0];
    bool ok = true;
    for (int l = 0; l < kLanes; ++l)
        ok &= J.law[j0 + l] == law;
    return ok;
}

// Node positions of the 8 joints, corner k (0..3) to P.x[k], P.y[k] lane by lane.
struct BlockPositions {
    alignas(64) Real x[4][kLanes];
    alignas(64) Real y[4][kLanes];
    alignas(64) Real fp[4][kLanes];  ///< last forces f0x, f0y, f1x, f1y (eq. 9.17)
    alignas(64) Real dp[4][kLanes];  ///< last separations dax, day, dbx, dby (eq. 9.17)
    // kDamaged blocks: per point z(D_max) (1 where D_max = 0) and the kept shares (eq. 9.32)
    alignas(64) Real z[3][kLanes];
    alignas(64) Real an[3][kLanes];
    alignas(64) Real as[3][kLanes];
};

// The damage state of a kDamaged block into P and B.live, B.softening (statuses, z, shares).
[[gnu::always_inline]] inline void load_block_damage(const JointState& s, const JointLaw& L,
                                                     bool mixed, int32_t j0, BlockPositions& P,
                                                     Block& B) {
    const bool prop = mixed && L.mixed == MixedMode::Proportional;
    int32_t soft = 0;
    for (int l = 0; l < kLanes; ++l) {
        const size_t j = static_cast<size_t>(j0 + l);
        const JointStatus st = s.status[j];
        B.live[l] = st != JointStatus::Broken ? 1.0 : 0.0;
        soft += st == JointStatus::Softening ? 1 : 0;
        for (int k = 0; k < 3; ++k) {
            P.z[k][l] = s.d_max[j][k] > 0 ? s.z_max[j][k] : 1.0;  // as joint_point's r.z
            P.an[k][l] = prop ? s.an_min[j][k] : 1.0;
            P.as[k][l] = prop ? s.as_min[j][k] : 1.0;
        }
    }
    B.softening = soft;
}

[[gnu::always_inline]] inline void gather_positions(const Joints& J, const Vec2* __restrict x,
                                                    int32_t j0, BlockPositions& P) {
    for (int l = 0; l < kLanes; ++l) {
        const auto& nd = J.nodes[j0 + l];
        for (int k = 0; k < 4; ++k)
            P.x[k][l] = x[nd[k]].x, P.y[k][l] = x[nd[k]].y;
    }
}

[[gnu::always_inline]] inline void load_block_state(const JointState& s, int32_t j0,
                                                    BlockPositions& P) {
    for (int l = 0; l < kLanes; ++l) {
        const auto& f4 = s.f_prev[j0 + l];
        const auto& d4 = s.d_prev[j0 + l];
        for (int k = 0; k < 4; ++k)
            P.fp[k][l] = f4[k], P.dp[k][l] = d4[k];
    }
}

// Joints j0 .. j0 + 7 (block_qualifies: intact, of law L), positions and last state in P: true
// and B filled when all are long enough and elastic at their three points (then B holds what
// one_joint would compute); false otherwise. Writes nothing else: the caller stores the eq. 9.17
// state (f_prev, d_prev) of a qualified block.
// kDamaged (never with kEnergy): softening and broken joints too, each intact or softening one
// in its elastic range at its three points (its damage does not grow this step: then
// one_joint changes nothing of its state but the eq. 9.17 records and counts it as softening);
// broken lanes are computed but qualify always, keep their records (B holds their old ones)
// and are skipped by the commit, as one_joint returns at once for them.
template <bool kEnergy, bool kDamaged = false>
[[gnu::always_inline]] inline bool block_core(const Joints& J, const JointLaw& L,
                                              const BlockPositions& P, int32_t j0, Block& B) {
    static_assert(!(kEnergy && kDamaged));
    const Real* x0x = P.x[0];
    const Real* x0y = P.y[0];
    const Real* x1x = P.x[1];
    const Real* x1y = P.y[1];
    const Real* x2x = P.x[2];
    const Real* x2y = P.y[2];
    const Real* x3x = P.x[3];
    const Real* x3y = P.y[3];
    const Real* len0 = J.length0.data() + j0;
    const auto& fp = P.fp;  // last forces and separations (eq. 9.17)
    const auto& dp = P.dp;
    alignas(64) Real good[kLanes];
    for (int l = 0; l < kLanes; ++l) {
        // eq. 9.1 (as one_joint)
        const Real ebx = 0.5 * ((x1x[l] - x0x[l]) + (x2x[l] - x3x[l]));
        const Real eby = 0.5 * ((x1y[l] - x0y[l]) + (x2y[l] - x3y[l]));
        const Real h = __builtin_sqrt(ebx * ebx + eby * eby);
        // one_joint's guard: h >= 1e-9 h_0 and finite (h >= 0 or NaN, so finite = below +inf)
        const bool lane_ok = (h >= kMinLengthRatio * len0[l]) & (h < kInf);
        const Real inv_h = 1.0 / h;
        const Real ex = inv_h * ebx, ey = inv_h * eby;
        const Real nx = -ey, ny = ex;
        // eq. 9.2
        const Real dax = x0x[l] - x3x[l], day = x0y[l] - x3y[l];
        const Real dbx = x1x[l] - x2x[l], dby = x1y[l] - x2y[l];
        const Real dmx = 0.5 * (dax + dbx), dmy = 0.5 * (day + dby);
        const Real oa = nx * dax + ny * day, sa = ex * dax + ey * day;
        const Real om = nx * dmx + ny * dmy, sm = ex * dmx + ey * dmy;
        const Real ob = nx * dbx + ny * dby, sb = ex * dbx + ey * dby;
        Real sga, taa, fsa, ma, sgm, tam, fsm, mm, sgb, tab, fsb, mb;
        if constexpr (kDamaged) {
            damaged_lane(L, inv_h, oa, sa, P.z[0][l], P.an[0][l], P.as[0][l], sga, taa, ma);
            damaged_lane(L, inv_h, om, sm, P.z[1][l], P.an[1][l], P.as[1][l], sgm, tam, mm);
            damaged_lane(L, inv_h, ob, sb, P.z[2][l], P.an[2][l], P.as[2][l], sgb, tab, mb);
            fsa = fsm = fsb = 0;  // (energy only)
        } else {
            intact_lane(L, inv_h, oa, sa, sga, taa, fsa, ma);
            intact_lane(L, inv_h, om, sm, sgm, tam, fsm, mm);
            intact_lane(L, inv_h, ob, sb, sgb, tab, fsb, mb);
        }
        // std::max({ma, mm, mb}) <= 1 as one_joint (first largest, operator<)
        Real mx = ma < mm ? mm : ma;
        mx = mx < mb ? mb : mx;
        good[l] = (lane_ok & (mx <= 1.0)) ? 1.0 : 0.0;
        if constexpr (kDamaged) good[l] = B.live[l] == 0.0 ? 1.0 : good[l];
        // eq. 9.3
        const Real tax = sga * nx + taa * ex, tay = sga * ny + taa * ey;
        const Real tmx = sgm * nx + tam * ex, tmy = sgm * ny + tam * ey;
        const Real tbx = sgb * nx + tab * ex, tby = sgb * ny + tab * ey;
        const Real mw = -(h / 6.0);
        B.f0x[l] = mw * (tax + 2.0 * tmx);
        B.f0y[l] = mw * (tay + 2.0 * tmy);
        B.f1x[l] = mw * (tbx + 2.0 * tmx);
        B.f1y[l] = mw * (tby + 2.0 * tmy);
        B.dax[l] = dax, B.day[l] = day, B.dbx[l] = dbx, B.dby[l] = dby;
        if constexpr (kDamaged) {  // a broken joint keeps its last records
            const bool dead = B.live[l] == 0.0;
            B.f0x[l] = dead ? fp[0][l] : B.f0x[l];
            B.f0y[l] = dead ? fp[1][l] : B.f0y[l];
            B.f1x[l] = dead ? fp[2][l] : B.f1x[l];
            B.f1y[l] = dead ? fp[3][l] : B.f1y[l];
            B.dax[l] = dead ? dp[0][l] : dax;
            B.day[l] = dead ? dp[1][l] : day;
            B.dbx[l] = dead ? dp[2][l] : dbx;
            B.dby[l] = dead ? dp[3][l] : dby;
        }
        // eq. 9.17 (as one_joint)
        B.dw[l] =
            -0.5 *
            (((fp[0][l] + B.f0x[l]) * (dax - dp[0][l]) + (fp[1][l] + B.f0y[l]) * (day - dp[1][l])) +
             ((fp[2][l] + B.f1x[l]) * (dbx - dp[2][l]) + (fp[3][l] + B.f1y[l]) * (dby - dp[3][l])));
        if constexpr (kEnergy) {
            // eq. 9.18 (as one_joint: w = h/6, weights 1, 4, 1)
            const Real w = h / 6.0;
            B.en[l] = w * (intact_energy_lane(L, h, oa, sa, fsa) +
                           4.0 * intact_energy_lane(L, h, om, sm, fsm) +
                           intact_energy_lane(L, h, ob, sb, fsb));
        }
    }
    Real all = 1.0;
    for (int l = 0; l < kLanes; ++l)
        all = std::min(all, good[l]);
    return all == 1.0;
}

// The eq. 9.17 state of a qualified block: last forces and separations of its 8 joints.
[[gnu::always_inline]] inline void store_block_state(JointState& s, int32_t j0, const Block& B) {
    for (int l = 0; l < kLanes; ++l) {
        s.f_prev[j0 + l] = {B.f0x[l], B.f0y[l], B.f1x[l], B.f1y[l]};
        s.d_prev[j0 + l] = {B.dax[l], B.day[l], B.dbx[l], B.dby[l]};
    }
}

// the block's law (all joints of one law, intact; kDamaged: of any status) and, for kDamaged,
// its damage state: false when the block does not qualify
template <bool kDamaged>
[[gnu::always_inline]] inline const JointLaw* block_law_of(const Joints& J, const JointState& s,
                                                           int32_t j0, BlockPositions& P,
                                                           Block& B) {
    int32_t law;
    if (kDamaged ? !block_qualifies_damaged(J, j0, law) : !block_qualifies(J, s, j0, law))
        return nullptr;
    const JointLaw* L = &J.laws[static_cast<size_t>(law)];
    if constexpr (kDamaged) load_block_damage(s, *L, !s.dn_max.empty(), j0, P, B);
    return L;
}

template <bool kEnergy, bool kDamaged = false>
bool block_law_portable(const Joints& J, JointState& s, const Vec2* __restrict x, int32_t j0,
                        Block& B) {
    BlockPositions P;
    const JointLaw* L = block_law_of<kDamaged>(J, s, j0, P, B);
    if (L == nullptr) return false;
    gather_positions(J, x, j0, P);
    load_block_state(s, j0, P);
    if (!block_core<kEnergy, kDamaged>(J, *L, P, j0, B)) return false;
    store_block_state(s, j0, B);
    return true;
}

#if defined(__x86_64__) && defined(__GNUC__)
#define FDEM_JOINT_AVX512 1
// GCC 12 warns inside its own avx512fintrin.h about the undefined upper half of
// _mm512_castpd256_pd512 (filled by the next insert): a false positive
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#define FDEM_JOINT_AVX512_TARGET __attribute__((target("avx512f,prefer-vector-width=512")))

// gather_positions with AVX-512: the 8 positions of one corner are loaded as 16-byte Vec2 at
// addresses from scalar id loads and de-interleaved by two permutes (as the CST kernel's
// load_corner; the auto-vectorised loop extracted the ids from vectors and inserted the
// positions one double at a time, ~200 instructions per block). Only moves data: same bits.
FDEM_JOINT_AVX512_TARGET [[gnu::always_inline]] inline void gather_positions_avx512(
    const Joints& J, const Vec2* __restrict x, int32_t j0, BlockPositions& P) {
    static_assert(sizeof(J.nodes[0]) == 4 * sizeof(int32_t) && sizeof(Vec2) == 2 * sizeof(double));
    const int32_t* q = J.nodes[static_cast<size_t>(j0)].data();
    const double* xd = reinterpret_cast<const double*>(x);
    const auto at = [&](int i, int k) {
        return _mm_loadu_pd(xd + 2 * static_cast<ptrdiff_t>(q[4 * i + k]));
    };
    const __m512i ix = _mm512_setr_epi64(0, 2, 4, 6, 8, 10, 12, 14);
    const __m512i iy = _mm512_setr_epi64(1, 3, 5, 7, 9, 11, 13, 15);
    for (int k = 0; k < 4; ++k) {
        const __m256d l0 = _mm256_insertf128_pd(_mm256_castpd128_pd256(at(0, k)), at(1, k), 1);
        const __m256d l1 = _mm256_insertf128_pd(_mm256_castpd128_pd256(at(2, k)), at(3, k), 1);
        const __m256d h0 = _mm256_insertf128_pd(_mm256_castpd128_pd256(at(4, k)), at(5, k), 1);
        const __m256d h1 = _mm256_insertf128_pd(_mm256_castpd128_pd256(at(6, k)), at(7, k), 1);
        const __m512d z0 = _mm512_insertf64x4(_mm512_castpd256_pd512(l0), l1, 1);
        const __m512d z1 = _mm512_insertf64x4(_mm512_castpd256_pd512(h0), h1, 1);
        _mm512_store_pd(P.x[k], _mm512_permutex2var_pd(z0, ix, z1));
        _mm512_store_pd(P.y[k], _mm512_permutex2var_pd(z0, iy, z1));
    }
}

// store_block_state with AVX-512: the four lane vectors a, b, c, d of the 8 joints transposed
// into their 8 records (a_l, b_l, c_l, d_l), contiguous at out (8 x 4 doubles), by permutes and
// four 64-byte stores instead of 32 scalar stores.
FDEM_JOINT_AVX512_TARGET [[gnu::always_inline]] inline void store_records_avx512(
    double* out, const double* a, const double* b, const double* c, const double* d) {
    const __m512d va = _mm512_load_pd(a), vb = _mm512_load_pd(b);
    const __m512d vc = _mm512_load_pd(c), vd = _mm512_load_pd(d);
    const __m512i lo = _mm512_setr_epi64(0, 8, 1, 9, 2, 10, 3, 11);
    const __m512i hi = _mm512_setr_epi64(4, 12, 5, 13, 6, 14, 7, 15);
    const __m512d ab_lo = _mm512_permutex2var_pd(va, lo, vb),
                  ab_hi = _mm512_permutex2var_pd(va, hi, vb);
    const __m512d cd_lo = _mm512_permutex2var_pd(vc, lo, vd),
                  cd_hi = _mm512_permutex2var_pd(vc, hi, vd);
    const __m512i r0 = _mm512_setr_epi64(0, 1, 8, 9, 2, 3, 10, 11);
    const __m512i r1 = _mm512_setr_epi64(4, 5, 12, 13, 6, 7, 14, 15);
    _mm512_storeu_pd(out, _mm512_permutex2var_pd(ab_lo, r0, cd_lo));
    _mm512_storeu_pd(out + 8, _mm512_permutex2var_pd(ab_lo, r1, cd_lo));
    _mm512_storeu_pd(out + 16, _mm512_permutex2var_pd(ab_hi, r0, cd_hi));
    _mm512_storeu_pd(out + 24, _mm512_permutex2var_pd(ab_hi, r1, cd_hi));
}

template <bool kEnergy, bool kDamaged = false>
FDEM_JOINT_AVX512_TARGET bool block_law_avx512(const Joints& J, JointState& s,
                                               const Vec2* __restrict x, int32_t j0, Block& B) {
    BlockPositions P;
    const JointLaw* L = block_law_of<kDamaged>(J, s, j0, P, B);
    if (L == nullptr) return false;
    gather_positions_avx512(J, x, j0, P);
    load_block_state(s, j0, P);
    if (!block_core<kEnergy, kDamaged>(J, *L, P, j0, B)) return false;
    static_assert(sizeof(s.f_prev[0]) == 4 * sizeof(double) &&
                  sizeof(s.d_prev[0]) == 4 * sizeof(double));
    store_records_avx512(s.f_prev[static_cast<size_t>(j0)].data(), B.f0x, B.f0y, B.f1x, B.f1y);
    store_records_avx512(s.d_prev[static_cast<size_t>(j0)].data(), B.dax, B.day, B.dbx, B.dby);
    return true;
}

// The same block for CPUs with AVX2 but without AVX-512 (e.g. AMD Zen 1-3, many desktop Intel):
// block_core compiled for 256-bit vectors (two per 8 lanes) instead of baseline SSE2's 128-bit
// ones. No FMA (the target adds none and -ffp-contract=off): the same IEEE operations in the
// same order, so the same bits as every other path (Joints.BlockedPathSameBits).
#define FDEM_JOINT_AVX2_TARGET __attribute__((target("avx2")))

// gather_positions with AVX2: per 4 lanes, two 32-byte vectors hold the 16-byte Vec2 of lanes
// (0, 2) and (1, 3), so one unpack gives x and one gives y in lane order. Only moves data.
FDEM_JOINT_AVX2_TARGET [[gnu::always_inline]] inline void gather_positions_avx2(
    const Joints& J, const Vec2* __restrict x, int32_t j0, BlockPositions& P) {
    static_assert(sizeof(J.nodes[0]) == 4 * sizeof(int32_t) && sizeof(Vec2) == 2 * sizeof(double));
    const int32_t* q = J.nodes[static_cast<size_t>(j0)].data();
    const double* xd = reinterpret_cast<const double*>(x);
    const auto at = [&](int i, int k) {
        return _mm_loadu_pd(xd + 2 * static_cast<ptrdiff_t>(q[4 * i + k]));
    };
    for (int k = 0; k < 4; ++k) {
        for (int h = 0; h < kLanes; h += 4) {
            // a = x_h y_h x_{h+2} y_{h+2}, b = x_{h+1} y_{h+1} x_{h+3} y_{h+3}
            const __m256d a =
                _mm256_insertf128_pd(_mm256_castpd128_pd256(at(h, k)), at(h + 2, k), 1);
            const __m256d b =
                _mm256_insertf128_pd(_mm256_castpd128_pd256(at(h + 1, k)), at(h + 3, k), 1);
            _mm256_store_pd(P.x[k] + h, _mm256_unpacklo_pd(a, b));
            _mm256_store_pd(P.y[k] + h, _mm256_unpackhi_pd(a, b));
        }
    }
}

// store_block_state with AVX2: per 4 lanes a 4 x 4 transpose of the lane vectors a, b, c, d into
// the 4 records (a_l, b_l, c_l, d_l), contiguous at out, by 4 unpacks, 4 lane permutes and 4
// stores instead of 16 scalar stores.
FDEM_JOINT_AVX2_TARGET [[gnu::always_inline]] inline void store_records_avx2(
    double* out, const double* a, const double* b, const double* c, const double* d) {
    for (int h = 0; h < kLanes; h += 4) {
        const __m256d va = _mm256_load_pd(a + h), vb = _mm256_load_pd(b + h);
        const __m256d vc = _mm256_load_pd(c + h), vd = _mm256_load_pd(d + h);
        const __m256d t0 = _mm256_unpacklo_pd(va, vb);  // a0 b0 a2 b2
        const __m256d t1 = _mm256_unpackhi_pd(va, vb);  // a1 b1 a3 b3
        const __m256d t2 = _mm256_unpacklo_pd(vc, vd);  // c0 d0 c2 d2
        const __m256d t3 = _mm256_unpackhi_pd(vc, vd);  // c1 d1 c3 d3
        double* o = out + 4 * h;
        _mm256_storeu_pd(o, _mm256_permute2f128_pd(t0, t2, 0x20));
        _mm256_storeu_pd(o + 4, _mm256_permute2f128_pd(t1, t3, 0x20));
        _mm256_storeu_pd(o + 8, _mm256_permute2f128_pd(t0, t2, 0x31));
        _mm256_storeu_pd(o + 12, _mm256_permute2f128_pd(t1, t3, 0x31));
    }
}

template <bool kEnergy, bool kDamaged = false>
FDEM_JOINT_AVX2_TARGET bool block_law_avx2(const Joints& J, JointState& s, const Vec2* __restrict x,
                                           int32_t j0, Block& B) {
    BlockPositions P;
    const JointLaw* L = block_law_of<kDamaged>(J, s, j0, P, B);
    if (L == nullptr) return false;
    gather_positions_avx2(J, x, j0, P);
    load_block_state(s, j0, P);
    if (!block_core<kEnergy, kDamaged>(J, *L, P, j0, B)) return false;
    store_records_avx2(s.f_prev[static_cast<size_t>(j0)].data(), B.f0x, B.f0y, B.f1x, B.f1y);
    store_records_avx2(s.d_prev[static_cast<size_t>(j0)].data(), B.dax, B.day, B.dbx, B.dby);
    return true;
}
#endif

using BlockFn = bool (*)(const Joints&, JointState&, const Vec2* __restrict, int32_t, Block&);

// set by choose_path (at load) or detail::set_joint_path; [kEnergy], then [2]: the kDamaged
// block (no energy)
BlockFn g_block[3] = {nullptr, nullptr, nullptr};
bool g_damaged = true;  // detail::set_damaged_blocks

void choose_path(detail::JointPath p) {
    switch (p) {
        case detail::JointPath::Scalar:
            g_block[0] = g_block[1] = g_block[2] = nullptr;
            break;
        case detail::JointPath::Portable:
            g_block[0] = &block_law_portable<false>;
            g_block[1] = &block_law_portable<true>;
            g_block[2] = &block_law_portable<false, true>;
            break;
        case detail::JointPath::Avx512:
#ifdef FDEM_JOINT_AVX512
            g_block[0] = &block_law_avx512<false>;
            g_block[1] = &block_law_avx512<true>;
            g_block[2] = &block_law_avx512<false, true>;
#else
            choose_path(detail::JointPath::Portable);
#endif
            break;
        case detail::JointPath::Avx2:
#ifdef FDEM_JOINT_AVX512
            g_block[0] = &block_law_avx2<false>;
            g_block[1] = &block_law_avx2<true>;
            g_block[2] = &block_law_avx2<false, true>;
#else
            choose_path(detail::JointPath::Portable);
#endif
            break;
        case detail::JointPath::Auto:
            choose_path(detail::joint_avx512_supported() ? detail::JointPath::Avx512
                        : detail::joint_avx2_supported() ? detail::JointPath::Avx2
                                                         : detail::JointPath::Portable);
            break;
    }
}

const bool g_chosen = (choose_path(detail::JointPath::Auto), true);

// The forces f0, f1 of joint j on nodes 0, 1 (-f1, -f0 on nodes 2, 3, eq. 9.3): added to f
// (kScatter) or kept in s.jf for the per-node gather.
template <bool kScatter>
[[gnu::always_inline]] inline void put_joint_forces(const Joints& J, JointState& s,
                                                    Vec2* __restrict f, int32_t j, Vec2 f0,
                                                    Vec2 f1) {
    if constexpr (kScatter) {
        const auto& nd = J.nodes[j];
        f[nd[0]] += f0;
        f[nd[1]] += f1;
        f[nd[2]] -= f1;
        f[nd[3]] -= f0;
    } else {
        s.jf[j] = {f0, f1};
    }
}

// The scalar commit of a qualified block, joint by joint in joint order (as one_joint).
// kDamaged: broken joints skipped (one_joint returns at once for them), the softening ones
// counted.
template <bool kEnergy, bool kScatter, bool kDamaged = false>
[[gnu::always_inline]] inline void commit_block(const Joints& J, JointState& s, Vec2* __restrict f,
                                                int32_t j0, const Block& B, ChunkOut& out) {
    if constexpr (kDamaged) {
        static_assert(!kEnergy);
        Real work = out.work;
        Real* __restrict wj = s.work.data() + j0;
        for (int l = 0; l < kLanes; ++l) {
            if (B.live[l] == 0.0) continue;
            work += B.dw[l];
            wj[l] += B.dw[l];
            put_joint_forces<kScatter>(J, s, f, j0 + l, {B.f0x[l], B.f0y[l]}, {B.f1x[l], B.f1y[l]});
        }
        out.work = work;
        out.softening += B.softening;
        return;
    }
    // the chunk's sums in joint order, carried in registers (`out` lives in memory: its address
    // is taken by the scalar path, so `out.work += ` per joint was a chain of a store-forward and
    // an addition, ~9 cycles per joint)
    Real work = out.work, energy = out.energy;
    for (int l = 0; l < kLanes; ++l) {
        if constexpr (kEnergy) energy += B.en[l];
        work += B.dw[l];
    }
    out.work = work;
    if constexpr (kEnergy) out.energy = energy;
    Real* __restrict wj = s.work.data() + j0;
    for (int l = 0; l < kLanes; ++l)
        wj[l] += B.dw[l];
    for (int l = 0; l < kLanes; ++l)
        put_joint_forces<kScatter>(J, s, f, j0 + l, {B.f0x[l], B.f0y[l]}, {B.f1x[l], B.f1y[l]});
}

// Joints [begin, end) in joint order, their sums into out (blocks of kLanes from begin: any
// start gives the same bits, the blocked and the scalar path agree)
template <bool kEnergy, bool kScatter, bool kMixed>
void run_range(const Joints& J, JointState& s, const Vec2* __restrict x, Vec2* __restrict f,
               int32_t begin, int32_t end, int64_t step, ChunkOut& out) {
    const auto scalar = [&](int32_t j) {
        Vec2 f0, f1;
        const bool loaded = one_joint<kEnergy, kMixed>(J, s, x, j, step, f0, f1, out);
        if (loaded || !kScatter) put_joint_forces<kScatter>(J, s, f, j, f0, f1);
    };
    int32_t j = begin;
    if (const BlockFn block = g_block[kEnergy ? 1 : 0]) {
        // blocks with softening or broken joints: without the energy only (the stored energy of
        // a softened point is not in the lanes)
        [[maybe_unused]] const BlockFn damaged =
            kEnergy || !g_damaged || s.block_wait.size() * kLanes < static_cast<size_t>(end)
                ? nullptr
                : g_block[2];
        static_assert(sizeof(JointStatus) == 1 && static_cast<int>(JointStatus::Intact) == 0 &&
                      static_cast<int>(JointStatus::Broken) == 2 && kLanes == 8);
        [[maybe_unused]] constexpr uint64_t kAllBroken = 0x0202020202020202ull;
        [[maybe_unused]] constexpr uint8_t kDamagedWait = 8;
        // (sized by make_joint_state; blocks start at multiples of 8 in every range's chunk)
        [[maybe_unused]] uint8_t* const block_wait = s.block_wait.data();
        Block B;
        // The joints are in the order of node 0 (model/renumber.cpp), so side A's nodes (0, 1)
        // stream through memory, but side B's (3, 2: the neighbouring triangle) jump: their
        // position lines (read by the block) and force lines (the scatter's read-modify-write)
        // missed in every block of a large model. Prefetched a few blocks ahead; a prefetch
        // changes no value.
        const bool prefetch = J.sorted_by_node0 && J.num_joints() >= kPrefetchJoints;
        const auto* __restrict nodes = J.nodes.data();
        for (; j + kLanes <= end; j += kLanes) {
            if (prefetch && j + (kPrefetchBlocks + 1) * kLanes <= end) {
                for (int l = 0; l < kLanes; ++l) {
                    const auto& nd = nodes[static_cast<size_t>(j + kPrefetchBlocks * kLanes + l)];
                    __builtin_prefetch(x + nd[2], 0);
                    __builtin_prefetch(x + nd[3], 0);
                    if constexpr (kScatter) {
                        __builtin_prefetch(f + nd[2], 1);
                        __builtin_prefetch(f + nd[3], 1);
                    }
                }
            }
            // the statuses of the block: all intact (0), all broken, or a mix
            uint64_t st;
            std::memcpy(&st, s.status.data() + j, sizeof st);
            if (st == 0) {
                if (block(J, s, x, j, B)) {
                    commit_block<kEnergy, kScatter>(J, s, f, j, B, out);
                    out.blocked += kLanes;
                    continue;
                }
            } else if constexpr (!kEnergy) {
                // (a block that failed waits kDamagedWait steps before it is tried again: in a
                // zone of growing damage most blocks fail, and a failed block was computed in
                // vain; example 11: +4.4 % instructions of the joints without the wait)
                uint8_t* wait = block_wait + j / kLanes;
                if (damaged != nullptr && st != kAllBroken && *wait == 0) {
                    if (damaged(J, s, x, j, B)) {
                        commit_block<kEnergy, kScatter, true>(J, s, f, j, B, out);
                        for (int l = 0; l < kLanes; ++l)
                            out.blocked += B.live[l] != 0.0 ? 1 : 0;
                        continue;
                    }
                    *wait = kDamagedWait;
                } else if (*wait > 0) {
                    --*wait;
                }
            }
            for (int l = 0; l < kLanes; ++l)
                scalar(j + l);
        }
    }
    for (; j < end; ++j)
        scalar(j);
}

template <bool kEnergy, bool kScatter, bool kMixed>
void run_chunk(const Joints& J, JointState& s, const Vec2* __restrict x, Vec2* __restrict f,
               int32_t c, int64_t step) {
    const int32_t begin = c * kJointChunk;
    const int32_t end = std::min(J.num_joints(), begin + kJointChunk);
    ChunkOut out;
    run_range<kEnergy, kScatter, kMixed>(J, s, x, f, begin, end, step, out);
    Real* slot = s.chunk_sums.data() + kSlots * static_cast<size_t>(c);
    slot[0] = out.work;
    slot[1] = out.energy;
    slot[2] = out.broken;
    slot[3] = out.softening;
    slot[4] = out.bad;
    slot[5] = out.blocked;
}

// entry k of a JointSubset: its chunk whole (the chunk's sums in its slots) or its ranges
template <bool kEnergy, bool kScatter, bool kMixed>
void run_entry(const Joints& J, JointState& s, const Vec2* __restrict x, Vec2* __restrict f,
               const JointSubset& sub, size_t k, int64_t step) {
    if (sub.counts[k]) {
        run_chunk<kEnergy, kScatter, kMixed>(J, s, x, f, sub.chunks[k], step);
        return;
    }
    ChunkOut out;  // (another process sums this chunk)
    for (int32_t r = sub.range_begin[k]; r < sub.range_begin[k + 1]; ++r) {
        const auto& [b, e] = sub.ranges[static_cast<size_t>(r)];
        run_range<kEnergy, kScatter, kMixed>(J, s, x, f, b, e, step, out);
    }
}

// fn.template operator()<kEnergy, kMixed>() for the run-time flags: energy, and whether the
// model has a MixedMode::Proportional law (then make_joint_state sized the per-mode history)
template <class Fn>
void with_flags(const JointState& s, bool energy, Fn&& fn) {
    const bool mixed = !s.dn_max.empty();
    if (energy) {
        if (mixed)
            fn.template operator()<true, true>();
        else
            fn.template operator()<true, false>();
    } else {
        if (mixed)
            fn.template operator()<false, true>();
        else
            fn.template operator()<false, false>();
    }
}

template <bool kScatter>
void run_entry(const Joints& J, JointState& s, const Vec2* x, Vec2* f, const JointSubset& sub,
               size_t k, int64_t step, bool energy) {
    with_flags(s, energy, [&]<bool kEnergy, bool kMixed>() {
        run_entry<kEnergy, kScatter, kMixed>(J, s, x, f, sub, k, step);
    });
}

// node gather_node[g] adds its joints' forces in joint order (entries ascending in j),
// skipping broken joints as the scatter does
inline void gather_joint_forces(const Joints& J, const JointState& s, Vec2* __restrict fp,
                                int32_t g) {
    Vec2 acc = fp[J.gather_node[g]];
    for (int32_t q = J.gather_begin[g]; q < J.gather_begin[g + 1]; ++q) {
        const int32_t e = J.gather_entry[q];
        const int32_t j = e >> 2;
        if (s.status[j] == JointStatus::Broken) continue;  // as the scatter
        switch (e & 3) {
            case 0:
                acc += s.jf[j][0];
                break;
            case 1:
                acc += s.jf[j][1];
                break;
            case 2:
                acc -= s.jf[j][1];
                break;
            default:
                acc -= s.jf[j][0];
                break;
        }
    }
    fp[J.gather_node[g]] = acc;
}

template <bool kScatter>
void run_chunk(const Joints& J, JointState& s, const Vec2* x, Vec2* f, int32_t c, int64_t step,
               bool energy) {
    with_flags(s, energy, [&]<bool kEnergy, bool kMixed>() {
        run_chunk<kEnergy, kScatter, kMixed>(J, s, x, f, c, step);
    });
}

}  // namespace

namespace detail {

bool joint_avx512_supported() {
#ifdef FDEM_JOINT_AVX512
    static const bool ok = __builtin_cpu_supports("avx512f");
    return ok;
#else
    return false;
#endif
}

bool joint_avx2_supported() {
#ifdef FDEM_JOINT_AVX512
    static const bool ok = __builtin_cpu_supports("avx2");
    return ok;
#else
    return false;
#endif
}

void set_damaged_blocks(bool on) {
    g_damaged = on;
}

void set_joint_path(JointPath p) {
    choose_path(p);
}

const char* joint_path_name() {
    if (g_block[0] == nullptr) return "scalar";
#ifdef FDEM_JOINT_AVX512
    if (g_block[0] == &block_law_avx512<false>) return "avx512";
    if (g_block[0] == &block_law_avx2<false>) return "avx2";
#endif
    return "portable";
}

}  // namespace detail

JointPass joint_forces(const Joints& J, JointState& s, std::span<const Vec2> x, std::span<Vec2> f,
                       bool need_energy, int64_t step, double time) {
    const int32_t nj = J.num_joints();
    const int32_t nc = (nj + kJointChunk - 1) / kJointChunk;
    const Vec2* xp = x.data();
    Vec2* fp = f.data();
    if (omp_get_max_threads() == 1 || nc < 2) {
        // serial: scatter in joint order, the order the gather reproduces
        for (int32_t c = 0; c < nc; ++c)
            run_chunk<true>(J, s, xp, fp, c, step, need_energy);
    } else {
        // the per-joint force slots of the gather path: allocated once, on the first call with
        // 2+ threads (a serial run never holds them; docs/performance.md, memory per triangle)
        if (s.jf.size() < static_cast<size_t>(nj)) s.jf.resize(static_cast<size_t>(nj));
        const int32_t ng = static_cast<int32_t>(J.gather_node.size());
#pragma omp parallel
        {
#pragma omp for schedule(static)
            for (int32_t c = 0; c < nc; ++c)
                run_chunk<false>(J, s, xp, fp, c, step, need_energy);
                // every node adds its joints' forces in joint order (entries ascending in j)
#pragma omp for schedule(static)
            for (int32_t g = 0; g < ng; ++g)
                gather_joint_forces(J, s, fp, g);
        }
    }
    JointPass out;
    int32_t bad = -1;
    // chunk partials combined exactly (theory §4.4): any grouping of the chunks gives these bits
    ExactSum elastic;
    for (int32_t c = 0; c < nc; ++c) {
        const Real* slot = s.chunk_sums.data() + kSlots * static_cast<size_t>(c);
        s.total_work_sum.add(slot[0]);
        elastic.add(slot[1]);
        out.newly_broken += static_cast<int32_t>(slot[2]);
        out.softening += static_cast<int32_t>(slot[3]);
        if (bad < 0 && slot[4] >= 0) bad = static_cast<int32_t>(slot[4]);
        out.blocked += static_cast<int32_t>(slot[5]);
    }
    if (bad >= 0) throw_joint_failure(bad, step, time);
    if (need_energy) out.elastic_energy = elastic.value();
    s.total_work = s.total_work_sum.value();
    out.work = s.total_work;
    if (need_energy) out.fracture = s.total_work - out.elastic_energy;  // eq. 9.19
    return out;
}

void add_joint_row_sums(const Joints& J, std::span<Real> k) {
    for (int32_t j = 0; j < J.num_joints(); ++j) {
        const JointLaw& L = J.laws[static_cast<size_t>(J.law[j])];
        for (NodeId n : J.nodes[j])
            k[static_cast<size_t>(n)] += std::max(L.p, L.ps);  // eq. 9.16
    }
}

Real joint_critical_dt(const Joints& J, std::span<const Real> node_mass) {
    Real w2 = 0;  // largest Gershgorin bound of omega^2 (eq. 9.16)
    for (size_t g = 0; g < J.gather_node.size(); ++g) {
        Real k = 0;
        for (int32_t q = J.gather_begin[g]; q < J.gather_begin[g + 1]; ++q) {
            const JointLaw& L = J.laws[static_cast<size_t>(J.law[J.gather_entry[q] >> 2])];
            k += std::max(L.p, L.ps);
        }
        w2 = std::max(w2, k / node_mass[static_cast<size_t>(J.gather_node[g])]);
    }
    return w2 > 0 ? 2.0 / std::sqrt(w2) : std::numeric_limits<Real>::infinity();
}

void throw_joint_failure(int32_t j, int64_t step, double time) {
    throw SimulationError(step, time, "joint " + std::to_string(j),
                          "joint length below 1e-9 of its reference length or not finite "
                          "(node positions non-finite or a face collapsed); reduce dt");
}

JointSubset joint_subset(const Joints& J, std::span<const int32_t> node_owner, int32_t rank) {
    JointSubset sub;
    const int32_t nj = J.num_joints();
    const int32_t nc = (nj + kJointChunk - 1) / kJointChunk;
    const auto mine = [&](int32_t j) {
        for (const NodeId n : J.nodes[static_cast<size_t>(j)]) {
            if (node_owner[static_cast<size_t>(n)] == rank) return true;
        }
        return false;
    };
    sub.range_begin.push_back(0);
    for (int32_t c = 0; c < nc; ++c) {
        const int32_t b = c * kJointChunk, e = std::min(nj, b + kJointChunk);
        // the chunk's sums: the owner of its first joint's node 0 (one process per chunk)
        const bool counts =
            node_owner[static_cast<size_t>(J.nodes[static_cast<size_t>(b)][0])] == rank;
        const size_t before = sub.ranges.size();
        if (!counts) {
            for (int32_t j = b; j < e; ++j) {
                if (!mine(j)) continue;
                if (sub.ranges.size() > before && sub.ranges.back()[1] == j) {
                    ++sub.ranges.back()[1];
                } else {
                    sub.ranges.push_back({j, j + 1});
                }
            }
            if (sub.ranges.size() == before) continue;  // nothing of this chunk
        }
        sub.chunks.push_back(c);
        sub.counts.push_back(counts ? 1 : 0);
        sub.range_begin.push_back(static_cast<int32_t>(sub.ranges.size()));
    }
    for (size_t g = 0; g < J.gather_node.size(); ++g) {
        if (node_owner[static_cast<size_t>(J.gather_node[g])] == rank)
            sub.gather.push_back(static_cast<int32_t>(g));
    }
    return sub;
}

JointSubsetPass joint_forces(const Joints& J, JointState& s, std::span<const Vec2> x,
                             std::span<Vec2> f, bool need_energy, const JointSubset& sub,
                             int64_t step) {
    const Vec2* xp = x.data();
    Vec2* fp = f.data();
    const size_t ne = sub.chunks.size();
    if (omp_get_max_threads() == 1 || ne < 2) {
        // serial: scatter in joint order (entries ascending)
        for (size_t k = 0; k < ne; ++k)
            run_entry<true>(J, s, xp, fp, sub, k, step, need_energy);
    } else {
        if (s.jf.size() < static_cast<size_t>(J.num_joints()))
            s.jf.resize(static_cast<size_t>(J.num_joints()));  // first call with 2+ threads
        const int32_t ng = static_cast<int32_t>(sub.gather.size());
        const int32_t nent = static_cast<int32_t>(ne);
#pragma omp parallel
        {
#pragma omp for schedule(static)
            for (int32_t k = 0; k < nent; ++k)
                run_entry<false>(J, s, xp, fp, sub, static_cast<size_t>(k), step, need_energy);
                // the owned nodes gather their joints (every one of them ran here)
#pragma omp for schedule(static)
            for (int32_t q = 0; q < ng; ++q)
                gather_joint_forces(J, s, fp, sub.gather[static_cast<size_t>(q)]);
        }
    }
    JointSubsetPass out;
    for (size_t k = 0; k < ne; ++k) {
        if (!sub.counts[k]) continue;
        const Real* slot = s.chunk_sums.data() + kSlots * static_cast<size_t>(sub.chunks[k]);
        out.work.add(slot[0]);
        if (need_energy) out.elastic.add(slot[1]);
        out.newly_broken += static_cast<int32_t>(slot[2]);
        if (out.bad < 0 && slot[4] >= 0) out.bad = static_cast<int32_t>(slot[4]);
    }
    return out;
}

}  // namespace fdem
