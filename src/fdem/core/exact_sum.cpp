// Rounding of the exact sum (theory §4.4): see fdem/exact_sum.hpp.
#include "fdem/exact_sum.hpp"

#include <cmath>

namespace fdem {

namespace {

__extension__ typedef unsigned __int128 u128;  // GCC / Clang

// word k -= floor(word k / 2^32) 2^32, carried into word k + 1: digits 0 .. n-2 in [0, 2^32)
void normalise_words(int64_t* w, int n) {
    for (int k = 0; k + 1 < n; ++k) {
        const int64_t c = w[k] >> 32;
        w[k] -= static_cast<int64_t>(static_cast<uint64_t>(c) << 32);
        w[k + 1] += c;
    }
}

}  // namespace

double ExactSum::value() const {
    if (has_special_) return special_;
    // two zero digits below word 0 so that a three-digit window always exists
    constexpr int kPad = 2;
    int64_t w[kWords + kPad] = {};
    for (int k = 0; k < kWords; ++k)
        w[k + kPad] = word_[k];
    normalise_words(w, kWords + kPad);
    const bool negative = w[kWords + kPad - 1] < 0;
    if (negative) {  // round the magnitude, then negate (rounding to nearest is symmetric)
        for (int64_t& d : w)
            d = -d;
        normalise_words(w, kWords + kPad);
    }
    int h = kWords + kPad - 1;
    while (h >= kPad && w[h] == 0)
        --h;
    if (h < kPad) return 0.0;
    // the three leading digits: the sum is M 2^base units (2^-1074) plus a remainder below, which
    // only decides ties (sticky)
    const u128 m = (static_cast<u128>(static_cast<uint64_t>(w[h])) << 64) |
                   (static_cast<u128>(static_cast<uint64_t>(w[h - 1])) << 32) |
                   static_cast<u128>(static_cast<uint64_t>(w[h - 2]));
    bool sticky = false;
    for (int k = 0; k < h - 2; ++k)
        sticky = sticky || w[k] != 0;
    const int base = 32 * (h - 2 - kPad);
    const uint64_t top = static_cast<uint64_t>(m >> 64);
    const int lead = 64 + 63 - std::countl_zero(top);  // top != 0: w[h] is the leading digit
    const int lead_abs = base + lead;                  // position of the leading bit in units
    double r = 0;
    if (lead_abs < 53) {
        // below 2^53 units = 2^-1021: every such integer multiple of 2^-1074 is a double
        // (subnormal, or normal with <= 53 significant bits)
        const uint64_t units = static_cast<uint64_t>(m >> (-base));  // base < 0 here
        r = std::ldexp(static_cast<double>(units), -1074);
    } else {
        // keep 53 bits: the quantum of a normal double with this leading bit is 2^(lead_abs - 52)
        const int shift = lead - 52;  // >= 12: lead >= 64
        uint64_t q = static_cast<uint64_t>(m >> shift);
        const u128 rem = m & ((static_cast<u128>(1) << shift) - 1);
        const u128 half = static_cast<u128>(1) << (shift - 1);
        if (rem > half || (rem == half && (sticky || (q & 1)))) ++q;  // ties to even
        r = std::ldexp(static_cast<double>(q), base + shift - 1074);  // exact, or inf on overflow
    }
    return negative ? -r : r;
}

bool operator==(const ExactSum& a, const ExactSum& b) {
    ExactSum x = a, y = b;
    x.carry();
    y.carry();
    for (int k = 0; k < ExactSum::kWords; ++k) {
        if (x.word_[k] != y.word_[k]) return false;
    }
    if (x.has_special_ != y.has_special_) return false;
    return !x.has_special_ ||
           std::bit_cast<uint64_t>(x.special_) == std::bit_cast<uint64_t>(y.special_);
}

double exact_sum(const double* x, long n) {
    ExactSum s;
    for (long i = 0; i < n; ++i)
        s.add(x[i]);
    return s.value();
}

}  // namespace fdem
