#pragma once
// exp(x) for x <= 0 in single precision, branch-free and without a table, so that a loop over
// arrays of it vectorises (GCC and Clang, in a file compiled with -fno-trapping-math: the clamp
// below is a comparison the compiler may otherwise not turn into a select). Cephes' expf:
// x = n ln 2 + r with |r| <= ln(2) / 2, e^r by a degree-7 polynomial, 2^n by the exponent bits.
// Relative error below 1e-7 over [-87, 0] (1 - exp_nonpositive(x) within 5e-8 of 1 - e^x;
// measured in tests/core/fast_exp_test.cpp); x below -87 (or NaN) gives e^-87, 1.6e-38.
// exp_bounded: the same for x up to 87 as well.

#include <bit>
#include <cstdint>

namespace tr {

namespace detail {

// e^x for |x| <= 87 (unchecked).
inline float exp_core(float x) {
    const float t = x * 1.44269504f;                              // x / ln 2
    const float n = (t + 12582912.0f) - 12582912.0f;              // rounded to the nearest integer
    const float r = (x - n * 0.693359375f) + n * 2.12194440e-4f;  // x - n ln 2, in two parts
    float p = 1.9875691500e-4f;
    p = p * r + 1.3981999507e-3f;
    p = p * r + 8.3334519073e-3f;
    p = p * r + 4.1665795894e-2f;
    p = p * r + 1.6666665459e-1f;
    p = p * r + 5.0000001201e-1f;
    const float e = p * r * r + r + 1.0f;
    return e * std::bit_cast<float>(static_cast<std::uint32_t>(static_cast<int>(n) + 127) << 23);
}

}  // namespace detail

inline float exp_nonpositive(float x) { return detail::exp_core(x > -87.0f ? x : -87.0f); }

// e^x for x in [-87, 87] (beyond: e^-87 or e^87; NaN: e^-87), as exp_nonpositive.
inline float exp_bounded(float x) {
    x = x > -87.0f ? x : -87.0f;
    return detail::exp_core(x < 87.0f ? x : 87.0f);
}

}  // namespace tr
