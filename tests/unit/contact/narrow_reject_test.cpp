// The narrow phase's body-box reject (contact.cpp body_boxes(), contact.hpp box_rejects()) must
// only skip pairs that the full locate test rejects: (1) on random bodies and points, including
// sliver and degenerate sub-triangles, points on edges and vertices and points just outside the
// widened box, a rejected point is accepted by no sub-triangle and fails the early edge-function
// test of every sub-triangle; (2) whole runs of the contact pack and the particle box give
// bitwise the same state with and without the reject.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <vector>

#include "contact/contact.hpp"
#include "contact/field.hpp"
#include "fdem/simulate.hpp"
#include "io/checkpoint.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

// the acceptance rule of the locate loop (contact.cpp evaluate_pair: kLocateEps) and its early
// reject (kRejectMargin), restated here as the specification the box reject must respect
constexpr Real kLocateEps = 1e-12;
constexpr Real kRejectMargin = 1e-9;

bool accepted(Vec2 p0, Vec2 p1, Vec2 p2, Vec2 x) {
    Real N[3];
    if (!barycentric(p0, p1, p2, x, N)) return false;
    return std::min({N[0], N[1], N[2]}) >= -kLocateEps;
}

bool early_rejected(Vec2 p0, Vec2 p1, Vec2 p2, Vec2 x) {
    const Real a2 = cross(p1 - p0, p2 - p0);
    const Real c0 = cross(p1 - x, p2 - x), c1 = cross(p2 - x, p0 - x), c2 = cross(p0 - x, p1 - x);
    const Real lim = kRejectMargin * std::abs(a2);
    return a2 > 0 ? std::min({c0, c1, c2}) < -lim : std::max({c0, c1, c2}) > lim;
}

// one body of n triangles over real nodes 0..3n-1 (no shared nodes needed for the test)
ContactTopology one_body(int n) {
    ContactTopology cm;
    cm.num_real_nodes = 3 * n;
    for (int t = 0; t < n; ++t) {
        cm.sub_tri.push_back({3 * t, 3 * t + 1, 3 * t + 2});
        cm.sub_body.push_back(0);
    }
    cm.body_sub_begin = {0, n};
    build_body_contact_nodes(cm);  // body_boxes() takes its production (distinct-node) path
    return cm;
}

struct Counts {
    int64_t points = 0, rejected = 0, rejected_near = 0;
};

// every point the box rejects must be rejected by every sub-triangle
void check_points(const ContactTopology& cm, const std::vector<Vec2>& x, const BodyBox& box,
                  const std::vector<Vec2>& pts, Counts& n) {
    for (const Vec2& p : pts) {
        ++n.points;
        if (!box_rejects(box, p)) continue;
        ++n.rejected;
        const Real w = std::max(box.hi.x - box.lo.x, box.hi.y - box.lo.y);
        const Real d = std::max({box.lo.x - p.x, p.x - box.hi.x, box.lo.y - p.y, p.y - box.hi.y});
        if (d < 1e-3 * w) ++n.rejected_near;
        for (const auto& q : cm.sub_tri) {
            const Vec2 a = x[q[0]], b = x[q[1]], c = x[q[2]];
            ASSERT_FALSE(accepted(a, b, c, p)) << p.x << " " << p.y;
            ASSERT_TRUE(early_rejected(a, b, c, p)) << p.x << " " << p.y;
        }
    }
}

