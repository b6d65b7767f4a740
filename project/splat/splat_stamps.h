#pragma once
// Footprint stamps: a splat kernel's footprint at one scale (pixels per kernel unit), sampled
// on the pixel grid in advance for a lattice of sub-pixel positions of the splat's centre — what
// the texture-mapping paper's hardware did with its footprint texture. An orthographic splat of
// that scale is then drawn by blending the four stamps around its centre's sub-pixel position
// (bilinearly), row by row, with no table lookup per pixel: the raster's inner loop becomes
// straight-line arithmetic the compiler vectorises.
//
// Geometry: pixel x's centre is at x + 0.5; a centre at pixel coordinate c (x and y alike) has
// the index position p = c - 0.5, its whole part X = floor(p) and its fraction o = p - X in
// [0, 1). Stamp (i, j) of the (steps + 1)^2 holds, at column u and row v of its width^2 samples,
// the footprint at the distance from ((u - reach) - i / steps, (v - reach) - j / steps), so
// column u is pixel X - reach + u. Samples outside the support's circle are 0 (as the footprint).
//
// Accuracy: blending in the offset is exact at the stamps' offsets and elsewhere off by the
// footprint's curvature times (1 / (steps * pixels_per_unit))^2 / 8 (kernel units); steps is
// chosen so that steps * pixels_per_unit >= kResolution, bounding that alike at any scale (from
// 1 pixel per kernel unit, 64 steps). Measured in tests/splat/splat_stamps_test.cpp: within
// 2.3e-4 of the footprint's peak from 1 to 30 pixels per kernel unit (a sixteenth of an 8-bit
// level).

#include <project/splat/splat_kernel.h>

#include <vector>

namespace tr {

class SplatStamps {
  public:
    // Samples per kernel unit the stamps resolve the centre's position to (steps * scale).
    static constexpr double kResolution = 64.0;
    // The widest stamp built (pixels): larger splats are drawn without stamps.
    static constexpr int kMaxWidth = 160;
    // The most sub-pixel steps: splats under kResolution / kMaxSteps = 1 pixel per kernel unit
    // (where stamps would be coarser than kResolution) are drawn without stamps.
    static constexpr int kMaxSteps = 64;

    // Whether a footprint at `pixels_per_unit` is stamped: at least 1 pixel per kernel unit, in
    // stamps of at most kMaxWidth pixels.
    static bool fits(const SplatFootprint& footprint, double pixels_per_unit);

    // Preconditions: pixels_per_unit > 0 and fits(footprint, pixels_per_unit) (checked).
    SplatStamps(const SplatFootprint& footprint, double pixels_per_unit);

    int width() const { return width_; }  // a multiple of 8
    int reach() const { return reach_; }
    int steps() const { return steps_; }
    float peak() const { return peak_; }  // the largest sample

    // A splat centred at pixel coordinates (cx, cy): its stamps' first pixel, the four stamps'
    // samples and weights, and per stamp row the columns that may be non-zero.
    struct Placement {
        int x0, y0;              // the pixel of column 0, row 0
        const float* stamp[4];   // width^2 samples each, row-major
        float weight[4];         // summing to 1
        const short* span_from;  // per row: the first column that may be non-zero
        const short* span_to;    // per row: one past the last (from == to: the row is empty)
    };
    Placement place(double cx, double cy) const;

  private:
    std::size_t area() const { return static_cast<std::size_t>(width_) * width_; }

    int width_ = 0, reach_ = 0, steps_ = 1;
    float peak_ = 0;
    std::vector<float> samples_;  // (steps + 1)^2 stamps of width^2, stamp (i, j) at j (s + 1) + i
    // Per stamp row v and pair of row offsets (j, j + 1) blended: the union of the non-zero
    // columns over the stamps of those rows (indexed [j * width + v]).
    std::vector<short> span_from_, span_to_;
};

}  // namespace tr
