#include <core/check.h>
#include <core/parallel.h>
#include <project/splat_renderer.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>

namespace tr {
namespace {

constexpr int kTile = 32;

// floor / ceil of a pixel coordinate as an int, limited to +-1e9 (NaN to -1e9): a splat far off
// the picture must not overflow the conversion.
int pixel_floor(double v) {
    return static_cast<int>(std::floor(v > -1e9 ? std::min(v, 1e9) : -1e9));
}
int pixel_ceil(double v) { return static_cast<int>(std::ceil(v > -1e9 ? std::min(v, 1e9) : -1e9)); }

struct Splat {
    Vec3 center;
    Vec3 color;          // the transfer function's colour at the point's value
    double kappa;        // its extinction
    double h;            // the kernel's scale: the spacing, or the point's radius
    double sx, sy;       // the projected centre, pixel units
    double depth;        // along the view (orthographic: the ray parameter of the centre)
    int x0, y0, x1, y1;  // pixels whose centres may lie in its footprint, inclusive
};

// A tile's sheet buffer: the current sheet's summed optical depth and depth-weighted colour
// per pixel, row-major with rows kTile long.
struct SheetTile {
    float tau[kTile * kTile] = {};
    float r[kTile * kTile] = {}, g[kTile * kTile] = {}, b[kTile * kTile] = {};
};

// Where an orthographic splat's fragments go: its pixels' rectangle in the tile, the tile's
// corner, the picture (per-splat compositing) or the tile's sheet buffer, and the opaque depths.
struct OrthographicTarget {
    int xa, xb, ya, yb;  // inclusive, inside the tile and the picture
    int x0, y0;          // the tile's corner
    Vec3f* pixels;       // the picture, row-major
    int width;
    SheetTile* sheet;
    const double* opaque_depth;  // or null (then unused)
};

// One splat of an orthographic view: rays are parallel, so the distance to each pixel's ray is
// that on the image (in kernel units) and the centre's ray parameter is its depth. Per row, the
// pixels whose centres lie strictly inside the support's circle; f read by rho^2. Returns the
// fragments drawn. Instantiated per compositing and opaque geometry: the inner loop has no
// branch but the opaque test.
template <bool kSheets, bool kOpaque>
std::size_t raster_orthographic(const Splat& s, double per_unit, const SplatFootprint& footprint,
                                const OrthographicTarget& t) {
    const auto support_sq = static_cast<float>(footprint.support() * footprint.support());
    const auto to_kernel = static_cast<float>(1.0 / (per_unit * s.h));
    const auto kappa_h = static_cast<float>(s.kappa * s.h);
    const auto sx = static_cast<float>(s.sx), sy = static_cast<float>(s.sy);
    const Vec3f colour(s.color);
    std::size_t count = 0;
    for (int y = t.ya; y <= t.yb; ++y) {
        const float dy = (static_cast<float>(y) + 0.5f - sy) * to_kernel;
        const float dy_sq = dy * dy;
        if (!(dy_sq < support_sq)) continue;
        const float half = std::sqrt(support_sq - dy_sq) / to_kernel;  // pixels
        const int from = std::max(t.xa, pixel_floor(sx - half - 0.5f) + 1);
        const int to = std::min(t.xb, pixel_ceil(sx + half - 0.5f) - 1);
        const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(t.width);
        const int local_row = (y - t.y0) * kTile - t.x0;
        for (int x = from; x <= to; ++x) {
            if constexpr (kOpaque) {
                if (!(s.depth < t.opaque_depth[row + static_cast<std::size_t>(x)])) continue;
            }
            const float dx = (static_cast<float>(x) + 0.5f - sx) * to_kernel;
            const float tau = kappa_h * footprint.of_squared_inside(dx * dx + dy_sq);
            ++count;
            if constexpr (kSheets) {
                const int local = local_row + x;
                t.sheet->tau[local] += tau;
                t.sheet->r[local] += tau * colour.r;
                t.sheet->g[local] += tau * colour.g;
                t.sheet->b[local] += tau * colour.b;
            } else {
                // 1 - exp rather than expm1: several times faster, and its absolute error (6e-8
                // in float) is far below the picture's 8 bits.
                const float alpha = 1.0f - std::exp(-tau);
                Vec3f& dst = t.pixels[row + static_cast<std::size_t>(x)];
                dst = colour * alpha + (1.0f - alpha) * dst;
            }
        }
    }
    return count;
}

}  // namespace

namespace {

// The distinct coordinates per axis and their extents.
void axis_counts(std::span<const Vec3> points, double count[3], double extent[3]) {
    for (int k = 0; k < 3; ++k) {
        std::vector<double> c(points.size());
        for (std::size_t i = 0; i < points.size(); ++i) c[i] = points[i][k];
        std::sort(c.begin(), c.end());
        c.erase(std::unique(c.begin(), c.end()), c.end());
        count[k] = static_cast<double>(c.size());
        extent[k] = c.back() - c.front();
    }
}

}  // namespace

bool is_axis_aligned_lattice(std::span<const Vec3> points) {
    if (points.size() < 2) return false;
    double count[3], extent[3];
    axis_counts(points, count, extent);
    return count[0] * count[1] * count[2] == static_cast<double>(points.size());
}

double lattice_spacing(std::span<const Vec3> points) {
    if (points.size() < 2) return 0.0;
    // An axis-aligned lattice: as many points as the product of the distinct coordinates per
    // axis; its spacings, exactly.
    double count[3], extent[3];
    axis_counts(points, count, extent);
    double measure = 1.0, cells = 1.0;
    int dims = 0;
    for (int k = 0; k < 3; ++k) {
        if (extent[k] > 0) measure *= extent[k], cells *= count[k] - 1, ++dims;
    }
    if (dims == 0) return 0.0;
    if (count[0] * count[1] * count[2] != static_cast<double>(points.size())) {
        // Not a full lattice: that of the same number of points filling the bounds (a lattice of
        // n points per axis spans n - 1 spacings).
        cells = std::pow(
            std::max(std::pow(static_cast<double>(points.size()), 1.0 / dims) - 1.0, 1.0), dims);
    }
    return std::pow(measure / cells, 1.0 / dims);
}

Image render_splats(const SplatInputs& in, SplatStats* stats) {
    const auto start = std::chrono::steady_clock::now();
    TR_CHECK(in.tf != nullptr && in.footprint != nullptr && in.camera != nullptr);
    TR_CHECK_EQ(in.scalar.size(), in.points.size());
    TR_CHECK(in.spacing > 0);
    if (!in.radius.empty()) TR_CHECK_EQ(in.radius.size(), in.points.size());
    const CameraFrame& camera = *in.camera;
    const int w = camera.width(), h = camera.height();
    if (in.opaque_color) {
        TR_CHECK_EQ(in.opaque_color->width, w);
        TR_CHECK_EQ(in.opaque_color->height, h);
    }
    if (in.opaque_depth) TR_CHECK_EQ(in.opaque_depth->size(), static_cast<std::size_t>(w) * h);
    const bool orthographic = camera.orthographic();
    const double support = in.footprint->support();
    // Pixels per world unit at unit depth (perspective) or anywhere (orthographic).
    const double per_unit =
        std::abs(camera.project(camera.eye() + camera.forward()).y -
                 camera.project(camera.eye() + camera.forward() + camera.up()).y);

    // The splats in view, back to front.
    std::vector<Splat> splats;
    std::vector<double> depth;
    for (std::size_t i = 0; i < in.points.size(); ++i) {
        const double kappa = in.tf->extinction(in.scalar[i]);
        if (!(kappa > 0)) continue;
        const Vec3& p = in.points[i];
        const Vec3 s = camera.project(p);
        const double kernel_h = in.radius.empty() ? in.spacing : static_cast<double>(in.radius[i]);
        const double radius = support * kernel_h;  // world units
        double r_px;
        if (orthographic) {
            r_px = radius * per_unit;
        } else {
            if (!(s.z > radius)) continue;  // its support reaches behind the eye
            // A sphere of the support's radius projects within this (its nearest depth, and
            // the stretch off the axis, distance over depth).
            const double distance = glm::length(p - camera.eye());
            r_px = radius * per_unit / (s.z - radius) * (distance / s.z);
        }
        Splat splat{p,
                    in.tf->color(in.scalar[i]),
                    kappa,
                    kernel_h,
                    s.x,
                    s.y,
                    s.z,
                    pixel_floor(s.x - r_px - 0.5),
                    pixel_floor(s.y - r_px - 0.5),
                    pixel_ceil(s.x + r_px - 0.5),
                    pixel_ceil(s.y + r_px - 0.5)};
        splat.x0 = std::max(splat.x0, 0), splat.y0 = std::max(splat.y0, 0);
        splat.x1 = std::min(splat.x1, w - 1), splat.y1 = std::min(splat.y1, h - 1);
        if (splat.x0 > splat.x1 || splat.y0 > splat.y1) continue;
        splats.push_back(splat);
        depth.push_back(orthographic ? s.z : glm::length(p - camera.eye()));
    }
    std::vector<std::uint32_t> order(splats.size());
    std::iota(order.begin(), order.end(), 0u);
    const bool sheets = in.compositing == SplatCompositing::kSheetBuffer;
    std::vector<std::int64_t> sheet;  // sheet buffer: each splat's sheet
    int axis = -1;
    if (sheets && !splats.empty()) {
        // The axis most parallel to the view, and the sheets of thickness `spacing` across it.
        Vec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
        for (const Splat& s : splats) lo = glm::min(lo, s.center), hi = glm::max(hi, s.center);
        const Vec3 view = orthographic ? camera.forward() : 0.5 * (lo + hi) - camera.eye();
        axis = 0;
        for (int k = 1; k < 3; ++k) {
            if (std::abs(view[k]) > std::abs(view[axis])) axis = k;
        }
        sheet.resize(splats.size());
        for (std::size_t i = 0; i < splats.size(); ++i) {
            sheet[i] = std::llround((splats[i].center[axis] - lo[axis]) / in.spacing);
        }
        // Back to front: orthographic, further along the view; perspective, further from the eye
        // across the sheets (ties, sheets either side of the eye, by index).
        const double sign = view[axis] < 0 ? -1.0 : 1.0;
        auto key = [&](std::int64_t index) {
            const double plane = lo[axis] + static_cast<double>(index) * in.spacing;
            return orthographic ? sign * plane : std::abs(plane - camera.eye()[axis]);
        };
        std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
            if (sheet[a] == sheet[b]) return depth[a] > depth[b];
            const double ka = key(sheet[a]), kb = key(sheet[b]);
            return ka != kb ? ka > kb : sheet[a] > sheet[b];
        });
    } else {
        std::stable_sort(order.begin(), order.end(),
                         [&](std::uint32_t a, std::uint32_t b) { return depth[a] > depth[b]; });
    }
    // Binned into tiles in that order.
    const int tiles_x = (w + kTile - 1) / kTile, tiles_y = (h + kTile - 1) / kTile;
    std::vector<std::vector<std::uint32_t>> bins(static_cast<std::size_t>(tiles_x) * tiles_y);
    for (std::uint32_t i : order) {
        const Splat& s = splats[i];
        for (int ty = s.y0 / kTile; ty <= s.y1 / kTile; ++ty) {
            for (int tx = s.x0 / kTile; tx <= s.x1 / kTile; ++tx) {
                bins[static_cast<std::size_t>(ty) * tiles_x + tx].push_back(i);
            }
        }
    }

    Image image(w, h, Vec3f(in.background));
    if (in.opaque_color) image = *in.opaque_color;
    const double support_sq = support * support;
    const SplatFootprint& fp = *in.footprint;
    const double* const opaque = in.opaque_depth ? in.opaque_depth->data() : nullptr;
    std::atomic<std::size_t> fragments{0};
    parallel_for(0, bins.size(), 1, [&](std::size_t tile) {
        const int x0 = static_cast<int>(tile % tiles_x) * kTile;
        const int y0 = static_cast<int>(tile / tiles_x) * kTile;
        const int x1 = std::min(x0 + kTile, w) - 1, y1 = std::min(y0 + kTile, h) - 1;
        Ray rays[kTile * kTile];
        for (int y = y0; !orthographic && y <= y1; ++y) {
            for (int x = x0; x <= x1; ++x)
                rays[(y - y0) * kTile + (x - x0)] = camera.pixel_ray(x, y);
        }
        std::size_t count = 0;
        // The sheet buffer: the current sheet's summed optical depth and depth-weighted colour.
        SheetTile sheet_buffer;
        float* const sheet_tau = sheet_buffer.tau;
        float* const sheet_r = sheet_buffer.r;
        float* const sheet_g = sheet_buffer.g;
        float* const sheet_b = sheet_buffer.b;
        std::int64_t current = 0;
        bool open = false;
        auto flush = [&] {
            for (int y = y0; y <= y1; ++y) {
                for (int x = x0; x <= x1; ++x) {
                    const int local = (y - y0) * kTile + (x - x0);
                    const float tau = sheet_tau[local];
                    if (!(tau > 0)) continue;
                    // 1 - exp in float: absolute error about 6e-8, far below the float
                    // picture's 8-bit output (expm1 in double cost a third of the raster).
                    const float alpha = 1.0f - std::exp(-tau);
                    const float scale = alpha / tau;
                    Vec3f& dst = image.pixels[static_cast<std::size_t>(y) * w + x];
                    dst = Vec3f(sheet_r[local] * scale, sheet_g[local] * scale,
                                sheet_b[local] * scale) +
                          (1.0f - alpha) * dst;
                    sheet_tau[local] = sheet_r[local] = sheet_g[local] = sheet_b[local] = 0.0f;
                }
            }
        };
        // One fragment: optical depth `tau` of splat colour `colour` on pixel (x, y).
        auto add = [&](int x, int y, float tau, const Vec3f& colour) {
            if (sheets) {
                const int local = (y - y0) * kTile + (x - x0);
                sheet_tau[local] += tau;
                sheet_r[local] += tau * colour.r;
                sheet_g[local] += tau * colour.g;
                sheet_b[local] += tau * colour.b;
                return;
            }
            // 1 - exp rather than expm1: several times faster, and its absolute error (6e-8 in
            // float) is far below the picture's 8 bits.
            const float alpha = 1.0f - std::exp(-tau);
            Vec3f& dst = image.pixels[static_cast<std::size_t>(y) * w + x];
            dst = colour * alpha + (1.0f - alpha) * dst;
        };
        for (std::uint32_t i : bins[tile]) {
            const Splat& s = splats[i];
            if (sheets) {
                if (open && sheet[i] != current) flush();
                current = sheet[i], open = true;
            }
            const Vec3f colour(s.color);
            const int ya = std::max(s.y0, y0), yb = std::min(s.y1, y1);
            const int xa = std::max(s.x0, x0), xb = std::min(s.x1, x1);
            if (orthographic) {
                if (!(s.depth > 0)) continue;
                const OrthographicTarget target{
                    xa, xb, ya, yb, x0, y0, image.pixels.data(), w, &sheet_buffer, opaque};
                if (sheets) {
                    count += opaque ? raster_orthographic<true, true>(s, per_unit, fp, target)
                                    : raster_orthographic<true, false>(s, per_unit, fp, target);
                } else {
                    count += opaque ? raster_orthographic<false, true>(s, per_unit, fp, target)
                                    : raster_orthographic<false, false>(s, per_unit, fp, target);
                }
                continue;
            }
            const double kappa_h = s.kappa * s.h, reach_sq = support_sq * s.h * s.h;
            for (int y = ya; y <= yb; ++y) {
                for (int x = xa; x <= xb; ++x) {
                    const Ray& ray = rays[(y - y0) * kTile + (x - x0)];
                    const Vec3 v = s.center - ray.origin;
                    const double t = glm::dot(v, ray.direction);  // the centre's ray parameter
                    const double rho_sq = glm::dot(v, v) - t * t;
                    if (!(rho_sq < reach_sq) || !(t > 0)) continue;
                    const std::size_t pixel = static_cast<std::size_t>(y) * w + x;
                    if (in.opaque_depth && !(t < (*in.opaque_depth)[pixel])) continue;
                    const double rho = std::sqrt(std::max(rho_sq, 0.0)) / s.h;
                    ++count;
                    add(x, y, static_cast<float>(kappa_h * (*in.footprint)(rho)), colour);
                }
            }
        }
        if (open) flush();
        fragments += count;
    });
    if (stats) {
        stats->splats_drawn = splats.size();
        stats->fragments = fragments.load();
        stats->sheet_axis = axis;
        if (sheets) {
            std::vector<std::int64_t> distinct = sheet;
            std::sort(distinct.begin(), distinct.end());
            stats->sheets = static_cast<std::size_t>(std::unique(distinct.begin(), distinct.end()) -
                                                     distinct.begin());
        }
        stats->raster_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
    }
    return image;
}

}  // namespace tr
