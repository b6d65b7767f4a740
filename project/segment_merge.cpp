#include <core/parallel.h>
#include <project/segment_merge.h>
#include <project/tet_fragments.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>

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
    std::vector<double> cuts = {a, b};
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
        double k0, k1;
        Vec3 e;
        medium(u0, k0, e);
        medium(u1, k1, e);
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

}  // namespace

Image render_segment_merge(const VolumeScene& scene, SegmentMergeStats* stats) {
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
    const std::size_t num_tiles = volumes.empty() ? 0 : volumes[0].bins.num_tiles();
    std::atomic<std::size_t> total_fragments{0}, total_overlaps{0};

    parallel_for(0, num_tiles, 1, [&](std::size_t tile) {
        TileRays rays;
        tile_rays(volumes[0].bins, tile, camera, rays);
        thread_local std::vector<Segment> segments;
        segments.clear();
        for (std::size_t v = 0; v < volumes.size(); ++v) {
            const VolumeState& state = volumes[v];
            const VolumeData& volume = *state.volume;
            for (std::uint32_t index : state.bins.bins[tile]) {
                const CellFragments cell(*volume.mesh, volume.scalar, state.cells[index], camera);
                for_each_fragment(
                    cell, state.bins.boxes[index], rays, w, max_depth,
                    [&](int x, int y, double t_in, double t_out, double s_in, double s_out) {
                        segments.push_back({t_in, t_out, s_in, s_out,
                                            static_cast<std::uint16_t>(
                                                (y - rays.y0) * kFragmentTile + (x - rays.x0)),
                                            static_cast<std::uint8_t>(v)});
                    });
            }
        }
        total_fragments += segments.size();
        // Each pixel's segments together, front to back (ties: volume, then exit), so the
        // picture does not depend on the order cells were binned in.
        std::sort(segments.begin(), segments.end(), [](const Segment& a, const Segment& b) {
            if (a.pixel != b.pixel) return a.pixel < b.pixel;
            if (a.t_in != b.t_in) return a.t_in < b.t_in;
            if (a.volume != b.volume) return a.volume < b.volume;
            return a.t_out < b.t_out;
        });
        std::size_t overlaps = 0;
        std::vector<const Segment*> active;
        std::vector<double> bounds;
        for (std::size_t i = 0; i < segments.size();) {
            std::size_t j = i;
            while (j < segments.size() && segments[j].pixel == segments[i].pixel) ++j;
            const int x = rays.x0 + segments[i].pixel % kFragmentTile;
            const int y = rays.y0 + segments[i].pixel / kFragmentTile;
            Pixel pixel;
            // Sweep the pixel's segments: between consecutive ends, the segments that cover
            // the whole interval are active.
            bounds.clear();
            for (std::size_t k = i; k < j; ++k) {
                bounds.push_back(segments[k].t_in);
                bounds.push_back(segments[k].t_out);
            }
            std::sort(bounds.begin(), bounds.end());
            bounds.erase(std::unique(bounds.begin(), bounds.end()), bounds.end());
            std::size_t next = i;  // the first segment not yet active
            active.clear();
            for (std::size_t b = 0; b + 1 < bounds.size() && pixel.transparency > 0; ++b) {
                const double a = bounds[b], e = bounds[b + 1];
                std::erase_if(active, [&](const Segment* s) { return s->t_out <= a; });
                while (next < j && segments[next].t_in <= a) active.push_back(&segments[next++]);
                if (active.empty()) continue;
                // Neighbouring cells meet at a shared face whose plane each computes for itself:
                // their ends may cross by a rounding error. Nothing to integrate there.
                if (e - a <= 1e-12 * std::max(std::abs(a), std::abs(e))) continue;
                if (active.size() == 1) {
                    // One segment alone here: its piece [a, e], shaded by its volume's shader.
                    const Segment& s = *active[0];
                    const ShadedSegment shaded = volumes[s.volume].volume->shader->shade(
                        scalar_at(s, a), scalar_at(s, e), e - a);
                    pixel.over(Vec3(shaded.color), shaded.alpha);
                    continue;
                }
                ++overlaps;
                integrate_overlap(volumes, active.data(), active.size(), a, e, pixel);
            }
            Vec3f& out = image.at(x, y);
            out = Vec3f(pixel.color + pixel.transparency * Vec3(out));
            i = j;
        }
        total_overlaps += overlaps;
    });
    if (stats) {
        stats->fragments = total_fragments.load();
        stats->overlap_intervals = total_overlaps.load();
        stats->raster_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    }
    return image;
}

}  // namespace tr
