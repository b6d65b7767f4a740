#include <core/check.h>
#include <core/parallel.h>
#include <core/stopwatch.h>
#include <project/splat/vector_splat.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>

namespace tr {
namespace {

constexpr int kTile = 32;
constexpr double kEndFade = 0.15;  // of the rectangle's length, faded at each end
constexpr double kFront = 0.04;    // of its length: the soft front ahead of a streak's head
// The texture's table per picture: samples along and across (the streaks' Gaussian width, 0.07
// of the width by default, spans 9 samples; the soft front 20).
constexpr int kTableU = 512, kTableV = 128;

// floor / ceil of a pixel coordinate as an int, limited to +-1e9 (NaN to -1e9): a splat far off
// the picture must not overflow the conversion.
int pixel_floor(double v) {
    return static_cast<int>(std::floor(v > -1e9 ? std::min(v, 1e9) : -1e9));
}
int pixel_ceil(double v) { return static_cast<int>(std::ceil(v > -1e9 ? std::min(v, 1e9) : -1e9)); }

struct Rect {
    Vec3 center;         // world
    Vec3 color;          // the transfer function's colour at the point's scalar
    double tau_scale;    // kappa h density
    double cx, cy;       // projected centre, pixel units
    double ax, ay;       // unit direction of motion on the image
    double half_length;  // pixels
    double half_width;   // pixels
    int x0, y0, x1, y1;  // pixels whose centres may lie in the rectangle, inclusive
};

double frac(double x) { return x - std::floor(x); }

double smoothstep01(double x) {
    x = std::clamp(x, 0.0, 1.0);
    return x * x * (3 - 2 * x);
}

}  // namespace

StreakTexture::StreakTexture(const StreakTextureOptions& options) : options_(options) {
    TR_CHECK(options.cycle >= 1 && options.streaks >= 1);
    TR_CHECK(options.streak_length > 0 && options.streak_length <= 1);
    TR_CHECK(options.streak_width > 0);
}

double StreakTexture::operator()(int frame, double u, double v) const {
    if (!(u >= 0 && u <= 1 && std::abs(v) <= 0.5)) return 0.0;
    const int n = options_.cycle;
    const int k = ((frame % n) + n) % n;  // frame k + N is frame k, exactly
    const double window = smoothstep01(u / kEndFade) * smoothstep01((1 - u) / kEndFade);
    const double length = options_.streak_length, width = options_.streak_width;
    double sum = 0;
    for (int j = 0; j < options_.streaks; ++j) {
        // Lanes evenly spaced across 0.8 of the width; heads spread by the golden ratio.
        const double lane = ((j + 0.5) / options_.streaks - 0.5) * 0.8;
        const double across = (v - lane) / width;
        if (across * across > 16) continue;
        const double head = frac(0.5 + j * 0.6180339887498949 + static_cast<double>(k) / n);
        const double behind = frac(head - u);  // 0 at the head, growing toward the tail
        // The ramp: 1 at the head falling to 0 at the tail; a short soft front ahead of the head.
        double along = 0;
        if (behind <= length) {
            along = 1 - behind / length;
        } else if (1 - behind < kFront) {
            along = 1 - (1 - behind) / kFront;
        }
        sum += along * std::exp(-across * across);
    }
    return std::min(sum, 1.0) * window;
}

ProjectedVector project_vector(const CameraFrame& camera, const Vec3& point, const Vec3& vector) {
    const Vec3 d = point - camera.eye();
    const double depth = glm::dot(d, camera.forward());
    const double dsx = glm::dot(vector, camera.right()), dsy = glm::dot(vector, camera.up());
    glm::dvec2 dir;
    Vec3 ray = camera.forward();
    if (camera.orthographic()) {
        dir = {dsx, -dsy};
    } else {
        if (!(depth > 0)) return {};
        const double ddepth = glm::dot(vector, camera.forward());
        dir = {dsx * depth - glm::dot(d, camera.right()) * ddepth,
               -(dsy * depth - glm::dot(d, camera.up()) * ddepth)};
        ray = glm::normalize(d);
    }
    const double speed = glm::length(vector - glm::dot(vector, ray) * ray);
    const double norm = glm::length(dir);
    if (!(speed > 0) || !(norm > 0) || !std::isfinite(norm)) return {};
    return {dir / norm, speed};
}

Image render_vector_splats(const VectorSplatInputs& in, VectorSplatStats* stats) {
    const auto start = std::chrono::steady_clock::now();
    TR_CHECK(in.tf != nullptr && in.texture != nullptr && in.camera != nullptr);
    TR_CHECK_EQ(in.scalar.size(), in.points.size());
    TR_CHECK_EQ(in.vectors.size(), in.points.size());
    TR_CHECK(in.spacing > 0 && in.half_width > 0);
    TR_CHECK(in.min_half_length > 0 && in.min_half_length <= in.max_half_length);
    const CameraFrame& camera = *in.camera;
    const int w = camera.width(), h = camera.height();
    if (in.opaque_color) {
        TR_CHECK_EQ(in.opaque_color->width, w);
        TR_CHECK_EQ(in.opaque_color->height, h);
    }
    if (in.opaque_depth) TR_CHECK_EQ(in.opaque_depth->size(), static_cast<std::size_t>(w) * h);
    const bool orthographic = camera.orthographic();
    // Pixels per world unit at unit depth (perspective) or anywhere (orthographic).
    const double per_unit =
        std::abs(camera.project(camera.eye() + camera.forward()).y -
                 camera.project(camera.eye() + camera.forward() + camera.up()).y);

    // The points to draw, their projected vectors, and the fastest.
    std::vector<std::uint32_t> drawn;
    std::vector<ProjectedVector> projected;
    double fastest = 0;
    for (std::size_t i = 0; i < in.points.size(); ++i) {
        if (!(in.tf->extinction(in.scalar[i]) > 0)) continue;
        const ProjectedVector pv = project_vector(camera, in.points[i], in.vectors[i]);
        if (!(pv.speed > 0)) continue;
        drawn.push_back(static_cast<std::uint32_t>(i));
        projected.push_back(pv);
        fastest = std::max(fastest, pv.speed);
    }
    std::vector<Rect> rects;
    std::vector<double> depth;
    const double reach = std::max(in.max_half_length, in.half_width) * in.spacing;
    for (std::size_t n = 0; n < drawn.size(); ++n) {
        const std::size_t i = drawn[n];
        const Vec3& p = in.points[i];
        const Vec3 s = camera.project(p);
        if (!orthographic && !(s.z > reach)) continue;  // it reaches behind the eye
        const double scale = orthographic ? per_unit : per_unit / s.z;
        const double length = in.min_half_length + (in.max_half_length - in.min_half_length) *
                                                       projected[n].speed / fastest;
        Rect r;
        r.center = p;
        r.color = in.tf->color(in.scalar[i]);
        r.tau_scale = in.tf->extinction(in.scalar[i]) * in.spacing * in.density;
        r.cx = s.x, r.cy = s.y;
        r.ax = projected[n].direction.x, r.ay = projected[n].direction.y;
        r.half_length = length * in.spacing * scale;
        r.half_width = in.half_width * in.spacing * scale;
        const double ex = std::abs(r.ax) * r.half_length + std::abs(r.ay) * r.half_width;
        const double ey = std::abs(r.ay) * r.half_length + std::abs(r.ax) * r.half_width;
        r.x0 = std::max(pixel_floor(s.x - ex - 0.5), 0);
        r.y0 = std::max(pixel_floor(s.y - ey - 0.5), 0);
        r.x1 = std::min(pixel_ceil(s.x + ex - 0.5), w - 1);
        r.y1 = std::min(pixel_ceil(s.y + ey - 0.5), h - 1);
        if (r.x0 > r.x1 || r.y0 > r.y1) continue;
        rects.push_back(r);
        depth.push_back(orthographic ? s.z : glm::length(p - camera.eye()));
    }
    std::vector<std::uint32_t> order(rects.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return depth[a] > depth[b]; });
    const int tiles_x = (w + kTile - 1) / kTile, tiles_y = (h + kTile - 1) / kTile;
    std::vector<std::vector<std::uint32_t>> bins(static_cast<std::size_t>(tiles_x) * tiles_y);
    for (std::uint32_t i : order) {
        const Rect& r = rects[i];
        for (int ty = r.y0 / kTile; ty <= r.y1 / kTile; ++ty) {
            for (int tx = r.x0 / kTile; tx <= r.x1 / kTile; ++tx) {
                bins[static_cast<std::size_t>(ty) * tiles_x + tx].push_back(i);
            }
        }
    }

