// Node update of the explicit step (integrate/step.cpp, docs/theory.md §5): one block of nodes,
// portable and AVX-512. Private to integrate/step.cpp (and its tests).
#pragma once

#include <cstdint>

#include "fdem/math.hpp"

namespace fdem {

/// Nodes per energy group: the node update's energy terms are summed naively over each group of
/// kNodeGroup consecutive node ids, then the groups exactly (theory §4.4); the unit of node
/// ownership of a distributed run (parallel/distributed.hpp).
constexpr int32_t kNodeGroup = 64;

/// Constants of one node update.
struct NodeUpdate {
    Real dt;     ///< step [s]
    Real dt_v;   ///< velocity step: dt/2 on the first step (theory eq. 5.1), else dt
    Real c;      ///< mass damping coefficient [1/s]
    Vec2 g;      ///< gravity [m/s^2]
    bool first;  ///< first step: v^0 is given, v^n = v^0
};

/// The arrays the node update reads and writes.
struct NodeArrays {
    Vec2* __restrict x;
    Vec2* __restrict v;
    const Vec2* __restrict f;
    const Real* __restrict mass;
    const Real* __restrict inv_mass;
    const Vec2* __restrict x0;
};

/// Which node-update kernel step() uses: Auto = AVX-512 when the CPU has it, else AVX2 when it
/// has that, else the plain loop; Portable = the plain loop; Avx2 = the AVX2 kernel (when the CPU
/// has AVX2, even with AVX-512, so tests reach it everywhere). Bitwise the same x, v and energies;
/// Portable and Avx2 exist so that tests can compare (tests/unit/integrate/node_update_simd_test
/// .cpp). Process-wide; not while a step runs.
enum class NodeKernel { Auto, Portable, Avx2 };
void set_node_kernel(NodeKernel k);
/// true when step() runs the AVX-512 node update.
bool node_update_uses_avx512();
/// true when step() runs the AVX2 node update.
bool node_update_uses_avx2();
/// true when the CPU runs the AVX2 node update (NodeKernel::Avx2 then selects it).
bool node_update_avx2_available();
/// The node update step() runs: "avx512", "avx2" or "portable" (printed by `fdem run`).
const char* node_update_kernel_name();

namespace detail {

/// Nodes [begin, end) (begin a multiple of kNodeGroup) with the AVX-512 kernel: the same
/// per-node expressions as the portable loop in integrate/step.cpp (update_nodes), 8 nodes per
/// instruction; the energy terms are then summed node by node in order, per group of kNodeGroup
/// nodes, into sums[3k .. 3k + 2] for the k-th group (kinetic2, gravity work, damping power), so
/// the sums have the same bits. Without `energy` sums[0] and sums[1] are 0 (not evaluated; the
/// damping power always is: it is integrated every step). Only call when the CPU has AVX-512F.
void node_block_avx512(const NodeArrays& a, const NodeUpdate& u, bool gravity, bool damped,
                       bool energy, int32_t begin, int32_t end, Real* sums);

/// node_block_avx512 with AVX2, 4 nodes per instruction (same bits). Only call when the CPU has
/// AVX2.
void node_block_avx2(const NodeArrays& a, const NodeUpdate& u, bool gravity, bool damped,
                     bool energy, int32_t begin, int32_t end, Real* sums);

}  // namespace detail
}  // namespace fdem
