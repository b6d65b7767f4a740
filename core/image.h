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

// How far `actual` is from `expected` over the pixels that matter: the foreground, where either
// picture differs from `background` by more than half an 8-bit level in some channel (so a
// picture that misses the volume, or draws where there is none, is judged on those pixels too).
struct ImageComparison {
    double psnr_all = 0;         // dB over every pixel (infinity when equal)
    double psnr_foreground = 0;  // dB over the foreground (infinity when equal or empty)
    double max_difference = 0;   // largest absolute channel difference anywhere
    int max_levels = 0;          // largest difference in 8-bit levels after rounding each picture
    std::size_t foreground_pixels = 0;
    std::size_t pixels_off_by_more_than_one_level = 0;  // after rounding to 8 bits
    int worst_x = -1, worst_y = -1;                     // where max_difference is
};

// Precondition: same size. Cost: O(pixels).
ImageComparison compare_images(const Image& actual, const Image& expected, const Vec3f& background);

}  // namespace tr