TEST(NarrowReject, RandomBodiesAndPoints) {
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<Real> u01(0, 1);
    Counts n;
    int finite_boxes = 0, infinite_boxes = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const int ntri = 1 + static_cast<int>(rng() % 6);
        const ContactTopology cm = one_body(ntri);
        const Real size = std::pow(10.0, -3 + 6 * u01(rng));
        const Vec2 origin{std::pow(10.0, -2 + 5 * u01(rng)) * (u01(rng) - 0.5),
                          std::pow(10.0, -2 + 5 * u01(rng)) * (u01(rng) - 0.5)};
        std::vector<Vec2> x(static_cast<size_t>(3 * ntri));
        for (int t = 0; t < ntri; ++t) {
            Vec2* p = &x[static_cast<size_t>(3 * t)];
            for (int k = 0; k < 3; ++k)
                p[k] = origin + size * Vec2{u01(rng), u01(rng)};
            const int kind = static_cast<int>(rng() % 8);
            if (kind == 0) {  // sliver: third vertex near the line of the first two
                const Real s = u01(rng), h = std::pow(10.0, -9 + 7 * u01(rng));
                const Vec2 e = p[1] - p[0];
                p[2] = p[0] + s * e + h * Vec2{-e.y, e.x};
            } else if (kind == 1) {  // exactly collinear (a2 may still round to nonzero)
                p[2] = p[0] + 0.5 * (p[1] - p[0]);
            } else if (kind == 2) {  // sharp vertex: two vertices close together
                p[2] = p[1] + std::pow(10.0, -8 + 6 * u01(rng)) * size * Vec2{u01(rng), u01(rng)};
            }
        }
        BodyBox box;
        body_boxes(cm, x.data(), nullptr, &box, 1);
        if (std::isinf(box.lo.x)) {
            ++infinite_boxes;
        } else {
            ++finite_boxes;
        }
        const Real w = std::max(box.hi.x - box.lo.x, box.hi.y - box.lo.y);

        std::vector<Vec2> pts;
        // points around the body
        for (int k = 0; k < 20; ++k)
            pts.push_back(origin + size * Vec2{3 * u01(rng) - 1, 3 * u01(rng) - 1});
        // on edges and vertices, and one or a few ulps off them
        for (int t = 0; t < ntri; ++t) {
            for (int k = 0; k < 3; ++k) {
                const Vec2 a = x[static_cast<size_t>(3 * t + k)];
                const Vec2 b = x[static_cast<size_t>(3 * t + (k + 1) % 3)];
                const Vec2 e = a + u01(rng) * (b - a);
                pts.push_back(a);
                pts.push_back(e);
                for (int sx = -1; sx <= 1; ++sx) {
                    for (int sy = -1; sy <= 1; ++sy) {
                        const Real inf = std::numeric_limits<Real>::infinity();
                        pts.push_back(
                            {std::nextafter(e.x, sx * inf), std::nextafter(e.y, sy * inf)});
                        pts.push_back(
                            {std::nextafter(a.x, sx * inf), std::nextafter(a.y, sy * inf)});
                    }
                }
            }
        }
        if (std::isfinite(w)) {
            // just outside / inside the widened box, from one ulp to 10 margins
            const Real mid_x = 0.5 * (box.lo.x + box.hi.x), mid_y = 0.5 * (box.lo.y + box.hi.y);
            for (int k = 0; k < 20; ++k) {
                const Real off =
                    std::pow(10.0, -16 + 11 * u01(rng)) * w * (u01(rng) < 0.5 ? -1 : 1);
                const Real along = box.lo.y + u01(rng) * (box.hi.y - box.lo.y);
                const Real across = box.lo.x + u01(rng) * (box.hi.x - box.lo.x);
                pts.push_back({box.lo.x - off, along});
                pts.push_back({box.hi.x + off, along});
                pts.push_back({across, box.lo.y - off});
                pts.push_back({across, box.hi.y + off});
                pts.push_back({std::nextafter(box.lo.x, -1e300), mid_y});
                pts.push_back({mid_x, std::nextafter(box.hi.y, 1e300)});
            }
            // far away: up to and beyond the far limit of the reject
            for (int k = 0; k < 10; ++k) {
                const Real r = std::pow(10.0, 3 * u01(rng) + 4 * (k % 2)) * w;
                pts.push_back({mid_x + r * (u01(rng) - 0.5), mid_y + r});
                pts.push_back({mid_x - r, mid_y + r * (u01(rng) - 0.5)});
            }
        }
        check_points(cm, x, box, pts, n);
    }
    // the test exercised both kinds of boxes and rejected points close to the box
    EXPECT_GT(finite_boxes, 1000);
    EXPECT_GT(infinite_boxes, 100);
    EXPECT_GT(n.rejected, n.points / 10);
    EXPECT_GT(n.rejected_near, 10000);
}

