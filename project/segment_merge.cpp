#include <core/parallel.h>
#include <core/stopwatch.h>
#include <project/segment_merge.h>
#include <project/tet_fragments.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>
#include <span>
#include <vector>

namespace tr {
namespace {

using Clock = std::chrono::steady_clock;

constexpr double kMaxDepthStep = 0.02;  // optical depth per midpoint step in overlaps
constexpr int kMaxSteps = 4096;         // per piece between control-point crossings

// One segment of one pixel ray through one cell.
struct Segment {
    double t_in, t_out;
    double s_in, s_out;
    std::uint16_t pixel;  // in the tile
    std::uint8_t volume;
};

struct VolumeState {
    const VolumeData* volume;
    TileBins bins;
    std::vector<CellId> cells;
    std::vector<double> breakpoints;  // control-point scalars of its transfer function, sorted
};

double scalar_at(const Segment& s, double t) {
    const double length = s.t_out - s.t_in;
    return length > 0 ? s.s_in + (s.s_out - s.s_in) * (t - s.t_in) / length : s.s_in;
}

// Front-to-back compositing of one pixel: colour so far and transparency left.
struct Pixel {
    Vec3 color{0.0};
    double transparency = 1.0;

    void over(const Vec3& premultiplied, double alpha) {
        color += transparency * premultiplied;
        transparency *= 1.0 - alpha;
    }
};

// The interval [a, b] where the `active` segments (of several volumes) overlap, integrated
// directly with their extinctions and emissions added.
void integrate_overlap(const std::vector<VolumeState>& volumes, const Segment* const* active,
                       std::size_t count, double a, double b, Pixel& pixel) {
    // Cut where any segment's scalar crosses a control point of its transfer function.
    thread_local std::vector<double> cuts;  // reused: this runs once per overlap interval
    cuts.assign({a, b});
    for (std::size_t i = 0; i < count; ++i) {
        const Segment& s = *active[i];
        const double s0 = scalar_at(s, a), s1 = scalar_at(s, b);
        if (s0 == s1) continue;
        const std::vector<double>& points = volumes[s.volume].breakpoints;
        const double lo = std::min(s0, s1), hi = std::max(s0, s1);
        for (auto it = std::upper_bound(points.begin(), points.end(), lo);
             it != points.end() && *it < hi; ++it) {
            cuts.push_back(a + (b - a) * (*it - s0) / (s1 - s0));
        }
    }
    std::sort(cuts.begin(), cuts.end());
    auto extinction = [&](double t) {
        double kappa = 0;
        for (std::size_t i = 0; i < count; ++i) {
            const Segment& s = *active[i];
            kappa += volumes[s.volume].volume->tf->extinction(scalar_at(s, t));
        }
        return kappa;
    };
    auto medium = [&](double t, double& kappa, Vec3& emission) {
        kappa = 0;
        emission = Vec3(0.0);
        for (std::size_t i = 0; i < count; ++i) {
            const Segment& s = *active[i];
            const TransferFunction& tf = *volumes[s.volume].volume->tf;
            const double scalar = scalar_at(s, t);
            const double k = tf.extinction(scalar);
            kappa += k;
            emission += k * tf.color(scalar);
        }
    };
    for (std::size_t p = 0; p + 1 < cuts.size(); ++p) {
        const double u0 = cuts[p], u1 = cuts[p + 1];
        if (!(u1 > u0)) continue;
        const double k0 = extinction(u0), k1 = extinction(u1);
        const int steps =
            std::clamp(static_cast<int>(std::ceil(std::max(k0, k1) * (u1 - u0) / kMaxDepthStep)), 1,
                       kMaxSteps);
        const double h = (u1 - u0) / steps;
        for (int i = 0; i < steps; ++i) {
            double kappa;
            Vec3 emission;
            medium(u0 + (i + 0.5) * h, kappa, emission);
            if (!(kappa > 0)) continue;
            const double alpha = -std::expm1(-kappa * h);
            pixel.over(emission / kappa * alpha, alpha);
        }
    }
}

constexpr std::size_t kTilePixels = kFragmentTile * kFragmentTile;

// A piece of a pixel's ray: where one segment is alone it is shaded by its volume's shader, all
// of the tile's together per volume (the shader overlaps their lookups); where segments overlap
// it is integrated directly.
struct Piece {
    std::uint32_t query;  // single: index into queries[volume]; overlap: kOverlap
    std::uint8_t volume;
    Vec3 color;  // overlap: premultiplied colour
    double alpha;
};
constexpr std::uint32_t kOverlap = ~std::uint32_t{0};

// A tile's working buffers, kept per worker between tiles.
struct TileWork {
    std::vector<Segment> segments;
    std::vector<Segment> sorted;                         // by pixel, then front to back
    std::array<std::uint32_t, kTilePixels + 1> first{};  // pixel p: sorted[first[p], first[p+1])
    std::vector<Piece> pieces;
    std::vector<std::uint32_t> piece_first;  // pixel p: pieces[piece_first[p], piece_first[p+1])
    std::vector<std::vector<SegmentQuery>> queries;
    std::vector<std::vector<ShadedSegment>> shaded;
    std::vector<const Segment*> active;
    std::vector<double> bounds;
};

// The tile's segments, all volumes.
void gather_segments(const std::vector<VolumeState>& volumes, std::size_t tile,
                     const TileRays& rays, const CameraFrame& camera,
                     std::span<const double> max_depth, std::vector<Segment>& segments) {
    segments.clear();
    for (std::size_t v = 0; v < volumes.size(); ++v) {
        const VolumeState& state = volumes[v];
        const VolumeData& volume = *state.volume;
        for (std::uint32_t index : state.bins.bins[tile]) {
            const CellFragments cell(*volume.mesh, volume.scalar, state.cells[index], camera);
            for_each_fragment(
                cell, state.bins.boxes[index], rays, camera.width(), max_depth,
                [&](int x, int y, double t_in, double t_out, double s_in, double s_out) {
                    segments.push_back(
                        {t_in, t_out, s_in, s_out,
                         static_cast<std::uint16_t>((y - rays.y0) * kFragmentTile + (x - rays.x0)),
                         static_cast<std::uint8_t>(v)});
                });
        }
    }
}

// Each pixel's segments together (a counting sort by pixel), then front to back (ties: volume,
// then exit), so the picture does not depend on the order cells were binned in.
void group_by_pixel(TileWork& work) {
    std::array<std::uint32_t, kTilePixels + 1>& first = work.first;
    first.fill(0);
    for (const Segment& seg : work.segments) ++first[seg.pixel + 1];
    for (std::size_t p = 0; p < kTilePixels; ++p) first[p + 1] += first[p];
    work.sorted.resize(work.segments.size());
    std::array<std::uint32_t, kTilePixels> fill;
    std::copy(first.begin(), first.end() - 1, fill.begin());
    for (const Segment& seg : work.segments) work.sorted[fill[seg.pixel]++] = seg;
    for (std::size_t p = 0; p < kTilePixels; ++p) {
        std::sort(work.sorted.begin() + first[p], work.sorted.begin() + first[p + 1],
                  [](const Segment& a, const Segment& b) {
                      if (a.t_in != b.t_in) return a.t_in < b.t_in;
                      if (a.volume != b.volume) return a.volume < b.volume;
                      return a.t_out < b.t_out;
                  });
    }
}

// Pixel p's pieces in order, appended to work.pieces (single pieces queued for their shader);
// returns how many intervals had segments overlapping.
std::size_t sweep_pixel(const std::vector<VolumeState>& volumes, std::size_t p, TileWork& work) {
    const std::size_t i = work.first[p], j = work.first[p + 1];
    if (i == j) return 0;
    // Between consecutive ends, the segments that cover the whole interval are active.
    std::vector<double>& bounds = work.bounds;
    bounds.clear();
    for (std::size_t k = i; k < j; ++k) {
        bounds.push_back(work.sorted[k].t_in);
        bounds.push_back(work.sorted[k].t_out);
    }
    std::sort(bounds.begin(), bounds.end());
    bounds.erase(std::unique(bounds.begin(), bounds.end()), bounds.end());
    std::size_t next = i;  // the first segment not yet active
    std::vector<const Segment*>& active = work.active;
    active.clear();
    std::size_t overlaps = 0;
    for (std::size_t b = 0; b + 1 < bounds.size(); ++b) {
        const double a = bounds[b], e = bounds[b + 1];
        std::erase_if(active, [&](const Segment* s) { return s->t_out <= a; });
        while (next < j && work.sorted[next].t_in <= a) active.push_back(&work.sorted[next++]);
        if (active.empty()) continue;
        // Neighbouring cells meet at a shared face whose plane each computes for itself: their
        // ends may cross by a rounding error. Nothing to integrate there.
        if (e - a <= 1e-12 * std::max(std::abs(a), std::abs(e))) continue;
        if (active.size() == 1) {
            // One segment alone here: its piece [a, e], shaded by its volume's shader.
            const Segment& seg = *active[0];
            std::vector<SegmentQuery>& q = work.queries[seg.volume];
            work.pieces.push_back(
                {static_cast<std::uint32_t>(q.size()), seg.volume, Vec3(0.0), 0.0});
            q.push_back({scalar_at(seg, a), scalar_at(seg, e), e - a});
            continue;
        }
        ++overlaps;
        Pixel part;
        integrate_overlap(volumes, active.data(), active.size(), a, e, part);
        work.pieces.push_back({kOverlap, 0, part.color, 1.0 - part.transparency});
    }
    return overlaps;
}

// The tile's pieces composited front to back over what lies behind in `image`.
void composite_tile(const TileWork& work, const TileRays& rays, Image& image, float* opacity) {
    for (std::size_t p = 0; p < kTilePixels; ++p) {
        if (work.piece_first[p] == work.piece_first[p + 1]) continue;
        Pixel pixel;
        for (std::uint32_t k = work.piece_first[p]; k < work.piece_first[p + 1]; ++k) {
            const Piece& piece = work.pieces[k];
            if (piece.query == kOverlap) {
                pixel.color += pixel.transparency * piece.color;
                pixel.transparency *= 1.0 - piece.alpha;
            } else {
                const ShadedSegment& sh = work.shaded[piece.volume][piece.query];
                pixel.over(Vec3(sh.color), sh.alpha);
            }
        }
        const int x = rays.x0 + static_cast<int>(p % kFragmentTile);
        const int y = rays.y0 + static_cast<int>(p / kFragmentTile);
        Vec3f& out = image.at(x, y);
        out = Vec3f(pixel.color + pixel.transparency * Vec3(out));
        if (opacity) {
            opacity[static_cast<std::size_t>(y) * image.width + x] =
                static_cast<float>(1.0 - pixel.transparency);
        }
    }
}

}  // namespace

Image render_segment_merge(const VolumeScene& scene, SegmentMergeStats* stats,
                           std::vector<float>* alpha) {
    const auto start = Clock::now();
    const CameraFrame& camera = *scene.camera;
    const int w = camera.width(), h = camera.height();
    std::vector<VolumeState> volumes;
    volumes.reserve(scene.volumes.size());
    for (const VolumeData& v : scene.volumes) {
        VolumeState state{&v, {}, {}, {}};
        state.cells.resize(v.mesh->num_real_tets());
        std::iota(state.cells.begin(), state.cells.end(), CellId{0});
        state.bins = bin_cells(*v.mesh, state.cells, camera);
        for (const ColorPoint& p : v.tf->color_points()) state.breakpoints.push_back(p.s);
        for (const OpacityPoint& p : v.tf->opacity_points()) state.breakpoints.push_back(p.s);
        std::sort(state.breakpoints.begin(), state.breakpoints.end());
        volumes.push_back(std::move(state));
    }
    const std::span<const double> max_depth = scene.opaque_depth
                                                  ? std::span<const double>(*scene.opaque_depth)
                                                  : std::span<const double>();
    Image image(w, h, Vec3f(scene.background));
    if (scene.opaque_color) image = *scene.opaque_color;
    if (alpha) alpha->assign(static_cast<std::size_t>(w) * h, 0.0f);
    float* const opacity = alpha ? alpha->data() : nullptr;
    const std::size_t num_tiles = volumes.empty() ? 0 : volumes[0].bins.num_tiles();
    std::atomic<std::size_t> total_fragments{0}, total_overlaps{0};

    parallel_for(0, num_tiles, 1, [&](std::size_t tile) {
        TileRays rays;
        tile_rays(volumes[0].bins, tile, camera, rays);
        thread_local TileWork work;
        gather_segments(volumes, tile, rays, camera, max_depth, work.segments);
        total_fragments += work.segments.size();
        group_by_pixel(work);
        // The pieces of every pixel in order, then the single pieces shaded per volume.
        work.queries.resize(volumes.size());
        work.shaded.resize(volumes.size());
        for (auto& q : work.queries) q.clear();
        work.pieces.clear();
        work.piece_first.assign(kTilePixels + 1, 0);
        std::size_t overlaps = 0;
        for (std::size_t p = 0; p < kTilePixels; ++p) {
            work.piece_first[p] = static_cast<std::uint32_t>(work.pieces.size());
            overlaps += sweep_pixel(volumes, p, work);
        }
        work.piece_first[kTilePixels] = static_cast<std::uint32_t>(work.pieces.size());
        for (std::size_t v = 0; v < volumes.size(); ++v) {
            work.shaded[v].resize(work.queries[v].size());
            if (!work.queries[v].empty()) {
                volumes[v].volume->shader->shade(work.queries[v], work.shaded[v]);
            }
        }
        composite_tile(work, rays, image, opacity);
        total_overlaps += overlaps;
    });
    if (stats) {
        stats->fragments = total_fragments.load();
        stats->overlap_intervals = total_overlaps.load();
        stats->raster_ms = ms_since(start);
    }
    return image;
}

}  // namespace tr
