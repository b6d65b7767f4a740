#include <core/fast_exp.h>
#include <core/vector_clones.h>

#include <algorithm>
#include <cmath>
#include <flowtex/detail/spot_rows.h>

namespace tr::spot_rows {
namespace {

// n pixels of a row of a spot: its first pixel's offset from the centre dx0, the row's q(dx) =
// qa dx^2 + b dx + c; where `hidden` is given, only where hidden[i] is beyond `depth`.
template <bool kHidden>
TR_FORCE_INLINE void add_row(float* __restrict intensity, float* __restrict coverage,
                             float* __restrict depth_sum, const double* __restrict hidden, int n,
                             float dx0, float qa, float b, float c, float amplitude, float depth) {
    for (int i = 0; i < n; ++i) {
        const float dx = dx0 + static_cast<float>(i);
        const float q = (qa * dx + b) * dx + c;
        const float x = -0.5f * q;
        float w = exp_nonpositive(x < 0.0f ? x : 0.0f);
        w = q < 9.0f ? w : 0.0f;
        if constexpr (kHidden) w = depth < hidden[i] ? w : 0.0f;
        intensity[i] += amplitude * w;
        coverage[i] += w;
        depth_sum[i] += depth * w;
    }
}

template <bool kHidden>
TR_FORCE_INLINE void add_spot(const BandSums& band, const detail::SpotPrint& f) {
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
            const int whole = (xb - xa + 7) & ~7;
            xb = std::min(xa + whole, band.width + band.apron);
            xa = xb - whole;
        }
        const std::size_t at =
            static_cast<std::size_t>(y - band.row0) * band.stride + band.apron + xa;
        const double* hidden =
            kHidden ? band.hidden + static_cast<std::size_t>(y) * band.width + xa : nullptr;
        add_row<kHidden>(band.intensity + at, band.coverage + at, band.depth + at, hidden, xb - xa,
                         static_cast<float>(xa + 0.5 - f.cx), static_cast<float>(qa),
                         static_cast<float>(2.0 * qb * dy), static_cast<float>(qc * dy * dy),
                         f.amplitude, f.depth);
    }
}

}  // namespace

TR_VECTOR_CLONES void add_spots(const BandSums& band, const detail::SpotPrint* prints,
                                const std::uint32_t* which, std::size_t count) {
    if (band.hidden) {
        for (std::size_t k = 0; k < count; ++k) add_spot<true>(band, prints[which[k]]);
    } else {
        for (std::size_t k = 0; k < count; ++k) add_spot<false>(band, prints[which[k]]);
    }
}

}  // namespace tr::spot_rows
