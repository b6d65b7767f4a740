#include <core/check.h>
#include <project/splat/splat_stamps.h>

#include <algorithm>
#include <cmath>

namespace tr {
namespace {

// The stamp side for a support of `radius` pixels: columns reach - floor(radius) ... reach +
// floor(radius) + 1 hold every pixel within the radius of a centre offset by [0, 1]; rounded up
// to a multiple of 8 (the row loops' whole vectors).
int stamp_width(double radius) { return (2 * static_cast<int>(std::floor(radius)) + 4 + 7) & ~7; }

}  // namespace

bool SplatStamps::fits(const SplatFootprint& footprint, double pixels_per_unit) {
    const double radius = footprint.support() * pixels_per_unit;
    return pixels_per_unit >= kResolution / kMaxSteps && radius < kMaxWidth &&
           stamp_width(radius) <= kMaxWidth;
}

SplatStamps::SplatStamps(const SplatFootprint& footprint, double pixels_per_unit) {
    TR_CHECK(fits(footprint, pixels_per_unit));
    const double radius = footprint.support() * pixels_per_unit;
    reach_ = static_cast<int>(std::floor(radius)) + 1;
    width_ = stamp_width(radius);
    steps_ = std::clamp(static_cast<int>(std::ceil(kResolution / pixels_per_unit)), 1, kMaxSteps);
    const int offsets = steps_ + 1;
    samples_.assign(static_cast<std::size_t>(offsets) * offsets * area(), 0.0f);
    // Per stamp: its rows' non-zero columns [from, to).
    std::vector<short> from(static_cast<std::size_t>(offsets) * offsets * width_);
    std::vector<short> to(from.size());
    for (int j = 0; j < offsets; ++j) {
        for (int i = 0; i < offsets; ++i) {
            const std::size_t stamp = static_cast<std::size_t>(j) * offsets + i;
            float* s = samples_.data() + stamp * area();
            for (int v = 0; v < width_; ++v) {
                const double dy =
                    ((v - reach_) - static_cast<double>(j) / steps_) / pixels_per_unit;
                int first = width_, last = -1;
                for (int u = 0; u < width_; ++u) {
                    const double dx =
                        ((u - reach_) - static_cast<double>(i) / steps_) / pixels_per_unit;
                    const float f = footprint.of_squared(static_cast<float>(dx * dx + dy * dy));
                    s[static_cast<std::size_t>(v) * width_ + u] = f;
                    if (f != 0.0f) first = std::min(first, u), last = u;
                }
                from[stamp * width_ + v] = static_cast<short>(first);
                to[stamp * width_ + v] = static_cast<short>(last + 1);
            }
        }
    }
    peak_ = *std::max_element(samples_.begin(), samples_.end());
    // Per pair of row offsets (j, j + 1) and row: the union over every column offset.
    span_from_.assign(static_cast<std::size_t>(steps_) * width_, static_cast<short>(width_));
    span_to_.assign(span_from_.size(), 0);
    for (int j = 0; j < steps_; ++j) {
        for (int v = 0; v < width_; ++v) {
            short& lo = span_from_[static_cast<std::size_t>(j) * width_ + v];
            short& hi = span_to_[static_cast<std::size_t>(j) * width_ + v];
            for (int jj = j; jj <= j + 1; ++jj) {
                for (int i = 0; i < offsets; ++i) {
                    const std::size_t row =
                        (static_cast<std::size_t>(jj) * offsets + i) * width_ + v;
                    if (from[row] < to[row]) {
                        lo = std::min(lo, from[row]), hi = std::max(hi, to[row]);
                    }
                }
            }
            if (lo >= hi) lo = hi = 0;
        }
    }
}

SplatStamps::Placement SplatStamps::place(double cx, double cy) const {
    const double px = cx - 0.5, py = cy - 0.5;
    const double fx = std::floor(px), fy = std::floor(py);
    const double tx = (px - fx) * steps_, ty = (py - fy) * steps_;
    const int i = std::min(static_cast<int>(tx), steps_ - 1);
    const int j = std::min(static_cast<int>(ty), steps_ - 1);
    const auto wx = static_cast<float>(tx - i), wy = static_cast<float>(ty - j);
    const int offsets = steps_ + 1;
    auto stamp = [&](int a, int b) {
        return samples_.data() + (static_cast<std::size_t>(b) * offsets + a) * area();
    };
    Placement p;
    p.x0 = static_cast<int>(fx) - reach_;
    p.y0 = static_cast<int>(fy) - reach_;
    p.stamp[0] = stamp(i, j), p.stamp[1] = stamp(i + 1, j);
    p.stamp[2] = stamp(i, j + 1), p.stamp[3] = stamp(i + 1, j + 1);
    p.weight[0] = (1 - wx) * (1 - wy), p.weight[1] = wx * (1 - wy);
    p.weight[2] = (1 - wx) * wy, p.weight[3] = wx * wy;
    p.span_from = span_from_.data() + static_cast<std::size_t>(j) * width_;
    p.span_to = span_to_.data() + static_cast<std::size_t>(j) * width_;
    return p;
}

}  // namespace tr
