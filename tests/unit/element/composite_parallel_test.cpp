// Parallel element pass with composite bodies (issue #7, element/cst.cpp schedule): chunks never
// split a composite, so the parallel pass is bitwise the same for 1 and 2 threads, including the
// strain energy, on a mix of a large composite body, small composite bodies and CST bodies.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>

#include "element/cst.hpp"
#include "fdem/simulate.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

Model mixed_model() {
    return scenes::make_mixed_element_model();
}

TEST(CompositeParallel, ForcesAndEnergyBitwiseEqualForOneAndTwoThreads) {
    const Model m = mixed_model();
    EXPECT_GE(m.element_schedule.num_chunks(), 32);
    auto run = [&](int threads, Real& energy) {
        omp_set_num_threads(threads);
        State s = make_state(m, 1e-6);
        for (size_t i = 0; i < s.x.size(); ++i)
            s.x[i] += 1e-4 * Vec2{std::sin(1.7 * i), std::cos(2.3 * i)};
        std::fill(s.f.begin(), s.f.end(), Vec2{});
        energy = add_internal_forces(m, s).strain_energy;
        return s.f;
    };
    Real e1 = 0, e2 = 0;
    const auto f1 = run(1, e1);
    const auto f2 = run(2, e2);
    omp_set_num_threads(2);
    EXPECT_EQ(e1, e2);
    EXPECT_GT(e1, 0);
    for (size_t i = 0; i < f1.size(); ++i) {
        ASSERT_EQ(f1[i].x, f2[i].x) << "node " << i;
        ASSERT_EQ(f1[i].y, f2[i].y) << "node " << i;
    }

    // and the parallel pass computes the serial loop's forces (up to the summation order of a
    // node shared by two chunks: 1e-9 relative to the largest force)
    State s = make_state(m, 1e-6);
    for (size_t i = 0; i < s.x.size(); ++i)
        s.x[i] += 1e-4 * Vec2{std::sin(1.7 * i), std::cos(2.3 * i)};
    std::vector<Vec2> fs(s.x.size());
    const ElementPass ps =
        add_internal_forces(m, s.x.data(), s.v.data(), fs.data(), 0, m.num_tris());
    Real fmax = 0;
    for (const Vec2& q : fs)
        fmax = std::max(fmax, norm(q));
    for (size_t i = 0; i < fs.size(); ++i)
        ASSERT_LT(norm(fs[i] - f1[i]), 1e-9 * fmax) << "node " << i;
    EXPECT_NEAR(ps.strain_energy, e1, 1e-12 * e1);
}

}  // namespace
}  // namespace fdem
