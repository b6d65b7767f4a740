#pragma once
// Float RGB images (linear, row 0 at the top) and the comparisons the tests and tools use.

#include <core/math.h>

#include <cstdint>
#include <vector>

namespace tr {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<Vec3f> pixels;  // row-major, row 0 at the top

    Image() = default;
    Image(int w, int h, Vec3f fill = Vec3f(0.0f))
        : width(w), height(h), pixels(static_cast<std::size_t>(w) * h, fill) {}
    Vec3f& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
    const Vec3f& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
};

// 8-bit RGB, row-major from the top: each channel clamped to [0, 1], times 255, rounded.
std::vector<std::uint8_t> to_rgb8(const Image& image);

// Peak signal-to-noise ratio in dB over all channels with peak 1 (infinity when equal).
// Precondition: same size.
double psnr(const Image& a, const Image& b);

// Largest absolute channel difference. Precondition: same size.
double max_abs_difference(const Image& a, const Image& b);

}  // namespace tr
