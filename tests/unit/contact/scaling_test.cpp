// ContactModel::scaling (docs/theory.md §6.11): the per-node factor of the target force is
// m_j / mbar (paper eq. 19) or l_j / lbar (tributary boundary length over the smallest boundary
// edge), and the stable dt uses m_dt = min m_j / scale_j. Expected values are the geometry of a
// structured rectangle, computed by hand below.
#include <gtest/gtest.h>

#include "fdem/build.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

Model two_rectangles(ContactScaling s) {
    Model m;
    m.materials.push_back(scenes::paper_material("paper"));
    // block 1 x 0.5 m in 4 x 2 cells (0.25 x 0.25), alternating diagonals; platform 2 x 0.2 m
    // in 5 x 1 cells (0.4 x 0.2): smallest boundary edge 0.2 m (platform sides)
    scenes::add_rectangle(m, 0.5, 0.2, 1.0, 0.5, 4, 2, 0, false, {}, true, "block");
    scenes::add_rectangle(m, 0.0, 0.0, 2.0, 0.2, 5, 1, 0, true, {}, false, "platform");
    m.contact.algorithm = ContactAlgorithm::Smooth;
    m.contact.scaling = s;
    m.contact.edge_targets =
        false;  // the node scales of eqs. 19 / 6.16 themselves (§6.12: a third)
    finalize_model(m);
    return m;
}

TEST(ContactScaling, LengthScaleIsTributaryBoundaryLengthOverSmallestEdge) {
    const Model m = two_rectangles(ContactScaling::Length);
    const ContactTopology topo = build_topology(m);
    const ContactTopology& cm = topo;
    EXPECT_DOUBLE_EQ(cm.l_bar, 0.2);
    for (NodeId i = m.bodies[0].node_begin; i < m.bodies[0].node_end; ++i) {
        const Vec2 p = m.node_x0[i];
        const bool on_x = std::abs(p.x - 0.5) < 1e-12 || std::abs(p.x - 1.5) < 1e-12;
        const bool on_y = std::abs(p.y - 0.2) < 1e-12 || std::abs(p.y - 0.7) < 1e-12;
        // corners: half of a 0.25 m top/bottom edge + half of a 0.25 m side edge = 0.25 m;
        // other face nodes: two halves of 0.25 m edges = 0.25 m; inner nodes: 0
        const double l = (on_x || on_y) ? 0.25 : 0.0;
        EXPECT_NEAR(cm.node_scale[i], l / 0.2, 1e-14) << "node " << i;
    }
    // platform: top/bottom edges 0.4 m, sides 0.2 m; corner = 0.2 + 0.1, face node = 0.4
    for (NodeId i = m.bodies[1].node_begin; i < m.bodies[1].node_end; ++i) {
        const Vec2 p = m.node_x0[i];
        const bool corner = (std::abs(p.x) < 1e-12 || std::abs(p.x - 2.0) < 1e-12);
        EXPECT_NEAR(cm.node_scale[i], (corner ? 0.3 : 0.4) / 0.2, 1e-14) << "node " << i;
    }
    // stable-dt mass: min over the block's (movable) boundary nodes of m_j lbar / l_j
    double m_dt = INFINITY;
    for (NodeId i = m.bodies[0].node_begin; i < m.bodies[0].node_end; ++i)
        if (cm.node_scale[i] > 0) m_dt = std::min(m_dt, m.node_mass[i] * 0.2 / 0.25);
    EXPECT_DOUBLE_EQ(cm.m_dt, m_dt);
}

TEST(ContactScaling, MassScaleIsEq19AndDefault) {
    EXPECT_EQ(ContactModel{}.scaling, ContactScaling::Mass);
    const Model m = two_rectangles(ContactScaling::Mass);
    const ContactTopology topo = build_topology(m);
    const ContactTopology& cm = topo;
    // mbar = smallest element mass: block cells 0.25 x 0.25 -> rho A = 1000 * 0.03125
    EXPECT_DOUBLE_EQ(m.contact.m_bar, 31.25);
    EXPECT_EQ(cm.m_dt, m.contact.m_bar);
    for (NodeId i = 0; i < m.num_nodes(); ++i)
        EXPECT_EQ(cm.node_scale[i],
                  m.node_mass[i] / m.contact.m_bar);  // bitwise the old expression
}

}  // namespace
}  // namespace fdem
