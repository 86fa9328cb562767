// max_speed2() (contact/contact.cpp, the skin trigger's speed, spec §2.3): the SSE2 maxima over
// two nodes at a time must give the bits of the plain ordered maximum std::max(m, |v|^2), NaN
// skipped, for any run boundaries (the distributed step passes a process's node runs).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "contact/contact.hpp"
#include "support/topology_compare.hpp"

namespace fdem {
namespace {

Real reference(const std::vector<Vec2>& v, const std::vector<std::pair<NodeId, NodeId>>& runs) {
    Real m = 0;
    for (const auto& [b, e] : runs) {
        for (NodeId i = b; i < e; ++i)
            m = std::max(m, v[static_cast<size_t>(i)].x * v[static_cast<size_t>(i)].x +
                                v[static_cast<size_t>(i)].y * v[static_cast<size_t>(i)].y);
    }
    return m;
}

using fdem::testing::same_bits;

TEST(MaxSpeed2, TheBitsOfTheOrderedMaximumForAnyRuns) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<Real> u(-3.0, 3.0);
    const NodeId n = 1001;
    std::vector<Vec2> v(static_cast<size_t>(n));
    for (Vec2& a : v)
        a = {u(rng), u(rng)};
    // special values: NaN (skipped), infinity (wins), -0 and subnormals
    v[17] = {std::numeric_limits<Real>::quiet_NaN(), 1.0};
    v[500] = {-0.0, -0.0};
    v[501] = {std::numeric_limits<Real>::denorm_min(), 0.0};
    const std::vector<std::vector<std::pair<NodeId, NodeId>>> cases = {
        {{0, n}}, {{0, 3}}, {{5, 6}}, {{1, 1000}}, {{0, 4}, {7, 8}, {9, 1001}}, {}, {{17, 18}}};
    for (const auto& runs : cases) {
        const Real got = max_speed2(v.data(), runs), want = reference(v, runs);
        EXPECT_TRUE(same_bits(got, want)) << got << " vs " << want;
    }
    // the largest node moved around every position of a 4-node block and the tail
    const std::vector<std::pair<NodeId, NodeId>> all = {{0, n}}, nine = {{0, 9}};
    for (NodeId at = 990; at < n; ++at) {
        std::vector<Vec2> w = v;
        w[static_cast<size_t>(at)] = {4.0, 4.0};
        EXPECT_EQ(max_speed2(w.data(), all), 32.0) << "at " << at;
    }
    v[600] = {std::numeric_limits<Real>::infinity(), 0.0};
    EXPECT_EQ(max_speed2(v.data(), all), std::numeric_limits<Real>::infinity());
    // all NaN: zero, as the ordered maximum from 0
    std::vector<Vec2> nan(9, Vec2{std::numeric_limits<Real>::quiet_NaN(), 0.0});
    EXPECT_TRUE(same_bits(max_speed2(nan.data(), nine), 0.0));
}

}  // namespace
}  // namespace fdem
