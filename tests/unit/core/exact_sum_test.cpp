// ExactSum (theory §4.4, spec parallel-and-python.md T10): correctly rounded against an
// independent reference (Shewchuk's non-overlapping expansions with the final rounding of
// CPython's math.fsum), and bitwise independent of order and of how the terms are split.
#include "fdem/exact_sum.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace fdem {
namespace {

uint64_t bits(double x) {
    return std::bit_cast<uint64_t>(x);
}

// CPython's math_fsum (Modules/mathmodule.c, after Shewchuk 1997): partials are a
// non-overlapping expansion of the exact sum; the last step rounds it half-even. Valid while no
// partial overflows (the tests keep |terms| <= 2^1000 there).
double reference_fsum(const std::vector<double>& xs) {
    std::vector<double> p;
    for (double x : xs) {
        size_t i = 0;
        for (double y : p) {
            if (std::fabs(x) < std::fabs(y)) std::swap(x, y);
            const double hi = x + y;
            const double lo = y - (hi - x);
            if (lo != 0.0) p[i++] = lo;
            x = hi;
        }
        p.resize(i);
        p.push_back(x);
    }
    double hi = 0.0;
    if (!p.empty()) {
        size_t n = p.size();
        hi = p[--n];
        double lo = 0;
        while (n > 0) {
            const double x = hi;
            const double y = p[--n];
            hi = x + y;
            const double yr = hi - x;
            lo = y - yr;
            if (lo != 0.0) break;
        }
        if (n > 0 && ((lo < 0.0 && p[n - 1] < 0.0) || (lo > 0.0 && p[n - 1] > 0.0))) {
            const double y = lo * 2.0;
            const double x = hi + y;
            const double yr = x - hi;
            if (y == yr) hi = x;
        }
    }
    return hi;
}

double sum_of(const std::vector<double>& xs) {
    ExactSum s;
    for (double x : xs)
        s.add(x);
    return s.value();
}

TEST(ExactSum, SmallCasesAreCorrectlyRounded) {
    EXPECT_EQ(sum_of({}), 0.0);
    EXPECT_EQ(bits(sum_of({1.0, -1.0})), bits(0.0));
    EXPECT_EQ(sum_of({0.1, 0.2}), 0.1 + 0.2);  // one addition is correctly rounded
    EXPECT_EQ(sum_of({1e100, 1.0, -1e100}), 1.0);
    EXPECT_EQ(sum_of({1.0, 0x1p-53}), 1.0);                      // tie: to even (down)
    EXPECT_EQ(sum_of({1.0 + 0x1p-52, 0x1p-53}), 1.0 + 0x1p-51);  // tie: to even (up)
    EXPECT_EQ(sum_of({1.0, 0x1p-53, 0x1p-200}), 1.0 + 0x1p-52);  // just above the tie: up
    EXPECT_EQ(sum_of({1.0, 0x1p-53, -0x1p-200}), 1.0);           // just below: down
    EXPECT_EQ(sum_of({-1.0, -0x1p-53, -0x1p-200}), -1.0 - 0x1p-52);
    // subnormals and the smallest normal
    EXPECT_EQ(sum_of({0x1p-1074, 0x1p-1074}), 0x1p-1073);
    EXPECT_EQ(sum_of({DBL_MIN, -0x1p-1074}), DBL_MIN - 0x1p-1074);
    EXPECT_EQ(sum_of({0x1p-1022, 0x1p-1074, 0x1p-1074, 0x1p-1074}), 0x1p-1022 + 0x1.8p-1073);
    // range: the intermediate 2 DBL_MAX does not overflow, the final overflow gives inf
    EXPECT_EQ(sum_of({DBL_MAX, DBL_MAX, -DBL_MAX}), DBL_MAX);
    EXPECT_EQ(sum_of({DBL_MAX, DBL_MAX}), INFINITY);
    EXPECT_EQ(sum_of({-DBL_MAX, -DBL_MAX}), -INFINITY);
    EXPECT_EQ(sum_of({DBL_MAX, 0x1p-1074, -DBL_MAX}), 0x1p-1074);
    // non-finite terms
    EXPECT_EQ(sum_of({1.0, INFINITY}), INFINITY);
    EXPECT_TRUE(std::isnan(sum_of({INFINITY, -INFINITY, 1.0})));
    EXPECT_TRUE(std::isnan(sum_of({NAN, 1.0})));
}

TEST(ExactSum, CarriesSurviveManyLargeTerms) {
    // 10^5 terms of the largest mantissa at one exponent: many carry propagations
    const double big = 0x1.fffffffffffffp+500;
    std::vector<double> xs(100000, big);
    for (size_t i = 0; i < xs.size(); i += 2)
        xs[i] = -big;
    xs.push_back(3.0);
    EXPECT_EQ(sum_of(xs), 3.0);
    std::vector<double> pos(100000, 1.0 + 0x1p-52);
    EXPECT_EQ(sum_of(pos), reference_fsum(pos));
}

// Random terms with heavy cancellation over a wide exponent range, as in T10.
std::vector<double> random_terms(uint64_t seed, size_t n, int max_exp) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> mant(-1.0, 1.0);
    std::uniform_int_distribution<int> ex(-max_exp, max_exp);
    std::vector<double> xs;
    xs.reserve(n);
    while (xs.size() < n) {
        const double x = std::ldexp(mant(rng), ex(rng));
        xs.push_back(x);
        if (xs.size() < n && (rng() & 3) == 0) xs.push_back(-x);  // exact cancellation
    }
    return xs;
}

