#include <tests/support/image_shift.h>

#include <algorithm>
#include <cmath>

namespace tr::testing {
namespace {

// Normalised cross-correlation of b(x) with a(x - d) for an integer shift d.
double ncc(const std::vector<float>& a, const std::vector<float>& b, int width, int height, int dx,
           int dy, int margin, std::size_t* overlap) {
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    std::size_t n = 0;
    for (int y = margin; y < height - margin; ++y) {
        const int ya = y - dy;
        if (ya < margin || ya >= height - margin) continue;
        for (int x = margin; x < width - margin; ++x) {
            const int xa = x - dx;
            if (xa < margin || xa >= width - margin) continue;
            const double va = a[static_cast<std::size_t>(ya) * width + xa];
            const double vb = b[static_cast<std::size_t>(y) * width + x];
            if (std::isnan(va) || std::isnan(vb)) continue;
            sa += va;
            sb += vb;
            saa += va * va;
            sbb += vb * vb;
            sab += va * vb;
            ++n;
        }
    }
    if (overlap) *overlap = n;
    if (n < 16) return -1.0;
    const double cov = sab - sa * sb / n;
    const double var = (saa - sa * sa / n) * (sbb - sb * sb / n);
    return var > 0 ? cov / std::sqrt(var) : -1.0;
}

// The offset in [-0.5, 0.5] of a parabola's vertex through (-1, m), (0, c), (1, p).
double parabola_vertex(double m, double c, double p) {
    const double denom = m - 2.0 * c + p;
    if (!(std::abs(denom) > 1e-15)) return 0.0;
    const double d = 0.5 * (m - p) / denom;
    return std::max(-0.5, std::min(0.5, d));
}

}  // namespace

ShiftEstimate estimate_shift(const std::vector<float>& a, const std::vector<float>& b, int width,
                             int height, glm::dvec2 guess, int search, int margin) {
    const int gx = static_cast<int>(std::lround(guess.x));
    const int gy = static_cast<int>(std::lround(guess.y));
    ShiftEstimate best;
    best.peak = -2.0;
    int bx = gx, by = gy;
    for (int dy = gy - search; dy <= gy + search; ++dy) {
        for (int dx = gx - search; dx <= gx + search; ++dx) {
            std::size_t n = 0;
            const double c = ncc(a, b, width, height, dx, dy, margin, &n);
            if (c > best.peak) {
                best.peak = c;
                best.overlap = n;
                bx = dx;
                by = dy;
            }
        }
    }
    auto at = [&](int dx, int dy) { return ncc(a, b, width, height, dx, dy, margin, nullptr); };
    const double c = best.peak;
    best.shift = glm::dvec2(bx + parabola_vertex(at(bx - 1, by), c, at(bx + 1, by)),
                            by + parabola_vertex(at(bx, by - 1), c, at(bx, by + 1)));
    return best;
}

}  // namespace tr::testing
