#pragma once
// The spot raster's inner loops (flowtex/spot_raster.cpp): a band of rows' spots, each a
// Gaussian weight w = exp(-q / 2) over its 3-sigma ellipse (q < 9, the squared Mahalanobis
// distance from its centre) added to the band's sums, row by row in straight loops the compiler
// vectorises (core/vector_clones.h; the exponential core/fast_exp.h's).

#include <core/fast_exp.h>

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace tr::detail {

// A spot as the raster draws it (one cache line).
struct SpotPrint {
    double cx, cy;      // centre, pixels
    double qa, qb, qc;  // q(dx, dy) = qa dx^2 + 2 qb dx dy + qc dy^2
    float depth;        // the centre's ray parameter (float: compared with the opaque depth)
    float amplitude;
    int x0, x1, y0, y1;  // the pixels of its ellipse's bounding box, inclusive; none: x1 < x0
};

}  // namespace tr::detail

namespace tr::spot_rows {

// A band of rows of the sums (intensity I, coverage W, depth-weighted sum D, or none when
// `depth` is null), `stride` floats a
// row with `apron` spare pixels either side of the picture's `width` (pixel x of row y at
// (y - row0) stride + apron + x), and the opaque geometry's depths of the picture (row-major,
// `width` a row), or null.
struct BandSums {
    float* intensity;
    float* coverage;
    float* depth;
    int stride, apron, width;
    int row0, row1;  // inclusive
    const double* hidden;
};

// A pixel's grey g = 0.5 + 0.5 tanh(contrast I / sqrt(1 + W)) and opacity 1 - exp(-opacity W)
// from its sums (W >= 0), in float (tanh |x| = (1 - e) / (1 + e), e = exp(-2 |x|)).
inline void spot_shade(float contrast, float opacity, float intensity, float coverage, float& grey,
                       float& alpha) {
    const float x = contrast * intensity / std::sqrt(1.0f + coverage);
    const float e = exp_nonpositive(-2.0f * std::fabs(x));
    grey = 0.5f + 0.5f * std::copysign((1.0f - e) / (1.0f + e), x);
    alpha = 1.0f - exp_nonpositive(-opacity * coverage);
}

// spot_shade over n pixels.
void shade_row(const float* intensity, const float* coverage, float* grey, float* alpha, int n,
               float contrast, float opacity);

// The spots prints[which[k]], k < count, in that order, added to the band: per pixel of each
// spot's ellipse (q < 9) the weight w = exp(-q / 2), I += amplitude w, W += w, D += depth w;
// where the opaque geometry's depth is not beyond the spot's, nothing. Rows of a spot run over
// its bounding box when it is under 16 pixels wide, else over its ellipse's span in that row,
// widened to a multiple of 4 pixels (vectors of 8 and 4) into the apron (the weights beyond the
// ellipse are 0) unless there is opaque geometry.
void add_spots(const BandSums& band, const detail::SpotPrint* prints, const std::uint32_t* which,
               std::size_t count);

}  // namespace tr::spot_rows
