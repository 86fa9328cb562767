// SIMD kernel of the elastic constant-strain triangle (docs/theory.md §2-3, docs/performance.md).
// Private to element/cst.cpp, which dispatches to it.
#pragma once

#include "element/cst.hpp"

namespace fdem::detail {

/// true when the CPU runs the AVX-512 kernel below (checked once, __builtin_cpu_supports).
bool cst_avx512_supported();

/// Elastic (eta = 0) triangles [begin, end) with Lame constants (lambda, mu), 8 triangles per
/// AVX-512 instruction: internal forces added to f, smallest det F, and (with_energy) the strain
/// energy added to out. Same expressions in the same order as the portable kernel, so f, the
/// energy and the smallest J are bitwise the same. Only call when cst_avx512_supported().
void elastic_range_avx512(const Model& m, const Vec2* x, Vec2* f, TriId begin, TriId end,
                          Real lambda, Real mu, bool with_energy, ElementPass& out);

}  // namespace fdem::detail
