#include <core/fast_exp.h>
#include <core/vector_clones.h>
#include <flowtex/detail/spot_rows.h>

#include <algorithm>
#include <cmath>

namespace tr::spot_rows {
namespace {

// A pixel's offset from a spot's centre, x + 0.5 - cx, in float: cx split into two floats
// (cx = hi + lo) so that the difference is near exact and the same for a pixel whichever row
// span holds it.
struct CentreX {
    float hi, lo;
    explicit CentreX(double cx)
        : hi(static_cast<float>(cx)), lo(static_cast<float>(cx - static_cast<float>(cx))) {}
    TR_FORCE_INLINE float offset(int x) const { return (static_cast<float>(x) + 0.5f - hi) - lo; }
};

// n pixels of a row of a spot from pixel x0, the row's q(dx) =
// qa dx^2 + b dx + c; where `hidden` is given, only where hidden[i] is beyond `depth`; the depth
// sum only with kDepth.
template <bool kHidden, bool kDepth>
TR_FORCE_INLINE void add_row(float* __restrict intensity, float* __restrict coverage,
                             float* __restrict depth_sum, const double* __restrict hidden, int n,
                             int x0, CentreX centre, float qa, float b, float c, float amplitude,
                             float depth) {
    for (int i = 0; i < n; ++i) {
        const float dx = centre.offset(x0 + i);
        const float q = (qa * dx + b) * dx + c;
        const float x = -0.5f * q;
        float w = exp_nonpositive(x < 0.0f ? x : 0.0f);
        w = q < 9.0f ? w : 0.0f;
        if constexpr (kHidden) w = depth < hidden[i] ? w : 0.0f;
        intensity[i] += amplitude * w;
        coverage[i] += w;
        if constexpr (kDepth) depth_sum[i] += depth * w;
    }
}

// A small spot (a bounding box of at most 16 pixels each way) whose weights factor within a
// float's range: w(i, j) = exp(-q / 2) = P_i S_i^k R_j, with dx_i, dy_j the pixel's offsets from
// the centre, k = j - j0, P_i = exp(-qa dx_i^2 / 2 - qb dx_i dy_j0), S_i = exp(-qb dx_i),
// R_j = exp(-qc dy_j^2 / 2): a few exponentials a spot, two multiplications a pixel. The 3-sigma
// cut (q < 9) from q itself, as for every spot.
constexpr int kSmallSpot = 16;

// Whether f is small and every exponent above stays within +-80 over its box (offsets up to D:
// its box's reach from the centre, and 3 more pixels the row may be widened by).
TR_FORCE_INLINE bool small_spot(const detail::SpotPrint& f) {
    if (f.x1 - f.x0 >= kSmallSpot || f.y1 - f.y0 >= kSmallSpot) return false;
    const double reach =
        std::max(std::max(std::abs(f.x0 + 0.5 - f.cx), std::abs(f.x1 + 0.5 - f.cx)),
                 std::max(std::abs(f.y0 + 0.5 - f.cy), std::abs(f.y1 + 0.5 - f.cy))) +
        4.0;
    const double square = reach * reach;
    return (0.5 * f.qa + std::abs(f.qb)) * square <= 80.0 && 0.5 * f.qc * square <= 80.0;
}

template <bool kHidden, bool kDepth>
TR_FORCE_INLINE void add_small_spot(const BandSums& band, const detail::SpotPrint& f) {
    const int ya = std::max(f.y0, band.row0), yb = std::min(f.y1, band.row1);
    if (ya > yb) return;
    // Rows widened to a multiple of 4 into the apron, but where the opaque depths are read.
    int whole = f.x1 + 1 - f.x0, xa = f.x0;
    if constexpr (!kHidden) {
        whole = (whole + 3) & ~3;
        xa = std::min(f.x0 + whole, band.width + band.apron) - whole;
    }
    const CentreX centre(f.cx);
    const auto qa = static_cast<float>(f.qa), qb = static_cast<float>(f.qb);
    const auto qc = static_cast<float>(f.qc);
    const float amplitude = f.amplitude, depth = f.depth;
    const auto dy0 = static_cast<float>(ya + 0.5 - f.cy);
    // Per column its offset, P_i and S_i; per row R_j: the exponentials in vector loops.
    float dxs[kSmallSpot], p[kSmallSpot], step[kSmallSpot], rows[kSmallSpot];
    for (int i = 0; i < whole; ++i) {
        const float dx = centre.offset(xa + i);
        dxs[i] = dx;
        p[i] = exp_bounded(-0.5f * qa * dx * dx - qb * dx * dy0);
        step[i] = exp_bounded(-qb * dx);
    }
    for (int j = 0; j <= yb - ya; ++j) {
        const float dy = dy0 + static_cast<float>(j);
        rows[j] = exp_nonpositive(-0.5f * qc * dy * dy);
    }
    for (int y = ya; y <= yb; ++y) {
        const float dy = dy0 + static_cast<float>(y - ya);
        const float r = rows[y - ya], c = qc * dy * dy, b = 2.0f * qb * dy;
        const std::size_t at =
            static_cast<std::size_t>(y - band.row0) * band.stride + band.apron + xa;
        float* __restrict intensity = band.intensity + at;
        float* __restrict coverage = band.coverage + at;
        float* __restrict depth_sum = kDepth ? band.depth + at : nullptr;
        const double* __restrict hidden =
            kHidden ? band.hidden + static_cast<std::size_t>(y) * band.width + xa : nullptr;
        for (int i = 0; i < whole; ++i) {
            const float dx = dxs[i];
            const float q = (qa * dx + b) * dx + c;
            float w = q < 9.0f ? p[i] * r : 0.0f;
            if constexpr (kHidden) w = depth < hidden[i] ? w : 0.0f;
            p[i] *= step[i];
            intensity[i] += amplitude * w;
            coverage[i] += w;
            if constexpr (kDepth) depth_sum[i] += depth * w;
        }
    }
}

template <bool kHidden, bool kDepth>
TR_FORCE_INLINE void add_spot(const BandSums& band, const detail::SpotPrint& f) {
    if (small_spot(f)) {
        add_small_spot<kHidden, kDepth>(band, f);
        return;
    }
    const double qa = f.qa, qb = f.qb, qc = f.qc;
    // The span of a row: q(dx) = 9 at dx = (-qb dy -+ sqrt(9 qa - det dy^2)) / qa, det = qa qc -
    // qb^2. Truncation toward zero keeps the span conservative (the q test in the row's loop is
    // exact), and is cheaper than floor and ceil. A narrow spot's rows all span its bounding
    // box (no square root a row).
    const double det = qa * qc - qb * qb, inv_qa = 1.0 / qa;
    const bool narrow = f.x1 - f.x0 < 16;
    for (int y = std::max(f.y0, band.row0); y <= std::min(f.y1, band.row1); ++y) {
        const double dy = y + 0.5 - f.cy;
        int xa = f.x0, xb = f.x1 + 1;  // exclusive
        if (!narrow) {
            const double disc = 9.0 * qa - det * dy * dy;
            if (!(disc > 0)) continue;
            const double half = std::sqrt(disc) * inv_qa;
            const double mid = f.cx - qb * dy * inv_qa - 0.5;
            xa = std::max(f.x0, static_cast<int>(mid - half));
            xb = std::min(f.x1, static_cast<int>(mid + half) + 1) + 1;
            if (xa >= xb) continue;
        }
        if constexpr (!kHidden) {
            const int whole = (xb - xa + 3) & ~3;  // the vector loop's 8, then its tail's 4
            xb = std::min(xa + whole, band.width + band.apron);
            xa = xb - whole;
        }
        const std::size_t at =
            static_cast<std::size_t>(y - band.row0) * band.stride + band.apron + xa;
        const double* hidden =
            kHidden ? band.hidden + static_cast<std::size_t>(y) * band.width + xa : nullptr;
        add_row<kHidden, kDepth>(
            band.intensity + at, band.coverage + at, kDepth ? band.depth + at : nullptr, hidden,
            xb - xa, xa, CentreX(f.cx), static_cast<float>(qa), static_cast<float>(2.0 * qb * dy),
            static_cast<float>(qc * dy * dy), f.amplitude, f.depth);
    }
}

}  // namespace

TR_VECTOR_CLONES void shade_row(const float* __restrict intensity, const float* __restrict coverage,
                                float* __restrict grey, float* __restrict alpha, int n,
                                float contrast, float opacity) {
    for (int i = 0; i < n; ++i) {
        spot_shade(contrast, opacity, intensity[i], coverage[i], grey[i], alpha[i]);
    }
}

TR_VECTOR_CLONES void add_spots(const BandSums& band, const detail::SpotPrint* prints,
                                const std::uint32_t* which, std::size_t count) {
    // A band's spots lie scattered through the prints: each fetched a few spots ahead.
    constexpr std::size_t kAhead = 8;
    for (std::size_t k = 0; k < count; ++k) {
        if (k + kAhead < count) __builtin_prefetch(&prints[which[k + kAhead]]);
        const detail::SpotPrint& f = prints[which[k]];
        if (band.hidden) {
            band.depth ? add_spot<true, true>(band, f) : add_spot<true, false>(band, f);
        } else {
            band.depth ? add_spot<false, true>(band, f) : add_spot<false, false>(band, f);
        }
    }
}

}  // namespace tr::spot_rows
