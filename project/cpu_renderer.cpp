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
#include <mutex>
#include <span>
#include <vector>

namespace tr {
namespace {

// --- Shirley-Tuchman projection (the exp-texture integrator, as in the paper's section 3.2) ---

// Edge function of the directed screen edge a -> b, set up once per triangle and computed from
// the lexicographically smaller endpoint, so that an edge shared by two triangles gives exactly
// opposite values at every pixel.
class EdgeFunction {
  public:
    EdgeFunction(const StVertex& a, const StVertex& b)
        : swapped_(b.x < a.x || (b.x == a.x && b.y < a.y)) {
        const StVertex& p = swapped_ ? b : a;
        const StVertex& q = swapped_ ? a : b;
        px_ = p.x, py_ = p.y, dx_ = q.x - p.x, dy_ = q.y - p.y;
    }
    double at(double x, double y) const {
        const double e = dx_ * (y - py_) - dy_ * (x - px_);
        return swapped_ ? -e : e;
    }

  private:
    bool swapped_;
    double px_ = 0, py_ = 0, dx_ = 0, dy_ = 0;
};

// One triangle of a cell's Shirley-Tuchman projection rasterized over the box b (clipped to the
// tile): thickness and the front and back scalars interpolated across it; each pixel that
// open(x, y) accepts shaded and passed to composite(x, y, shaded). Pixels on the triangle's edges
// go to draw_exact(x, y, ray) instead, once per cell
// (`on_edges` lists them). Returns the fragments composited.
template <class Open, class Composite, class DrawExact>
std::size_t draw_st_triangle(StVertex (&tri)[3], const ScreenBox& b, const TileRays& rays,
                             const RenderInputs& in, int w, std::vector<int>& on_edges, Open&& open,
                             Composite&& composite, DrawExact&& draw_exact) {
    double area = EdgeFunction(tri[0], tri[1]).at(tri[2].x, tri[2].y);
    if (area == 0) return 0;
    if (area < 0) {
        std::swap(tri[1], tri[2]);
        area = -area;
    }
    const StVertex &v0 = tri[0], &v1 = tri[1], &v2 = tri[2];
    const ScreenBox box =
        pixels_centred_in(std::min({v0.x, v1.x, v2.x}), std::min({v0.y, v1.y, v2.y}),
                          std::max({v0.x, v1.x, v2.x}), std::max({v0.y, v1.y, v2.y}))
            .clipped_to(b);
    const EdgeFunction e0(v1, v2), e1(v2, v0), e2(v0, v1);
    const double inverse_area = 1.0 / area;
    std::size_t fragments = 0;
    for (int y = box.y0; y <= box.y1; ++y) {
        const double py = y + 0.5;
        for (int x = box.x0; x <= box.x1; ++x) {
            const double px = x + 0.5;
            const double w0 = e0.at(px, py), w1 = e1.at(px, py), w2 = e2.at(px, py);
            if (w0 < 0 || w1 < 0 || w2 < 0) continue;
            if (!open(x, y)) continue;
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
            const double b0 = w0 * inverse_area, b1 = w1 * inverse_area, b2 = w2 * inverse_area;
            double u = b0 * v0.thickness + b1 * v1.thickness + b2 * v2.thickness;
            const double sf = b0 * v0.s_front + b1 * v1.s_front + b2 * v2.s_front;
            double sb = b0 * v0.s_back + b1 * v1.s_back + b2 * v2.s_back;
            if (in.opaque_depth) {
                const double tf = b0 * v0.t_front + b1 * v1.t_front + b2 * v2.t_front;
                const double room = (*in.opaque_depth)[static_cast<std::size_t>(y) * w + x] - tf;
                if (!(room > 0)) continue;
                if (room < u) {
                    sb = sf + (sb - sf) * room / u;
                    u = room;
                }
            }
            if (!(u > 0)) continue;
            composite(x, y, in.shader->shade(sf, sb, u));
            ++fragments;
        }
    }
    return fragments;
}

// Front to back over one tile: per pixel the colour gathered so far and the transmittance left.
// A pixel whose transmittance falls below kSaturated (2^-24, the rounding of a float near 1)
// takes no more fragments: what lies behind it could add no more than the rounding of what it
// holds (an optical depth of 16.6 in front saturates a pixel). Cost of a fragment: two
// multiply-adds.
class TileAccumulator {
  public:
    static constexpr float kSaturated = 0x1.0p-24f;