TEST(NarrowReject, GuardsGiveInfiniteBoxes) {
    const ContactTopology cm = one_body(1);
    const Real inf = std::numeric_limits<Real>::infinity();
    auto box_of = [&](std::vector<Vec2> x) {
        BodyBox b;
        body_boxes(cm, x.data(), nullptr, &b, 1);
        return b;
    };
    // a proper triangle gets a finite box slightly larger than its bounds
    const BodyBox ok = box_of({{0, 0}, {1, 0}, {0, 1}});
    EXPECT_LT(ok.lo.x, 0);
    EXPECT_GT(ok.lo.x, -1e-5);
    EXPECT_GT(ok.hi.y, 1);
    EXPECT_LT(ok.hi.y, 1 + 1e-5);
    // collinear, sliver below the aspect guard, NaN, infinite, tiny body far from the origin
    const std::vector<std::vector<Vec2>> bad = {
        {{0, 0}, {1, 1}, {2, 2}},
        {{0, 0}, {1, 0}, {0.5, 1e-7}},
        {{0, 0}, {1, 0}, {std::nan(""), 1}},
        {{0, 0}, {inf, 0}, {0, 1}},
        {{1e9, 1e9}, {1e9 + 1e-3, 1e9}, {1e9, 1e9 + 1e-3}},
    };
    for (const auto& x : bad) {
        const BodyBox b = box_of(x);
        EXPECT_EQ(b.lo.x, -inf);
        EXPECT_EQ(b.hi.y, inf);
        EXPECT_FALSE(box_rejects(b, {1e6, 1e6}));
    }
    // a NaN target is never rejected by the box (the locate loop rejects it itself)
    EXPECT_FALSE(box_rejects(ok, {std::nan(""), 2}));
}

// box_rejects() (SSE2 pairs where available) answers as the scalar reference formula, also for
// NaN, infinite and empty boxes, ties and points on the box faces
TEST(NarrowReject, VectorTestMatchesScalarFormula) {
    std::mt19937_64 rng(777);
    std::uniform_real_distribution<Real> u01(0, 1);
    const Real inf = std::numeric_limits<Real>::infinity(), nan = std::nan("");
    const Real specials[] = {0.0, -0.0, 1.0, -1.0, 1e-300, 1e300, inf, -inf, nan};
    auto pick = [&](Real lo, Real hi) {
        const uint64_t r = rng() % 16;
        if (r < 3) return specials[rng() % 9];
        if (r < 5) return u01(rng) < 0.5 ? lo : hi;  // on a face
        return lo + (hi - lo) * (3 * u01(rng) - 1);
    };
    int64_t rejected = 0, kept = 0;
    for (int k = 0; k < 200000; ++k) {
        const Real s = std::pow(10.0, -6 + 12 * u01(rng));
        BodyBox b{{s * (u01(rng) - 0.5), s * (u01(rng) - 0.5)}, {}};
        b.hi = {b.lo.x + s * u01(rng), b.lo.y + s * u01(rng)};
        if (rng() % 8 == 0) b.lo.x = specials[rng() % 9];
        if (rng() % 8 == 0) b.hi.y = specials[rng() % 9];
        const Vec2 p{pick(b.lo.x, b.hi.x), pick(b.lo.y, b.hi.y)};
        const bool r = box_rejects(b, p);
        ASSERT_EQ(r, box_rejects_scalar(b, p)) << b.lo.x << " " << b.lo.y << " " << b.hi.x << " "
                                               << b.hi.y << " | " << p.x << " " << p.y;
        (r ? rejected : kept) += 1;
    }
    EXPECT_GT(rejected, 20000);
    EXPECT_GT(kept, 20000);
}

