// Baseline A of the smooth-contact paper: Munjiza's 2004 per-triangle contact potential
// phi_e = 3 min(N_1, N_2, N_3) and its exact triangle-to-triangle edge integration
// (spec §1.2 steps 1-9, Munjiza 2004 eqs. 2.17-2.29; docs/theory.md §7.1-7.3).
// Kept for comparison with the smooth field of Lei et al. 2020 (paper §1).
#pragma once

#include <cstdint>
#include <vector>

#include "fdem/model.hpp"
#include "fdem/state.hpp"

namespace fdem {

// ---- point potential (docs/theory.md eq. 7.1) ------------------------------------------------

/// Baseline A potential of triangle p at x: phi_e = 3 min_i N_i(x) (1 at the centroid, 0 on the
/// edges, negative outside), and its gradient 3 grad N_k with k the (first) smallest N, i.e. the
/// gradient of the sub-triangle (edge opposite k, centroid) that contains x. Either orientation.
/// Returns false (outputs untouched) for a degenerate triangle.
bool legacy_triangle_potential(const Vec2 p[3], Vec2 x, Real& phi, Vec2& grad);

// ---- one edge against one triangle (spec §1.2 steps 1-6; theory eqs. 7.2-7.4) ----------------

/// Exact integrals of the baseline A potential along the part of edge a->b inside triangle p.
/// s is the edge parameter, x(s) = (1-s) a + s b; q(s) = min_j lambda_j(s) = phi_p(x(s)) / 3.
struct EdgeIntegral {
    bool hit = false;  ///< the edge has a part of positive length inside p
    Real s_min = 0;    ///< clipped interval [s_min, s_max] inside p
    Real s_max = 0;
    Real I0 = 0;         ///< int q ds over [s_min, s_max] [-]
    Real I1 = 0;         ///< int s q ds over [s_min, s_max] [-]
    Real s_mean = 0;     ///< mean abscissa of the break points (friction velocity, step 9)
    int num_breaks = 0;  ///< break points s_0 < ... < s_K incl. the clip ends (<= 5)
    Real s[5] = {0, 0, 0, 0, 0};
    Real q[5] = {0, 0, 0, 0, 0};
    Real lambda_a[3] = {0, 0, 0};  ///< barycentric coordinates of a in p (step 1)
    Real lambda_b[3] = {0, 0, 0};  ///< and of b
};

/// Clip edge a->b to triangle p and integrate q exactly (piecewise linear, so the trapezoidal
/// rule between break points is exact). Returns out.hit.
bool legacy_edge_integral(Vec2 a, Vec2 b, const Vec2 p[3], EdgeIntegral& out);

// ---- one pass and one couple (spec §1.2 steps 7-9) -------------------------------------------

/// Friction of Y (spec §1.2 step 9). Off when friction <= 0 or tangential_penalty <= 0.
struct LegacyFriction {
    Real tangential_penalty = 0;  ///< p_t [Pa]: tangential force per unit sliding distance
    Real friction = 0;            ///< Coulomb coefficient mu [-]
    Real dt = 0;                  ///< time step [s]
};

/// One pass: the three edges of triangle e sunk into the potential of triangle p with penalty
/// [Pa]. Adds the forces on the nodes of e to fe[3] and the reactions on the nodes of p to fp[3]
/// (both accumulate). Friction needs ve, vp (node velocities v^{n-1/2}) and slide[3], the
/// sliding distance [m] of each edge of e (edge k = node k -> node k+1); slide is updated and
/// reset to 0 for edges out of contact. Returns the dissipated friction energy [J/m] of the
/// step (return mapping as law.hpp, plus the spring energy of a reset), 0 without friction.
/// Pass fr = nullptr for no friction.
Real legacy_edge_pass(const Vec2 xe[3], const Vec2 xp[3], Real penalty, Vec2 fe[3], Vec2 fp[3],
                      const LegacyFriction* fr = nullptr, const Vec2* ve = nullptr,
                      const Vec2* vp = nullptr, Real* slide = nullptr);

/// Both passes of a couple (edges of a in the potential of b, then edges of b in a), as Y's
/// Yid2TRITRI. fa, fb (3 each) are overwritten with the forces on the 6 nodes. slide[6]
/// (optional): edge sliding distances, [0..3) for a's edges, [3..6) for b's. Returns the
/// dissipated friction energy [J/m].
Real legacy_triangle_couple(const Vec2 xa[3], const Vec2 xb[3], Real penalty, Vec2 fa[3],
                            Vec2 fb[3], const LegacyFriction* fr = nullptr,
                            const Vec2* va = nullptr, const Vec2* vb = nullptr,
                            Real* slide = nullptr);

/// Stored energy of a couple [J/m]: p int_S (phi_a + phi_b) dA over the overlap S of the two
/// triangles (theory eq. 7.10; Munjiza 2004 eqs. 2.17-2.23). Its derivative with respect to a
/// rigid motion of a is minus the resultant (and moment) of legacy_triangle_couple() on a.
Real legacy_couple_energy(const Vec2 xa[3], const Vec2 xb[3], Real penalty);

// ---- wiring into the time step ---------------------------------------------------------------

// LegacyCouple and LegacyTriangleState (couples, sliding history, scratch) are in
// fdem/contact_state.hpp; ContactState::legacy holds the one of a run.

/// Candidate couples (a, b) of contact-topology boundary triangles (ContactTopology::boundary_tris)
/// of different bodies, not both fixed, whose bounding circles (centroid, largest
/// centroid-vertex distance) are closer than the buffer m.contact.buffer. Keeps the sliding
/// history of couples that stay candidates. Deterministic (sorted by (a, b)).
void find_legacy_couples(const Model& m, const ContactTopology& t, const Vec2* x,
                         LegacyTriangleState& ls);

/// O(N^2) reference of find_legacy_couples (tests).
void find_legacy_couples_brute_force(const Model& m, const ContactTopology& t, const Vec2* x,
                                     LegacyTriangleState& ls);

/// Baseline A contact forces for positions s.x and velocities s.v (v^{n-1/2}): rebuilds the
/// couples when the skin is used up, then adds legacy_triangle_couple() of every couple to s.f
/// and s.f_contact, penalty p = k_n of pair_parameters() (Munjiza's p: traction = p phi), and
/// friction with p_t = k_t and mu of the same parameters. Friction dissipation is added to
/// s.energy.dissipated_contact. Returns the stored normal contact energy of all couples at s.x
/// [J/m] (legacy_couple_energy, theory eq. 7.10) plus the tangential springs 1/2 p_t s^2; the
/// caller assigns it to s.energy.contact. Requires s.topology (boundary_tris,
/// resolved params, buffer).
Real add_legacy_triangle_forces(const Model& m, State& s, LegacyTriangleState& ls);

}  // namespace fdem
