#include <project/splat/splat_kernel.h>

#include <cmath>
#include <numbers>

namespace tr {

std::string_view splat_kernel_name(SplatKernel kernel) {
    return kernel == SplatKernel::kCrawfisMax ? "crawfis-max" : "gaussian";
}

double splat_kernel(SplatKernel kernel, double r) {
    if (kernel == SplatKernel::kCrawfisMax) {
        if (r <= kCrawfisMaxS) return 0.557526 - 1.157743 * r * r + 0.671033 * r * r * r;
        if (r <= kCrawfisMaxT) {
            const double d = kCrawfisMaxT - r;
            return 0.067599 * d * d + 0.282474 * d * d * d;
        }
        return 0.0;
    }
    if (r >= kGaussianSupport) return 0.0;
    const double norm = std::pow(kGaussianSigma * std::sqrt(std::numbers::pi), 3);
    return std::exp(-r * r / (kGaussianSigma * kGaussianSigma)) / norm;
}

double splat_kernel_support(SplatKernel kernel) {
    return kernel == SplatKernel::kCrawfisMax ? kCrawfisMaxT : kGaussianSupport;
}

double splat_lattice_sum(SplatKernel kernel, const Vec3& x) {
    const double support = splat_kernel_support(kernel);
    double sum = 0.0;
    for (int i = static_cast<int>(std::floor(x.x - support));
         i <= static_cast<int>(std::ceil(x.x + support)); ++i) {
        for (int j = static_cast<int>(std::floor(x.y - support));
             j <= static_cast<int>(std::ceil(x.y + support)); ++j) {
            for (int k = static_cast<int>(std::floor(x.z - support));
                 k <= static_cast<int>(std::ceil(x.z + support)); ++k) {
                sum += splat_kernel(kernel, glm::length(x - Vec3(i, j, k)));
            }
        }
    }
    return sum;
}

double SplatFootprint::integrate(SplatKernel kernel, double rho) {
    const double support = splat_kernel_support(kernel);
    if (!(rho < support)) return 0.0;
    // f(rho) = 2 * integral over w in [0, sqrt(support^2 - rho^2)] of h(sqrt(rho^2 + w^2)). The
    // cubic has a kink in r at s: split there so each piece is smooth for Simpson's rule.
    const double w_max = std::sqrt(support * support - rho * rho);
    auto piece = [&](double a, double b) {
        constexpr int kIntervals = 2048;  // even
        const double step = (b - a) / kIntervals;
        double sum = 0.0;
        for (int i = 0; i <= kIntervals; ++i) {
            const double w = a + i * step;
            const double weight = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 ? 4.0 : 2.0);
            sum += weight * splat_kernel(kernel, std::sqrt(rho * rho + w * w));
        }
        return sum * step / 3.0;
    };
    double total;
    if (kernel == SplatKernel::kCrawfisMax && rho < kCrawfisMaxS) {
        const double w_kink = std::sqrt(kCrawfisMaxS * kCrawfisMaxS - rho * rho);
        total = piece(0.0, w_kink) + piece(w_kink, w_max);
    } else {
        total = piece(0.0, w_max);
    }
    return 2.0 * total;
}

SplatFootprint::SplatFootprint(SplatKernel kernel, int samples)
    : kernel_(kernel), support_(splat_kernel_support(kernel)) {
    const int n = std::max(samples, 2);
    scale_ = (n - 1) / support_;
    table_.resize(static_cast<std::size_t>(n) + 1, 0.0);  // one 0 past the support
    for (int i = 0; i < n; ++i) table_[static_cast<std::size_t>(i)] = integrate(kernel, i / scale_);
    const double squared_scale = (n - 1) / (support_ * support_);
    squared_scale_ = static_cast<float>(squared_scale);
    squared_last_ = static_cast<float>(n - 1);
    squared_table_.resize(static_cast<std::size_t>(n) + 1, 0.0f);
    for (int i = 0; i < n; ++i) {
        squared_table_[static_cast<std::size_t>(i)] =
            static_cast<float>(integrate(kernel, std::sqrt(i / squared_scale)));
    }
}

}  // namespace tr
