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

ImageComparison compare_images(const Image& actual, const Image& expected,
                               const Vec3f& background) {
    ImageComparison c;
    double sum_all = 0.0, sum_fg = 0.0;
    constexpr float kHalfLevel = 0.5f / 255.0f;
    auto level = [](float v) {
        return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
    };
    for (std::size_t i = 0; i < actual.pixels.size(); ++i) {
        const Vec3f& a = actual.pixels[i];
        const Vec3f& e = expected.pixels[i];
        bool foreground = false;
        double sum = 0.0;
        int levels = 0;
        for (int k = 0; k < 3; ++k) {
            foreground = foreground || std::abs(a[k] - background[k]) > kHalfLevel ||
                         std::abs(e[k] - background[k]) > kHalfLevel;
            const double d = static_cast<double>(a[k]) - e[k];
            sum += d * d;
            if (std::abs(d) > c.max_difference) {
                c.max_difference = std::abs(d);
                c.worst_x = static_cast<int>(i % static_cast<std::size_t>(actual.width));
                c.worst_y = static_cast<int>(i / static_cast<std::size_t>(actual.width));
            }
            levels = std::max(levels, std::abs(level(a[k]) - level(e[k])));
        }
        c.max_levels = std::max(c.max_levels, levels);
        c.pixels_off_by_more_than_one_level += levels > 1;
        sum_all += sum;
        if (foreground) {
            sum_fg += sum;
            ++c.foreground_pixels;
        }
    }
    auto db = [](double sum, std::size_t n) {
        if (n == 0 || sum == 0.0) return std::numeric_limits<double>::infinity();
        return 10.0 * std::log10(3.0 * static_cast<double>(n) / sum);
    };
    c.psnr_all = db(sum_all, actual.pixels.size());
    c.psnr_foreground = db(sum_fg, c.foreground_pixels);
    return c;
}

}  // namespace tr
