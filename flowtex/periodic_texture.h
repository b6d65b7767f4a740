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

}  // namespace tr