    Image image(w, h, Vec3f(in.background));
    if (in.opaque_color) image = *in.opaque_color;
    // The frame's texture sampled once on a grid, read bilinearly.
    std::vector<float> table(static_cast<std::size_t>(kTableU + 1) * (kTableV + 1));
    for (int j = 0; j <= kTableV; ++j) {
        for (int i = 0; i <= kTableU; ++i) {
            table[static_cast<std::size_t>(j) * (kTableU + 1) + i] =
                static_cast<float>((*in.texture)(in.frame, static_cast<double>(i) / kTableU,
                                                 static_cast<double>(j) / kTableV - 0.5));
        }
    }
    auto texture = [&](double u, double v) {  // u in [0, 1], v in [-1/2, 1/2]
        const double fu = u * kTableU, fv = (v + 0.5) * kTableV;
        const int i = std::clamp(static_cast<int>(fu), 0, kTableU - 1);
        const int j = std::clamp(static_cast<int>(fv), 0, kTableV - 1);
        const double a = fu - i, b = fv - j;
        const float* row = &table[static_cast<std::size_t>(j) * (kTableU + 1) + i];
        const float* next = row + (kTableU + 1);
        return (1 - b) * ((1 - a) * row[0] + a * row[1]) + b * ((1 - a) * next[0] + a * next[1]);
    };
    std::atomic<std::size_t> fragments{0};
    parallel_for(0, bins.size(), 1, [&](std::size_t tile) {
        const int x0 = static_cast<int>(tile % tiles_x) * kTile;
        const int y0 = static_cast<int>(tile / tiles_x) * kTile;
        const int x1 = std::min(x0 + kTile, w) - 1, y1 = std::min(y0 + kTile, h) - 1;
        std::size_t count = 0;
        for (std::uint32_t i : bins[tile]) {
            const Rect& r = rects[i];
            for (int y = std::max(r.y0, y0); y <= std::min(r.y1, y1); ++y) {
                for (int x = std::max(r.x0, x0); x <= std::min(r.x1, x1); ++x) {
                    const double dx = x + 0.5 - r.cx, dy = y + 0.5 - r.cy;
                    const double along = (dx * r.ax + dy * r.ay) / r.half_length;
                    const double across = (dy * r.ax - dx * r.ay) / r.half_width;
                    if (!(std::abs(along) <= 1 && std::abs(across) <= 1)) continue;
                    const std::size_t pixel = static_cast<std::size_t>(y) * w + x;
                    if (in.opaque_depth) {
                        const Ray ray = camera.pixel_ray(x, y);
                        const double t = glm::dot(r.center - ray.origin, ray.direction);
                        if (!(t < (*in.opaque_depth)[pixel])) continue;
                    }
                    const double t = texture(0.5 * (along + 1), 0.5 * across);
                    if (!(t > 0)) continue;
                    const double alpha = -std::expm1(-r.tau_scale * t);
                    Vec3f& dst = image.pixels[pixel];
                    dst = Vec3f(r.color * alpha) + static_cast<float>(1.0 - alpha) * dst;
                    ++count;
                }
            }
        }
        fragments += count;
    });
    if (stats) {
        stats->splats_drawn = rects.size();
        stats->fragments = fragments.load();
        stats->fastest = fastest;
        stats->raster_ms = ms_since(start);
    }
    return image;
}

}  // namespace tr
