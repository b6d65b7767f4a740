#include <core/check.h>
#include <core/stopwatch.h>
#include <sort/order_verifier.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

namespace tr {
namespace {

// Möller-Trumbore: distance along the ray to triangle (a, b, c), or NaN when it misses.
double ray_triangle(const Ray& ray, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 e1 = b - a, e2 = c - a;
    const Vec3 p = glm::cross(ray.direction, e2);
    const double det = glm::dot(e1, p);
    if (std::abs(det) < 1e-300) return std::nan("");
    const double inv = 1.0 / det;
    const Vec3 s = ray.origin - a;
    const double u = glm::dot(s, p) * inv;
    if (u < 0 || u > 1) return std::nan("");
    const Vec3 q = glm::cross(s, e1);
    const double v = glm::dot(ray.direction, q) * inv;
    if (v < 0 || u + v > 1) return std::nan("");
    return glm::dot(e2, q) * inv;
}

struct Segment {
    double near, far;
    CellId cell;
};

constexpr int kTile = 8;

}  // namespace

OrderCheck check_order(const TetMesh& mesh, std::span<const CellId> order,
                       const CameraFrame& camera, double min_segment) {
    const auto start = std::chrono::steady_clock::now();
    OrderCheck check;
    const int w = camera.width(), h = camera.height();
    const int tiles_x = (w + kTile - 1) / kTile, tiles_y = (h + kTile - 1) / kTile;
    std::vector<std::vector<CellId>> bins(static_cast<std::size_t>(tiles_x) * tiles_y);
    std::vector<CellId> everywhere;  // cells reaching behind a perspective eye
    std::vector<std::int64_t> position(mesh.num_tets(), -1);
    for (std::size_t i = 0; i < order.size(); ++i) {
        TR_CHECK(order[i] < mesh.num_tets());  // would write past the end of `position`
        position[order[i]] = static_cast<std::int64_t>(i);
    }

    for (CellId t = 0; t < mesh.num_real_tets(); ++t) {
        double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
        bool straddles = false, all_behind = true;
        for (PointId p : mesh.tet(t)) {
            const Vec3 s = camera.project(mesh.point(p));
            if (!camera.orthographic() && s.z <= 0) {
                straddles = true;
                continue;
            }
            all_behind = false;
            x0 = std::min(x0, s.x), x1 = std::max(x1, s.x);
            y0 = std::min(y0, s.y), y1 = std::max(y1, s.y);
        }
        if (all_behind && !camera.orthographic()) continue;
        if (straddles) {
            everywhere.push_back(t);
            continue;
        }
        const int tx0 = std::max(0, static_cast<int>(std::floor(x0 / kTile)));
        const int tx1 = std::min(tiles_x - 1, static_cast<int>(std::floor(x1 / kTile)));
        const int ty0 = std::max(0, static_cast<int>(std::floor(y0 / kTile)));
        const int ty1 = std::min(tiles_y - 1, static_cast<int>(std::floor(y1 / kTile)));
        for (int ty = ty0; ty <= ty1; ++ty)
            for (int tx = tx0; tx <= tx1; ++tx) bins[ty * tiles_x + tx].push_back(t);
    }

    const double min_length = min_segment * mesh.bounds().diagonal();
    std::vector<Segment> hits;
    for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
            const Ray ray = camera.pixel_ray(i, j);
            hits.clear();
            auto test = [&](CellId t) {
                const Tet& v = mesh.tet(t);
                double lo = std::numeric_limits<double>::infinity(), hi = -lo;
                int n = 0;
                for (int k = 0; k < 4; ++k) {
                    const double d =
                        ray_triangle(ray, mesh.point(v[(k + 1) % 4]), mesh.point(v[(k + 2) % 4]),
                                     mesh.point(v[(k + 3) % 4]));
                    if (std::isnan(d)) continue;
                    lo = std::min(lo, d), hi = std::max(hi, d);
                    ++n;
                }
                if (n < 2) return;
                lo = std::max(lo, 0.0);  // the part in front of the eye
                if (!(hi - lo > min_length)) return;
                // A ray running along a face touches the cell without entering it: keep the
                // segment only if its middle is strictly inside.
                const Vec3 m = ray.origin + (0.5 * (lo + hi)) * ray.direction;
                const Vec3 &a = mesh.point(v[0]), &b = mesh.point(v[1]), &c = mesh.point(v[2]),
                           &d = mesh.point(v[3]);
                const double margin = 1e-9 * orient3d(a, b, c, d);
                if (orient3d(m, b, c, d) > margin && orient3d(a, m, c, d) > margin &&
                    orient3d(a, b, m, d) > margin && orient3d(a, b, c, m) > margin) {
                    hits.push_back({lo, hi, t});
                }
            };
            for (CellId t : bins[(j / kTile) * tiles_x + i / kTile]) test(t);
            for (CellId t : everywhere) test(t);
            if (hits.empty()) continue;
            ++check.rays;
            std::sort(hits.begin(), hits.end(), [](const Segment& a, const Segment& b) {
                return a.near + a.far < b.near + b.far;
            });
            for (const Segment& s : hits) check.missing_cells += position[s.cell] < 0;
            for (std::size_t k = 0; k + 1 < hits.size(); ++k) {
                // Overlapping segments: the ray runs along the face two cells share (or grazes
                // an edge), where neither needs to be in front.
                if (hits[k + 1].near < hits[k].far - min_length) continue;
                const std::int64_t nearer = position[hits[k].cell];
                const std::int64_t farther = position[hits[k + 1].cell];
                if (nearer < 0 || farther < 0) continue;
                ++check.pairs;
                // Back to front: the farther cell must be drawn first.
                if (farther > nearer) ++check.violations;
            }
        }
    }
    check.milliseconds = ms_since(start);
    return check;
}

}  // namespace tr
