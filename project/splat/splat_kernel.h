#pragma once
// The reconstruction kernels of splatting (texture-mapping paper, 3.1) and their footprints.
//
// A field sampled on a lattice of unit spacing is reconstructed as W(x) = sum_i h(|x - i|) V(i)
// (the paper's equation 3) with a radially symmetric kernel h, so that one footprint
// f(rho) = integral of h(sqrt(rho^2 + w^2)) dw over the line (equation 5) serves every view
// direction. Kernels:
// - kCrawfisMax: the paper's piecewise cubic, optimised so that the lattice sum (equation 7) is
//   as constant as possible: h(r) = 0.557526 - 1.157743 r^2 + 0.671033 r^3 for r <= s,
//   0.067599 (t - r)^2 + 0.282474 (t - r)^3 for s <= r <= t, 0 beyond, with s = 0.889392 and
//   t = 1.556228.
// - kGaussian: Westover's exp(-r^2 / sigma^2) with sigma = kGaussianSigma, divided by its
//   integral (sigma sqrt(pi))^3 and cut at kGaussianSupport.
//
// Normalisation: neither kernel sums to exactly 1 over the lattice (no radially symmetric kernel
// can). Their integrals over space are 1 (the Crawfis-Max cubic as published, to 1e-6; the
// Gaussian by construction, less what the cut drops), so the lattice sum averages 1 over a cell
// and a constant field reconstructs as that constant times the sum, whose ripple is measured in
// tests/splat/splat_kernel_test.cpp and stated in docs/benchmarks.md.

#include <core/math.h>

#include <algorithm>
#include <string_view>
#include <vector>

namespace tr {

enum class SplatKernel { kCrawfisMax, kGaussian };

inline constexpr double kCrawfisMaxS = 0.889392;
inline constexpr double kCrawfisMaxT = 1.556228;
inline constexpr double kGaussianSigma = 0.8;
inline constexpr double kGaussianSupport = 2.4;  // 3 sigma: the cut drops 4.4e-4 of the weight

std::string_view splat_kernel_name(SplatKernel kernel);  // "crawfis-max", "gaussian"

// h(r) at distance r >= 0 (lattice units).
double splat_kernel(SplatKernel kernel, double r);

// The radius beyond which h is 0.
double splat_kernel_support(SplatKernel kernel);

// The lattice sum (equation 7) at x: sum over every lattice point i within the support of
// h(|x - i|). Cost: O(support^3).
double splat_lattice_sum(SplatKernel kernel, const Vec3& x);

// The footprint f(rho) of a kernel, tabulated: `samples` values over [0, support] of the line
// integral (composite Simpson's rule, 2048 intervals, split at the cubic's kink), read back by
// linear interpolation; as many over [0, support^2] in rho^2. The table's own error is measured in
// tests/splat/splat_kernel_test.cpp (far below an 8-bit level with the default 1024 samples).
class SplatFootprint {
  public:
    explicit SplatFootprint(SplatKernel kernel, int samples = 1024);

    SplatKernel kernel() const { return kernel_; }
    double support() const { return support_; }

    // f(rho) from the table; 0 at and beyond the support.
    double operator()(double rho) const {
        const double x = rho * scale_;
        if (!(x < static_cast<double>(table_.size() - 1))) return 0.0;
        const auto i = static_cast<std::size_t>(x);
        const double f = x - static_cast<double>(i);
        return table_[i] + f * (table_[i + 1] - table_[i]);
    }

    // f(rho) at q = rho^2 from a second table, uniform in q and in float (the orthographic
    // raster's inner loop: no square root); 0 at and beyond support^2. Its error is measured
    // beside the first's.
    float of_squared(float q) const {
        const float x = q * squared_scale_;
        if (!(x < static_cast<float>(squared_table_.size() - 1))) return 0.0f;
        const auto i = static_cast<std::size_t>(x);
        const float f = x - static_cast<float>(i);
        return squared_table_[i] + f * (squared_table_[i + 1] - squared_table_[i]);
    }

    // of_squared without the test for q beyond the support, for q in [0, support^2] up to
    // rounding (clamped there): the raster's inner loop, which stays inside the support's circle.
    float of_squared_inside(float q) const {
        const float x = std::min(q * squared_scale_, squared_last_);
        const int i = static_cast<int>(x);  // x >= 0; int: one instruction, no sign branch
        const float f = x - static_cast<float>(i);
        const float* entry = squared_table_.data() + i;
        return entry[0] + f * (entry[1] - entry[0]);
    }

    // The rho^2 table as of_squared_inside reads it: its samples, index per unit of rho^2, and
    // the index of support^2 (for loops that inline the lookup).
    const float* squared_table() const { return squared_table_.data(); }
    float squared_scale() const { return squared_scale_; }
    float squared_last() const { return squared_last_; }

    // f(rho) by direct quadrature (what the tables hold at their samples).
    static double integrate(SplatKernel kernel, double rho);

  private:
    SplatKernel kernel_;
    double support_;
    double scale_;  // table index per unit of rho
    std::vector<double> table_;
    float squared_scale_;  // squared_table_ index per unit of rho^2
    float squared_last_;   // the index of support^2
    std::vector<float> squared_table_;
};

}  // namespace tr
