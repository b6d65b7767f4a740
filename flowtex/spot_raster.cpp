#include <core/parallel.h>
#include <flowtex/detail/spot_random.h>
#include <flowtex/detail/spot_rows.h>
#include <flowtex/spot_raster.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tr {
namespace {

// Rows a band: a spot (about 10 rows high) pays its set-up again in each band it meets; 32 rows
// rendered 17% faster than 16 on 2 threads (bench/spotnoise_bench, 100k spots at 512^2).
constexpr int kBandRows = 32;
constexpr double kCutQ = 9.0;  // 3 sigma
constexpr int kApron = 8;      // a band's rows' spare pixels either side (whole vectors)

int clamp_pixel(double v, int hi) {
    return static_cast<int>(std::clamp(std::floor(v), -1.0, static_cast<double>(hi)));
}

}  // namespace

std::optional<SpotEllipse> spot_ellipse(const CameraFrame& camera, const Vec3& point,
                                        const Vec3& velocity, const SpotRasterOptions& options) {
    const Vec3 c = camera.project(point);
    if (!camera.orthographic() && !(c.z > 0)) return std::nullopt;
    if (!std::isfinite(c.x) || !std::isfinite(c.y)) return std::nullopt;
    SpotEllipse e;
    e.centre = {c.x, c.y};
    e.sigma_short = options.sigma_px;
    const Vec3 c1 = camera.project(point + velocity * options.dt);
    double length = 0;
    if (camera.orthographic() || c1.z > 0) {
        const glm::dvec2 d(c1.x - c.x, c1.y - c.y);
        length = glm::length(d);
        if (length > 0 && std::isfinite(length)) {
            e.direction = d / length;
        } else {
            length = 0;
        }
    }
    e.sigma_long = std::min(options.sigma_px + options.stretch * length,
                            std::max(options.max_sigma_px, options.sigma_px));
    const Ray ray = camera.ray(c.x, c.y);
    e.depth = glm::dot(point - ray.origin, ray.direction);
    return e;
}

