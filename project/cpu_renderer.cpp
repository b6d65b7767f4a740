#include <core/check.h>
#include <core/parallel.h>
#include <core/stopwatch.h>
#include <project/cpu_renderer.h>
#include <project/tet_fragments.h>
#include <project/tet_projection.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

namespace tr {
namespace {

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

// One triangle of a cell's Shirley-Tuchman projection rasterized over the box b (clipped to the
// tile): thickness and the front and back scalars interpolated across it, each pixel's segment
// shaded and passed to composite(pixel, shaded). Pixels on the triangle's edges go to
// draw_exact(x, y, tile-local pixel) instead, once per cell (`on_edges` lists them). Returns the
// fragments composited.
template <class Composite, class DrawExact>
std::size_t draw_st_triangle(StVertex (&tri)[3], const ScreenBox& b, const TileRays& rays,
                             const RenderInputs& in, int w, std::vector<int>& on_edges,
                             Composite&& composite, DrawExact&& draw_exact) {
    double area = edge_function(tri[0], tri[1], tri[2].x, tri[2].y);
    if (area == 0) return 0;
    if (area < 0) {
        std::swap(tri[1], tri[2]);
        area = -area;
    }
    const ScreenBox box = pixels_centred_in(std::min({tri[0].x, tri[1].x, tri[2].x}),
                                            std::min({tri[0].y, tri[1].y, tri[2].y}),
                                            std::max({tri[0].x, tri[1].x, tri[2].x}),
                                            std::max({tri[0].y, tri[1].y, tri[2].y}))
                              .clipped_to(b);
    const int x0 = box.x0, x1 = box.x1, y0 = box.y0, y1 = box.y1;
    std::size_t fragments = 0;
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
            const double px = x + 0.5, py = y + 0.5;
            const double w0 = edge_function(tri[1], tri[2], px, py);
            const double w1 = edge_function(tri[2], tri[0], px, py);
            const double w2 = edge_function(tri[0], tri[1], px, py);
            if (w0 < 0 || w1 < 0 || w2 < 0) continue;
            if (w0 == 0 || w1 == 0 || w2 == 0) {
                // On an edge of the projection: screen-space T-junctions in degenerate views
                // make edge rules disagree between cells, so the exact ray test decides (and
                // shades) this pixel, once per cell although it lies on two of its triangles.
                const int local = (y - rays.y0) * kFragmentTile + (x - rays.x0);
                if (std::find(on_edges.begin(), on_edges.end(), local) != on_edges.end()) {
                    continue;
                }
                on_edges.push_back(local);
                draw_exact(x, y, rays.rays[local]);
                continue;
            }
            const double b0 = w0 / area, b1 = w1 / area, b2 = w2 / area;
            double u = b0 * tri[0].thickness + b1 * tri[1].thickness + b2 * tri[2].thickness;
            const double sf = b0 * tri[0].s_front + b1 * tri[1].s_front + b2 * tri[2].s_front;
            double sb = b0 * tri[0].s_back + b1 * tri[1].s_back + b2 * tri[2].s_back;
            const std::size_t pixel = static_cast<std::size_t>(y) * w + x;
            if (in.opaque_depth) {
                const double tf = b0 * tri[0].t_front + b1 * tri[1].t_front + b2 * tri[2].t_front;
                const double room = (*in.opaque_depth)[pixel] - tf;
                if (!(room > 0)) continue;
                if (room < u) {
                    sb = sf + (sb - sf) * room / u;
                    u = room;
                }
            }
            if (!(u > 0)) continue;
            composite(pixel, in.shader->shade(sf, sb, u));
            ++fragments;
        }
    }
    return fragments;
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

Image render_projected_tetrahedra(const RenderInputs& in, RenderStats* stats,
                                  std::vector<float>* alpha) {
    const auto start = std::chrono::steady_clock::now();
    // Preconditions whose violation would read or write out of bounds (a bug in the caller).
    TR_CHECK(in.mesh != nullptr && in.shader != nullptr && in.camera != nullptr);
    const TetMesh& mesh = *in.mesh;
    const CameraFrame& camera = *in.camera;
    const int w = camera.width(), h = camera.height();
    TR_CHECK_EQ(in.scalar.size(), mesh.num_points());
    if (in.opaque_color) {
        TR_CHECK_EQ(in.opaque_color->width, w);
        TR_CHECK_EQ(in.opaque_color->height, h);
    }
    if (in.opaque_depth) TR_CHECK_EQ(in.opaque_depth->size(), static_cast<std::size_t>(w) * h);
    const std::size_t num_real = mesh.num_real_tets();
    for (CellId t : in.order) TR_CHECK(t < num_real);

    // The cells binned into screen tiles, keeping their order (project/tet_fragments.h).
    const TileBins bins = bin_cells(mesh, in.order, camera);
    // The paper's projection for the exp-texture integrator; the exact per-pixel segments for
    // the others (and for cells reaching behind the eye, which must be clipped).
    const bool shirley_tuchman = in.shader->integrator() == Integrator::kExpTexture;
    const std::span<const double> max_depth =
        in.opaque_depth ? std::span<const double>(*in.opaque_depth) : std::span<const double>();

    Image image(w, h, Vec3f(in.background));
    if (in.opaque_color) image = *in.opaque_color;
    // The volume's opacity per pixel, when asked for: composited with the same over operator.
    if (alpha) alpha->assign(static_cast<std::size_t>(w) * h, 0.0f);
    float* const opacity = alpha ? alpha->data() : nullptr;
    std::atomic<std::size_t> fragments{0};
    // One tile; `with_alpha` (std::true_type or std::false_type) decides at compile time whether
    // the opacity is composited too, so that the per-fragment loops have no branch for it.
    auto render_tile = [&](std::size_t tile, auto with_alpha) {
        constexpr bool kWithAlpha = decltype(with_alpha)::value;
        // The premultiplied over operator: a fragment in front of what the pixel holds.
        auto composite = [&](std::size_t pixel, const ShadedSegment& seg) {
            Vec3f& dst = image.pixels[pixel];
            dst = seg.color + (1.0f - seg.alpha) * dst;
            if constexpr (kWithAlpha) {
                float& a = opacity[pixel];
                a = seg.alpha + (1.0f - seg.alpha) * a;
            }
        };
        TileRays rays;  // the tile's rays, computed once
        tile_rays(bins, tile, camera, rays);
        std::size_t tile_fragments = 0;
        // A cell's fragments in this tile: segments, their pixels, their shading.
        SegmentQuery queries[kFragmentTile * kFragmentTile];
        std::uint32_t pixels[kFragmentTile * kFragmentTile];
        ShadedSegment shaded[kFragmentTile * kFragmentTile];
        std::vector<int> on_edges;  // pixels of the current cell decided by the exact test
        for (std::uint32_t index : bins.bins[tile]) {
            const CellId t = in.order[index];
            const ScreenBox b = bins.boxes[index].clipped_to({rays.x0, rays.y0, rays.x1, rays.y1});
            // Face planes, the scalar's gradient and the exact segments of pixel rays.
            const CellFragments cell(mesh, in.scalar, t, camera);
            const TetPlanes& planes = cell.planes();
            // One pixel's exact segment, shaded and composited.
            auto draw_exact = [&](int x, int y, const Ray& ray) {
                const std::size_t pixel = static_cast<std::size_t>(y) * w + x;
                const double limit =
                    max_depth.empty() ? std::numeric_limits<double>::infinity() : max_depth[pixel];
                double t_in, t_out, s_in, s_out;
                if (!cell.segment(ray, limit, t_in, t_out, s_in, s_out)) return;
                composite(pixel, in.shader->shade(s_in, s_out, t_out - t_in));
                ++tile_fragments;
            };
            if (shirley_tuchman && !bins.behind_eye[index]) {
                // Project, classify (3 or 4 triangles around the thick vertex), rasterize with
                // thickness and the front and back scalars interpolated across the triangles.
                StProjection st;
                if (!shirley_tuchman_projection(mesh, in.scalar, t, planes, camera, st)) continue;
                const int n = st.num_hull;
                on_edges.clear();
                for (int e = 0; e < n; ++e) {
                    StVertex tri[3] = {st.thick, st.corners[st.hull[e]],
                                       st.corners[st.hull[(e + 1) % n]]};
                    tile_fragments +=
                        draw_st_triangle(tri, b, rays, in, w, on_edges, composite, draw_exact);
                }
                continue;
            }
            // The cell's segments in this tile first, then shaded together (the shader
            // overlaps their lookups) and composited: each pixel appears once per cell, so the
            // order of compositing per pixel is the cells' order.
            int count = 0;
            for_each_fragment(
                cell, b, rays, w, max_depth,
                [&](int x, int y, double t_in, double t_out, double s_in, double s_out) {
                    queries[count] = {s_in, s_out, t_out - t_in};
                    pixels[count++] =
                        static_cast<std::uint32_t>(static_cast<std::size_t>(y) * w + x);
                });
            const std::size_t n = static_cast<std::size_t>(count);
            in.shader->shade(std::span(queries, n), std::span(shaded, n));
            for (std::size_t f = 0; f < n; ++f) composite(pixels[f], shaded[f]);
            tile_fragments += n;
        }
        fragments += tile_fragments;
    };
    if (opacity) {
        parallel_for(0, bins.num_tiles(), 1,
                     [&](std::size_t tile) { render_tile(tile, std::true_type{}); });
    } else {
        parallel_for(0, bins.num_tiles(), 1,
                     [&](std::size_t tile) { render_tile(tile, std::false_type{}); });
    }
    if (stats) {
        stats->cells_drawn = bins.cells_drawn;
        stats->fragments = fragments.load();
        stats->raster_ms = ms_since(start);
    }
    return image;
}

}  // namespace tr
