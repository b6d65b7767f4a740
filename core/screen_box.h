#pragma once
// Screen boxes: the pixels a projected shape may cover, by the pixel-centre rule the CPU
// rasters share (pixel (i, j) is covered when its centre (i + 0.5, j + 0.5) is). The reference
// ray caster and the sort verifier keep their own boxes on purpose: they are the oracles.

#include <algorithm>
#include <cmath>

namespace tr {

// Pixels x0..x1, y0..y1, inclusive; empty when x0 > x1 or y0 > y1.
struct ScreenBox {
    int x0, y0, x1, y1;
    bool empty() const { return x0 > x1 || y0 > y1; }

    // This box clipped to `other`.
    ScreenBox clipped_to(const ScreenBox& other) const {
        return {std::max(x0, other.x0), std::max(y0, other.y0), std::min(x1, other.x1),
                std::min(y1, other.y1)};
    }
};

// The pixels whose centres lie in [lo_x, hi_x] x [lo_y, hi_y] (pixel coordinates), the bounds
// widened by `pad` on every side; not clipped to any picture.
inline ScreenBox pixels_centred_in(double lo_x, double lo_y, double hi_x, double hi_y,
                                   double pad = 0.0) {
    return {static_cast<int>(std::ceil(lo_x - 0.5 - pad)),
            static_cast<int>(std::ceil(lo_y - 0.5 - pad)),
            static_cast<int>(std::floor(hi_x - 0.5 + pad)),
            static_cast<int>(std::floor(hi_y - 0.5 + pad))};
}

}  // namespace tr