TEST(ExactSum, MatchesTheReferenceOnRandomTerms) {
    for (uint64_t seed = 1; seed <= 40; ++seed) {
        const int max_exp = seed % 2 ? 60 : 1000;
        const std::vector<double> xs = random_terms(seed, 2000, max_exp);
        EXPECT_EQ(bits(sum_of(xs)), bits(reference_fsum(xs))) << "seed " << seed;
    }
    // sums that end in the subnormal range
    for (uint64_t seed = 41; seed <= 50; ++seed) {
        std::vector<double> xs = random_terms(seed, 500, 20);
        for (double& x : xs)
            x = std::ldexp(x, -1050);
        EXPECT_EQ(bits(sum_of(xs)), bits(reference_fsum(xs))) << "seed " << seed;
    }
}

// T10: 10^6 terms in 5 orders, split over 1-7 simulated ranks and merged: the same bits, equal
// to the reference.
TEST(ExactSum, SameBitsForAnyOrderAndSplit) {
    std::vector<double> xs = random_terms(2026, 1000000, 40);
    const double ref = reference_fsum(xs);
    std::mt19937_64 rng(7);
    for (int order = 0; order < 5; ++order) {
        std::shuffle(xs.begin(), xs.end(), rng);
        for (int ranks = 1; ranks <= 7; ++ranks) {
            std::vector<ExactSum> part(static_cast<size_t>(ranks));
            for (size_t i = 0; i < xs.size(); ++i)
                part[(i * 7919) % static_cast<size_t>(ranks)].add(xs[i]);
            ExactSum total;
            for (int r = ranks - 1; r >= 0; --r)
                total.add(part[static_cast<size_t>(r)]);
            EXPECT_EQ(bits(total.value()), bits(ref)) << "order " << order << " ranks " << ranks;
        }
    }
    // and the naive sum is not order independent on these terms (the test has teeth)
    double a = 0, b = 0;
    for (double x : xs)
        a += x;
    for (auto it = xs.rbegin(); it != xs.rend(); ++it)
        b += *it;
    EXPECT_NE(bits(a), bits(b));
}

TEST(ExactSum, WordsRoundTripAndCompare) {
    const std::vector<double> xs = random_terms(3, 5000, 300);
    ExactSum a, b;
    for (double x : xs)
        a.add(x);
    for (auto it = xs.rbegin(); it != xs.rend(); ++it)
        b.add(*it);
    EXPECT_TRUE(a == b);
    a.normalise();
    ExactSum c;
    c.assign(a.words(), a.has_special(), a.special());
    EXPECT_TRUE(c == a);
    EXPECT_EQ(bits(c.value()), bits(a.value()));
    c.add(0x1p-1074);
    EXPECT_FALSE(c == a);
}

}  // namespace
}  // namespace fdem
