// validate_topology() (issue #14 item 3): passes on every topology the builder makes (test
// scenes of each layout, every example scenario) and catches each invariant broken once.
#include "contact/validate.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <functional>

#include "fdem/scenario.hpp"
#include "unit/contact/contact_fixture.hpp"

namespace fdem {
namespace {

using testing::ModelBuilder;

std::string joined(const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& m : v)
        s += m + "\n";
    return s;
}

// Three bodies: a 3 x 2 rectangle (chords, virtual mid-nodes, inner nodes with distances), a
// single triangle (incenter fan) and a fixed 2 x 1 rectangle, alternate diagonals.
Model three_bodies(ContactScaling scaling = ContactScaling::Mass, bool edge_targets = true,
                   ContactAlgorithm algorithm = ContactAlgorithm::Smooth) {
    ModelBuilder b;
    b.m.contact.scaling = scaling;
    b.m.contact.edge_targets = edge_targets;
    b.m.contact.algorithm = algorithm;
    MeshData r = make_rectangle_mesh(0, 0, 3, 2, 3, 2);
    testing::perturb_interior(r, 0.1, 7);
    b.add_body(r);
    b.add_body(testing::mesh_of({{5, 0}, {6, 0}, {5.2, 0.9}}, {{{0, 1, 2}}}));
    b.add_body(make_rectangle_mesh(0, -2, 2, 1, 2, 1, true), true);
    return b.finalize();
}

TEST(ValidateTopology, PassesOnBuiltTopologies) {
    for (ContactScaling sc : {ContactScaling::Mass, ContactScaling::Length}) {
        for (bool et : {false, true}) {
            for (ContactAlgorithm a : {ContactAlgorithm::Smooth, ContactAlgorithm::LegacyTriangle,
                                       ContactAlgorithm::LegacyBoundary, ContactAlgorithm::None}) {
                const Model m = three_bodies(sc, et, a);
                const auto v = validate_topology(m, build_topology(m));
                EXPECT_TRUE(v.empty()) << joined(v);
            }
        }
    }
}

TEST(ValidateTopology, PassesOnCompositeLayouts) {
    for (CompositeSpecialCase o : {CompositeSpecialCase::Fan, CompositeSpecialCase::Split}) {
        for (int shape = 0; shape < 2; ++shape) {
            ModelBuilder b;
            b.m.contact.composite_special_case = o;
            // 1 x 1: one composite per triangle of two (two boundary edges each, case 1);
            // 3 x 2: special and plain composites
            b.add_body(shape == 0 ? make_rectangle_mesh_order2(0, 0, 1, 1, 1, 1)
                                  : make_rectangle_mesh_order2(0, 0, 3, 2, 3, 2, true));
            const Model& m = b.finalize();
            ASSERT_EQ(m.bodies[0].element, ElementKind::Composite6);
            const auto v = validate_topology(m, b.topo);
            EXPECT_TRUE(v.empty()) << joined(v);
        }
    }
}

// every scenario under examples/ (one test each: 04_particles takes seconds to load)
class ValidateExample : public ::testing::TestWithParam<std::string> {};

TEST_P(ValidateExample, Passes) {
    const Scenario sc = load_scenario(FDEM_SOURCE_DIR "/examples/" + GetParam());
    const auto v = validate_topology(sc.model, build_topology(sc.model));
    EXPECT_TRUE(v.empty()) << joined(v);
}

std::vector<std::string> example_scenarios() {
    std::vector<std::string> files;
    for (const auto& dir : std::filesystem::directory_iterator(FDEM_SOURCE_DIR "/examples")) {
        for (const auto& f : std::filesystem::directory_iterator(dir.path())) {
            if (f.path().extension() == ".toml")
                files.push_back(dir.path().filename().string() + "/" +
                                f.path().filename().string());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

INSTANTIATE_TEST_SUITE_P(Examples, ValidateExample, ::testing::ValuesIn(example_scenarios()),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                             std::string n = i.param.substr(0, i.param.size() - 5);
                             for (char& c : n) {
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             }
                             return n;
                         });

TEST(ValidateTopology, ExamplesFound) {
    EXPECT_GE(example_scenarios().size(), 7u);  // a moved examples/ folder must not pass silently
}

// Each case corrupts one invariant of a valid topology; the validator must name it.
struct Corruption {
    const char* name;
    std::function<void(ContactTopology&, const Model&)> apply;
    const char* expect;  ///< substring of one of the messages
};

// first inner (non-boundary) real node of body 0 that is a vertex of a sub-triangle
NodeId inner_contact_node(const ContactTopology& t) {
    for (int32_t s = t.body_sub_begin[0]; s < t.body_sub_begin[1]; ++s) {
        for (NodeId i : t.sub_tri[s]) {
            if (i < t.num_real_nodes && !t.node_on_boundary[i]) return i;
        }
    }
    return kNone;
}

TEST(ValidateTopology, CatchesEachBrokenInvariant) {
    const Model base = three_bodies();
    const ContactTopology t0 = build_topology(base);
    ASSERT_TRUE(validate_topology(base, t0).empty());
    ASSERT_GE(t0.chords.size(), 2u);
    ASSERT_GE(t0.num_virtual(), 2);
    ASSERT_NE(inner_contact_node(t0), kNone);

    const std::vector<Corruption> cases = {
        {"array size", [](ContactTopology& t, const Model&) { t.node_dist.pop_back(); },
         "sizes: node_dist has"},
        {"edge target base", [](ContactTopology& t, const Model&) { ++t.edge_target_base; },
         "sizes: edge_target_base"},
        {"body range order",
         [](ContactTopology& t, const Model&) { t.body_sub_begin[1] = t.body_sub_begin[2] + 1; },
         "ranges: body_sub_begin decreases"},
        {"body range end", [](ContactTopology& t, const Model&) { --t.body_bnode_begin.back(); },
         "ranges: body_bnode_begin ends"},
        {"edge orientation",
         [](ContactTopology& t, const Model&) {
             std::swap(t.boundary_edges[0][0], t.boundary_edges[0][1]);
         },
         "oriented against its triangle"},
        {"edge order",
         [](ContactTopology& t, const Model&) {
             std::swap(t.boundary_edges[1], t.boundary_edges[2]);
         },
         "in (min, max) order"},
        {"edge not on the boundary",
         [](ContactTopology& t, const Model&) {
             // a chord is an interior edge: used by two triangles
             t.boundary_edges[0] = t.chords[0];
         },
         "triangles of body 0, not 1"},
        {"edge missing",
         [](ContactTopology& t, const Model&) {
             t.boundary_edges.erase(t.boundary_edges.begin());
             t.edge_scale.erase(t.edge_scale.begin());
             for (size_t b = 1; b < t.body_bedge_begin.size(); ++b)
                 --t.body_bedge_begin[b];
         },
         "boundary_edges: body 0 lists"},
        {"edge in another body",
         [](ContactTopology& t, const Model&) { t.boundary_edges[0] = t.boundary_edges.back(); },
         "is not in body 0"},
        {"boundary node order",
         [](ContactTopology& t, const Model&) {
             std::swap(t.boundary_nodes[0], t.boundary_nodes[1]);
         },
         "boundary_nodes: not strictly ascending"},
        {"boundary flag",
         [](ContactTopology& t, const Model&) { t.node_on_boundary[inner_contact_node(t)] = 1; },
         "node_on_boundary: node"},
        {"chord missing",
         [](ContactTopology& t, const Model&) {
             t.chords.pop_back();  // and out of its body's range
             for (int32_t& e : t.body_chord_begin)
                 e = std::min(e, static_cast<int32_t>(t.chords.size()));
         },
         "listed, the mesh has"},
        {"chord not interior",
         [](ContactTopology& t, const Model&) {
             const auto& e = t.boundary_edges[0];
             t.chords[0] = {std::min(e[0], e[1]), std::max(e[0], e[1])};
         },
         "is not an interior edge joining two boundary nodes"},
        {"chord order",
         [](ContactTopology& t, const Model&) { std::swap(t.chords[0], t.chords[1]); },
         "chords: not strictly ascending"},
        {"boundary element missing",
         [](ContactTopology& t, const Model&) {
             t.boundary_tris.pop_back();
             for (int32_t& e : t.body_btri_begin)
                 e = std::min(e, static_cast<int32_t>(t.boundary_tris.size()));
         },
         "boundary_tris: "},
        {"virtual node range", [](ContactTopology& t, const Model&) { t.body_virt_begin[1] -= 1; },
         "body_virt_begin: virtual node"},
        {"chord range", [](ContactTopology& t, const Model&) { t.body_chord_begin[1] -= 1; },
         "body_chord_begin: chord"},
        {"boundary element range",
         [](ContactTopology& t, const Model&) { t.body_btri_begin[1] -= 1; },
         "body_btri_begin: boundary element"},
        {"fallback count", [](ContactTopology& t, const Model&) { t.body_fallback[1] += 1; },
         "body_fallback: the bodies' counts"},
        {"virtual weights", [](ContactTopology& t, const Model&) { t.virt_weight[0][0] += 0.1; },
         "sum to"},
        {"virtual parent in another body",
         [](ContactTopology& t, const Model& m) { t.virt_parent[0][2] = m.bodies[2].node_begin; },
         "has parents in bodies"},
        {"sub-triangle orientation",
         [](ContactTopology& t, const Model&) { std::swap(t.sub_tri[0][1], t.sub_tri[0][2]); },
         "is not counter-clockwise"},
        {"sub-triangle body", [](ContactTopology& t, const Model&) { t.sub_body[0] = 1; },
         "sub_body: sub-triangle 0"},
        {"sub-triangle parent",
         [](ContactTopology& t, const Model& m) { t.sub_parent[0] = m.bodies[1].tri_begin; },
         "sub_parent: sub-triangle 0"},
        {"sub-triangle coverage",
         [](ContactTopology& t, const Model&) {
             // a boundary edge's sub-triangle replaced by a copy of another one: the edge is
             // uncovered and the area is wrong
             int32_t s = t.body_sub_begin[0];
             while (!t.node_on_boundary[t.sub_tri[s][0]] || !t.node_on_boundary[t.sub_tri[s][1]])
                 ++s;
             t.sub_tri[s] = t.sub_tri[s == 0 ? 1 : 0];
         },
         "sub-triangles of body 0 cover"},
        {"contact node list order",
         [](ContactTopology& t, const Model&) { std::swap(t.body_cnode[0], t.body_cnode[1]); },
         "body_cnode: body 0"},
        {"real contact node count",
         [](ContactTopology& t, const Model&) { ++t.body_cnode_nreal[0]; }, "body_cnode_nreal"},
        {"local vertex index", [](ContactTopology& t, const Model&) { t.sub_local[0][0] ^= 1; },
         "sub_local: vertex 0 of sub-triangle 0"},
        {"boundary node distance",
         [](ContactTopology& t, const Model&) { t.node_dist[t.boundary_nodes[0]] = 0.1; },
         "(boundary node) has distance"},
        {"inner node distance",
         [](ContactTopology& t, const Model&) { t.node_dist[inner_contact_node(t)] *= 1.5; },
         "its distance to boundary edge"},
        {"distance of a virtual node",
         [](ContactTopology& t, const Model&) {
             const size_t v = static_cast<size_t>(t.num_real_nodes);
             t.node_dist[v] *= 0.5;
         },
         "its distance to boundary edge"},
        {"distance edge of another body",
         [](ContactTopology& t, const Model&) {
             t.node_dist_edge[inner_contact_node(t)] = t.body_bedge_begin[1];
         },
         "of another body"},
        {"node scale",
         [](ContactTopology& t, const Model&) { t.node_scale[t.boundary_nodes[0]] = 0; },
         "node_scale: node"},
        {"edge scale", [](ContactTopology& t, const Model&) { t.edge_scale[3] = -1; },
         "edge_scale: boundary edge 3"},
        {"fixed flag", [](ContactTopology& t, const Model&) { t.body_fixed[2] = 0; },
         "body_fixed: body 2"},
    };
    for (const Corruption& c : cases) {
        ContactTopology t = t0;
        c.apply(t, base);
        const auto v = validate_topology(base, t);
        ASSERT_FALSE(v.empty()) << c.name << ": not caught";
        const std::string all = joined(v);
        EXPECT_NE(all.find(c.expect), std::string::npos)
            << c.name << ": expected \"" << c.expect << "\" in\n"
            << all;
    }
}

TEST(ValidateTopology, MessageLimit) {
    const Model m = three_bodies();
    ContactTopology t = build_topology(m);
    for (Real& d : t.node_dist)
        d += 1;  // every contact node wrong
    EXPECT_EQ(validate_topology(m, t, 5).size(), 5u);
}

}  // namespace
}  // namespace fdem
