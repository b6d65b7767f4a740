#pragma once
// The scene the particle-based alpha tests share (header-only): a box [0, 3]^3 whose scalar runs
// with x from 0 to 1 and whose opacity ramps from none (x = 0) to opaque (x = 3), optionally a
// faint second volume [0, 2]^3 in the same space (fused), seen nearly down z so that the ray
// through (2.7, 1.5, 1.5) crosses the box where it is opaque (optical depth above 14), with
// empty margins; and a tilted opaque plane through them, drawn over a grey background. Also the
// alpha checks both PBVR methods run over it for each of their variants, and what they measure of
// alpha as a fraction of random draws (hit_fractions).

#include <core/camera.h>
#include <mesh/surface_mesh.h>
#include <project/cpu_renderer.h>
#include <project/opaque_geometry.h>
#include <project/segment_shader.h>
#include <project/volume_scene.h>
#include <tests/project/alpha_check.h>
#include <tests/support/test_scenes.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace tr::testing {

struct PbvrAlphaScene {
    TetMesh a_mesh = uniform_box(3, 3.0);
    TetMesh b_mesh = uniform_box(2, 2.0);
    std::vector<float> a_scalar = [this] {
        std::vector<float> s;
        for (const Vec3& p : a_mesh.points()) s.push_back(static_cast<float>(p.x / 3.0));
        return s;
    }();
    std::vector<float> b_scalar = std::vector<float>(b_mesh.num_points(), 0.5f);
    TransferFunction a_tf =
        TransferFunction::create({{0.0, {0.1, 0.2, 0.9}}, {1.0, {0.9, 0.3, 0.1}}},
                                 {{0.0, 0.0}, {0.5, 0.1}, {1.0, 0.95}}, 0.25)
            .value();
    TransferFunction b_tf =
        TransferFunction::create({{0.0, {0.2, 0.9, 0.3}}}, {{0.0, 0.1}}, 1.0).value();
    SegmentShader a_shader{a_tf, Integrator::kPreintegrated, longest_edge(a_mesh)};
    CameraFrame frame{camera_at({3.5, 2.5, 14}, {1.5, 1.5, 1.5}, false, 30), 64, 64};
    SurfaceMesh plane = tilted_plane(-1, 4, 0.2, 1.7);  // z = 0.5 + 0.3 x
    OpaqueLayer layer = plane_layer(plane, frame);
    Vec3 background{0.3, 0.6, 0.9};  // the non-black background the pictures are drawn over

    // With `shader`, the box's shader is given (image-space PBVR then takes each segment's mean
    // colour); with `fused`, the second volume is drawn too.
    VolumeScene scene(const Vec3& background, bool opaque_depth, bool opaque_color, bool shader,
                      bool fused) const {
        VolumeScene s;
        s.volumes.push_back({&a_mesh, a_scalar, &a_tf, shader ? &a_shader : nullptr});
        if (fused) s.volumes.push_back({&b_mesh, b_scalar, &b_tf, nullptr});
        s.camera = &frame;
        s.background = background;
        if (opaque_depth) s.opaque_depth = &layer.depth;
        if (opaque_color) s.opaque_color = &layer.color;
        return s;
    }

    // The pixel of the ray through (2.7, 1.5, 1.5): nearly opaque.
    std::size_t opaque_pixel() const { return pixel_of(frame, Vec3(2.7, 1.5, 1.5)); }
};

// What a PBVR method's alpha promises over the scene, bounded per variant: the picture composes
// within `max_difference`; alpha is 0 where the centre ray misses the box [0, 3]^3 grown by
// `margin`; the opaque layer never raises alpha by more than `raise_slack` (when given); at least
// `min_missed` pixels are missed and `min_lowered` lowered by the layer.
struct PbvrAlphaBounds {
    double max_difference;
    double margin;
    std::optional<float> raise_slack;
    std::size_t min_missed, min_lowered;
};

// For each of `variants` (each with a `name`), with the render callable `render_for(scene,
// variant)` (tests/project/alpha_check.h): the picture composes over the background and over the
// opaque layer from the one over black, alpha is 0 where the rays miss, the layer lowers it, and
// it is above 0.99 at the opaque pixel. Prints the largest difference over all, tagged `tag`.
template <class Variants, class RenderFor>
void expect_pbvr_alpha_composes(const PbvrAlphaScene& s, const std::string& tag,
                                const Variants& variants, const RenderFor& render_for,
                                const PbvrAlphaBounds& bounds) {
    ASSERT_GT(s.layer.pixels_covered, 1000u);
    double worst = 0;
    for (const auto& v : variants) {
        SCOPED_TRACE(v.name);
        AlphaRun r;
        ASSERT_NO_FATAL_FAILURE(expect_alpha_composes(tag + ", " + v.name, render_for(s, v),
                                                      s.background, s.layer.color,
                                                      bounds.max_difference, &r));
        worst = std::max(worst, r.largest_difference());
        const AlphaCounts n =
            count_missed_and_lowered(s.frame, r, 3.0, bounds.margin, bounds.raise_slack);
        EXPECT_GT(n.missed, bounds.min_missed);
        EXPECT_GT(n.lowered, bounds.min_lowered);
        EXPECT_GT(r.alpha[s.opaque_pixel()], 0.99f);
    }
    std::printf("[ %s ] largest difference over all: %.2g\n", tag.c_str(), worst);
}

// For each of `variants`: asking for alpha changes no bit of the picture (alpha_check.h).
template <class Variants, class RenderFor>
void expect_pbvr_alpha_changes_no_bit(const PbvrAlphaScene& s, const Variants& variants,
                                      const RenderFor& render_for) {
    for (const auto& v : variants) {
        SCOPED_TRACE(v.name);
        expect_alpha_changes_no_bit(render_for(s, v), s.background);
    }
}

struct HitFractions {
    double off_grid = 0;           // the largest distance of alpha x samples from a whole number
    double mean_z = 0, rms_z = 0;  // of the z-scores over the pixels counted
    std::size_t pixels = 0;
};

// Alpha read as the fraction of `samples` draws with a particle: how far it lies off the grid of
// multiples of 1 / samples, and over the pixels whose known opacity `expected` is in [0.05, 0.95]
// the z-scores of alpha against it (the binomial's standard error).
inline HitFractions hit_fractions(const std::vector<float>& alpha,
                                  const std::vector<double>& expected, double samples) {
    HitFractions h;
    for (std::size_t p = 0; p < expected.size(); ++p) {
        const double hits = alpha[p] * samples;
        h.off_grid = std::max(h.off_grid, std::abs(hits - std::round(hits)));
        const double a = expected[p];
        if (a < 0.05 || a > 0.95) continue;
        const double z = (alpha[p] - a) / std::sqrt(a * (1 - a) / samples);
        h.mean_z += z, h.rms_z += z * z, ++h.pixels;
    }
    h.mean_z /= static_cast<double>(h.pixels);
    h.rms_z = std::sqrt(h.rms_z / static_cast<double>(h.pixels));
    return h;
}

}  // namespace tr::testing
