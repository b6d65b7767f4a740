#pragma once
// A periodic grey texture (filtered noise) with a mip-map pyramid, looked up trilinearly with
// wrap-around, so that regions the flow has stretched are averaged, not aliased (the seed's
// hardware did this with mip-mapping, Williams 1983).

#include <cstdint>
#include <vector>

namespace tr {

class PeriodicTexture {
  public:
    // White noise of side `size` (a power of two, 8..4096) smoothed periodically by three box
    // passes of radius `feature_texels` (>= 1; about the size of a spot), then stretched to mean
    // 0.5 and standard deviation 0.2 and clamped to [0, 1]. The same seed gives the same texture.
    // Cost: O(size^2 * 3) plus the pyramid. Precondition: the arguments as stated.
    static PeriodicTexture filtered_noise(int size, std::uint64_t seed, int feature_texels);

    int size() const { return size_; }
    int levels() const { return static_cast<int>(levels_.size()); }

    // The texture at (u, v) in periods (1 is one whole texture; any real value, wrapped) over a
    // footprint of `footprint` level-0 texels (the pixel's extent in the texture): bilinear on
    // level 0 for footprints <= 1, else trilinear between the levels around log2(footprint),
    // clamped to the coarsest (the mean). Cost: 8 texel reads.
    float sample(double u, double v, double footprint) const;

    // The same at a level of detail lod = log2(footprint) computed by the caller (once per
    // triangle): lod <= 0 is bilinear on level 0.
    float sample_lod(double u, double v, double lod) const;

    // Bilinear on one level (0 = full size). Precondition: 0 <= level < levels().
    float sample_level(double u, double v, int level) const;

    // Texel (i, j) of a level (no wrap). Precondition: in range.
    float texel(int level, int i, int j) const {
        const int n = size_ >> level;
        return levels_[static_cast<std::size_t>(level)][static_cast<std::size_t>(j) * n + i];
    }

  private:
    int size_ = 0;
    std::vector<std::vector<float>> levels_;  // level k: (size >> k)^2 texels, row-major
};

// Inline: a sheet's raster calls these four times a pixel.

inline float PeriodicTexture::sample_level(double u, double v, int level) const {
    // floor(x) as an integer without a libm call (x within +-9e18).
    const auto floor_int = [](double x) {
        const auto i = static_cast<std::int64_t>(x);
        return i - (x < static_cast<double>(i) ? 1 : 0);
    };
    const int n = size_ >> level;
    const float* t = levels_[static_cast<std::size_t>(level)].data();
    // Texel centres at (i + 0.5) / n; wrapping is the mask on the integer part.
    const double x = u * n - 0.5, y = v * n - 0.5;
    const std::int64_t x0 = floor_int(x), y0 = floor_int(y);
    const float fx = static_cast<float>(x - static_cast<double>(x0));
    const float fy = static_cast<float>(y - static_cast<double>(y0));
    const std::int64_t mask = n - 1;
    const std::size_t i0 = static_cast<std::size_t>(x0 & mask);
    const std::size_t j0 = static_cast<std::size_t>(y0 & mask);
    const std::size_t i1 = static_cast<std::size_t>((x0 + 1) & mask);
    const std::size_t r0 = j0 * n, r1 = static_cast<std::size_t>((y0 + 1) & mask) * n;
    const float top = t[r0 + i0] + fx * (t[r0 + i1] - t[r0 + i0]);
    const float bottom = t[r1 + i0] + fx * (t[r1 + i1] - t[r1 + i0]);
    return top + fy * (bottom - top);
}

inline float PeriodicTexture::sample_lod(double u, double v, double lod) const {
    if (!(lod > 0.0)) return sample_level(u, v, 0);
    const int last = levels() - 1;
    if (lod >= last) return levels_.back()[0];
    const int l0 = static_cast<int>(lod);
    const float f = static_cast<float>(lod - l0);
    const float a = sample_level(u, v, l0);
    const float b = sample_level(u, v, l0 + 1);
    return a + f * (b - a);
}

}  // namespace tr
