#include <core/fast_exp.h>
#include <core/vector_clones.h>
#include <project/splat/splat_rows.h>

#include <algorithm>

namespace tr::splat_rows {
namespace {

// e^x for -kSmallDepth <= x <= 0: 1 + x + x^2/2 + x^3/6 + x^4/24 (exactly 1 at 0).
TR_FORCE_INLINE float exp_small(float x) {
    return 1.0f + x * (1.0f + x * (0.5f + x * (1.0f / 6.0f + x * (1.0f / 24.0f))));
}

// Four stamps' weights, by value (held in registers across a loop).
struct Weights {
    float w0, w1, w2, w3;
    explicit Weights(const float* w) : w0(w[0]), w1(w[1]), w2(w[2]), w3(w[3]) {}
};

// The optical depth at pixel i of four stamps' rows, weighted.
// (Plain pointers: the loops' own are restrict.)
TR_FORCE_INLINE float blend(const float* sa, const float* sb, const float* sc, const float* sd,
                            Weights w, int i) {
    return w.w0 * sa[i] + w.w1 * sb[i] + w.w2 * sc[i] + w.w3 * sd[i];
}

}  // namespace

TR_VECTOR_CLONES void blend_stamps(float* __restrict out, const StampRows& stamps, int n) {
    const auto& s = stamps.stamp;
    const Weights w(stamps.weight);
    for (int i = 0; i < n; ++i) out[i] = blend(s[0], s[1], s[2], s[3], w, i);
}

// (GCC 12 does not vectorise this loop, the table lookup being a gather; in float from the
// table by rho^2 it is still about twice the per-pixel double path it replaced.)
TR_VECTOR_CLONES void perspective_depths(float* __restrict tau, const double* __restrict dx,
                                         const double* __restrict dy, const double* __restrict dz,
                                         int n, const Vec3& v, double inv_h_sq, float kappa_h,
                                         const FootprintTable& table) {
    const double vx = v.x, vy = v.y, vz = v.z;
    const float* __restrict values = table.values;
    const float scale = table.scale, last = table.last, support_sq = table.support_sq;
    for (int i = 0; i < n; ++i) {
        const double t = vx * dx[i] + vy * dy[i] + vz * dz[i];
        const double cx = vy * dz[i] - vz * dy[i], cy = vz * dx[i] - vx * dz[i];
        const double cz = vx * dy[i] - vy * dx[i];
        const auto q = static_cast<float>((cx * cx + cy * cy + cz * cz) * inv_h_sq);
        const float x = std::min(q * scale, last);
        const int k = static_cast<int>(x);
        const float f = values[k] + (x - static_cast<float>(k)) * (values[k + 1] - values[k]);
        tau[i] = q < support_sq && t > 0.0 ? kappa_h * f : 0.0f;
    }
}

TR_VECTOR_CLONES void composite(const ColorRow& row, const float* __restrict tau, int n,
                                const Vec3f& c) {
    float* __restrict r = row.r;
    float* __restrict g = row.g;
    float* __restrict b = row.b;
    const float cr = c.r, cg = c.g, cb = c.b;
    for (int i = 0; i < n; ++i) {
        const float e = exp_nonpositive(-tau[i]), alpha = 1.0f - e;
        r[i] = e * r[i] + alpha * cr;
        g[i] = e * g[i] + alpha * cg;
        b[i] = e * b[i] + alpha * cb;
    }
}

namespace {

// The loops with every pointer a restrict parameter (GCC vectorises without alias checks).
template <bool kSmall>
TR_FORCE_INLINE void composite_stamps_loop(float* __restrict r, float* __restrict g,
                                           float* __restrict b, const float* __restrict sa,
                                           const float* __restrict sb, const float* __restrict sc,
                                           const float* __restrict sd, Weights w, int n,
                                           const Vec3f& c) {
    const float cr = c.r, cg = c.g, cb = c.b;
    for (int i = 0; i < n; ++i) {
        const float tau = blend(sa, sb, sc, sd, w, i);
        const float e = kSmall ? exp_small(-tau) : exp_nonpositive(-tau), alpha = 1.0f - e;
        r[i] = e * r[i] + alpha * cr;
        g[i] = e * g[i] + alpha * cg;
        b[i] = e * b[i] + alpha * cb;
    }
}

TR_FORCE_INLINE void add_stamps_loop(float* __restrict t, float* __restrict r, float* __restrict g,
                                     float* __restrict b, const float* __restrict sa,
                                     const float* __restrict sb, const float* __restrict sc,
                                     const float* __restrict sd, Weights w, int n, const Vec3f& c) {
    const float cr = c.r, cg = c.g, cb = c.b;
    for (int i = 0; i < n; ++i) {
        const float tau = blend(sa, sb, sc, sd, w, i);
        t[i] += tau;
        r[i] += tau * cr;
        g[i] += tau * cg;
        b[i] += tau * cb;
    }
}

TR_FORCE_INLINE void composite_sheet_loop(float* __restrict r, float* __restrict g,
                                          float* __restrict b, float* __restrict t,
                                          float* __restrict tr, float* __restrict tg,
                                          float* __restrict tb, int n) {
    for (int i = 0; i < n; ++i) {
        const float e = exp_nonpositive(-t[i]);
        const float scale = t[i] > 0.0f ? (1.0f - e) / t[i] : 0.0f;
        r[i] = tr[i] * scale + e * r[i];
        g[i] = tg[i] * scale + e * g[i];
        b[i] = tb[i] * scale + e * b[i];
        t[i] = tr[i] = tg[i] = tb[i] = 0.0f;
    }
}

}  // namespace

namespace {

// For each row of the block: the first pixel's offset from the tile's origin (ahead of the
// block's origin), the offset into the stamps and the pixel count.
template <class Row>
TR_FORCE_INLINE int for_each_block_row(const StampBlock& block, Row&& row) {
    // Rows are widened to a multiple of 8 pixels where the stamps and the clip allow (the
    // samples outside the span are 0: those pixels stay as they are), so that the vector loops
    // run whole.
    const int lo = std::max(0, block.pad_lo), hi = std::min(block.width, block.pad_hi);
    int drawn = 0;
    for (int v = block.v_from; v <= block.v_to; ++v) {
        int from = std::max<int>(block.span_from[v], block.u_lo);
        int to = std::min<int>(block.span_to[v], block.u_hi);
        if (from >= to) continue;
        drawn += to - from;
        const int whole = (to - from + 7) & ~7;
        to = std::min(from + whole, hi);
        from = std::max(to - whole, lo);
        row(block.origin + v * block.stride + from, v * block.width + from, to - from);
    }
    return drawn;
}

}  // namespace

TR_VECTOR_CLONES int composite_stamp_block(const ColorRow& tile, const StampBlock& block,
                                           const Vec3f& c, bool small) {
    const auto& s = block.stamps.stamp;
    const Weights w(block.stamps.weight);
    return for_each_block_row(block, [&](int pixel, int sample, int n) TR_FORCE_INLINE_LAMBDA {
        if (small) {
            composite_stamps_loop<true>(tile.r + pixel, tile.g + pixel, tile.b + pixel,
                                        s[0] + sample, s[1] + sample, s[2] + sample, s[3] + sample,
                                        w, n, c);
        } else {
            composite_stamps_loop<false>(tile.r + pixel, tile.g + pixel, tile.b + pixel,
                                         s[0] + sample, s[1] + sample, s[2] + sample, s[3] + sample,
                                         w, n, c);
        }
    });
}

TR_VECTOR_CLONES int add_stamp_block_to_sheet(const SheetRow& tile, const StampBlock& block,
                                              const Vec3f& c) {
    const auto& s = block.stamps.stamp;
    const Weights w(block.stamps.weight);
    return for_each_block_row(block, [&](int pixel, int sample, int n) TR_FORCE_INLINE_LAMBDA {
        add_stamps_loop(tile.tau + pixel, tile.r + pixel, tile.g + pixel, tile.b + pixel,
                        s[0] + sample, s[1] + sample, s[2] + sample, s[3] + sample, w, n, c);
    });
}

TR_VECTOR_CLONES void add_to_sheet(const SheetRow& sheet, const float* __restrict tau, int n,
                                   const Vec3f& c) {
    float* __restrict t = sheet.tau;
    float* __restrict r = sheet.r;
    float* __restrict g = sheet.g;
    float* __restrict b = sheet.b;
    const float cr = c.r, cg = c.g, cb = c.b;
    for (int i = 0; i < n; ++i) {
        t[i] += tau[i];
        r[i] += tau[i] * cr;
        g[i] += tau[i] * cg;
        b[i] += tau[i] * cb;
    }
}

TR_VECTOR_CLONES void composite_sheet(const ColorRow& row, const SheetRow& sheet, int n) {
    composite_sheet_loop(row.r, row.g, row.b, sheet.tau, sheet.r, sheet.g, sheet.b, n);
}

}  // namespace tr::splat_rows
