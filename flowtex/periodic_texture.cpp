#include <core/check.h>
#include <flowtex/periodic_texture.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace tr {
namespace {

// One periodic box pass of radius r along rows (transpose = false) or columns.
void box_pass(std::vector<float>& img, int n, int r, bool columns) {
    std::vector<float> line(static_cast<std::size_t>(n)), out(static_cast<std::size_t>(n));
    const float scale = 1.0f / static_cast<float>(2 * r + 1);
    for (int k = 0; k < n; ++k) {
        for (int i = 0; i < n; ++i) {
            line[i] = columns ? img[static_cast<std::size_t>(i) * n + k]
                              : img[static_cast<std::size_t>(k) * n + i];
        }
        double sum = 0;
        for (int d = -r; d <= r; ++d) sum += line[((d % n) + n) % n];
        for (int i = 0; i < n; ++i) {
            out[i] = static_cast<float>(sum) * scale;
            sum += line[(i + r + 1) % n] - line[((i - r) % n + n) % n];
        }
        for (int i = 0; i < n; ++i) {
            (columns ? img[static_cast<std::size_t>(i) * n + k]
                     : img[static_cast<std::size_t>(k) * n + i]) = out[i];
        }
    }
}

}  // namespace

PeriodicTexture PeriodicTexture::filtered_noise(int size, std::uint64_t seed, int feature_texels) {
    TR_CHECK(size >= 8 && size <= 4096 && (size & (size - 1)) == 0);
    TR_CHECK(feature_texels >= 1);
    const int n = size;
    const int r = std::min(feature_texels, n / 2 - 1);
    std::vector<float> img(static_cast<std::size_t>(n) * n);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (float& t : img) t = uniform(rng);
    for (int pass = 0; pass < 3; ++pass) {
        box_pass(img, n, r, false);
        box_pass(img, n, r, true);
    }
    double mean = 0, sq = 0;
    for (float t : img) mean += t;
    mean /= static_cast<double>(img.size());
    for (float t : img) sq += (t - mean) * (t - mean);
    const double sd = std::sqrt(sq / static_cast<double>(img.size()));
    for (float& t : img) {
        t = static_cast<float>(std::clamp(0.5 + 0.2 * (t - mean) / std::max(sd, 1e-12), 0.0, 1.0));
    }
    PeriodicTexture tex;
    tex.size_ = n;
    tex.levels_.push_back(std::move(img));
    for (int m = n / 2; m >= 1; m /= 2) {
        const std::vector<float>& fine = tex.levels_.back();
        std::vector<float> coarse(static_cast<std::size_t>(m) * m);
        const int f = 2 * m;
        for (int j = 0; j < m; ++j) {
            for (int i = 0; i < m; ++i) {
                const std::size_t a = static_cast<std::size_t>(2 * j) * f + 2 * i;
                coarse[static_cast<std::size_t>(j) * m + i] =
                    0.25f * (fine[a] + fine[a + 1] + fine[a + f] + fine[a + f + 1]);
            }
        }
        tex.levels_.push_back(std::move(coarse));
    }
    return tex;
}

namespace {}  // namespace

float PeriodicTexture::sample(double u, double v, double footprint) const {
    if (!(footprint > 1.0)) return sample_level(u, v, 0);
    return sample_lod(u, v, std::log2(footprint));
}

}  // namespace tr