// body_boxes() (bounds over each body's distinct contact nodes, areas through sub_local) gives
// bitwise the boxes of body_boxes_reference() (every sub-triangle's vertices in turn): random
// bodies sharing nodes, real and virtual nodes, repeated vertices, signed zeros (ties of -0 and
// +0 in the bounds), NaN, infinities, slivers, huge and tiny scales, and bodies with more
// nodes than the local buffer (reference path)
TEST(NarrowReject, CompactBoxesMatchReference) {
    std::mt19937_64 rng(4242);
    std::uniform_real_distribution<Real> u01(0, 1);
    const Real inf = std::numeric_limits<Real>::infinity(), nan = std::nan("");
    int64_t finite = 0, infinite = 0, large = 0;
    for (int trial = 0; trial < 6000; ++trial) {
        ContactTopology cm;
        const bool big = trial % 50 == 0;
        const int nreal = big ? 200 : 3 + static_cast<int>(rng() % 8);
        const int nvirt = static_cast<int>(rng() % 4);
        cm.num_real_nodes = nreal;
        const int nbodies = 1 + static_cast<int>(rng() % 3);
        cm.body_sub_begin = {0};
        for (int b = 0; b < nbodies; ++b) {
            const int ntri = big ? 60 : static_cast<int>(rng() % 7);  // 0: empty body
            for (int t = 0; t < ntri; ++t) {
                std::array<NodeId, 3> q{};
                for (NodeId& i : q)
                    i = static_cast<NodeId>(rng() % static_cast<uint64_t>(nreal + nvirt));
                cm.sub_tri.push_back(q);
                cm.sub_body.push_back(b);
            }
            cm.body_sub_begin.push_back(static_cast<int32_t>(cm.sub_tri.size()));
        }
        build_body_contact_nodes(cm);
        const Real size = std::pow(10.0, -8 + 16 * u01(rng));
        const Vec2 origin{std::pow(10.0, -2 + 8 * u01(rng)) * (u01(rng) - 0.5), 0.0};
        auto coord = [&](Real base) {
            const uint64_t r = rng() % 64;
            if (r == 0) return nan;
            if (r == 1) return rng() % 2 ? inf : -inf;
            if (r < 6) return 0.0;
            if (r < 10) return -0.0;
            return base + size * u01(rng);
        };
        std::vector<Vec2> x(static_cast<size_t>(nreal)), xv(static_cast<size_t>(nvirt));
        for (Vec2& p : x)
            p = {coord(origin.x), coord(origin.y)};
        for (Vec2& p : xv)
            p = {coord(origin.x), coord(origin.y)};
        if (rng() % 4 == 0 && nreal >= 3) x[2] = x[0] + 0.5 * (x[1] - x[0]);  // collinear
        std::vector<BodyBox> a(static_cast<size_t>(nbodies)), r(static_cast<size_t>(nbodies));
        body_boxes(cm, x.data(), xv.data(), a.data(), nbodies);
        body_boxes_reference(cm, x.data(), xv.data(), r.data(), nbodies);
        ASSERT_EQ(std::memcmp(a.data(), r.data(), a.size() * sizeof(BodyBox)), 0) << trial;
        for (const BodyBox& b : r)
            (std::isinf(b.lo.x) ? infinite : finite) += 1;
        large += big ? nbodies : 0;
    }
    EXPECT_GT(finite, 1000);
    EXPECT_GT(infinite, 1000);
    EXPECT_GT(large, 100);
}

// the same on the real topologies (virtual chord midpoints and incenters) along a run
TEST(NarrowReject, CompactBoxesMatchReferenceInRuns) {
    scenes::PackOptions po;
    po.blocks_x = po.blocks_y = 8;
    scenes::ParticleOptions pa;
    pa.nx = pa.ny = 5;
    pa.v_max = 20;
    for (const Model& m : {scenes::make_contact_pack(po), scenes::make_particle_box(pa)}) {
        State s = make_state(m, 0.5 * stable_time_step(m));
        ASSERT_EQ(s.topology.body_cnode_begin.size(), static_cast<size_t>(m.num_bodies()) + 1);
        std::vector<BodyBox> a(static_cast<size_t>(m.num_bodies()));
        std::vector<BodyBox> r(a.size());
        int64_t finite = 0;
        for (int n = 0; n < 200; ++n) {
            step(m, s);
            if (n % 10 != 0) continue;
            update_virtual_nodes(m, s);
            body_boxes(s.topology, s.x.data(), s.contact.xv.data(), a.data(), m.num_bodies());
            body_boxes_reference(s.topology, s.x.data(), s.contact.xv.data(), r.data(),
                                 m.num_bodies());
            ASSERT_EQ(std::memcmp(a.data(), r.data(), a.size() * sizeof(BodyBox)), 0) << n;
            for (const BodyBox& b : r)
                finite += std::isfinite(b.lo.x) ? 1 : 0;
        }
        EXPECT_GT(finite, 10 * m.num_bodies());  // the real boxes were finite
    }
}

