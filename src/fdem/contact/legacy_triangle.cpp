// Baseline A: Munjiza's per-triangle potential phi_e = 3 min N_i with the exact
// triangle-to-triangle edge integration of the Y code (spec §1.2, docs/theory.md §7.1-7.3).
// Re-implemented from the formulas of the spec, not from the Y sources.
#include "contact/legacy_triangle.hpp"

#include <algorithm>
#include <cmath>

#include "contact/field.hpp"
#include "detect/grid.hpp"

namespace fdem {

bool legacy_triangle_potential(const Vec2 p[3], Vec2 x, Real& phi, Vec2& grad) {
    Real N[3];
    if (!barycentric(p[0], p[1], p[2], x, N)) return false;

    // the smallest barycentric coordinate selects the sub-triangle (edge opposite k, centroid)
    // that contains x; there phi = A(i, j, x) / A(i, j, c) = 3 N_k (theory eq. 7.1)
    int k = 0;
    if (N[1] < N[k]) k = 1;
    if (N[2] < N[k]) k = 2;
    Vec2 g[3];
    shape_gradients(p[0], p[1], p[2], g);
    phi = 3.0 * N[k];
    grad = 3.0 * g[k];
    return true;
}

bool legacy_edge_integral(Vec2 a, Vec2 b, const Vec2 p[3], EdgeIntegral& out) {
    out = EdgeIntegral{};

    // step 1: barycentric coordinates of both edge nodes in p; lambda_j(s) is linear in s
    if (!barycentric(p[0], p[1], p[2], a, out.lambda_a)) return false;
    barycentric(p[0], p[1], p[2], b, out.lambda_b);
    const Real* al = out.lambda_a;
    const Real* be = out.lambda_b;

    // steps 3-4: clip [0, 1] to lambda_j(s) >= 0 for all j (the part of the edge inside p)
    Real s_min = 0, s_max = 1;
    for (int j = 0; j < 3; ++j) {
        if (al[j] < 0 && be[j] < 0) return false;  // whole edge beyond one side of p
        if (al[j] < 0) {
            s_min = std::max(s_min, al[j] / (al[j] - be[j]));  // entering: lambda_j rises to 0
        } else if (be[j] < 0) {
            s_max = std::min(s_max, al[j] / (al[j] - be[j]));  // leaving: lambda_j falls to 0
        }
    }
    if (!(s_max > s_min)) return false;

    // step 5: break points of q(s) = min_j lambda_j(s): the clip ends and every crossing
    // lambda_j = lambda_l inside the interval (crossings where neither is the minimum are
    // harmless extra points: q stays linear between consecutive points)
    int n = 0;
    out.s[n++] = s_min;
    for (int j = 0; j < 3; ++j) {
        for (int l = j + 1; l < 3; ++l) {
            const Real da = al[j] - al[l];
            const Real db = be[j] - be[l];
            if ((da < 0 && db > 0) || (da > 0 && db < 0)) {
                const Real sc = da / (da - db);
                if (sc > s_min && sc < s_max) out.s[n++] = sc;
            }
        }
    }
    out.s[n++] = s_max;
    std::sort(out.s + 1, out.s + n - 1);
    out.num_breaks = n;
    out.s_min = s_min;
    out.s_max = s_max;

    // q at the break points; >= 0 inside p (round-off at the clip ends is cut to 0)
    Real s_sum = 0;
    for (int k = 0; k < n; ++k) {
        const Real sk = out.s[k];
        Real q = al[0] + sk * (be[0] - al[0]);
        q = std::min(q, al[1] + sk * (be[1] - al[1]));
        q = std::min(q, al[2] + sk * (be[2] - al[2]));
        out.q[k] = std::max(q, Real(0));
        s_sum += sk;
    }
    out.s_mean = s_sum / n;

    // step 6: exact integrals of the piecewise-linear q (theory eqs. 7.3-7.4)
    for (int k = 0; k + 1 < n; ++k) {
        const Real s0 = out.s[k], s1 = out.s[k + 1], q0 = out.q[k], q1 = out.q[k + 1];
        const Real ds = s1 - s0;
        out.I0 += 0.5 * (q0 + q1) * ds;
        out.I1 += ds / 6.0 * (q0 * (2.0 * s0 + s1) + q1 * (s0 + 2.0 * s1));
    }
    out.hit = out.I0 > 0;
    return out.hit;
}

Real legacy_edge_pass(const Vec2 xe[3], const Vec2 xp[3], Real penalty, Vec2 fe[3], Vec2 fp[3],
                      const LegacyFriction* fr, const Vec2* ve, const Vec2* vp, Real* slide) {
    const Real ae2 = cross(xe[1] - xe[0], xe[2] - xe[0]);
    if (ae2 == 0) return 0;
    const Real o = ae2 > 0 ? 1.0 : -1.0;  // orientation: outward normals for either sense
    const bool friction = fr != nullptr && ve != nullptr && vp != nullptr && slide != nullptr &&
                          fr->friction > 0 && fr->tangential_penalty > 0;
    Real dissipated = 0;

    for (int k = 0; k < 3; ++k) {
        const int k1 = (k + 1) % 3;
        const Vec2 a = xe[k], b = xe[k1];
        EdgeIntegral ei;
        if (!legacy_edge_integral(a, b, xp, ei)) {
            // out of contact: the tangential spring resets and its energy leaves the books
            if (slide != nullptr) {
                if (friction) dissipated += 0.5 * fr->tangential_penalty * slide[k] * slide[k];
                slide[k] = 0;
            }
            continue;
        }

        // step 7: normal force -p int phi dGamma nu_hat, split by the linear shape functions of
        // the edge: F = 3 p I0 (times |nu| = L), F_b = 3 p I1, F_a = F - F_b (theory eq. 7.5)
        const Vec2 nu = o * Vec2{b.y - a.y, a.x - b.x};  // scaled outward normal, |nu| = L
        const Real F = 3.0 * penalty * ei.I0;
        const Real Fb = 3.0 * penalty * ei.I1;
        const Real Fa = F - Fb;
        Vec2 f_a = -Fa * nu;
        Vec2 f_b = -Fb * nu;

        // step 9: Y friction, a tangential spring on the sliding distance of this edge, with the
        // relative velocity at the mean break-point abscissa and a return mapping to mu |F|
        if (friction) {
            const Real L = norm(nu);
            const Vec2 t = (b - a) / L;
            const Real sm = ei.s_mean;
            const Vec2 v_edge = (1.0 - sm) * ve[k] + sm * ve[k1];
            Vec2 v_tri;
            for (int j = 0; j < 3; ++j) {
                const Real lj = (1.0 - sm) * ei.lambda_a[j] + sm * ei.lambda_b[j];
                v_tri += lj * vp[j];
            }
            const Real trial = slide[k] + dot(v_edge - v_tri, t) * fr->dt;
            const Real cap = fr->friction * F * L;  // mu |normal force|
            const Real pt = fr->tangential_penalty;
            Real s = trial;
            if (pt * std::abs(trial) > cap) {
                s = std::copysign(cap / pt, trial);
                dissipated += 0.5 * pt * (trial * trial - s * s);  // spring energy lost to slip
            }
            slide[k] = s;
            const Vec2 ft = (-pt * s) * t;  // opposes the edge's sliding relative to p
            f_a += (Fa / F) * ft;
            f_b += (Fb / F) * ft;
        }
        fe[k] += f_a;
        fe[k1] += f_b;

        // step 8: reaction on p at the edge nodes, -lambda_j(x_n) f_n: same resultant and,
        // because sum_j lambda_j(x_n) x_j = x_n, the same moment (theory eq. 7.6)
        for (int j = 0; j < 3; ++j) {
            fp[j] -= ei.lambda_a[j] * f_a;
            fp[j] -= ei.lambda_b[j] * f_b;
        }
    }
    return dissipated;
}

Real legacy_triangle_couple(const Vec2 xa[3], const Vec2 xb[3], Real penalty, Vec2 fa[3],
                            Vec2 fb[3], const LegacyFriction* fr, const Vec2* va, const Vec2* vb,
                            Real* slide) {
    for (int i = 0; i < 3; ++i) {
        fa[i] = Vec2{};
        fb[i] = Vec2{};
    }
    Real dissipated = legacy_edge_pass(xa, xb, penalty, fa, fb, fr, va, vb, slide);
    dissipated += legacy_edge_pass(xb, xa, penalty, fb, fa, fr, vb, va,
                                   slide != nullptr ? slide + 3 : nullptr);
    return dissipated;
}

// ---- stored energy of a couple (theory eq. 7.10) ----------------------------------------------

namespace {

// convex polygon of at most 16 vertices (a triangle clipped by 3 + 2 lines has at most 8)
struct Poly {
    Vec2 v[16];
    int n = 0;
};

// keep the part of P where the affine function g >= 0 (Sutherland-Hodgman, one line)
template <class G>
void clip(Poly& P, const G& g) {
    if (P.n == 0) return;
    Poly out;
    Real gv[16];
    for (int i = 0; i < P.n; ++i)
        gv[i] = g(P.v[i]);
    for (int i = 0; i < P.n; ++i) {
        const int j = (i + 1) % P.n;
        if (gv[i] >= 0) out.v[out.n++] = P.v[i];
        if ((gv[i] >= 0) != (gv[j] >= 0)) {
            const Real t = gv[i] / (gv[i] - gv[j]);
            out.v[out.n++] = P.v[i] + t * (P.v[j] - P.v[i]);
        }
    }
    P = out;
}

// integral over P of the affine function f: area times f at the centroid
template <class F>
Real integrate_affine(const Poly& P, const F& f) {
    if (P.n < 3) return 0;
    Real a2 = 0;
    Vec2 c;
    for (int i = 0; i < P.n; ++i) {
        const Vec2 p = P.v[i], q = P.v[(i + 1) % P.n];
        const Real w = cross(p, q);
        a2 += w;
        c += w * (p + q);
    }
    if (a2 == 0) return 0;
    c = c / (3.0 * a2);
    return 0.5 * std::abs(a2) * f(c);
}

// int_S phi_t dA with phi_t = 3 min N of triangle t (eq. 7.1): S split by the sub-triangles of t
Real integrate_potential(const Poly& S, const Vec2 t[3]) {
    auto N = [t](Vec2 x, int k) {
        Real n[3] = {0, 0, 0};
        barycentric(t[0], t[1], t[2], x, n);
        return n[k];
    };
    Real sum = 0;
    for (int k = 0; k < 3; ++k) {
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        Poly P = S;
        clip(P, [&](Vec2 x) { return N(x, i) - N(x, k); });
        clip(P, [&](Vec2 x) { return N(x, j) - N(x, k); });
        sum += integrate_affine(P, [&](Vec2 x) { return 3.0 * N(x, k); });
    }
    return sum;
}

}  // namespace

Real legacy_couple_energy(const Vec2 xa[3], const Vec2 xb[3], Real penalty) {
    if (cross(xa[1] - xa[0], xa[2] - xa[0]) == 0 || cross(xb[1] - xb[0], xb[2] - xb[0]) == 0) {
        return 0;
    }

    // overlap S = a clipped by the three half-planes N^b_j >= 0
    Poly S;
    S.n = 3;
    for (int i = 0; i < 3; ++i)
        S.v[i] = xa[i];
    for (int j = 0; j < 3; ++j) {
        clip(S, [&](Vec2 x) {
            Real n[3] = {0, 0, 0};
            barycentric(xb[0], xb[1], xb[2], x, n);
            return n[j];
        });
    }
    if (S.n < 3) return 0;
    return penalty * (integrate_potential(S, xa) + integrate_potential(S, xb));
}

// ---- couples (broad phase of the triangle-to-triangle scheme, spec §2.3) ----------------------

namespace {

bool couple_allowed(const Model& m, const ContactTopology& t, TriId a, TriId b) {
    const ContactModel& cm = m.contact;
    const BodyId ba = m.tri_body[a], bb = m.tri_body[b];
    return is_contactor_for(cm, t, ba, bb) || is_contactor_for(cm, t, bb, ba);
}

Real bounding_circles(const Model& m, const ContactTopology& t, const Vec2* x,
                      LegacyTriangleState& ls) {
    const auto& bt = t.boundary_tris;
    ls.center.resize(bt.size());
    ls.radius.resize(bt.size());
    Real r_max = 0;
    for (size_t i = 0; i < bt.size(); ++i) {
        const auto& n = m.tri_nodes[bt[i]];
        const Vec2 p = x[n[0]], q = x[n[1]], r = x[n[2]];
        const Vec2 c = (p + q + r) / 3.0;
        const Real rad = std::sqrt(std::max({norm2(p - c), norm2(q - c), norm2(r - c)}));
        ls.center[i] = c;
        ls.radius[i] = rad;
        r_max = std::max(r_max, rad);
    }
    return r_max;
}

// replace ls.couples by ls.next, carrying the sliding history of couples present in both
void merge_history(LegacyTriangleState& ls) {
    size_t k = 0;
    for (LegacyCouple& c : ls.next) {
        while (k < ls.couples.size() &&
               (ls.couples[k].a < c.a || (ls.couples[k].a == c.a && ls.couples[k].b < c.b))) {
            ++k;
        }
        if (k < ls.couples.size() && ls.couples[k].a == c.a && ls.couples[k].b == c.b) {
            std::copy(ls.couples[k].slide, ls.couples[k].slide + 6, c.slide);
        }
    }
    ls.couples.swap(ls.next);
    ++ls.rebuilds;
    ls.need_rebuild = false;
    ls.skin_used = 0;
}

}  // namespace

void find_legacy_couples(const Model& m, const ContactTopology& t, const Vec2* x,
                         LegacyTriangleState& ls) {
    const auto& bt = t.boundary_tris;
    const Real buf = m.contact.buffer;
    ls.next.clear();
    const int32_t nt = static_cast<int32_t>(bt.size());
    if (nt == 0) {
        merge_history(ls);
        return;
    }
    const Real r_max = bounding_circles(m, t, x, ls);

    // grid over the centroids (detect/grid.hpp, shared with the smooth-contact broad phase);
    // cell >= 2 r_max + b, so every partner centroid lies in the 3x3 block around a triangle's
    // cell (NBS idea, spec §2.2)
    const GridDims g = build_grid(ls.center.data(), nt, 2.0 * r_max + buf, ls.cell, ls.cell_start,
                                  ls.cell_items, ls.cursor);
    const int32_t nx = g.nx, ny = g.ny;

    // each triangle against the 3x3 block; keep partners with a larger id, sorted
    for (int32_t i = 0; i < nt; ++i) {
        const TriId ta = bt[i];
        const int32_t ix = ls.cell[i] % nx, iy = ls.cell[i] / nx;
        ls.query.clear();
        for (int32_t cy = std::max(0, iy - 1); cy <= std::min(ny - 1, iy + 1); ++cy) {
            for (int32_t cx = std::max(0, ix - 1); cx <= std::min(nx - 1, ix + 1); ++cx) {
                const size_t c = static_cast<size_t>(cy * nx + cx);
                for (int32_t k = ls.cell_start[c]; k < ls.cell_start[c + 1]; ++k) {
                    const int32_t j = ls.cell_items[static_cast<size_t>(k)];
                    const TriId tb = bt[j];
                    if (tb <= ta) continue;
                    const Real reach = ls.radius[i] + ls.radius[j] + buf;
                    if (norm2(ls.center[i] - ls.center[j]) >= reach * reach) continue;
                    if (!couple_allowed(m, t, ta, tb)) continue;
                    ls.query.push_back(tb);
                }
            }
        }
        std::sort(ls.query.begin(), ls.query.end());
        for (TriId tb : ls.query) {
            LegacyCouple c;
            c.a = ta;
            c.b = tb;
            ls.next.push_back(c);
        }
    }
    merge_history(ls);
}

void find_legacy_couples_brute_force(const Model& m, const ContactTopology& t, const Vec2* x,
                                     LegacyTriangleState& ls) {
    const auto& bt = t.boundary_tris;
    const Real buf = m.contact.buffer;
    ls.next.clear();
    bounding_circles(m, t, x, ls);
    for (size_t i = 0; i < bt.size(); ++i) {
        for (size_t j = 0; j < bt.size(); ++j) {
            if (bt[j] <= bt[i]) continue;
            const Real reach = ls.radius[i] + ls.radius[j] + buf;
            if (norm2(ls.center[i] - ls.center[j]) >= reach * reach) continue;
            if (!couple_allowed(m, t, bt[i], bt[j])) continue;
            LegacyCouple c;
            c.a = bt[i];
            c.b = bt[j];
            ls.next.push_back(c);
        }
    }
    std::sort(ls.next.begin(), ls.next.end(), [](const LegacyCouple& p, const LegacyCouple& q) {
        return p.a != q.a ? p.a < q.a : p.b < q.b;
    });
    merge_history(ls);
}

namespace {

// couples per step below which the couple loop runs on one thread (a couple costs ~1 us)
constexpr int32_t kMinParallelCouples = 256;

}  // namespace

Real add_legacy_triangle_forces(const Model& m, State& s, LegacyTriangleState& ls) {
    const ContactModel& cm = m.contact;

    // Verlet skin (spec §2.3): rebuild when the accumulated 2 dt max|v| exceeds the buffer
    Real v2 = 0;
    for (const Vec2& v : s.v)
        v2 = std::max(v2, norm2(v));
    ls.skin_used += 2.0 * s.dt * std::sqrt(v2);
    if (ls.need_rebuild || ls.skin_used > cm.buffer)
        find_legacy_couples(m, s.topology, s.x.data(), ls);

    // 1. every couple independently (its sliding history is its own): forces on its 6 nodes,
    //    stored and dissipated energy into per-couple buffers, in parallel
    const int32_t nc = static_cast<int32_t>(ls.couples.size());
    ls.couple_force.resize(6 * static_cast<size_t>(nc));
    ls.couple_stored.resize(static_cast<size_t>(nc));
    ls.couple_dissipated.resize(static_cast<size_t>(nc));
    const Vec2* x = s.x.data();
    const Vec2* vel = s.v.data();
    const Real dt = s.dt;
    LegacyCouple* couples = ls.couples.data();
    Vec2* cf = ls.couple_force.data();
    Real* cst = ls.couple_stored.data();
    Real* cdi = ls.couple_dissipated.data();
#pragma omp parallel for schedule(static) if (nc > kMinParallelCouples)
    for (int32_t k = 0; k < nc; ++k) {
        LegacyCouple& c = couples[k];
        const auto& na = m.tri_nodes[c.a];
        const auto& nb = m.tri_nodes[c.b];
        Vec2 xa[3], xb[3], va[3], vb[3];
        for (int i = 0; i < 3; ++i) {
            xa[i] = x[na[i]];
            xb[i] = x[nb[i]];
            va[i] = vel[na[i]];
            vb[i] = vel[nb[i]];
        }
        const int32_t mat_a = m.bodies[m.tri_body[c.a]].material;
        const int32_t mat_b = m.bodies[m.tri_body[c.b]].material;
        const ContactParams& p = pair_parameters(cm, mat_a, mat_b);
        LegacyFriction fr;
        fr.tangential_penalty = p.tangential_penalty;
        fr.friction = p.friction;
        fr.dt = dt;
        Vec2* f = cf + 6 * static_cast<size_t>(k);
        cdi[k] = legacy_triangle_couple(xa, xb, p.penalty, f, f + 3, &fr, va, vb, c.slide);
        Real stored = legacy_couple_energy(xa, xb, p.penalty);  // theory eq. 7.10
        if (fr.friction > 0) {
            for (Real sl : c.slide)
                stored += 0.5 * fr.tangential_penalty * sl * sl;
        }
        cst[k] = stored;
    }

    // 2. scatter in couple order: the same sums whatever the thread count
    ls.active = 0;
    // energies summed exactly (theory §4.4), the dissipation into the run's running sum
    ExactSum stored;
    ExactSum& dissipated = s.energy_sums.dissipated_contact;
    for (int32_t k = 0; k < nc; ++k) {
        const auto& na = m.tri_nodes[couples[k].a];
        const auto& nb = m.tri_nodes[couples[k].b];
        const Vec2* f = cf + 6 * static_cast<size_t>(k);
        if (cdi[k] != 0) dissipated.add(cdi[k]);  // (most couples are apart: skip the zeros)
        if (cst[k] != 0) stored.add(cst[k]);
        bool any = false;
        for (int i = 0; i < 3; ++i) {
            any = any || f[i].x != 0 || f[i].y != 0;
            s.f[na[i]] += f[i];
            s.f_contact[na[i]] += f[i];
            s.f[nb[i]] += f[3 + i];
            s.f_contact[nb[i]] += f[3 + i];
        }
        if (any) ++ls.active;
    }
    s.energy.dissipated_contact = dissipated.value();
    return stored.value();
}

}  // namespace fdem