    void reset(const TileRays& rays) {
        open_pixels_ = 0;
        for (int y = rays.y0; y <= rays.y1; ++y) {
            for (int x = rays.x0; x <= rays.x1; ++x) {
                const int local = (y - rays.y0) * kFragmentTile + (x - rays.x0);
                gathered_[local] = Vec3f(0.0f);
                left_[local] = 1.0f;
                ++open_pixels_;
            }
        }
    }
    bool open(int local) const { return left_[local] >= kSaturated; }
    bool saturated() const { return open_pixels_ == 0; }
    // A fragment behind what the pixel gathered (premultiplied colour). Precondition: open.
    void under(int local, const ShadedSegment& seg) {
        gathered_[local] += left_[local] * seg.color;
        left_[local] *= 1.0f - seg.alpha;
        if (left_[local] < kSaturated) --open_pixels_;
    }
    // The tile's pixels of `image` (background or opaque colour) under the gathered colour;
    // `opacity`, when given, the volume's opacity there.
    void finish(const TileRays& rays, Image& image, float* opacity) const {
        const std::size_t w = static_cast<std::size_t>(image.width);
        for (int y = rays.y0; y <= rays.y1; ++y) {
            for (int x = rays.x0; x <= rays.x1; ++x) {
                const int local = (y - rays.y0) * kFragmentTile + (x - rays.x0);
                const std::size_t pixel = static_cast<std::size_t>(y) * w + x;
                image.pixels[pixel] = gathered_[local] + left_[local] * image.pixels[pixel];
                if (opacity) opacity[pixel] = 1.0f - left_[local];
            }
        }
    }