// x, v, f and the energies of two runs are bitwise equal
void expect_same_state(const State& a, const State& b) {
    ASSERT_EQ(a.x.size(), b.x.size());
    EXPECT_EQ(std::memcmp(a.x.data(), b.x.data(), a.x.size() * sizeof(Vec2)), 0);
    EXPECT_EQ(std::memcmp(a.v.data(), b.v.data(), a.v.size() * sizeof(Vec2)), 0);
    EXPECT_EQ(std::memcmp(a.f_contact.data(), b.f_contact.data(), a.f.size() * sizeof(Vec2)), 0);
    EXPECT_EQ(std::memcmp(&a.energy.contact, &b.energy.contact, sizeof(Real)), 0);
    EXPECT_EQ(std::memcmp(&a.energy.dissipated_contact, &b.energy.dissipated_contact, sizeof(Real)),
              0);
    EXPECT_EQ(a.contact.active_contacts, b.contact.active_contacts);
    EXPECT_EQ(a.contact.rebuilds, b.contact.rebuilds);
}

// returns the smallest number of bodies whose boxes a step computed (ContactState::box_bodies)
size_t run_with_and_without(const Model& m, int steps, int min_active) {
    State with = make_state(m, 0.5 * stable_time_step(m));
    State without = with;
    without.contact.box_reject = false;
    int max_active = 0;
    size_t fewest_boxes = static_cast<size_t>(m.num_bodies());
    for (int n = 0; n < steps; ++n) {
        step(m, with);
        step(m, without);
        max_active = std::max(max_active, with.contact.active_contacts);
        fewest_boxes = std::min(fewest_boxes, with.contact.box_bodies.size());
    }
    EXPECT_GE(max_active, min_active);  // the runs did have contacts
    expect_same_state(with, without);
    return fewest_boxes;
}

TEST(NarrowReject, PackBitwiseWithAndWithout) {
    scenes::PackOptions o;
    o.blocks_x = o.blocks_y = 12;
    o.shuffled = true;
    run_with_and_without(scenes::make_contact_pack(o), 400, 20);
}

TEST(NarrowReject, ParticleBoxBitwiseWithAndWithout) {
    scenes::ParticleOptions o;
    o.nx = o.ny = 6;
    o.v_max = 20;
    const Model m = scenes::make_particle_box(o);
    // only the candidates' contactors have boxes computed: here fewer than all bodies, so the
    // list (rebuilt after every broad phase) is what the equality above tested
    EXPECT_LT(run_with_and_without(m, 600, 5), static_cast<size_t>(m.num_bodies()));
}

// A checkpoint read into a State that has stepped already (its list of contactor bodies made for
// other candidates) continues as the run that wrote it: the read clears the list.
TEST(NarrowReject, CheckpointReadRenewsTheContactorList) {
    scenes::ParticleOptions o;
    o.nx = o.ny = 6;
    o.v_max = 20;
    const Model m = scenes::make_particle_box(o);
    State ref = make_state(m, 0.5 * stable_time_step(m));
    State s = ref;
    step(m, s);  // the particles apart: few contactors
    for (int n = 0; n < 450; ++n)
        step(m, ref);
    // the written candidates have contactors that s's list lacks (else the test shows nothing)
    const std::vector<BodyId>& old_list = s.contact.box_bodies;
    bool lacks = false;
    for (const BodyId b : ref.contact.cand.body)
        lacks = lacks || !std::binary_search(old_list.begin(), old_list.end(), b);
    ASSERT_TRUE(lacks);
    const std::string path = ::testing::TempDir() + "/contactor_list.fdck";
    write_checkpoint(path, m, ref, {});
    RunProgress progress;
    read_checkpoint(path, m, s, progress);
    // the next step (no broad phase in it) computes the boxes of the read candidates'
    // contactors: the list is theirs, not the one s had
    const int64_t rebuilds = s.contact.rebuilds;
    step(m, ref);
    step(m, s);
    ASSERT_EQ(s.contact.rebuilds, rebuilds);
    std::vector<BodyId> want(s.contact.cand.body.begin(), s.contact.cand.body.end());
    std::sort(want.begin(), want.end());
    want.erase(std::unique(want.begin(), want.end()), want.end());
    EXPECT_EQ(s.contact.box_bodies, want);
    int max_active = 0;
    for (int n = 0; n < 300; ++n) {
        step(m, ref);
        step(m, s);
        max_active = std::max(max_active, s.contact.active_contacts);
    }
    EXPECT_GE(max_active, 5);
    expect_same_state(ref, s);
    std::filesystem::remove(path);
}

}  // namespace
}  // namespace fdem
