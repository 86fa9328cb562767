// Exact (correctly rounded) summation of doubles: a small superaccumulator (theory §4.4, spec
// parallel-and-python.md D8.2; after R. M. Neal, "Fast exact summation using small and large
// superaccumulators", arXiv:1505.05571).
//
// Every finite double is an integer multiple of 2^-1074. ExactSum keeps the running sum as that
// integer, in 67 signed 64-bit words of 32-bit digits (word k weighs 2^(32 k - 1074)), so adding
// is exact and the order of the additions cannot change the result: the sum of the same terms is
// bitwise the same however they are split over threads (or, later, processes) and merged.
// value() rounds the exact sum once, to nearest with ties to even. Non-finite terms make the
// result their naive sum (inf, -inf or NaN).
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>

namespace fdem {

class ExactSum {
public:
    static constexpr int kWords = 67;
    /// adds between carry propagations: a word takes at most 2^53 per add, so 512 adds stay far
    /// below 2^63 on top of a normalised digit (< 2^32)
    static constexpr int kCarryEvery = 512;

    /// Add x exactly: two integer additions (the 53-bit mantissa shifted into place spans at
    /// most two 32-bit digits, the upper part kept whole in the 64-bit word).
    void add(double x) {
        const uint64_t bits = std::bit_cast<uint64_t>(x);
        if ((bits << 1) == 0)
            return;  // +-0 adds nothing (most energy partials of a step
                     // without need_energy are zeros)
        int e = static_cast<int>((bits >> 52) & 0x7FF);
        uint64_t mant = bits & ((uint64_t{1} << 52) - 1);
        if (e == 0x7FF) {  // inf or NaN
            special_ += x;
            has_special_ = true;
            return;
        }
        if (e == 0) {
            e = 1;  // subnormal
        } else {
            mant |= uint64_t{1} << 52;
        }
        // x = ±mant 2^(e - 1075) = ±mant 2^p units of 2^-1074, p = e - 1 in [0, 2045]
        const int p = e - 1;
        const int w = p >> 5;
        const int s = p & 31;
        const int64_t lo = static_cast<int64_t>((mant << s) & 0xFFFFFFFFu);
        const int64_t hi = static_cast<int64_t>(mant >> (32 - s));
        const int64_t neg = static_cast<int64_t>(bits) >> 63;  // 0 or -1
        word_[w] += (lo ^ neg) - neg;
        word_[w + 1] += (hi ^ neg) - neg;
        if (++adds_ >= kCarryEvery) carry();
    }

    /// Add another exact sum (associative and commutative, like add()).
    void add(const ExactSum& o) {
        carry();
        for (int k = 0; k < kWords; ++k)
            word_[k] += o.word_[k];
        adds_ = o.adds_ + 1;  // the normalised digits count as one add
        if (adds_ >= kCarryEvery) carry();
        if (o.has_special_) {
            special_ += o.special_;
            has_special_ = true;
        }
    }

    void clear() { *this = ExactSum{}; }

    /// The exact sum rounded to the nearest double, ties to even; +0 for an exact zero; ±inf on
    /// overflow; the naive sum of the non-finite terms if there were any.
    double value() const;

    /// Normalised digits (word 0 .. 65 in [0, 2^32), word 66 signed): equal sums give equal
    /// words, so checkpoints save them and compare them bitwise.
    void normalise() { carry(); }
    const int64_t* words() const { return word_; }
    bool has_special() const { return has_special_; }
    double special() const { return special_; }
    /// Restore from words() / has_special() / special() (checkpoints); the words need not be
    /// normalised.
    void assign(const int64_t* words, bool has_special, double special) {
        std::memcpy(word_, words, sizeof(word_));
        has_special_ = has_special;
        special_ = has_special ? special : 0.0;
        adds_ = kCarryEvery;  // unknown history: normalise before the next add can overflow
        carry();
    }

    friend bool operator==(const ExactSum& a, const ExactSum& b);

private:
    void carry() {
        for (int k = 0; k + 1 < kWords; ++k) {
            const int64_t c = word_[k] >> 32;  // floor(word / 2^32)
            word_[k] -= static_cast<int64_t>(static_cast<uint64_t>(c) << 32);
            word_[k + 1] += c;
        }
        adds_ = 0;
    }

    int64_t word_[kWords] = {};
    int32_t adds_ = 0;
    bool has_special_ = false;
    double special_ = 0.0;
};

/// The correctly rounded sum of n doubles (any order gives the same bits).
double exact_sum(const double* x, long n);

}  // namespace fdem
