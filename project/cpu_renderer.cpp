#include <core/check.h>
#include <core/parallel.h>
#include <project/cpu_renderer.h>
#include <project/tet_projection.h>

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

// --- Shirley-Tuchman projection (the exp-texture integrator, as in the paper's section 3.2) ---

// Edge function of the directed screen edge a -> b at p, computed from the lexicographically
// smaller endpoint so that an edge shared by two triangles gives exactly opposite values.
double edge_function(const StVertex& a, const StVertex& b, double px, double py) {
    const bool swap = b.x < a.x || (b.x == a.x && b.y < a.y);
    const StVertex& p = swap ? b : a;
    const StVertex& q = swap ? a : b;
    const double e = (q.x - p.x) * (py - p.y) - (q.y - p.y) * (px - p.x);
    return swap ? -e : e;
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
    // Preconditions whose violation would read or write out of bounds (a bug in the caller).
    TR_CHECK(in.mesh != nullptr && in.shader != nullptr && in.camera != nullptr);
    const TetMesh& mesh = *in.mesh;
    const CameraFrame& camera = *in.camera;
    const bool orthographic = camera.orthographic();
    const int w = camera.width(), h = camera.height();
    TR_CHECK_EQ(in.scalar.size(), mesh.num_points());
    if (in.opaque_color) {
        TR_CHECK_EQ(in.opaque_color->width, w);
        TR_CHECK_EQ(in.opaque_color->height, h);
    }
    if (in.opaque_depth) TR_CHECK_EQ(in.opaque_depth->size(), static_cast<std::size_t>(w) * h);
    const int tiles_x = (w + kTile - 1) / kTile, tiles_y = (h + kTile - 1) / kTile;

    // Screen boxes of the cells, then the cells binned into tiles keeping the order.
    std::vector<ScreenBox> boxes(in.order.size());
    std::vector<std::uint8_t> straddles(in.order.size(), 0);  // reaches behind the eye
    const std::size_t num_real = mesh.num_real_tets();
    parallel_for(0, in.order.size(), 4096, [&](std::size_t i) {
        TR_CHECK(in.order[i] < num_real);
        boxes[i] = screen_box(mesh, in.order[i], camera);
        if (!orthographic) {
            for (PointId p : mesh.tet(in.order[i])) {
                if (glm::dot(mesh.point(p) - camera.eye(), camera.forward()) <= 0) straddles[i] = 1;
            }
        }
    });
    // The paper's projection for the exp-texture integrator; the exact per-pixel segments for
    // the others (and for cells reaching behind the eye, which must be clipped).
    const bool shirley_tuchman = in.shader->integrator() == Integrator::kExpTexture;
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
        // A cell's fragments in this tile: segments, their pixels, their shading.
        SegmentQuery queries[kTile * kTile];
        std::uint32_t pixels[kTile * kTile];
        ShadedSegment shaded[kTile * kTile];
        std::vector<int> on_edges;  // pixels of the current cell decided by the exact test
        for (std::uint32_t index : bins[tile]) {
            const CellId t = in.order[index];
            ScreenBox b = boxes[index];
            b.x0 = std::max(b.x0, px0), b.y0 = std::max(b.y0, py0);
            b.x1 = std::min(b.x1, px1), b.y1 = std::min(b.y1, py1);
            // Face planes n . x = w (outward), the scalar's gradient.
            const TetPlanes planes = tet_planes(mesh, in.scalar, t);
            const Vec3* normals = planes.normals;
            const double* offsets = planes.offsets;
            const Vec3& p0 = planes.p0;
            const double s0 = planes.s0;
            const Vec3& gradient = planes.gradient;
            // Perspective: every ray starts at the eye, so the numerators are per cell.
            double eye_num[4] = {0, 0, 0, 0};
            double s_eye = 0;
            if (!orthographic) {
                for (int k = 0; k < 4; ++k)
                    eye_num[k] = offsets[k] - glm::dot(normals[k], camera.eye());
                s_eye = s0 + glm::dot(gradient, camera.eye() - p0);
            }
            // The exact segment of pixel (x, y)'s ray through this cell, clipped at the eye and
            // at opaque depth: false when the ray misses it. A ray in the plane of a face shared
            // by two cells belongs to the one whose outward normal is "positive".
            auto segment_of = [&](std::size_t pixel, const Ray& ray, SegmentQuery& q) {
                double t_in = 0.0;  // clipped at the eye (near plane)
                double t_out = std::numeric_limits<double>::infinity();
                for (int k = 0; k < 4; ++k) {
                    const double denom = glm::dot(normals[k], ray.direction);
                    const double num =
                        orthographic ? offsets[k] - glm::dot(normals[k], ray.origin) : eye_num[k];
                    if (denom < 0) {
                        t_in = std::max(t_in, num / denom);
                    } else if (denom > 0) {
                        t_out = std::min(t_out, num / denom);
                    } else if (num < 0 || (num == 0 && !owns_plane(normals[k]))) {
                        return false;
                    }
                }
                if (!(t_out > t_in)) return false;
                if (in.opaque_depth) {
                    t_out = std::min(t_out, (*in.opaque_depth)[pixel]);
                    if (!(t_out > t_in)) return false;
                }
                const double s_origin =
                    orthographic ? s0 + glm::dot(gradient, ray.origin - p0) : s_eye;
                const double slope = glm::dot(gradient, ray.direction);
                q = {s_origin + t_in * slope, s_origin + t_out * slope, t_out - t_in};
                return true;
            };
            // One pixel's segment, shaded and composited.
            auto draw_exact = [&](int x, int y, const Ray& ray) {
                const std::size_t pixel = static_cast<std::size_t>(y) * w + x;
                SegmentQuery q;
                if (!segment_of(pixel, ray, q)) return;
                const ShadedSegment seg = in.shader->shade(q.s_front, q.s_back, q.length);
                Vec3f& dst = image.pixels[pixel];
                dst = seg.color + (1.0f - seg.alpha) * dst;
                ++tile_fragments;
            };
            if (shirley_tuchman && !straddles[index]) {
                // Project, classify (3 or 4 triangles around the thick vertex), rasterize with
                // thickness and the front and back scalars interpolated across the triangles.
                StProjection st;
                if (!shirley_tuchman_projection(mesh, in.scalar, t, planes, camera, st)) continue;
                const StVertex* corners = st.corners;
                const int* hull = st.hull;
                const int n = st.num_hull;
                const StVertex& thick = st.thick;
                on_edges.clear();
                for (int e = 0; e < n; ++e) {
                    StVertex tri[3] = {thick, corners[hull[e]], corners[hull[(e + 1) % n]]};
                    double area = edge_function(tri[0], tri[1], tri[2].x, tri[2].y);
                    if (area == 0) continue;
                    if (area < 0) {
                        std::swap(tri[1], tri[2]);
                        area = -area;
                    }
                    const double lo_x = std::min({tri[0].x, tri[1].x, tri[2].x});
                    const double hi_x = std::max({tri[0].x, tri[1].x, tri[2].x});
                    const double lo_y = std::min({tri[0].y, tri[1].y, tri[2].y});
                    const double hi_y = std::max({tri[0].y, tri[1].y, tri[2].y});
                    const int x0 = std::max(b.x0, static_cast<int>(std::ceil(lo_x - 0.5)));
                    const int x1 = std::min(b.x1, static_cast<int>(std::floor(hi_x - 0.5)));
                    const int y0 = std::max(b.y0, static_cast<int>(std::ceil(lo_y - 0.5)));
                    const int y1 = std::min(b.y1, static_cast<int>(std::floor(hi_y - 0.5)));
                    for (int y = y0; y <= y1; ++y) {
                        for (int x = x0; x <= x1; ++x) {
                            const double px = x + 0.5, py = y + 0.5;
                            const double w0 = edge_function(tri[1], tri[2], px, py);
                            const double w1 = edge_function(tri[2], tri[0], px, py);
                            const double w2 = edge_function(tri[0], tri[1], px, py);
                            if (w0 < 0 || w1 < 0 || w2 < 0) continue;
                            if (w0 == 0 || w1 == 0 || w2 == 0) {
                                // On an edge of the projection: screen-space T-junctions in
                                // degenerate views make edge rules disagree between cells,
                                // so the exact ray test decides (and shades) this pixel, once
                                // per cell although it lies on two of its triangles.
                                const int local = (y - py0) * kTile + (x - px0);
                                if (std::find(on_edges.begin(), on_edges.end(), local) !=
                                    on_edges.end()) {
                                    continue;
                                }
                                on_edges.push_back(local);
                                draw_exact(x, y, rays[local]);
                                continue;
                            }
                            const double b0 = w0 / area, b1 = w1 / area, b2 = w2 / area;
                            double u = b0 * tri[0].thickness + b1 * tri[1].thickness +
                                       b2 * tri[2].thickness;
                            const double sf =
                                b0 * tri[0].s_front + b1 * tri[1].s_front + b2 * tri[2].s_front;
                            double sb =
                                b0 * tri[0].s_back + b1 * tri[1].s_back + b2 * tri[2].s_back;
                            const std::size_t pixel = static_cast<std::size_t>(y) * w + x;
                            if (in.opaque_depth) {
                                const double tf =
                                    b0 * tri[0].t_front + b1 * tri[1].t_front + b2 * tri[2].t_front;
                                const double room = (*in.opaque_depth)[pixel] - tf;
                                if (!(room > 0)) continue;
                                if (room < u) {
                                    sb = sf + (sb - sf) * room / u;
                                    u = room;
                                }
                            }
                            if (!(u > 0)) continue;
                            const ShadedSegment seg = in.shader->shade(sf, sb, u);
                            Vec3f& dst = image.pixels[pixel];
                            dst = seg.color + (1.0f - seg.alpha) * dst;
                            ++tile_fragments;
                        }
                    }
                }
                continue;
            }
            // The cell's segments in this tile first, then shaded together (the shader
            // overlaps their lookups) and composited: each pixel appears once per cell, so the
            // order of compositing per pixel is the cells' order.
            int count = 0;
            for (int y = b.y0; y <= b.y1; ++y) {
                for (int x = b.x0; x <= b.x1; ++x) {
                    const std::size_t pixel = static_cast<std::size_t>(y) * w + x;
                    if (segment_of(pixel, rays[(y - py0) * kTile + (x - px0)], queries[count])) {
                        pixels[count++] = static_cast<std::uint32_t>(pixel);
                    }
                }
            }
            const std::size_t n = static_cast<std::size_t>(count);
            in.shader->shade(std::span(queries, n), std::span(shaded, n));
            for (std::size_t f = 0; f < n; ++f) {
                Vec3f& dst = image.pixels[pixels[f]];
                dst = shaded[f].color + (1.0f - shaded[f].alpha) * dst;
            }
            tile_fragments += n;
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
