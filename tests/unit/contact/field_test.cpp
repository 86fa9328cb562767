// T1 (spec §8): barycentric coordinates (paper eq. 4) and the distance-field gradient (eq. 8)
// on random triangles of both orientations, against identities and central finite differences.
#include <gtest/gtest.h>

#include <random>

#include "contact/field.hpp"

namespace fdem {
namespace {

TEST(ContactField, BarycentricPartitionOfUnityAndReproduction) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<Real> u(-1, 1);
    for (int trial = 0; trial < 1000; ++trial) {
        const Vec2 p[3] = {{u(rng), u(rng)}, {u(rng), u(rng)}, {u(rng), u(rng)}};
        if (std::abs(signed_area(p[0], p[1], p[2])) < 1e-3) continue;
        const Vec2 x{u(rng), u(rng)};
        Real N[3];
        ASSERT_TRUE(barycentric(p[0], p[1], p[2], x, N));
        // 1e-10: a few ulps amplified by 1/A with A >= 1e-3 and coordinates O(1)
        EXPECT_NEAR(N[0] + N[1] + N[2], 1.0, 1e-10);
        const Vec2 y = N[0] * p[0] + N[1] * p[1] + N[2] * p[2];
        EXPECT_NEAR(y.x, x.x, 1e-10);
        EXPECT_NEAR(y.y, x.y, 1e-10);
    }
}

TEST(ContactField, GradientMatchesFiniteDifferencesBothOrientations) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<Real> u(-1, 1), ud(0, 0.5);
    int checked = 0;
    for (int trial = 0; trial < 1000; ++trial) {
        Vec2 p[3] = {{u(rng), u(rng)}, {u(rng), u(rng)}, {u(rng), u(rng)}};
        if (std::abs(signed_area(p[0], p[1], p[2])) < 1e-2) continue;
        if (trial % 2) std::swap(p[1], p[2]);  // both orientations
        const Real dist[3] = {ud(rng), ud(rng), ud(rng)};
        const Vec2 x{u(rng), u(rng)};
        auto field = [&](Vec2 y) {
            FieldSample fs;
            barycentric(p[0], p[1], p[2], y, fs.N);
            smooth_field(p, dist, fs);
            return fs;
        };
        const FieldSample fs = field(x);
        const Real h = 1e-6;
        const Real gx = (field({x.x + h, x.y}).d - field({x.x - h, x.y}).d) / (2 * h);
        const Real gy = (field({x.x, x.y + h}).d - field({x.x, x.y - h}).d) / (2 * h);
        // d is affine, so the central difference is exact up to round-off ~ eps d / h
        const Real scale = std::max(1.0, norm(fs.grad));
        EXPECT_NEAR(fs.grad.x, gx, 1e-8 * scale);
        EXPECT_NEAR(fs.grad.y, gy, 1e-8 * scale);
        // eq. 8 with eqs. 9-10: grad d = -(n1 d1 + n2 d2 + n3 d3) / (2A), o = sign(A) e_z
        const Real A = signed_area(p[0], p[1], p[2]);
        const Real o = A > 0 ? 1.0 : -1.0;
        Vec2 sum;
        for (int i = 0; i < 3; ++i) {
            const Vec2 e = p[(i + 2) % 3] - p[(i + 1) % 3];  // x_k - x_j
            const Vec2 n{e.y * o, -e.x * o};                 // (x_k - x_j) x o
            sum += dist[i] * n;
        }
        const Vec2 g8 = -1.0 / (2 * std::abs(A)) * sum;
        EXPECT_NEAR(fs.grad.x, g8.x, 1e-10 * scale);
        EXPECT_NEAR(fs.grad.y, g8.y, 1e-10 * scale);
        ++checked;
    }
    EXPECT_GT(checked, 500);
}

}  // namespace
}  // namespace fdem
