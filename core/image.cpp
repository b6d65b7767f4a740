#include <core/image.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tr {

std::vector<std::uint8_t> to_rgb8(const Image& image) {
    std::vector<std::uint8_t> out(image.pixels.size() * 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const float v = std::clamp(image.pixels[i][c], 0.0f, 1.0f);
            out[3 * i + c] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
        }
    }
    return out;
}

double psnr(const Image& a, const Image& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const double d = static_cast<double>(a.pixels[i][c]) - b.pixels[i][c];
            sum += d * d;
        }
    }
    const double mse = sum / (3.0 * static_cast<double>(a.pixels.size()));
    if (mse == 0.0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(1.0 / mse);
}

double max_abs_difference(const Image& a, const Image& b) {
    double m = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            m = std::max(m, std::abs(static_cast<double>(a.pixels[i][c]) - b.pixels[i][c]));
        }
    }
    return m;
}

}  // namespace tr
