#include <core/parallel.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <flowtex/detail/spot_random.h>
#include <flowtex/spot_raster.h>

namespace tr {
namespace {

constexpr int kBandRows = 16;
constexpr double kCutQ = 9.0;  // 3 sigma
constexpr float kCutQf = 9.0f;
constexpr int kTableSize = 1024;

struct Footprint {
    SpotEllipse e;
    float amplitude = 0;
    int x0 = 0, x1 = -1, y0 = 0, y1 = -1;  // inclusive pixel bounds
};

// What the inner loop reads of a footprint, copied into each band it meets so that a band
// reads its spots in sequence.
struct BandSpot {
    double cx, cy;      // centre, pixels
    double qa, qb, qc;  // q(dx, dy) = qa dx^2 + 2 qb dx dy + qc dy^2
    float depth;        // the centre's ray parameter (float: compared with the opaque depth)
    float amplitude;
    int x0, x1, y0, y1;
};

const std::array<float, kTableSize + 1>& gaussian_table() {
    static const std::array<float, kTableSize + 1> table = [] {
        std::array<float, kTableSize + 1> t{};
        for (int k = 0; k <= kTableSize; ++k) {
            t[k] = static_cast<float>(std::exp(-0.5 * kCutQ * k / kTableSize));
        }
        return t;
    }();
    return table;
}

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

void splat_spots(const CameraFrame& camera, const SpotNoise& spots,
                 const SpotRasterOptions& options, SpotBuffers& buffers) {
    const int w = camera.width(), h = camera.height();
    buffers.width = w;
    buffers.height = h;
    const std::size_t pixels = static_cast<std::size_t>(w) * h;
    buffers.intensity.assign(pixels, 0.0f);
    buffers.coverage.assign(pixels, 0.0f);
    buffers.depth.assign(pixels, 0.0f);
    const std::size_t n = spots.size();
    std::vector<Footprint> prints(n);
    const auto positions = spots.positions();
    const auto velocities = spots.velocities();
    const auto generations = spots.generations();
    parallel_for(0, n, 2048, [&](std::size_t i) {
        Footprint& f = prints[i];
        const auto e = spot_ellipse(camera, positions[i], velocities[i], options);
        if (!e) return;
        f.e = *e;
        // The bounding box of the 3-sigma ellipse.
        const double r = std::sqrt(kCutQ);
        const double dx = e->direction.x, dy = e->direction.y;
        const double ex = r * std::hypot(e->sigma_long * dx, e->sigma_short * dy);
        const double ey = r * std::hypot(e->sigma_long * dy, e->sigma_short * dx);
        f.x0 = std::max(clamp_pixel(e->centre.x - ex, w), 0);
        f.x1 = std::min(clamp_pixel(e->centre.x + ex, w), w - 1);
        f.y0 = std::max(clamp_pixel(e->centre.y - ey, h), 0);
        f.y1 = std::min(clamp_pixel(e->centre.y + ey, h), h - 1);
        detail::SpotRandom random(0xa11ce, i, generations[i]);
        const double a = 0.5 + 0.5 * random.uniform();
        f.amplitude = static_cast<float>(random.uniform() < 0.5 ? -a : a);
    });
    const int num_bands = (h + kBandRows - 1) / kBandRows;
    std::vector<std::vector<BandSpot>> bins(num_bands);
    for (std::size_t i = 0; i < n; ++i) {
        const Footprint& f = prints[i];
        if (f.x1 < f.x0 || f.y1 < f.y0) continue;
        const double il = 1.0 / (f.e.sigma_long * f.e.sigma_long);
        const double is = 1.0 / (f.e.sigma_short * f.e.sigma_short);
        const double ux = f.e.direction.x, uy = f.e.direction.y;
        const BandSpot spot{f.e.centre.x,
                            f.e.centre.y,
                            ux * ux * il + uy * uy * is,
                            ux * uy * (il - is),
                            uy * uy * il + ux * ux * is,
                            static_cast<float>(f.e.depth),
                            f.amplitude,
                            f.x0,
                            f.x1,
                            f.y0,
                            f.y1};
        for (int b = f.y0 / kBandRows; b <= f.y1 / kBandRows; ++b) bins[b].push_back(spot);
    }
    const auto& table = gaussian_table();
    const float to_table = static_cast<float>(kTableSize / kCutQ);
    const std::vector<double>* depth = options.opaque_depth;
    parallel_for(0, bins.size(), 1, [&](std::size_t band) {
        const int row0 = static_cast<int>(band) * kBandRows;
        const int row1 = std::min(row0 + kBandRows, h) - 1;
        for (const BandSpot& f : bins[band]) {
            const double qa = f.qa, qb = f.qb, qc = f.qc;
            // The span of a row: q(dx) = 9 at dx = (-qb dy -+ sqrt(9 qa - det dy^2)) / qa, det =
            // qa qc - qb^2. Truncation toward zero keeps the span conservative (the q test below
            // is exact), and is cheaper than floor and ceil.
            const double det = qa * qc - qb * qb, inv_qa = 1.0 / qa;
            for (int y = std::max(f.y0, row0); y <= std::min(f.y1, row1); ++y) {
                const double dy = y + 0.5 - f.cy;
                const double disc = kCutQ * qa - det * dy * dy;
                if (!(disc > 0)) continue;
                const double half = std::sqrt(disc) * inv_qa;
                const double mid = f.cx - qb * dy * inv_qa - 0.5;
                const int xa = std::max(f.x0, static_cast<int>(mid - half));
                const int xb = std::min(f.x1, static_cast<int>(mid + half) + 1);
                const double dx0 = xa + 0.5 - f.cx;
                float q = static_cast<float>(qa * dx0 * dx0 + 2 * qb * dx0 * dy + qc * dy * dy);
                float dq = static_cast<float>(qa * (2 * dx0 + 1) + 2 * qb * dy);
                const float ddq = static_cast<float>(2 * qa);
                const std::size_t row = static_cast<std::size_t>(y) * w;
                float* intensity = buffers.intensity.data() + row;
                float* coverage = buffers.coverage.data() + row;
                float* depth_sum = buffers.depth.data() + row;
                const double* hidden = depth ? depth->data() + row : nullptr;
                for (int x = xa; x <= xb; ++x, q += dq, dq += ddq) {
                    if (!(q < kCutQf)) continue;
                    if (hidden && !(f.depth < hidden[x])) continue;
                    const float weight =
                        table[static_cast<int>(std::max(q, 0.0f) * to_table + 0.5f)];
                    intensity[x] += f.amplitude * weight;
                    coverage[x] += weight;
                    depth_sum[x] += f.depth * weight;
                }
            }
        }
    });
}

void spot_color(const SpotRasterOptions& options, float intensity, float coverage, Vec3f& color,
                float& alpha) {
    const double cover = coverage;
    const double g = 0.5 + 0.5 * std::tanh(options.contrast * intensity / std::sqrt(1.0 + cover));
    alpha = static_cast<float>(-std::expm1(-options.opacity * cover));
    color = options.dark + static_cast<float>(g) * (options.light - options.dark);
}

void render_spots(const CameraFrame& camera, const SpotNoise& spots,
                  const SpotRasterOptions& options, SpotBuffers& buffers, Image& image) {
    splat_spots(camera, spots, options, buffers);
    const int w = camera.width(), h = camera.height();
    if (image.width != w || image.height != h) image = Image(w, h);
    const Image* opaque = options.opaque_color;
    parallel_for(0, static_cast<std::size_t>(h), 8, [&](std::size_t y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t pixel = y * w + x;
            const Vec3f base = opaque ? opaque->pixels[pixel] : options.background;
            const double cover = buffers.coverage[pixel];
            if (!(cover > 0)) {
                image.pixels[pixel] = base;
                continue;
            }
            Vec3f spot;
            float alpha = 0;
            spot_color(options, buffers.intensity[pixel], buffers.coverage[pixel], spot, alpha);
            image.pixels[pixel] = alpha * spot + (1.0f - alpha) * base;
        }
    });
}

}  // namespace tr
