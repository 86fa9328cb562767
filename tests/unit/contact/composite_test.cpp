// Contact on the 6-node composite triangle (issue #7; paper §2.4, Figs. 7-10; spec §4.2-4.4;
// docs/theory.md §6.1.1): topology of the special cases with both options, the distance field
// against the exact distance to the polygon boundary, continuity, and pair-force balance through
// virtual nodes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "contact/contact.hpp"
#include "fdem/error.hpp"
#include "fdem/simulate.hpp"
#include "support/composite.hpp"
#include "unit/contact/contact_fixture.hpp"

namespace fdem {
namespace {

using Option = CompositeSpecialCase;

const char* name_of(Option o) {
    return o == Option::Fan ? "fan" : "split";
}

/// A model with the paper's material and smooth contact, composite bodies from meshes.
struct CompositeScene {
    Model m;
    explicit CompositeScene(Option o, ContactAlgorithm alg = ContactAlgorithm::Smooth) {
        Material mat;
        mat.name = "rock";
        mat.density = 1000;
        mat.youngs_modulus = 1e9;
        m.materials.push_back(mat);
        m.contact.algorithm = alg;
        m.contact.composite_special_case = o;
    }
    BodyId add(const scenes::CompositeMesh& mesh, Vec2 v = {}) {
        return scenes::add_composite_body(m, mesh, 0, false, v);
    }
    Model& finalize() {
        finalize_model(m);
        topo = build_topology(m);
        return m;
    }
    ContactTopology topo;  ///< built by finalize()
};

// 3-4-5 triangle: inradius 1, incenter (1, 1) (scalene: a centroid fan would not be exact)
const std::vector<Vec2> kTri{{0, 0}, {4, 0}, {0, 3}};
scenes::CompositeMesh single() {
    return scenes::composite_mesh(kTri, {{0, 1, 2}});
}

// rhombus with half-diagonals 1 and 0.6 cut along its short diagonal B-D into two composites;
// each has two boundary edges (paper case 1) and the inner edge B-D, whose mid-node n4 is the
// rhombus centre. Inradius = 1 x 0.6 / sqrt(1 + 0.36).
const std::vector<Vec2> kDiamond{{1, 0}, {0, 0.6}, {-1, 0}, {0, -0.6}};
scenes::CompositeMesh diamond() {
    return scenes::composite_mesh(kDiamond, {{0, 1, 3}, {1, 2, 3}});
}

struct Counts {
    size_t bedges, bnodes, btris, chords, virt, subs;
};
Counts counts(const Model& m) {
    const ContactTopology topo = build_topology(m);
    const ContactTopology& c = topo;
    return {c.boundary_edges.size(),
            c.boundary_nodes.size(),
            c.boundary_tris.size(),
            c.chords.size(),
            static_cast<size_t>(c.num_virtual()),
            c.sub_tri.size()};
}

Real sub_area(const Model& m, int32_t s) {
    const ContactTopology topo = build_topology(m);
    const auto& q = topo.sub_tri[s];
    return signed_area(testing::contact_node_x0(m, topo, q[0]),
                       testing::contact_node_x0(m, topo, q[1]),
                       testing::contact_node_x0(m, topo, q[2]));
}

// every contact sub-triangle counter-clockwise; together with the mesh triangles that are not
// boundary elements they tile the body; the triangulation is conforming: every edge is a
// boundary half-edge of the body or is used in the opposite direction by exactly one other
// sub-triangle or by a mesh triangle that is not a contactor
void expect_conforming_tiling(const Model& m, Real body_area) {
    const ContactTopology topo = build_topology(m);
    const ContactTopology& cm = topo;
    std::map<std::pair<NodeId, NodeId>, int> inner;  // directed edges of non-contactor triangles
    for (TriId t = 0; t < m.num_tris(); ++t) {
        if (std::count(cm.boundary_tris.begin(), cm.boundary_tris.end(), t) > 0) continue;
        const auto& n = m.tri_nodes[t];
        body_area -= signed_area(m.node_x0[n[0]], m.node_x0[n[1]], m.node_x0[n[2]]);
        for (int k = 0; k < 3; ++k)
            ++inner[{n[k], n[(k + 1) % 3]}];
    }
    Real area = 0;
    std::map<std::pair<NodeId, NodeId>, int> directed;
    for (int32_t s = 0; s < cm.num_sub_tris(); ++s) {
        EXPECT_GT(sub_area(m, s), 0) << "sub-triangle " << s;
        area += sub_area(m, s);
        const auto& q = cm.sub_tri[s];
        for (int k = 0; k < 3; ++k)
            ++directed[{q[k], q[(k + 1) % 3]}];
    }
    // sums of up to a few hundred areas (and a difference for non-contactors): round-off
    EXPECT_NEAR(area, body_area, 1e-13 * body_area);
    std::map<std::pair<NodeId, NodeId>, int> bedges;
    for (const auto& e : cm.boundary_edges)
        ++bedges[{e[0], e[1]}];
    for (const auto& [e, n] : directed) {
        EXPECT_EQ(n, 1) << e.first << "-" << e.second;
        const bool on_boundary = bedges.count(e) > 0;
        const bool twin =
            directed.count({e.second, e.first}) + inner.count({e.second, e.first}) > 0;
        EXPECT_TRUE(on_boundary != twin) << "edge " << e.first << "-" << e.second;
    }
}

bool inside_convex(const std::vector<Vec2>& p, Vec2 x) {
    for (size_t i = 0; i < p.size(); ++i) {
        if (signed_area(p[i], p[(i + 1) % p.size()], x) < 0) return false;
    }
    return true;
}

struct FieldError {
    Real max_abs = 0;       ///< max |d - exact| [m]
    Real min_ratio = 1e30;  ///< min d / exact (no false zero valley: > 0)
    Real max_over = -1e30;  ///< max d - exact [m]
    int samples = 0;
};

// the field of body 0 at n random points of the convex polygon vs the exact distance to it;
// points in no contactor sub-triangle are skipped if skip_outside, else a failure
FieldError field_error(const Model& m, const std::vector<Vec2>& poly, int n, unsigned seed,
                       bool skip_outside = false) {
    const ContactTopology topo = build_topology(m);
    Vec2 lo = poly[0], hi = lo;
    for (const Vec2& p : poly) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> ux(lo.x, hi.x), uy(lo.y, hi.y);
    FieldError e;
    while (e.samples < n) {
        const Vec2 x{ux(rng), uy(rng)};
        if (!inside_convex(poly, x)) continue;
        FieldSample fs;
        const bool found = testing::field_at(m, topo, 0, x, fs);
        if (!found && skip_outside) continue;
        EXPECT_TRUE(found) << x.x << ", " << x.y;
        const Real exact = testing::polygon_distance(poly, x);
        e.max_abs = std::max(e.max_abs, std::abs(fs.d - exact));
        e.max_over = std::max(e.max_over, fs.d - exact);
        if (exact > 1e-9) e.min_ratio = std::min(e.min_ratio, fs.d / exact);
        ++e.samples;
    }
    return e;
}

// ---- topology counts -------------------------------------------------------------------------

// paper case 2 (Fig. 9): a body of one composite element, all six nodes on the boundary
TEST(CompositeContact, SingleElementCounts) {
    for (Option o : {Option::Fan, Option::Split}) {
        CompositeScene sc(o);
        sc.add(single());
        const Model& m = sc.finalize();
        const ContactTopology& topo = sc.topo;
        const Counts c = counts(m);
        EXPECT_EQ(c.bedges, 6u) << name_of(o);
        EXPECT_EQ(c.bnodes, 6u);
        EXPECT_EQ(c.btris, 4u);
        EXPECT_EQ(c.chords, 3u);  // the central sub-triangle's edges n2-n4, n4-n6, n6-n2
        EXPECT_EQ(topo.num_fallback_nodes, 0);
        if (o == Option::Fan) {
            EXPECT_EQ(c.virt, 1u);  // n7 (Fig. 10b)
            EXPECT_EQ(c.subs, 6u);  // one per boundary half-edge
            // n7 at the incenter (1, 1) of the corner triangle, d = inradius = 1 (eq. 1)
            const NodeId n7 = topo.num_real_nodes;
            EXPECT_NEAR(testing::contact_node_x0(m, topo, n7).x, 1.0, 1e-15);
            EXPECT_NEAR(testing::contact_node_x0(m, topo, n7).y, 1.0, 1e-15);
            EXPECT_NEAR(topo.node_dist[n7], 1.0, 1e-15);
        } else {
            EXPECT_EQ(c.virt, 3u);   // n7, n8, n9 (Fig. 10a)
            EXPECT_EQ(c.subs, 10u);  // ten sub-elements
        }
        expect_conforming_tiling(m, 6.0);
    }
}

// paper case 1 (Fig. 7) in both elements of the diamond (Figs. 17-18)
TEST(CompositeContact, DiamondCounts) {
    for (Option o : {Option::Fan, Option::Split}) {
        CompositeScene sc(o);
        sc.add(diamond());
        const Model& m = sc.finalize();
        const ContactTopology& topo = sc.topo;
        const Counts c = counts(m);
        EXPECT_EQ(m.num_nodes(), 9) << name_of(o);
        EXPECT_EQ(c.bedges, 8u);
        EXPECT_EQ(c.bnodes, 8u);
        EXPECT_EQ(c.btris, 8u);
        EXPECT_EQ(c.chords, 2u);  // n2-n6 of each element
        if (o == Option::Fan) {
            EXPECT_EQ(c.virt, 0u);  // Fig. 8b: no new node, the fans share n4
            EXPECT_EQ(c.subs, 8u);
        } else {
            EXPECT_EQ(c.virt, 6u);   // n7, n8, n9 per element (Fig. 8a)
            EXPECT_EQ(c.subs, 20u);  // ten per element
        }
        // n4 = the rhombus centre (origin), eq. 1 over the half-edges: the inradius
        for (NodeId i = 0; i < m.num_nodes(); ++i) {
            if (norm(m.node_x0[i]) == 0) {
                EXPECT_FALSE(topo.node_on_boundary[i]);
                EXPECT_NEAR(topo.node_dist[i], 0.6 / std::sqrt(1.36), 1e-15);
            }
        }
        expect_conforming_tiling(m, 1.2);
    }
}

// a 2 x 1 rectangle of eight composites: the two corner elements not cut by a diagonal have two
// boundary edges (case 1); the others are left as they are
TEST(CompositeContact, RectangleMixesSpecialAndPlainElements) {
    const std::vector<Vec2> corners{{0, 0},   {1, 0}, {2, 0}, {0, 0.5}, {1, 0.5},
                                    {2, 0.5}, {0, 1}, {1, 1}, {2, 1}};
    const std::vector<std::array<int32_t, 3>> tris{{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4},
                                                   {3, 4, 7}, {3, 7, 6}, {4, 5, 8}, {4, 8, 7}};
    for (Option o : {Option::Fan, Option::Split}) {
        CompositeScene sc(o);
        sc.add(scenes::composite_mesh(corners, tris));
        const Model& m = sc.finalize();
        const ContactTopology& topo = sc.topo;
        const Counts c = counts(m);
        EXPECT_EQ(c.bedges, 16u) << name_of(o);  // 8 element edges, 2 halves each
        EXPECT_EQ(c.chords, 2u);                 // elements (1,2,5) and (3,7,6)
        // sub-triangles without a boundary node: the corner one at the centre node 4 of the
        // four elements with one boundary edge, and two in each of (1,5,4) and (3,4,7), which
        // have none: 32 - 8
        EXPECT_EQ(c.btris, 24u);
        // plain elements keep their boundary sub-triangles; the two special ones: 4 (fan) or 10
        EXPECT_EQ(c.subs, o == Option::Fan ? 24u : 36u);
        EXPECT_EQ(c.virt, o == Option::Fan ? 0u : 6u);
        expect_conforming_tiling(m, 2.0);
        for (const auto& q : topo.sub_tri) {  // every inner node of a contactor: d > 0
            for (NodeId i : q) {
                if (i >= m.num_nodes() || !topo.node_on_boundary[i]) {
                    EXPECT_GT(topo.node_dist[i], 0) << i;
                }
            }
        }
        const FieldError e = field_error(m, {{0, 0}, {2, 0}, {2, 1}, {0, 1}}, 4000, 7, true);
        std::printf(
            "[ info ] rectangle of composites, %s: max |d - exact| = %.3g (x 1 m), "
            "min d/exact = %.3f\n",
            name_of(o), e.max_abs, e.min_ratio);
        EXPECT_GT(e.min_ratio, 0.2);  // no false zero valley anywhere inside the body
    }
}

// the same bodies through the mesh path (6-node MeshData -> add_bodies, issue #7 layout)
// give the same contact topology as the hand-built ones above
TEST(CompositeContact, MeshPathMatchesHandBuiltBodies) {
    auto from_mesh = [](const scenes::CompositeMesh& cm) {
        MeshData g;
        g.file = "test";
        g.nodes = cm.nodes;
        for (const auto& e : cm.elems) {
            g.tris.push_back({e[0], e[2], e[4]});
            g.tri_mid.push_back({e[1], e[3], e[5]});
        }
        g.tri_tag.assign(g.tris.size(), 1);
        return g;
    };
    for (Option o : {Option::Fan, Option::Split}) {
        for (int shape = 0; shape < 3; ++shape) {
            const MeshData g = shape == 0   ? from_mesh(single())
                               : shape == 1 ? from_mesh(diamond())
                                            : make_rectangle_mesh_order2(0, 0, 2, 1, 2, 2);
            CompositeScene sc(o);
            BodyOptions opt;
            opt.name = "mesh";
            add_bodies(sc.m, g, testing::all_tris(g), opt);
            const Model& m = sc.finalize();
            ASSERT_EQ(m.bodies[0].element, ElementKind::Composite6);
            const Counts c = counts(m);
            const bool fan = o == Option::Fan;
            // expected: SingleElementCounts, DiamondCounts, RectangleMixesSpecialAndPlainElements
            const Counts want = shape == 0   ? Counts{6, 6, 4, 3, fan ? 1u : 3u, fan ? 6u : 10u}
                                : shape == 1 ? Counts{8, 8, 8, 2, fan ? 0u : 6u, fan ? 8u : 20u}
                                             : Counts{16, 0, 24, 2, fan ? 0u : 6u, fan ? 24u : 36u};
            EXPECT_EQ(c.bedges, want.bedges) << name_of(o) << " " << shape;
            if (shape < 2) {
                EXPECT_EQ(c.bnodes, want.bnodes);
            }
            EXPECT_EQ(c.btris, want.btris);
            EXPECT_EQ(c.chords, want.chords);
            EXPECT_EQ(c.virt, want.virt);
            EXPECT_EQ(c.subs, want.subs);
            if (shape == 0 && fan) {
                const FieldError e = field_error(m, kTri, 2000, 4);
                EXPECT_LE(e.max_abs, 1e-12 * 5.0);  // exact (FanFieldIsExact), size 5 m
            }
        }
    }
}

// an unstructured second-order Gmsh mesh (paper Fig. 20 analogue: boundary mid-nodes on the
// curved boundary, corner elements with two boundary edges): both options build a conforming,
// counter-clockwise contact triangulation; the field is reported against the exact distance to
// the polygon through the boundary nodes
TEST(CompositeContact, GmshEllipseMesh) {
    const MeshData g =
        read_mesh(std::string(FDEM_SOURCE_DIR) + "/tests/validation/data/ellipse.geo", 0.6, 2);
    ASSERT_TRUE(g.second_order());
    for (Option o : {Option::Fan, Option::Split}) {
        CompositeScene sc(o);
        BodyOptions opt;
        opt.name = "ellipse";
        add_bodies(sc.m, g, testing::all_tris(g), opt);
        const Model& m = sc.finalize();
        const ContactTopology& topo = sc.topo;
        ASSERT_EQ(m.num_bodies(), 1);
        Real area = 0;
        for (TriId t = 0; t < m.num_tris(); ++t)
            area += m.tri_area0[t];
        expect_conforming_tiling(m, area);
        // the boundary polygon, in order (boundary edges are oriented, material on the left)
        std::map<NodeId, NodeId> next;
        for (const auto& e : topo.boundary_edges)
            next[e[0]] = e[1];
        std::vector<Vec2> poly;
        NodeId i = topo.boundary_edges[0][0];
        do {
            poly.push_back(m.node_x0[i]);
            i = next[i];
        } while (i != topo.boundary_edges[0][0] && poly.size() <= next.size());
        ASSERT_EQ(poly.size(), next.size());
        const FieldError e = field_error(m, poly, 4000, 9, true);
        std::printf(
            "[ info ] gmsh ellipse (order 2, h = 0.6), %s: %d composites, %d special "
            "chords, max |d - exact| = %.3g m, min d/exact = %.3f, %d fallback nodes\n",
            name_of(o), m.num_tris() / 4, static_cast<int>(topo.chords.size()), e.max_abs,
            e.min_ratio, topo.num_fallback_nodes);
        EXPECT_GT(e.samples, 1000);
        EXPECT_GT(e.min_ratio, 0.2);  // no false zero valley
    }
}

// ---- the distance field against the exact distance (paper Figs. 15-18) -----------------------

// option (b): exact for a single element (incenter fan) and the diamond (fan around its centre):
// every fan triangle is the region nearest to its base (spec §4.4 "When is the field exact?")
TEST(CompositeContact, FanFieldIsExact) {
    {
        CompositeScene sc(Option::Fan);
        sc.add(single());
        const FieldError e = field_error(sc.finalize(), kTri, 20000, 1);
        std::printf("[ info ] single composite, fan: max |d - exact| = %.3g m (size 5 m)\n",
                    e.max_abs);
        EXPECT_LE(e.max_abs, 1e-12 * 5.0);  // round-off of the interpolation, size 5 m
    }
    {
        CompositeScene sc(Option::Fan);
        sc.add(diamond());
        const FieldError e = field_error(sc.finalize(), kDiamond, 20000, 2);
        std::printf(
            "[ info ] diamond of two composites, fan: max |d - exact| = %.3g m "
            "(size 2 m)\n",
            e.max_abs);
        EXPECT_LE(e.max_abs, 1e-12 * 2.0);  // round-off, size 2 m
    }
}

// option (a) is not exact (reported); it removes the zero-distance valley: d > 0 inside. Its
// nodal values are exact distances here (heights over the nearest side; n4 of the diamond from
// the fallback), and the exact distance is concave in a convex polygon, so d <= exact.
TEST(CompositeContact, SplitFieldErrorIsReported) {
    struct Case {
        const char* name;
        scenes::CompositeMesh mesh;
        std::vector<Vec2> poly;
        Real inradius;
    };
    for (const Case& k : {Case{"single", single(), kTri, 1.0},
                          Case{"diamond", diamond(), kDiamond, 0.6 / std::sqrt(1.36)}}) {
        CompositeScene sc(Option::Split);
        sc.add(k.mesh);
        const Model& m = sc.finalize();
        const ContactTopology& topo = sc.topo;
        const FieldError e = field_error(m, k.poly, 20000, 3);
        std::printf(
            "[ info ] %s, split: max |d - exact| = %.4g m = %.4f x inradius, "
            "min d/exact = %.4f, max d - exact = %.2g m, fallback nodes %d\n",
            k.name, e.max_abs, e.max_abs / k.inradius, e.min_ratio, e.max_over,
            topo.num_fallback_nodes);
        EXPECT_GT(e.min_ratio, 0.2);
        EXPECT_LE(e.max_over, 1e-15);  // round-off of an interpolation of O(1) values
    }
}

// the field is continuous across every interior edge of the contact triangulation: evaluated
// from both sides at points along the edge, the two values agree to round-off (spec §6.5)
TEST(CompositeContact, FieldContinuousAcrossEdges) {
    for (Option o : {Option::Fan, Option::Split}) {
        for (int shape = 0; shape < 2; ++shape) {
            CompositeScene sc(o);
            sc.add(shape == 0 ? single() : diamond());
            const Model& m = sc.finalize();
            const ContactTopology& topo = sc.topo;
            const ContactTopology& cm = topo;
            int edges = 0;
            Real worst = 0;
            for (int32_t s = 0; s < cm.num_sub_tris(); ++s) {
                for (int32_t r = 0; r < cm.num_sub_tris(); ++r) {
                    if (r == s) continue;
                    const auto& qs = cm.sub_tri[s];
                    const auto& qr = cm.sub_tri[r];
                    for (int k = 0; k < 3; ++k) {
                        const Vec2 a = testing::contact_node_x0(m, topo, qs[k]);
                        const Vec2 b = testing::contact_node_x0(m, topo, qs[(k + 1) % 3]);
                        // r has a geometric edge b-a (checked by position, not by id)
                        bool shared = false;
                        for (int j = 0; j < 3; ++j) {
                            shared |= norm(testing::contact_node_x0(m, topo, qr[j]) - b) < 1e-14 &&
                                      norm(testing::contact_node_x0(m, topo, qr[(j + 1) % 3]) - a) <
                                          1e-14;
                        }
                        if (!shared) continue;
                        ++edges;
                        for (Real t : {0.1, 0.37, 0.5, 0.81}) {
                            const Vec2 x = a + t * (b - a);
                            Real d[2];
                            for (int side = 0; side < 2; ++side) {
                                const auto& q = side == 0 ? qs : qr;
                                const Vec2 p[3] = {testing::contact_node_x0(m, topo, q[0]),
                                                   testing::contact_node_x0(m, topo, q[1]),
                                                   testing::contact_node_x0(m, topo, q[2])};
                                FieldSample fs;
                                ASSERT_TRUE(barycentric(p[0], p[1], p[2], x, fs.N));
                                const Real dist[3] = {cm.node_dist[q[0]], cm.node_dist[q[1]],
                                                      cm.node_dist[q[2]]};
                                smooth_field(p, dist, fs);
                                d[side] = fs.d;
                            }
                            worst = std::max(worst, std::abs(d[0] - d[1]));
                        }
                    }
                }
            }
            EXPECT_GT(edges, 0);
            EXPECT_LE(worst, 1e-14);  // same nodal values on both sides: round-off only
        }
    }
}

// ---- forces through virtual nodes ------------------------------------------------------------

// A single-triangle target body pokes its apex into a composite contactor (near n7 of the fan,
// or into the central split triangles): the pair forces sum to zero with zero moment, including
// the shares of the virtual nodes passed to their parents (spec §4.4-6), and the target force
// is minus the gradient of the stored potential.
TEST(CompositeContact, PairForcesBalanceThroughVirtualNodes) {
    for (Option o : {Option::Fan, Option::Split}) {
        for (int shape = 0; shape < 2; ++shape) {
            CompositeScene sc(o);
            sc.add(shape == 0 ? single() : diamond());
            // apex inside, near the centre; the other two vertices well outside
            const Vec2 apex = shape == 0 ? Vec2{1.1, 0.8} : Vec2{0.13, 0.21};
            const Real s = shape == 0 ? 4.0 : 1.0;
            Model& m = sc.m;
            BodyOptions opt;
            opt.name = "target";
            add_bodies(
                m,
                testing::mesh_of({apex, apex + s * Vec2{0.1, 1.5}, apex + s * Vec2{-0.1, 1.5}},
                                 {{0, 1, 2}}),
                {0}, opt);
            sc.finalize();
            State st = make_state(m, 1e-6);
            add_contact_forces(m, st);
            EXPECT_GE(st.contact.active_contacts, 1) << name_of(o) << " " << shape;
            Vec2 sum;
            Real moment = 0, fscale = 0, mscale = 0;
            for (NodeId i = 0; i < m.num_nodes(); ++i) {
                const Vec2 f = st.f_contact[i];
                sum += f;
                moment += cross(st.x[i], f);
                fscale += norm(f);
                mscale += norm(st.x[i]) * norm(f);
            }
            // 1e-12 relative: sums of O(1e9) terms, round-off only
            EXPECT_LE(norm(sum), 1e-12 * fscale) << name_of(o) << " " << shape;
            EXPECT_LE(std::abs(moment), 1e-12 * mscale) << name_of(o) << " " << shape;

            // force on the apex = -grad of the stored energy (central difference)
            const NodeId j = m.bodies[1].node_begin;
            ASSERT_EQ(m.node_x0[j].x, apex.x);
            const State s0 = make_state(m, 1e-6);
            auto energy = [&](Vec2 dx) {
                State t = s0;
                t.x[j] += dx;
                add_contact_forces(m, t);
                return t.energy.contact;
            };
            const Real h = 1e-6;
            const Vec2 g{(energy({h, 0}) - energy({-h, 0})) / (2 * h),
                         (energy({0, h}) - energy({0, -h})) / (2 * h)};
            const Vec2 f = st.f_contact[j];
            ASSERT_GT(norm(f), 0);
            // phi = d^2 is quadratic in x_j inside a sub-triangle: the central difference is
            // exact up to round-off eps E / h ~ 1e-10 relative
            EXPECT_NEAR(f.x, -g.x, 1e-7 * norm(f)) << name_of(o) << " " << shape;
            EXPECT_NEAR(f.y, -g.y, 1e-7 * norm(f)) << name_of(o) << " " << shape;
        }
    }
}

// ---- options, baseline B, bad elements -------------------------------------------------------

// baseline B (phi_B per mesh sub-triangle, theory §7.4) needs sub-triangles nested in mesh
// sub-triangles: it uses the option (a) layout whatever the key says
TEST(CompositeContact, LegacyBoundaryUsesNestedSplit) {
    for (Option o : {Option::Fan, Option::Split}) {
        CompositeScene sc(o, ContactAlgorithm::LegacyBoundary);
        sc.add(single());
        const Model& m = sc.finalize();
        const ContactTopology& topo = sc.topo;
        EXPECT_EQ(topo.num_sub_tris(), 10);
        ASSERT_EQ(topo.sub_legacy_b.size(), 10u);
        // every contact sub-triangle lies inside its mesh parent
        for (int32_t s = 0; s < topo.num_sub_tris(); ++s) {
            const auto& t = m.tri_nodes[topo.sub_parent[s]];
            for (NodeId i : topo.sub_tri[s]) {
                Real N[3];
                ASSERT_TRUE(barycentric(m.node_x0[t[0]], m.node_x0[t[1]], m.node_x0[t[2]],
                                        testing::contact_node_x0(m, topo, i), N));
                EXPECT_GE(std::min({N[0], N[1], N[2]}), -1e-15);
            }
        }
    }
}

// option (b) with the fan parent: the mesh sub-triangle holding the fan triangle's boundary
// half-edge
TEST(CompositeContact, FanParentHoldsTheBoundaryHalfEdge) {
    CompositeScene sc(Option::Fan);
    sc.add(single());
    const Model& m = sc.finalize();
    const ContactTopology& topo = sc.topo;
    for (int32_t s = 0; s < topo.num_sub_tris(); ++s) {
        const auto& q = topo.sub_tri[s];
        const auto& t = m.tri_nodes[topo.sub_parent[s]];
        bool found = false;  // (q0, q1) is an edge of the parent, same direction
        for (int k = 0; k < 3; ++k)
            found |= q[0] == t[k] && q[1] == t[(k + 1) % 3];
        EXPECT_TRUE(found) << s;
        EXPECT_TRUE(topo.node_on_boundary[q[0]] && topo.node_on_boundary[q[1]]);
    }
}

// a mid-edge node pulled far inwards: the fan around the incenter folds over; the error says
// which element and offers option (a)
TEST(CompositeContact, DistortedElementFanIsAnInputError) {
    scenes::CompositeMesh mesh = scenes::composite_mesh({{0, 0}, {1, 0}, {0.5, 0.9}}, {{0, 1, 2}});
    mesh.nodes[3] = {0.5, 0.35};  // n2 of the only element (mid of n1-n3), incenter y ~ 0.28
    {
        CompositeScene sc(Option::Fan);
        sc.add(mesh);
        try {
            sc.finalize();
            FAIL() << "no InputError";
        } catch (const InputError& e) {
            EXPECT_THAT(e.what(), ::testing::HasSubstr("composite element 0 is too distorted"));
            EXPECT_THAT(e.what(), ::testing::HasSubstr("composite_special_case = \"split\""));
        }
    }
    CompositeScene sc(Option::Split);
    sc.add(mesh);
    EXPECT_NO_THROW(sc.finalize());
}

}  // namespace
}  // namespace fdem
