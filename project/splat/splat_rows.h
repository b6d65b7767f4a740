#pragma once
// The splat raster's inner loops (project/splat/splat_renderer.cpp), one row of pixels at a time
// over planar float buffers: each a straight loop the compiler vectorises (but perspective_depths),
// built twice on x86-64 (AVX2 and the baseline, chosen when the program loads: target_clones). The
// arithmetic is the same in both (no fused multiply-add: ISO C++ mode), so are the pictures.
//
// Compositing a splat over a pixel, optical depth tau and colour c: e = e^-tau,
// p <- e p + (1 - e) c (tau = 0 leaves p exactly as it was). A sheet buffer sums tau and tau c per
// pixel; composited, alpha = 1 - e^-tau and colour sum(tau c) / tau alpha.

#include <core/math.h>

namespace tr::splat_rows {

// A row of a planar picture: its three colour planes at the row's first pixel.
struct ColorRow {
    float* r;
    float* g;
    float* b;
};

// A row of a sheet buffer: summed optical depth and optical-depth-weighted colour.
struct SheetRow {
    float* tau;
    float* r;
    float* g;
    float* b;
};

// Four footprint stamps' rows and their weights (kappa h times the bilinear weights): the
// optical depth at pixel i is sum_k weight[k] stamp[k][i].
struct StampRows {
    const float* stamp[4];
    float weight[4];
};

// The largest optical depth composite_stamp_block takes `small` for: its degree-4 Taylor
// exponential is then within 1e-8 of e^-tau (the truncation, tau^5 / 120).
inline constexpr float kSmallDepth = 1.0f / 16.0f;

// The optical depths of `stamps` over n pixels into out.
void blend_stamps(float* out, const StampRows& stamps, int n);

// n pixels of optical depth tau[i] and colour c composited over `row`.
void composite(const ColorRow& row, const float* tau, int n, const Vec3f& c);

// n pixels of optical depth tau[i] and colour c added to a sheet buffer's row.
void add_to_sheet(const SheetRow& sheet, const float* tau, int n, const Vec3f& c);

// n pixels of a sheet buffer composited over `row`, and the sheet's pixels set to 0.
void composite_sheet(const ColorRow& row, const SheetRow& sheet, int n);

// A footprint's rho^2 table (SplatFootprint::squared_table and its scale and last index) and
// its support^2 (kernel units).
struct FootprintTable {
    const float* values;
    float scale, last;
    float support_sq;
};

// A perspective splat's optical depths over n pixels of a row whose rays leave the eye along the
// unit directions (dx[i], dy[i], dz[i]), the splat's centre at v from the eye: tau[i] = kappa_h
// f(rho^2 / h^2), rho the distance from the centre to the ray (|v x d|, in double), where the
// centre lies ahead (v . d > 0) and rho < the support, else 0. f read from the table by rho^2.
void perspective_depths(float* tau, const double* dx, const double* dy, const double* dz, int n,
                        const Vec3& v, double inv_h_sq, float kappa_h, const FootprintTable& table);

// A whole splat drawn from stamps into a tile (row-major, rows `stride` long): rows v_from ...
// v_to of the stamps (`width` samples a row, a multiple of 8), in each the columns within the
// row's span [span_from[v], span_to[v]) and the clip [u_lo, u_hi), widened to a multiple of 8
// columns within the stamp and [pad_lo, pad_hi) (where the tile's buffers have room: the samples
// outside the span are 0, the pixels unchanged); stamp column u of row v is the tile's pixel
// origin + v stride + u (every pixel drawn lies in the tile's buffers).
struct StampBlock {
    StampRows stamps;  // at row 0, column 0
    int width;
    int v_from, v_to;    // inclusive
    int u_lo, u_hi;      // [u_lo, u_hi)
    int pad_lo, pad_hi;  // [pad_lo, pad_hi), containing [u_lo - 7, u_hi + 7)
    const short* span_from;
    const short* span_to;
    int origin, stride;
};

// The splat composited over the tile's picture (small: every optical depth is at most
// kSmallDepth: a cheaper exponential). Returns the pixels drawn (within the clip).
int composite_stamp_block(const ColorRow& tile, const StampBlock& block, const Vec3f& c,
                          bool small);

// The splat added to the tile's sheet buffer. Returns the pixels drawn (within the clip).
int add_stamp_block_to_sheet(const SheetRow& tile, const StampBlock& block, const Vec3f& c);

}  // namespace tr::splat_rows
