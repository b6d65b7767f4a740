#include <core/parallel.h>
#include <project/cpu_renderer.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

namespace tr {
namespace {

constexpr int kTile = 32;

// Of two tets sharing a face whose plane holds a pixel's ray, the one with the "positive"
// outward normal takes it.
bool owns_plane(const Vec3& n) {
    if (n.x != 0) return n.x > 0;
    if (n.y != 0) return n.y > 0;
    return n.z > 0;
}

struct ScreenBox {
    int x0, y0, x1, y1;  // pixel range, inclusive; empty when x0 > x1
};

// Pixels whose centres may lie in the tet's projection; the whole image when the tet reaches
// behind a perspective eye; empty when it is wholly behind.
ScreenBox screen_box(const TetMesh& mesh, CellId t, const CameraFrame& camera) {
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    bool behind = false, front = false;
    for (PointId p : mesh.tet(t)) {
        const Vec3 s = camera.project(mesh.point(p));
        if (!camera.orthographic() && s.z <= 0) {
            behind = true;
            continue;
        }
        front = true;
        x0 = std::min(x0, s.x), x1 = std::max(x1, s.x);
        y0 = std::min(y0, s.y), y1 = std::max(y1, s.y);
    }
    if (!front) return {1, 1, 0, 0};
    if (behind) return {0, 0, camera.width() - 1, camera.height() - 1};
    // Pixel i's centre is at i + 0.5: the centres in [x0, x1] are i = ceil(x0 - 0.5) ...
    // (padded a little: the exact ray test decides, the box only has to be conservative).
    constexpr double kPad = 1e-6;
    ScreenBox box{static_cast<int>(std::ceil(x0 - 0.5 - kPad)),
                  static_cast<int>(std::ceil(y0 - 0.5 - kPad)),
                  static_cast<int>(std::floor(x1 - 0.5 + kPad)),
                  static_cast<int>(std::floor(y1 - 0.5 + kPad))};
    box.x0 = std::max(box.x0, 0), box.y0 = std::max(box.y0, 0);
    box.x1 = std::min(box.x1, camera.width() - 1), box.y1 = std::min(box.y1, camera.height() - 1);
    return box;
}

}  // namespace

double longest_edge(const TetMesh& mesh) {
    double longest = 0.0;
    for (CellId t = 0; t < mesh.num_real_tets(); ++t) {
        const Tet& v = mesh.tet(t);
        for (int a = 0; a < 4; ++a) {
            for (int b = a + 1; b < 4; ++b) {
                longest = std::max(longest, glm::length(mesh.point(v[a]) - mesh.point(v[b])));
            }
        }
    }
    return longest;
}

Image render_projected_tetrahedra(const RenderInputs& in, RenderStats* stats) {
    const auto start = std::chrono::steady_clock::now();
    const TetMesh& mesh = *in.mesh;
    const CameraFrame& camera = *in.camera;
    const bool orthographic = camera.orthographic();
    const int w = camera.width(), h = camera.height();
    const int tiles_x = (w + kTile - 1) / kTile, tiles_y = (h + kTile - 1) / kTile;

    // Screen boxes of the cells, then the cells binned into tiles keeping the order.
    std::vector<ScreenBox> boxes(in.order.size());
    parallel_for(0, in.order.size(), 4096,
                 [&](std::size_t i) { boxes[i] = screen_box(mesh, in.order[i], camera); });
    std::vector<std::vector<std::uint32_t>> bins(static_cast<std::size_t>(tiles_x) * tiles_y);
    std::size_t drawn = 0;
    for (std::uint32_t i = 0; i < in.order.size(); ++i) {
        const ScreenBox& b = boxes[i];
        if (b.x0 > b.x1 || b.y0 > b.y1) continue;
        ++drawn;
        for (int ty = b.y0 / kTile; ty <= b.y1 / kTile; ++ty) {
            for (int tx = b.x0 / kTile; tx <= b.x1 / kTile; ++tx)
                bins[ty * tiles_x + tx].push_back(i);
        }
    }

    Image image(w, h, Vec3f(in.background));
    if (in.opaque_color) image = *in.opaque_color;
    std::atomic<std::size_t> fragments{0};
    parallel_for(0, bins.size(), 1, [&](std::size_t tile) {
        const int tx = static_cast<int>(tile) % tiles_x, ty = static_cast<int>(tile) / tiles_x;
        const int px0 = tx * kTile, py0 = ty * kTile;
        const int px1 = std::min(px0 + kTile, w) - 1, py1 = std::min(py0 + kTile, h) - 1;
        // The tile's rays, computed once.
        Ray rays[kTile * kTile];
        for (int y = py0; y <= py1; ++y) {
            for (int x = px0; x <= px1; ++x)
                rays[(y - py0) * kTile + (x - px0)] = camera.pixel_ray(x, y);
        }
        std::size_t tile_fragments = 0;
        for (std::uint32_t index : bins[tile]) {
            const CellId t = in.order[index];
            ScreenBox b = boxes[index];
            b.x0 = std::max(b.x0, px0), b.y0 = std::max(b.y0, py0);
            b.x1 = std::min(b.x1, px1), b.y1 = std::min(b.y1, py1);
            const Tet& v = mesh.tet(t);
            // Face planes n . x = w (outward), the scalar's gradient.
            Vec3 normals[4];
            double offsets[4];
            for (int k = 0; k < 4; ++k) {
                const Vec3& a = mesh.point(v[kTetFaceVertices[k][0]]);
                normals[k] = glm::cross(mesh.point(v[kTetFaceVertices[k][1]]) - a,
                                        mesh.point(v[kTetFaceVertices[k][2]]) - a);
                offsets[k] = glm::dot(normals[k], a);
            }
            const Vec3& p0 = mesh.point(v[0]);
            const double s0 = in.scalar[v[0]];
            const glm::dmat3 edges(mesh.point(v[1]) - p0, mesh.point(v[2]) - p0,
                                   mesh.point(v[3]) - p0);
            const Vec3 ds(in.scalar[v[1]] - s0, in.scalar[v[2]] - s0, in.scalar[v[3]] - s0);
            const Vec3 gradient = glm::inverse(glm::transpose(edges)) * ds;
            // Perspective: every ray starts at the eye, so the numerators are per cell.
            double eye_num[4] = {0, 0, 0, 0};
            double s_eye = 0;
            if (!orthographic) {
                for (int k = 0; k < 4; ++k)
                    eye_num[k] = offsets[k] - glm::dot(normals[k], camera.eye());
                s_eye = s0 + glm::dot(gradient, camera.eye() - p0);
            }
            for (int y = b.y0; y <= b.y1; ++y) {
                for (int x = b.x0; x <= b.x1; ++x) {
                    const Ray& ray = rays[(y - py0) * kTile + (x - px0)];
                    double t_in = 0.0;  // clipped at the eye (near plane)
                    double t_out = std::numeric_limits<double>::infinity();
                    bool inside = true;
                    for (int k = 0; k < 4; ++k) {
                        const double denom = glm::dot(normals[k], ray.direction);
                        const double num = orthographic
                                               ? offsets[k] - glm::dot(normals[k], ray.origin)
                                               : eye_num[k];
                        if (denom < 0) {
                            t_in = std::max(t_in, num / denom);
                        } else if (denom > 0) {
                            t_out = std::min(t_out, num / denom);
                        } else if (num < 0 || (num == 0 && !owns_plane(normals[k]))) {
                            inside = false;
                            break;
                        }
                    }
                    if (!inside || !(t_out > t_in)) continue;
                    const std::size_t pixel = static_cast<std::size_t>(y) * w + x;
                    if (in.opaque_depth) {
                        t_out = std::min(t_out, (*in.opaque_depth)[pixel]);
                        if (!(t_out > t_in)) continue;
                    }
                    const double s_origin =
                        orthographic ? s0 + glm::dot(gradient, ray.origin - p0) : s_eye;
                    const double slope = glm::dot(gradient, ray.direction);
                    const ShadedSegment seg = in.shader->shade(
                        s_origin + t_in * slope, s_origin + t_out * slope, t_out - t_in);
                    Vec3f& dst = image.pixels[pixel];
                    dst = seg.color + (1.0f - seg.alpha) * dst;
                    ++tile_fragments;
                }
            }
        }
        fragments += tile_fragments;
    });
    if (stats) {
        stats->cells_drawn = drawn;
        stats->fragments = fragments.load();
        stats->raster_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
    }
    return image;
}

}  // namespace tr
