#pragma once
// Drawing spot noise (flowtex/spot_noise.h): each spot a Gaussian stretched into an ellipse along
// its projected velocity, composited additively, depth-tested against opaque geometry.

#include <core/camera.h>
#include <core/image.h>
#include <flowtex/detail/spot_rows.h>
#include <flowtex/spot_noise.h>
#include <project/view.h>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace tr {

// How the spots are drawn.
struct SpotRasterOptions {
    double sigma_px = 1.5;  // the round spot's Gaussian sigma, pixels
    // The long axis's sigma is sigma_px + stretch x (the spot's projected displacement over
    // one frame's dt, pixels), at most max_sigma_px: faster across the view, longer.
    double stretch = 1.0;
    double max_sigma_px = 24.0;
    double dt = 0.05;  // the flow time the displacement is taken over
    // Colour: additive compositing. Each spot i has a random intensity a_i = +-(0.5 .. 1)
    // (zero mean, from its index and generation) and weight w_i(x) = exp(-q/2), q the squared
    // Mahalanobis distance from its centre (cut at q = 9, 3 sigma). Per pixel I = sum a_i w_i,
    // W = sum w_i (in spot order: deterministic); grey g = 0.5 + 0.5 tanh(contrast I /
    // sqrt(1 + W)), opacity alpha = 1 - exp(-opacity W), colour mix(dark, light, g) over the
    // view's background (or its opaque colour) by alpha.
    double contrast = 1.2;
    double opacity = 1.5;
    Vec3f dark{0.05f, 0.08f, 0.22f};
    Vec3f light{1.0f, 0.93f, 0.72f};
    // Whether splat_spots fills SpotBuffers::depth (a scene's depth compositing needs it; the
    // colouring does not, and render_spots skips it: a third of the raster's stores).
    bool depth_sums = true;
};

// The sums per pixel (row-major from the top), and the raster's working memory, kept between
// frames.
struct SpotBuffers {
    int width = 0, height = 0;
    std::vector<float> intensity;  // I
    std::vector<float> coverage;   // W
    std::vector<float> depth;      // sum w_i d_i, d_i spot i's centre's ray parameter (empty
                                   // unless SpotRasterOptions::depth_sums)

    std::vector<detail::SpotPrint> prints;  // per spot
    // Per spot: the first and last band of rows its print meets (first > last: none).
    std::vector<std::array<std::uint32_t, 2>> print_bands;
    std::vector<std::size_t> band_start;    // per band of rows: its first in band_spots
    std::vector<std::uint32_t> band_spots;  // the spots meeting each band, in spot order
};

// A pixel's spot colour (before compositing) and opacity from its sums I and W (W > 0), as
// render_spots colours them.
void spot_color(const SpotRasterOptions& options, float intensity, float coverage, Vec3f& color,
                float& alpha);

// The projected ellipse of a spot at `point` moving with `velocity`: centre (pixels), unit
// long-axis direction on the image (x right, y down; (1, 0) when the projected velocity is
// zero), sigmas along and across. Nothing behind a perspective eye.
struct SpotEllipse {
    glm::dvec2 centre{0.0}, direction{1.0, 0.0};
    double sigma_long = 0, sigma_short = 0;
    double depth = 0;  // the centre's ray parameter
};
std::optional<SpotEllipse> spot_ellipse(const CameraFrame& camera, const Vec3& point,
                                        const Vec3& velocity, const SpotRasterOptions& options);

// Accumulates the spots seen in `view` (project/view.h) into `buffers` (resized, zeroed): with
// the view's opaque depth, a spot is drawn on a pixel only where its centre's ray parameter
// (along the ray through the pixel holding the centre) is nearer. Bit-identical for any thread
// count (bands of rows, spots in order within a band). Cost: O(spots + covered pixels).
void splat_spots(const View& view, const SpotNoise& spots, const SpotRasterOptions& options,
                 SpotBuffers& buffers);

// splat_spots and the colouring over the view's background or opaque colour into `image`
// (resized; every pixel written).
void render_spots(const View& view, const SpotNoise& spots, const SpotRasterOptions& options,
                  SpotBuffers& buffers, Image& image);

}  // namespace tr