void splat_spots(const View& view, const SpotNoise& spots, const SpotRasterOptions& options,
                 SpotBuffers& buffers) {
    const CameraFrame& camera = *view.camera;
    const int w = camera.width(), h = camera.height();
    buffers.width = w;
    buffers.height = h;
    const std::size_t pixels = static_cast<std::size_t>(w) * h;
    // Every row is written below (a band's sums are copied in, an empty band's zeroed).
    buffers.intensity.resize(pixels);
    buffers.coverage.resize(pixels);
    const bool depth_sums = options.depth_sums;
    buffers.depth.resize(depth_sums ? pixels : 0);
    const std::size_t n = spots.size();
    std::vector<detail::SpotPrint>& prints = buffers.prints;
    prints.resize(n);
    buffers.print_bands.resize(n);
    const auto positions = spots.positions();
    const auto velocities = spots.velocities();
    const auto generations = spots.generations();
    parallel_for(0, n, 2048, [&](std::size_t i) {
        detail::SpotPrint& f = prints[i];
        f.x0 = f.y0 = 0, f.x1 = f.y1 = -1;  // none
        buffers.print_bands[i] = {1, 0};    // none
        const auto e = spot_ellipse(camera, positions[i], velocities[i], options);
        if (!e) return;
        // The bounding box of the 3-sigma ellipse.
        const double r = std::sqrt(kCutQ);
        const double ux = e->direction.x, uy = e->direction.y;
        const double lx = e->sigma_long * ux, ly = e->sigma_long * uy;
        const double sx = e->sigma_short * ux, sy = e->sigma_short * uy;
        const double ex = r * std::sqrt(lx * lx + sy * sy), ey = r * std::sqrt(ly * ly + sx * sx);
        const double il = 1.0 / (e->sigma_long * e->sigma_long);
        const double is = 1.0 / (e->sigma_short * e->sigma_short);
        detail::SpotRandom random(0xa11ce, i, generations[i]);
        const double a = 0.5 + 0.5 * random.uniform();
        f.cx = e->centre.x, f.cy = e->centre.y;
        f.qa = ux * ux * il + uy * uy * is;
        f.qb = ux * uy * (il - is);
        f.qc = uy * uy * il + ux * ux * is;
        f.depth = static_cast<float>(e->depth);
        f.amplitude = static_cast<float>(random.uniform() < 0.5 ? -a : a);
        f.x0 = std::max(clamp_pixel(e->centre.x - ex, w), 0);
        f.x1 = std::min(clamp_pixel(e->centre.x + ex, w), w - 1);
        f.y0 = std::max(clamp_pixel(e->centre.y - ey, h), 0);
        f.y1 = std::min(clamp_pixel(e->centre.y + ey, h), h - 1);
        if (f.x0 <= f.x1 && f.y0 <= f.y1) {
            buffers.print_bands[i] = {static_cast<std::uint32_t>(f.y0 / kBandRows),
                                      static_cast<std::uint32_t>(f.y1 / kBandRows)};
        }
    });
    // Each band's spots, in spot order: band b's are band_spots[band_start[b], band_start[b + 1]).
    const int num_bands = (h + kBandRows - 1) / kBandRows;
    std::vector<std::size_t>& band_start = buffers.band_start;
    band_start.assign(static_cast<std::size_t>(num_bands) + 1, 0);
    // The bands each print meets (from the parallel pass above: two small words a spot read
    // here, not its 64-byte print).
    const auto& bands = buffers.print_bands;
    for (const auto& [first, last] : bands) {
        for (std::uint32_t b = first; b <= last; ++b) ++band_start[b + 1];
    }
    std::partial_sum(band_start.begin(), band_start.end(), band_start.begin());
    std::vector<std::uint32_t>& band_spots = buffers.band_spots;
    band_spots.resize(band_start.back());
    {
        std::vector<std::size_t> next(band_start.begin(), band_start.end() - 1);
        for (std::size_t i = 0; i < n; ++i) {
            for (std::uint32_t b = bands[i][0]; b <= bands[i][1]; ++b) {
                band_spots[next[b]++] = static_cast<std::uint32_t>(i);
            }
        }
    }
    const std::vector<double>* depth = view.opaque_depth;
    // A band's sums in rows of `stride` floats with an apron of kApron pixels either side, so
    // that rows of spots run in whole vectors of 8 (the weights outside a spot's ellipse are 0);
    // copied into the picture's rows after the band's spots. With opaque geometry the rows are
    // not widened (the depths exist inside the picture only).
    const int stride = w + 2 * kApron;
    parallel_for(0, static_cast<std::size_t>(num_bands), 1, [&](std::size_t band) {
        const int row0 = static_cast<int>(band) * kBandRows;
        const int row1 = std::min(row0 + kBandRows, h) - 1;
        if (band_start[band] == band_start[band + 1]) {
            const std::size_t from = static_cast<std::size_t>(row0) * w;
            const std::size_t count = static_cast<std::size_t>(row1 - row0 + 1) * w;
            std::fill_n(buffers.intensity.data() + from, count, 0.0f);
            std::fill_n(buffers.coverage.data() + from, count, 0.0f);
            if (depth_sums) std::fill_n(buffers.depth.data() + from, count, 0.0f);
            return;
        }
        const std::size_t band_floats = static_cast<std::size_t>(stride) * kBandRows;
        std::vector<float> sums((depth_sums ? 3 : 2) * band_floats, 0.0f);
        float* const band_intensity = sums.data();
        float* const band_coverage = band_intensity + band_floats;
        float* const band_depth = depth_sums ? band_coverage + band_floats : nullptr;
        spot_rows::add_spots({band_intensity, band_coverage, band_depth, stride, kApron, w, row0,
                              row1, depth ? depth->data() : nullptr},
                             prints.data(), band_spots.data() + band_start[band],
                             band_start[band + 1] - band_start[band]);
        for (int y = row0; y <= row1; ++y) {
            const std::size_t from = static_cast<std::size_t>(y - row0) * stride + kApron;
            const std::size_t to = static_cast<std::size_t>(y) * w;
            std::copy_n(band_intensity + from, w, buffers.intensity.data() + to);
            std::copy_n(band_coverage + from, w, buffers.coverage.data() + to);
            if (depth_sums) std::copy_n(band_depth + from, w, buffers.depth.data() + to);
        }
    });
}

void spot_color(const SpotRasterOptions& options, float intensity, float coverage, Vec3f& color,
                float& alpha) {
    float grey = 0;
    spot_rows::spot_shade(static_cast<float>(options.contrast), static_cast<float>(options.opacity),
                          intensity, coverage, grey, alpha);
    color = options.dark + grey * (options.light - options.dark);
}

void render_spots(const View& view, const SpotNoise& spots, const SpotRasterOptions& options,
                  SpotBuffers& buffers, Image& image) {
    SpotRasterOptions sums_only = options;  // the colouring needs no depth sums
    sums_only.depth_sums = false;
    splat_spots(view, spots, sums_only, buffers);
    const int w = view.camera->width(), h = view.camera->height();
    if (image.width != w || image.height != h) image = Image(w, h);
    const Image* opaque = view.opaque_color;
    const Vec3f background(view.background);
    const Vec3f dark = options.dark, range = options.light - options.dark;
    parallel_for(0, static_cast<std::size_t>(h), 8, [&](std::size_t y) {
        // The row's greys and opacities (vectorised: spot_color's), then the colours over the
        // background (the sums of uncovered pixels are 0: opacity 0).
        std::vector<float> grey(static_cast<std::size_t>(w)), alpha(static_cast<std::size_t>(w));
        const std::size_t row = y * w;
        spot_rows::shade_row(buffers.intensity.data() + row, buffers.coverage.data() + row,
                             grey.data(), alpha.data(), w, static_cast<float>(options.contrast),
                             static_cast<float>(options.opacity));
        for (int x = 0; x < w; ++x) {
            const std::size_t pixel = row + x;
            const Vec3f base = opaque ? opaque->pixels[pixel] : background;
            const float a = alpha[static_cast<std::size_t>(x)];
            image.pixels[pixel] =
                a * (dark + grey[static_cast<std::size_t>(x)] * range) + (1.0f - a) * base;
        }
    });
}

}  // namespace tr
