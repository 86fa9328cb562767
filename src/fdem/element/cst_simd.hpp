// SIMD kernels of the constant-strain triangle (docs/theory.md §2-3, docs/performance.md).
// Private to element/cst.cpp, which dispatches to it.
#pragma once

#include "element/cst.hpp"

namespace fdem::detail {

/// true when the CPU runs the AVX-512 kernel below (checked once, __builtin_cpu_supports).
bool cst_avx512_supported();

/// Triangles [begin, end) of one material with Lame constants (lambda, mu), 8 triangles per
/// AVX-512 instruction: internal forces added to f, smallest det F, (with_energy) the strain
/// energy and (viscous: the material may have tri_eta > 0) the viscous stress eta D from the
/// velocities v and its power added to out. Same expressions in the same order as the portable
/// kernel (element_range, elastic_range), so f, the energy, the power and the smallest J are
/// bitwise the same. first: a chunk_first range (its nodes are its triangles' alone): their
/// forces are stored as 0 + f_i instead of added (first_internal_forces()). Only call when
/// cst_avx512_supported().
void cst_range_avx512(const Model& m, const Vec2* x, const Vec2* v, Vec2* f, TriId begin, TriId end,
                      Real lambda, Real mu, bool viscous, bool with_energy, ElementPass& out,
                      bool first = false);

/// cst_range_avx512 for CPUs with AVX2: 8 triangles per group as two 4-wide halves, the same
/// expressions, so the same bits. Only call when the CPU has AVX2.
void cst_range_avx2(const Model& m, const Vec2* x, const Vec2* v, Vec2* f, TriId begin, TriId end,
                    Real lambda, Real mu, bool viscous, bool with_energy, ElementPass& out,
                    bool first = false);

}  // namespace fdem::detail
