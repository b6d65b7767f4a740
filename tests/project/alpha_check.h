#pragma once
// What the renderers promise when asked for alpha (premultiplied RGBA for compositing across
// ranks), measured: the picture over anything behind (a background colour or an opaque layer's
// colour picture) is the picture over black plus (1 - alpha) times what is behind, and asking for
// alpha changes no bit of the picture. Header-only, shared by the render, fused and pbvr tests.

#include <core/camera.h>
#include <core/image.h>
#include <mesh/surface_mesh.h>
#include <project/opaque_geometry.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
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

// The opaque plane the alpha tests tilt through their volumes: the square [lo, hi]^2 in x and y,
// at height z_lo where x = lo and z_hi where x = hi.
inline SurfaceMesh tilted_plane(double lo, double hi, double z_lo, double z_hi) {
    SurfaceMesh p;
    p.points = {{lo, lo, z_lo}, {hi, lo, z_hi}, {hi, hi, z_hi}, {lo, hi, z_lo}};
    p.triangles = {{0, 1, 2}, {0, 2, 3}};
    return p;
}

// Its opaque layer: the plane green over a grey background.
inline OpaqueLayer plane_layer(const SurfaceMesh& plane, const CameraFrame& frame) {
    return render_opaque({{&plane, Vec3(0.2, 0.9, 0.3)}}, frame, Vec3(0.4, 0.35, 0.3));
}

// The pixel (row-major index) whose square holds the projection of `point`.
inline std::size_t pixel_of(const CameraFrame& frame, const Vec3& point) {
    const Vec3 q = frame.project(point);
    return static_cast<std::size_t>(q.y) * frame.width() + static_cast<std::size_t>(q.x);
}

// What one alpha test renders and measures: alpha over black, and with the opaque layer's depth
// (alpha_cut); the picture over a background and over the layer's colour, each checked against
// the one over black (check_alpha).
struct AlphaRun {
    std::vector<float> alpha, alpha_cut;
    AlphaCheck over_background, over_layer;
    double largest_difference() const {
        return std::max(over_background.largest_difference, over_layer.largest_difference);
    }
};

// `render(background, opaque_depth, opaque_color, alpha)` draws the volumes over `background`,
// or over the opaque layer (its depth, and its colour when asked), and gives alpha when `alpha`
// is not null. Proves that alpha is the volumes' alone (the same bits over any background), that
// the picture over `background` and over `layer_color` composes from the one over black within
// `max_difference`, that alpha lies in [0, 1], and that partly transparent (over 200 pixels) and
// nearly opaque (over 100) pixels are both present. Prints the measured values tagged `tag`.
// A fatal failure (alpha not one per pixel) returns early: call it in ASSERT_NO_FATAL_FAILURE.
template <class Render>
void expect_alpha_composes(const std::string& tag, const Render& render, const Vec3& background,
                           const Image& layer_color, double max_difference, AlphaRun* run) {
    std::vector<float> alpha_b;
    const Image black = render(Vec3(0.0), false, false, &run->alpha);
    const Image over_b = render(background, false, false, &alpha_b);
    ASSERT_EQ(run->alpha.size(), black.pixels.size());
    EXPECT_TRUE(bit_identical(run->alpha, alpha_b));
    run->over_background =
        check_alpha(black, run->alpha, over_b, Image(black.width, black.height, Vec3f(background)));
    const Image black_cut = render(Vec3(0.0), true, false, &run->alpha_cut);
    const Image over_layer = render(Vec3(0.0), true, true, nullptr);
    run->over_layer = check_alpha(black_cut, run->alpha_cut, over_layer, layer_color);
    const AlphaCheck &c = run->over_background, &cut = run->over_layer;
    std::printf(
        "[ %s ] largest difference %.2g over a background, %.2g over opaque geometry; alpha in "
        "[%g, %g]; %zu pixels 0, %zu partial, %zu above 0.99\n",
        tag.c_str(), c.largest_difference, cut.largest_difference, c.min_alpha, c.max_alpha,
        c.pixels_transparent, c.pixels_partial, c.pixels_opaque);
    EXPECT_LE(c.largest_difference, max_difference) << "at " << c.worst_x << ", " << c.worst_y;
    EXPECT_LE(cut.largest_difference, max_difference)
        << "at " << cut.worst_x << ", " << cut.worst_y;
    EXPECT_GE(c.min_alpha, 0.0f);
    EXPECT_LE(c.max_alpha, 1.0f);
    EXPECT_GE(cut.min_alpha, 0.0f);
    EXPECT_LE(cut.max_alpha, 1.0f);
    EXPECT_GT(c.pixels_partial, 200u);
    EXPECT_GT(c.pixels_opaque, 100u);
}

struct AlphaCounts {
    std::size_t missed = 0;   // pixels whose centre ray misses the box
    std::size_t lowered = 0;  // pixels whose alpha the opaque layer lowers by more than 0.05
};

// Walks the pixels of `run`: where the centre ray misses the box [0, side]^3 grown by `margin`,
// alpha is exactly 0, with the layer's depth and without; with `raise_slack`, the layer never
// raises alpha by more than that. Prints and returns the pixels missed and those lowered.
inline AlphaCounts count_missed_and_lowered(const CameraFrame& frame, const AlphaRun& run,
                                            double side, double margin,
                                            std::optional<float> raise_slack) {
    AlphaCounts n;
    for (int j = 0; j < frame.height(); ++j) {
        for (int i = 0; i < frame.width(); ++i) {
            const std::size_t p = static_cast<std::size_t>(j) * frame.width() + i;
            if (misses_box(frame.pixel_ray(i, j), 0.0, side, margin)) {
                ++n.missed;
                EXPECT_EQ(run.alpha[p], 0.0f) << i << ", " << j;
                EXPECT_EQ(run.alpha_cut[p], 0.0f) << i << ", " << j;
            }
            if (raise_slack) {
                EXPECT_LE(run.alpha_cut[p], run.alpha[p] + *raise_slack) << i << ", " << j;
            }
            n.lowered += run.alpha_cut[p] < run.alpha[p] - 0.05f;
        }
    }
    std::printf("[ alpha ] %zu pixels missed, %zu lowered by the opaque layer\n", n.missed,
                n.lowered);
    return n;
}

// Asking for alpha changes no bit of the picture: `render` (as for expect_alpha_composes) over
// `background`, with and without the opaque layer's depth and colour, gives the same picture
// with alpha as without, and not a blank one (which would be the same trivially).
template <class Render>
void expect_alpha_changes_no_bit(const Render& render, const Vec3& background) {
    std::vector<float> alpha;
    for (bool depth : {false, true}) {
        for (bool color : {false, true}) {
            SCOPED_TRACE(std::string(depth ? "opaque depth" : "no opaque depth") +
                         (color ? ", opaque colour" : ""));
            const Image without = render(background, depth, color, nullptr);
            const Image with = render(background, depth, color, &alpha);
            EXPECT_LT(psnr(without, Image(without.width, without.height, Vec3f(background))), 30.0);
            EXPECT_TRUE(bit_identical(without, with));
        }
    }
}

}  // namespace tr::testing
