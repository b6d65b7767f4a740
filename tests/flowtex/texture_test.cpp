// The periodic noise texture: periodicity, the mip pyramid's averages, filtered lookups.
#include <flowtex/periodic_texture.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace tr {
namespace {

TEST(PeriodicTexture, WrapsAndItsPyramidAverages) {
    const PeriodicTexture tex = PeriodicTexture::filtered_noise(64, 7, 2);
    ASSERT_EQ(tex.levels(), 7);  // 64, 32, ..., 1
    // Periodic: whole periods apart give the same value at every level.
    for (int k = 0; k < 50; ++k) {
        const double u = 0.013 * k - 0.3, v = 0.029 * k + 0.1;
        for (int level = 0; level < tex.levels(); ++level) {
            EXPECT_NEAR(tex.sample_level(u, v, level), tex.sample_level(u + 3, v - 2, level), 1e-5);
        }
    }
    // Each coarser texel is the mean of the four finer ones below it; so every level has the
    // same mean, and the 1x1 level is it (the mean is 0.5 before clamping to [0, 1]).
    double mean0 = 0;
    for (int j = 0; j < 64; ++j) {
        for (int i = 0; i < 64; ++i) mean0 += tex.texel(0, i, j);
    }
    mean0 /= 64 * 64;
    EXPECT_NEAR(tex.texel(6, 0, 0), mean0, 1e-5);
    EXPECT_NEAR(mean0, 0.5, 0.01);
    EXPECT_NEAR(tex.texel(1, 3, 5),
                0.25 * (tex.texel(0, 6, 10) + tex.texel(0, 7, 10) + tex.texel(0, 6, 11) +
                        tex.texel(0, 7, 11)),
                1e-6);
}

TEST(PeriodicTexture, WideFootprintsAverageInsteadOfAliasing) {
    // A pixel covering 16 texels reads level 4: its value varies far less than single texels
    // do (the point of mip-mapping a stretched texture), and a footprint past the whole texture
    // reads the mean.
    const PeriodicTexture tex = PeriodicTexture::filtered_noise(128, 3, 1);
    auto spread = [&](double footprint) {
        double s = 0, ss = 0;
        const int n = 2000;
        for (int k = 0; k < n; ++k) {
            const double u = std::fmod(k * 0.6180339887, 1.0), v = std::fmod(k * 0.7548776662, 1.0);
            const double x = tex.sample(u, v, footprint);
            s += x;
            ss += x * x;
        }
        return std::sqrt(ss / n - (s / n) * (s / n));
    };
    const double sharp = spread(1.0), blurred = spread(16.0);
    std::printf("spread: footprint 1 %.4f, footprint 16 %.4f\n", sharp, blurred);
    // Measured: footprint 1 spreads 0.1948, footprint 16 0.0375; bounds 0.9x and 1.25x.
    EXPECT_GT(sharp, 0.1948 * 0.9);
    EXPECT_LT(blurred, 0.0375 * 1.25);
    EXPECT_FLOAT_EQ(tex.sample(0.3, 0.8, 1e6), tex.texel(tex.levels() - 1, 0, 0));
}

}  // namespace
}  // namespace tr
