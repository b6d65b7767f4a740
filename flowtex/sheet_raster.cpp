#include <core/parallel.h>
#include <flowtex/sheet_raster.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>

namespace tr {
namespace {

constexpr int kBandRows = 8;

// log2(x) for x > 0, exact at powers of two and linear between them (within 0.086): enough to
// pick a mip level, as graphics hardware does, at a fraction of std::log2's cost.
double approximate_log2(double x) {
    // x = 2^e * m, m in [1, 2), read from the bits of a normal double (x < 2^-1022 is taken
    // as 2^-1022: a mip level far below 0 either way).
    const auto bits = std::bit_cast<std::uint64_t>(std::max(x, 0x1p-1022));
    const int exponent = static_cast<int>((bits >> 52) & 0x7ff) - 1023;
    const double mantissa =
        std::bit_cast<double>((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL);
    return exponent + (mantissa - 1.0);
}

struct Projected {
    double x = 0, y = 0, inv_w = 0;  // screen position, 1 / depth (1 for orthographic)
    bool ok = false;
};

// Rasterises the triangles of layers[first, last) (which share positions, triangles and the
// alive mask) once, writing each layer's texture value into values[k] (NaN = not covered).
void raster_group(const CameraFrame& frame, std::span<const TexturedMeshView> layers,
                  std::size_t first, std::size_t last, const PeriodicTexture& texture,
                  std::vector<std::vector<float>>& values) {
    const TexturedMeshView& geometry = layers[first];
    const int width = frame.width(), height = frame.height();
    const std::size_t n = geometry.positions.size();
    std::vector<Projected> proj(n);
    const bool ortho = frame.orthographic();
    parallel_for(0, n, 4096, [&](std::size_t i) {
        if (!geometry.alive.empty() && !geometry.alive[i]) return;
        const Vec3 s = frame.project(geometry.positions[i]);
        if (!ortho && !(s.z > 1e-9)) return;
        proj[i] = Projected{s.x, s.y, ortho ? 1.0 : 1.0 / s.z, true};
    });
    // Bin triangles by the bands of rows their bounds touch (counting sort: order kept).
    const int num_bands = (height + kBandRows - 1) / kBandRows;
    const std::size_t num_tris = geometry.triangles.size();
    std::vector<std::uint32_t> band_count(static_cast<std::size_t>(num_bands) + 1, 0);
    std::vector<std::array<int, 2>> tri_bands(num_tris, {0, -1});
    for (std::size_t t = 0; t < num_tris; ++t) {
        const auto& tri = geometry.triangles[t];
        const Projected &a = proj[tri[0]], &b = proj[tri[1]], &c = proj[tri[2]];
        if (!a.ok || !b.ok || !c.ok) continue;
        const double y0 = std::min({a.y, b.y, c.y}), y1 = std::max({a.y, b.y, c.y});
        const double x0 = std::min({a.x, b.x, c.x}), x1 = std::max({a.x, b.x, c.x});
        if (y1 < 0 || y0 > height || x1 < 0 || x0 > width) continue;
        const int r0 = std::max(0, static_cast<int>(std::floor(y0 - 0.5)));
        const int r1 = std::min(height - 1, static_cast<int>(std::ceil(y1 - 0.5)));
        if (r0 > r1) continue;
        tri_bands[t] = {r0 / kBandRows, r1 / kBandRows};
        for (int band = r0 / kBandRows; band <= r1 / kBandRows; ++band) ++band_count[band + 1];
    }
    for (int band = 0; band < num_bands; ++band) band_count[band + 1] += band_count[band];
    std::vector<std::uint32_t> band_tris(band_count.back());
    {
        std::vector<std::uint32_t> fill(band_count.begin(), band_count.end() - 1);
        for (std::size_t t = 0; t < num_tris; ++t) {
            for (int band = tri_bands[t][0]; band <= tri_bands[t][1]; ++band) {
                band_tris[fill[band]++] = static_cast<std::uint32_t>(t);
            }
        }
    }
    const std::size_t num_layers = last - first;
    const double log2_size = std::log2(static_cast<double>(texture.size()));
    parallel_for(0, static_cast<std::size_t>(num_bands), 1, [&](std::size_t band) {
        const int row0 = static_cast<int>(band) * kBandRows;
        const int row1 = std::min(height, row0 + kBandRows);
        constexpr std::size_t kMaxLayers = 4;
        std::array<glm::dvec2, kMaxLayers> qa{}, qb{}, qc{};
        std::array<double, kMaxLayers> lod{};
        for (std::uint32_t k = band_count[band]; k < band_count[band + 1]; ++k) {
            const auto& tri = geometry.triangles[band_tris[k]];
            const Projected &a = proj[tri[0]], &b = proj[tri[1]], &c = proj[tri[2]];
            const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
            if (!(std::abs(area) > 1e-12)) continue;
            const double y0 = std::min({a.y, b.y, c.y}), y1 = std::max({a.y, b.y, c.y});
            const double x0 = std::min({a.x, b.x, c.x}), x1 = std::max({a.x, b.x, c.x});
            const int j0 = std::max(row0, static_cast<int>(std::floor(y0 - 0.5)));
            const int j1 = std::min(row1 - 1, static_cast<int>(std::ceil(y1 - 0.5)));
            const int i0 = std::max(0, static_cast<int>(std::floor(x0 - 0.5)));
            const int i1 = std::min(width - 1, static_cast<int>(std::ceil(x1 - 0.5)));
            if (j0 > j1 || i0 > i1) continue;
            const double inv_area = 1.0 / area;
            const double dx1 = b.x - a.x, dy1 = b.y - a.y, dx2 = c.x - a.x, dy2 = c.y - a.y;
            // The layers' set-up waits for the first covered pixel: at one point per pixel,
            // about half the triangles cover none.
            bool set_up = false;
            auto set_up_layers = [&] {
                for (std::size_t l = 0; l < num_layers; ++l) {
                    const TexturedMeshView& layer = layers[first + l];
                    const glm::dvec2 ta = layer.texcoords[tri[0]], tb = layer.texcoords[tri[1]],
                                     tc = layer.texcoords[tri[2]];
                    // Screen-space derivatives of the texture coordinates (affine over the
                    // triangle) give the mip level: log2 of the longer pixel step in texels.
                    const glm::dvec2 e1 = tb - ta, e2 = tc - ta;
                    const glm::dvec2 d_dx = (e1 * dy2 - e2 * dy1) * inv_area;
                    const glm::dvec2 d_dy = (e2 * dx1 - e1 * dx2) * inv_area;
                    const double step2 = std::max(glm::dot(d_dx, d_dx), glm::dot(d_dy, d_dy));
                    lod[l] = step2 > 0 ? 0.5 * approximate_log2(step2) + log2_size : 0.0;
                    // Perspective-correct: interpolate t / w and 1 / w.
                    qa[l] = ta * a.inv_w;
                    qb[l] = tb * b.inv_w;
                    qc[l] = tc * c.inv_w;
                }
                set_up = true;
            };
            constexpr double kEdgeSlack = -1e-9;
            for (int j = j0; j <= j1; ++j) {
                const double py = j + 0.5;
                const std::size_t row = static_cast<std::size_t>(j) * width;
                for (int i = i0; i <= i1; ++i) {
                    const double px = i + 0.5;
                    // Barycentric weights of b and c (and a = 1 - wb - wc).
                    const double wb = ((px - a.x) * dy2 - dx2 * (py - a.y)) * inv_area;
                    const double wc = (dx1 * (py - a.y) - (px - a.x) * dy1) * inv_area;
                    const double wa = 1.0 - wb - wc;
                    if (wa < kEdgeSlack || wb < kEdgeSlack || wc < kEdgeSlack) continue;
                    if (!set_up) set_up_layers();
                    const double inv_w = 1.0 / (wa * a.inv_w + wb * b.inv_w + wc * c.inv_w);
                    for (std::size_t l = 0; l < num_layers; ++l) {
                        const glm::dvec2 uv = (wa * qa[l] + wb * qb[l] + wc * qc[l]) * inv_w;
                        values[first + l][row + i] = texture.sample_lod(uv.x, uv.y, lod[l]);
                    }
                }
            }
        }
    });
}

// raster_group for layers on a grid sheet (TexturedMeshView::grid): each pixel's ray meets the
// sheet's plane at one point, whose grid square and triangle (the diagonal (i, j)-(i + 1,
// j + 1), as the sheet's triangles) give the texture coordinates by the same barycentric
// weights, exact in perspective; the triangle's texture gradient times the pixel's footprint on
// the plane gives the mip level, as raster_group's per-triangle screen derivatives. Pixel
// centres on the sheet's outer edges (within 1e-9 of a square) count as on it. Cost: O(pixels x
// layers x 8 texel reads), whatever the number of triangles.
void raster_grid(const CameraFrame& frame, const Sheet& sheet,
                 std::span<const TexturedMeshView> layers, std::size_t first, std::size_t last,
                 const PeriodicTexture& texture, std::vector<std::vector<float>>& values) {
    const int width = frame.width(), height = frame.height();
    const bool ortho = frame.orthographic();
    const Vec3 normal = sheet.normal;
    // A ray from O along D meets the plane at O + t D, t = (S - O).n / D.n, S the sheet's
    // origin; with D scaled to D.forward = 1, both O and D are affine in the image point (x, y)
    // (O constant in perspective, D in orthographic), and so are the five dot products below:
    // each is kept as its value at (0, 0) and its steps along x and y.
    const auto ray_at = [&](double x, double y) {
        Ray r = frame.ray(x, y);
        r.direction /= glm::dot(r.direction, frame.forward());
        return r;
    };
    struct Affine {
        double at0 = 0, dx = 0, dy = 0;
        double operator()(double x, double y) const { return at0 + dx * x + dy * y; }
    };
    const auto affine = [&](auto&& f) {
        const double f0 = f(ray_at(0, 0));
        return Affine{f0, f(ray_at(1, 0)) - f0, f(ray_at(0, 1)) - f0};
    };
    const double inv_spacing = 1.0 / sheet.spacing;
    const Affine to_plane =
        affine([&](const Ray& r) { return glm::dot(sheet.origin - r.origin, normal); });
    const Affine along = affine([&](const Ray& r) { return glm::dot(r.direction, normal); });
    const Affine origin_u = affine([&](const Ray& r) {
        return glm::dot(r.origin - sheet.origin, sheet.axis_u) * inv_spacing;
    });
    const Affine origin_v = affine([&](const Ray& r) {
        return glm::dot(r.origin - sheet.origin, sheet.axis_v) * inv_spacing;
    });
    const Affine dir_u =
        affine([&](const Ray& r) { return glm::dot(r.direction, sheet.axis_u) * inv_spacing; });
    const Affine dir_v =
        affine([&](const Ray& r) { return glm::dot(r.direction, sheet.axis_v) * inv_spacing; });
    // Grid coordinates (in squares) where the ray through image point (x, y) meets the plane;
    // nothing when it is parallel to the plane or (perspective) meets it behind the eye.
    auto grid_hit = [&](double x, double y) -> std::optional<glm::dvec2> {
        const double a = along(x, y);
        if (!(std::abs(a) > 1e-12)) return std::nullopt;
        const double t = to_plane(x, y) / a;
        if (!ortho && !(t > 0)) return std::nullopt;
        return glm::dvec2(origin_u(x, y) + t * dir_u(x, y), origin_v(x, y) + t * dir_v(x, y));
    };
    glm::dvec2 ortho_dx(0.0), ortho_dy(0.0);
    if (const auto h0 = grid_hit(0.5, 0.5); ortho && h0) {
        ortho_dx = grid_hit(1.5, 0.5).value_or(*h0) - *h0;
        ortho_dy = grid_hit(0.5, 1.5).value_or(*h0) - *h0;
    }
    const std::size_t num_layers = last - first;
    const double log2_size = std::log2(static_cast<double>(texture.size()));
    const int stride = sheet.nu + 1;
    auto point = [&](int a, int b) {
        return sheet.grid_point[static_cast<std::size_t>(b) * stride + a];
    };
    parallel_for(0, static_cast<std::size_t>(height), 4, [&](std::size_t row) {
        const double py = static_cast<double>(row) + 0.5;
        for (int i = 0; i < width; ++i) {
            const double px = i + 0.5;
            const auto hit = grid_hit(px, py);
            if (!hit) continue;
            constexpr double kSlack = 1e-9;
            const double u = hit->x, v = hit->y;
            if (!(u >= -kSlack && v >= -kSlack && u <= sheet.nu + kSlack &&
                  v <= sheet.nv + kSlack)) {
                continue;
            }
            const int gi = std::clamp(static_cast<int>(std::floor(u)), 0, sheet.nu - 1);
            const int gj = std::clamp(static_cast<int>(std::floor(v)), 0, sheet.nv - 1);
            const double fu = std::clamp(u - gi, 0.0, 1.0), fv = std::clamp(v - gj, 0.0, 1.0);
            const bool lower = fu >= fv;  // (i, j), (i + 1, j), (i + 1, j + 1)
            const std::int32_t a = point(gi, gj), c = point(gi + 1, gj + 1);
            const std::int32_t b = lower ? point(gi + 1, gj) : point(gi, gj + 1);
            if (a < 0 || b < 0 || c < 0) continue;
            // The pixel's steps on the plane, in squares (the same everywhere for an
            // orthographic camera).
            glm::dvec2 dx = ortho_dx, dy = ortho_dy;
            if (!ortho) {
                const auto hx = grid_hit(px + 1.0, py), hy = grid_hit(px, py + 1.0);
                dx = hx ? *hx - *hit : glm::dvec2(0.0);
                dy = hy ? *hy - *hit : glm::dvec2(0.0);
            }
            for (std::size_t l = 0; l < num_layers; ++l) {
                const std::span<const glm::dvec2> tc = layers[first + l].texcoords;
                const glm::dvec2 ta = tc[static_cast<std::size_t>(a)];
                const glm::dvec2 tb = tc[static_cast<std::size_t>(b)];
                const glm::dvec2 tcc = tc[static_cast<std::size_t>(c)];
                // Texture coordinates per square along u and v over this triangle.
                const glm::dvec2 d_du = lower ? tb - ta : tcc - tb;
                const glm::dvec2 d_dv = lower ? tcc - tb : tb - ta;
                const glm::dvec2 uv = lower ? (1.0 - fu) * ta + (fu - fv) * tb + fv * tcc
                                            : (1.0 - fv) * ta + (fv - fu) * tb + fu * tcc;
                const glm::dvec2 d_dx = d_du * dx.x + d_dv * dx.y;
                const glm::dvec2 d_dy = d_du * dy.x + d_dv * dy.y;
                const double step2 = std::max(glm::dot(d_dx, d_dx), glm::dot(d_dy, d_dy));
                const double lod = step2 > 0 ? 0.5 * approximate_log2(step2) + log2_size : 0.0;
                values[first + l][row * static_cast<std::size_t>(width) + i] =
                    texture.sample_lod(uv.x, uv.y, lod);
            }
        }
    });
}

}  // namespace

std::vector<float> rasterize_sheet_values(const CameraFrame& frame,
                                          std::span<const TexturedMeshView> layers,
                                          const PeriodicTexture& texture) {
    const std::size_t num_pixels = static_cast<std::size_t>(frame.width()) * frame.height();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<std::vector<float>> per_layer(layers.size(), std::vector<float>(num_pixels, nan));
    // Layers that share their geometry (backward advection: every layer) are traversed once.
    for (std::size_t first = 0; first < layers.size();) {
        std::size_t last = first + 1;
        auto same = [&](const TexturedMeshView& x, const TexturedMeshView& y) {
            return x.positions.data() == y.positions.data() &&
                   x.positions.size() == y.positions.size() &&
                   x.triangles.data() == y.triangles.data() &&
                   x.triangles.size() == y.triangles.size() && x.alive.data() == y.alive.data() &&
                   x.alive.size() == y.alive.size() && x.grid == y.grid;
        };
        while (last < layers.size() && last - first < 4 && same(layers[first], layers[last])) {
            ++last;
        }
        if (layers[first].grid != nullptr) {
            raster_grid(frame, *layers[first].grid, layers, first, last, texture, per_layer);
        } else {
            raster_group(frame, layers, first, last, texture, per_layer);
        }
        first = last;
    }
    std::vector<float> out(num_pixels, nan);
    parallel_for(0, num_pixels, 4096, [&](std::size_t p) {
        double sum = 0, sum_sq = 0, plain = 0;
        int covered = 0;
        for (std::size_t k = 0; k < layers.size(); ++k) {
            const float v = per_layer[k][p];
            if (std::isnan(v)) continue;
            const double w = layers[k].weight;
            sum += w * (v - 0.5);
            sum_sq += w * w;
            plain += v;
            ++covered;
        }
        if (covered == 0) return;
        const double value = sum_sq > 1e-12 ? 0.5 + sum / std::sqrt(sum_sq) : plain / covered;
        out[p] = static_cast<float>(std::clamp(value, 0.0, 1.0));
    });
    return out;
}

void rasterize_sheet(const CameraFrame& frame, std::span<const TexturedMeshView> layers,
                     const PeriodicTexture& texture, const SheetRasterOptions& options,
                     Image& image) {
    const std::vector<float> values = rasterize_sheet_values(frame, layers, texture);
    image.width = frame.width();
    image.height = frame.height();
    image.pixels.resize(values.size());
    parallel_for(0, values.size(), 4096, [&](std::size_t p) {
        const float v = values[p];
        image.pixels[p] =
            std::isnan(v) ? options.background : options.dark + v * (options.light - options.dark);
    });
}

Camera sheet_camera(const Sheet& sheet, int width, int height, const std::optional<Vec3>& view_up) {
    if (!view_up) {
        return plane_camera(sheet.points, sheet.origin, sheet.axis_u, sheet.axis_v, sheet.normal,
                            width, height);
    }
    const Vec3 up = glm::normalize(*view_up - glm::dot(*view_up, sheet.normal) * sheet.normal);
    return plane_camera(sheet.points, sheet.origin, glm::cross(up, sheet.normal), up, sheet.normal,
                        width, height);
}

Camera plane_camera(std::span<const Vec3> points, const Vec3& origin, const Vec3& right,
                    const Vec3& up, const Vec3& normal, int width, int height) {
    glm::dvec2 lo(1e300), hi(-1e300);
    for (const Vec3& p : points) {
        const glm::dvec2 st(glm::dot(p - origin, right), glm::dot(p - origin, up));
        lo = glm::min(lo, st);
        hi = glm::max(hi, st);
    }
    if (points.empty()) lo = hi = glm::dvec2(0.0);
    const glm::dvec2 centre = 0.5 * (lo + hi);
    const Vec3 focal = origin + centre.x * right + centre.y * up;
    const double half_w = 0.5 * (hi.x - lo.x), half_h = 0.5 * (hi.y - lo.y);
    const double aspect = static_cast<double>(width) / height;
    Camera camera;
    camera.parallel = true;
    camera.parallel_scale = 1.02 * std::max({half_h, half_w / aspect, 1e-12});
    const double distance = std::max(1.0, 4.0 * std::max(half_w, half_h));
    camera.focal_point = focal;
    camera.position = focal + distance * normal;
    camera.view_up = up;
    return camera;
}

Vec3 upright_view_up(const Vec3& normal) {
    const Vec3 a = glm::abs(normal);
    const Vec3 up = a.z >= a.x && a.z >= a.y ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
    return glm::normalize(up - glm::dot(up, normal) * normal);
}

}  // namespace tr
