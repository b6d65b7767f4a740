#pragma once
// Sub-pixel translation between two pictures of the same size, for tests of moving textures:
// brute-force normalised cross-correlation over integer shifts, refined by a parabola through
// the peak and its neighbours along each axis (no FFT).

#include <glm/glm.hpp>

#include <vector>

namespace tr::testing {

struct ShiftEstimate {
    glm::dvec2 shift{0.0};    // b(x, y) ~ a(x - shift.x, y - shift.y), in pixels
    double peak = 0;          // the normalised correlation at the integer peak (<= 1)
    std::size_t overlap = 0;  // pixels compared there
};

// a, b: width x height values, row-major, NaN where a picture has nothing (skipped). Searches
// integer shifts within `search` pixels of `guess` (rounded), comparing the pixels at least
// `margin` from the border. Cost: O((2 search + 1)^2 * pixels).
ShiftEstimate estimate_shift(const std::vector<float>& a, const std::vector<float>& b, int width,
                             int height, glm::dvec2 guess, int search, int margin);

}  // namespace tr::testing
