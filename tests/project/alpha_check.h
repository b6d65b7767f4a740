#pragma once
// What the renderers promise when asked for alpha (premultiplied RGBA for compositing across
// ranks), measured: the picture over anything behind (a background colour or an opaque layer's
// colour picture) is the picture over black plus (1 - alpha) times what is behind. Header-only,
// shared by the render, fused and pbvr tests.

#include <core/camera.h>
#include <core/image.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

namespace tr::testing {

struct AlphaCheck {
    // The largest |over_behind - (over_black + (1 - alpha) behind)| over pixels and channels.
    double largest_difference = 0;
    int worst_x = -1, worst_y = -1;
    float min_alpha = 1, max_alpha = 0;
    std::size_t pixels_transparent = 0;  // alpha exactly 0
    std::size_t pixels_partial = 0;      // 0.05 < alpha < 0.9
    std::size_t pixels_opaque = 0;       // alpha > 0.99
};

// Preconditions: the pictures the same size, alpha one per pixel (the caller asserts these).
inline AlphaCheck check_alpha(const Image& over_black, const std::vector<float>& alpha,
                              const Image& over_behind, const Image& behind) {
    AlphaCheck c;
    for (int y = 0; y < over_black.height; ++y) {
        for (int x = 0; x < over_black.width; ++x) {
            const float a = alpha[static_cast<std::size_t>(y) * over_black.width + x];
            c.min_alpha = std::min(c.min_alpha, a);
            c.max_alpha = std::max(c.max_alpha, a);
            c.pixels_transparent += a == 0.0f;
            c.pixels_partial += a > 0.05f && a < 0.9f;
            c.pixels_opaque += a > 0.99f;
            for (int k = 0; k < 3; ++k) {
                const double expected = static_cast<double>(over_black.at(x, y)[k]) +
                                        (1.0 - static_cast<double>(a)) * behind.at(x, y)[k];
                const double d = std::abs(static_cast<double>(over_behind.at(x, y)[k]) - expected);
                if (d > c.largest_difference) {
                    c.largest_difference = d;
                    c.worst_x = x, c.worst_y = y;
                }
            }
        }
    }
    return c;
}

// Whether a ray misses the box [lo, hi]^3 grown by `margin` on every side (slab test): where
// nothing can be drawn.
inline bool misses_box(const Ray& r, double lo, double hi, double margin) {
    double t0 = 0, t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (r.direction[a] == 0) {
            if (r.origin[a] < lo - margin || r.origin[a] > hi + margin) return true;
            continue;
        }
        double ta = (lo - margin - r.origin[a]) / r.direction[a];
        double tb = (hi + margin - r.origin[a]) / r.direction[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    }
    return t1 < t0;
}

inline bool bit_identical(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Vec3f)) == 0;
}

inline bool bit_identical(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace tr::testing
