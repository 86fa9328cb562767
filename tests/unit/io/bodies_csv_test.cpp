// bodies.csv (src/fdem/io/bodies_csv.cpp): it opens as CSV, has 12 columns per set named
// SET.quantity (quoted where a name needs it), and its numbers read back bit-exact.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "fdem/build.hpp"
#include "fdem/output.hpp"
#include "fdem/simulate.hpp"
#include "support/csv.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

namespace fs = std::filesystem;

TEST(BodiesCsv, OpensAsCsvWithTwelveColumnsPerSet) {
    Model m;
    m.materials.push_back(scenes::paper_material());
    m.gravity = {0, -9.81};
    scenes::add_rectangle(m, 0, 0, 0.2, 0.1, 2, 1, 0, false, {1, 0}, false, "a,b");
    BoundaryCondition bc;
    bc.name = "a,b/left";
    bc.has_x = true;
    bc.nodes = {0};
    m.bcs.push_back(bc);
    finalize_model(m);
    State s = make_state(m, 1e-6);
    const Resultants r(m);
    const fs::path dir = fs::path(::testing::TempDir()) / "fdem_bodies_csv";
    fs::create_directories(dir);
    const std::string path = (dir / "bodies.csv").string();
    IntervalImpulses acc = r.make_impulses();
    {
        BodiesWriter w(path, r);
        for (int k = 0; k < 3; ++k) {
            step(m, s);
            r.accumulate(m, s, acc);
            w.write(m, s, acc);
        }
    }
    const auto rows = testing::read_csv(path);
    ASSERT_EQ(rows.size(), 4u);
    ASSERT_EQ(rows[0].size(), 2u + 2 * 12);
    EXPECT_EQ(rows[0][0], "step");
    EXPECT_EQ(rows[0][1], "time");
    EXPECT_EQ(rows[0][2], "a,b.ux");
    EXPECT_EQ(rows[0][13], "a,b.reaction_avg_y");
    EXPECT_EQ(rows[0][14], "a,b/left.ux");
    EXPECT_EQ(rows[0][22], "a,b/left.reaction_x");
    for (size_t k = 1; k < rows.size(); ++k)
        EXPECT_EQ(rows[k].size(), rows[0].size());
    std::vector<SetValues> v(2);
    r.evaluate(m, s, acc, v.data());
    EXPECT_EQ(std::strtod(rows[3][1].c_str(), nullptr), s.time);
    EXPECT_EQ(std::strtod(rows[3][2].c_str(), nullptr), v[0].u.x);
    EXPECT_EQ(std::strtod(rows[3][22].c_str(), nullptr), v[1].reaction.x);
    EXPECT_EQ(std::strtod(rows[3][24].c_str(), nullptr), v[1].reaction_avg.x);
    EXPECT_NE(v[1].reaction.x, 0.0);  // the support holds the node against the moving body
}

}  // namespace
}  // namespace fdem