  private:
    Vec3f gathered_[kFragmentTile * kFragmentTile];
    float left_[kFragmentTile * kFragmentTile];
    int open_pixels_ = 0;
};

// The cells of `order` (in its order) whose scalar range the shader does not leave clear:
// the others shade to nothing, so drawing them changes no bit of the picture.
std::vector<CellId> cells_not_clear(const TetMesh& mesh, std::span<const float> scalar,
                                    std::span<const CellId> order, const SegmentShader& shader) {
    std::vector<std::uint8_t> clear(order.size());
    parallel_for(0, order.size(), 4096, [&](std::size_t i) {
        const Tet& v = mesh.tet(order[i]);
        const auto [lo, hi] = std::minmax({scalar[v[0]], scalar[v[1]], scalar[v[2]], scalar[v[3]]});
        clear[i] = shader.clear_between(lo, hi);
    });
    std::vector<CellId> kept;
    kept.reserve(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        if (!clear[i]) kept.push_back(order[i]);
    }
    return kept;
}

}  // namespace

double longest_edge(const TetMesh& mesh) {
    std::mutex longest_mutex;
    double longest = 0.0;
    parallel_for_chunks(0, mesh.num_real_tets(), 65536, [&](std::size_t begin, std::size_t end) {
        double chunk_longest = 0.0;
        for (std::size_t t = begin; t < end; ++t) {
            const Tet& v = mesh.tet(static_cast<CellId>(t));
            for (int a = 0; a < 4; ++a) {
                for (int b = a + 1; b < 4; ++b) {
                    chunk_longest =
                        std::max(chunk_longest, glm::length(mesh.point(v[a]) - mesh.point(v[b])));
                }
            }
        }
        const std::lock_guard<std::mutex> lock(longest_mutex);
        longest = std::max(longest, chunk_longest);
    });
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

    // The cells binned into screen tiles, keeping their order (project/tet_fragments.h); those
    // the transfer function leaves clear left out.
    const std::vector<CellId> order = cells_not_clear(mesh, in.scalar, in.order, *in.shader);
    const TileBins bins = bin_cells(mesh, order, camera);
    // The paper's projection for the exp-texture integrator; the exact per-pixel segments for
    // the others (and for cells reaching behind the eye, which must be clipped).
    const bool shirley_tuchman = in.shader->integrator() == Integrator::kExpTexture;
    const std::span<const double> max_depth =
        in.opaque_depth ? std::span<const double>(*in.opaque_depth) : std::span<const double>();

    Image image(w, h, Vec3f(in.background));
    if (in.opaque_color) image = *in.opaque_color;
    // The volume's opacity per pixel, when asked for: one less the transmittance left.
    if (alpha) alpha->assign(static_cast<std::size_t>(w) * h, 0.0f);
    float* const opacity = alpha ? alpha->data() : nullptr;
    std::atomic<std::size_t> fragments{0};
    // One tile, its cells front to back (the order reversed) under what the pixels gathered.
    auto render_tile = [&](std::size_t tile) {
        TileRays rays;  // the tile's rays, computed once
        tile_rays(bins, tile, camera, rays);
        TileAccumulator gathered;
        gathered.reset(rays);
        auto open = [&](int x, int y) {
            return gathered.open((y - rays.y0) * kFragmentTile + (x - rays.x0));
        };
        auto composite = [&](int x, int y, const ShadedSegment& seg) {
            const int local = (y - rays.y0) * kFragmentTile + (x - rays.x0);
            if (gathered.open(local)) gathered.under(local, seg);
        };
        std::size_t tile_fragments = 0;
        // A cell's fragments in this tile: segments, their pixels, their shading.
        SegmentQuery queries[kFragmentTile * kFragmentTile];
        std::uint16_t pixels[kFragmentTile * kFragmentTile];
        ShadedSegment shaded[kFragmentTile * kFragmentTile];
        std::vector<int> on_edges;  // pixels of the current cell decided by the exact test
        const std::vector<std::uint32_t>& cells = bins.bins[tile];
        for (auto entry = cells.rbegin(); entry != cells.rend() && !gathered.saturated(); ++entry) {
            const std::uint32_t index = *entry;
            const CellId t = order[index];
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
                composite(x, y, in.shader->shade(s_in, s_out, t_out - t_in));
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
                    tile_fragments += draw_st_triangle(tri, b, rays, in, w, on_edges, open,
                                                       composite, draw_exact);
                }
                continue;
            }
            // The cell's segments in this tile first (but at pixels whose transmittance is spent),
            // then shaded together (the shader overlaps their lookups) and composited: each
            // pixel appears once per cell, so the order of compositing per pixel is the cells'.
            int count = 0;
            for_each_fragment(
                cell, b, rays, w, max_depth,
                [&](int x, int y, double t_in, double t_out, double s_in, double s_out) {
                    const int local = (y - rays.y0) * kFragmentTile + (x - rays.x0);
                    if (!gathered.open(local)) return;
                    queries[count] = {s_in, s_out, t_out - t_in};
                    pixels[count++] = static_cast<std::uint16_t>(local);
                });
            const std::size_t n = static_cast<std::size_t>(count);
            in.shader->shade(std::span(queries, n), std::span(shaded, n));
            for (std::size_t f = 0; f < n; ++f) gathered.under(pixels[f], shaded[f]);
            tile_fragments += n;
        }
        gathered.finish(rays, image, opacity);
        fragments += tile_fragments;
    };
    parallel_for(0, bins.num_tiles(), 1, [&](std::size_t tile) { render_tile(tile); });
    if (stats) {
        stats->cells_drawn = bins.cells_drawn;
        stats->fragments = fragments.load();
        stats->raster_ms = ms_since(start);
    }
    return image;
}

}  // namespace tr
