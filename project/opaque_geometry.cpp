#include <core/parallel.h>
#include <project/opaque_geometry.h>

#include <algorithm>
#include <cmath>

namespace tr {
namespace {

constexpr int kTile = 32;

struct TriangleRef {
    std::uint32_t surface;
    std::uint32_t triangle;
};

}  // namespace

OpaqueLayer render_opaque(const std::vector<OpaqueSurface>& surfaces, const CameraFrame& camera,
                          const Vec3& background) {
    const int w = camera.width(), h = camera.height();
    const int tiles_x = (w + kTile - 1) / kTile, tiles_y = (h + kTile - 1) / kTile;
    std::vector<std::vector<TriangleRef>> bins(static_cast<std::size_t>(tiles_x) * tiles_y);
    for (std::uint32_t s = 0; s < surfaces.size(); ++s) {
        const SurfaceMesh& mesh = *surfaces[s].surface;
        for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
            double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
            bool behind = false, front = false;
            for (std::uint32_t p : mesh.triangles[t]) {
                const Vec3 q = camera.project(mesh.points[p]);
                if (!camera.orthographic() && q.z <= 0) {
                    behind = true;
                    continue;
                }
                front = true;
                x0 = std::min(x0, q.x), x1 = std::max(x1, q.x);
                y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
            }
            if (!front) continue;
            int tx0 = 0, ty0 = 0, tx1 = tiles_x - 1, ty1 = tiles_y - 1;
            if (!behind) {
                tx0 = std::max(0, static_cast<int>(std::floor((x0 - 1) / kTile)));
                ty0 = std::max(0, static_cast<int>(std::floor((y0 - 1) / kTile)));
                tx1 = std::min(tiles_x - 1, static_cast<int>(std::floor((x1 + 1) / kTile)));
                ty1 = std::min(tiles_y - 1, static_cast<int>(std::floor((y1 + 1) / kTile)));
            }
            for (int ty = ty0; ty <= ty1; ++ty)
                for (int tx = tx0; tx <= tx1; ++tx) bins[ty * tiles_x + tx].push_back({s, t});
        }
    }
    OpaqueLayer layer;
    layer.color = Image(w, h, Vec3f(background));
    layer.depth.assign(static_cast<std::size_t>(w) * h, std::numeric_limits<double>::infinity());
    std::vector<std::size_t> covered(bins.size(), 0);
    parallel_for(0, bins.size(), 1, [&](std::size_t tile) {
        const int tx = static_cast<int>(tile) % tiles_x, ty = static_cast<int>(tile) / tiles_x;
        for (int y = ty * kTile; y < std::min((ty + 1) * kTile, h); ++y) {
            for (int x = tx * kTile; x < std::min((tx + 1) * kTile, w); ++x) {
                const Ray ray = camera.pixel_ray(x, y);
                double best = std::numeric_limits<double>::infinity();
                Vec3 shade(0.0);
                for (const TriangleRef& ref : bins[tile]) {
                    const SurfaceMesh& mesh = *surfaces[ref.surface].surface;
                    const auto& tri = mesh.triangles[ref.triangle];
                    const Vec3 &a = mesh.points[tri[0]], &b = mesh.points[tri[1]],
                               &c = mesh.points[tri[2]];
                    const Vec3 e1 = b - a, e2 = c - a;
                    const Vec3 p = glm::cross(ray.direction, e2);
                    const double det = glm::dot(e1, p);
                    if (det == 0) continue;
                    const Vec3 s = ray.origin - a;
                    const double u = glm::dot(s, p) / det;
                    if (u < 0 || u > 1) continue;
                    const Vec3 q = glm::cross(s, e1);
                    const double v = glm::dot(ray.direction, q) / det;
                    if (v < 0 || u + v > 1) continue;
                    const double t = glm::dot(e2, q) / det;
                    if (!(t > 0) || !(t < best)) continue;
                    best = t;
                    const Vec3 n = glm::normalize(glm::cross(e1, e2));
                    const double lambert = std::abs(glm::dot(n, ray.direction));
                    shade = surfaces[ref.surface].color * (0.2 + 0.8 * lambert);
                }
                if (best < std::numeric_limits<double>::infinity()) {
                    const std::size_t i = static_cast<std::size_t>(y) * w + x;
                    layer.depth[i] = best;
                    layer.color.pixels[i] = Vec3f(shade);
                    ++covered[tile];
                }
            }
        }
    });
    for (std::size_t c : covered) layer.pixels_covered += c;
    return layer;
}

SurfaceMesh make_cylinder_surface(double radius, double z0, double z1, int sides) {
    SurfaceMesh m;
    m.name = "cylinder";
    for (int i = 0; i < sides; ++i) {
        const double a = 2.0 * M_PI * i / sides;
        m.points.emplace_back(radius * std::cos(a), radius * std::sin(a), z0);
        m.points.emplace_back(radius * std::cos(a), radius * std::sin(a), z1);
    }
    const auto bottom = static_cast<std::uint32_t>(m.points.size());
    m.points.emplace_back(0, 0, z0);
    m.points.emplace_back(0, 0, z1);
    for (int i = 0; i < sides; ++i) {
        const auto a = static_cast<std::uint32_t>(2 * i),
                   b = static_cast<std::uint32_t>(2 * ((i + 1) % sides));
        m.triangles.push_back({a, b, b + 1});
        m.triangles.push_back({a, b + 1, a + 1});
        m.triangles.push_back({bottom, b, a});
        m.triangles.push_back({bottom + 1, a + 1, b + 1});
    }
    return m;
}

View view_over(const CameraFrame& camera, const Vec3& background, const OpaqueLayer& layer) {
    View view{.camera = &camera, .background = background};
    if (!layer.depth.empty()) {
        view.opaque_color = &layer.color;
        view.opaque_depth = &layer.depth;
    }
    return view;
}

}  // namespace tr
