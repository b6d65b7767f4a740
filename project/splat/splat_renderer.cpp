#include <core/check.h>
#include <core/parallel.h>
#include <core/stopwatch.h>
#include <project/splat/splat_renderer.h>
#include <project/splat/splat_rows.h>
#include <project/splat/splat_stamps.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>
#include <span>

namespace tr {
namespace {

constexpr int kTile = 32;
// Each row of a tile's buffers has kApron pixels more either side, which rows of splats may
// spill into so that the vector loops run on whole multiples of 8 (they are never stored).
constexpr int kApron = 8;
constexpr int kStride = kTile + 2 * kApron;

// The index in a tile's buffers of the pixel at (dx, dy) from the tile's corner.
constexpr int tile_index(int dx, int dy) { return dy * kStride + dx + kApron; }
constexpr std::size_t kPrefetch = 8;  // splats fetched ahead of the raster

// floor / ceil of a pixel coordinate as an int, limited to +-1e9 (NaN to -1e9): a splat far off
// the picture must not overflow the conversion.
int pixel_floor(double v) {
    return static_cast<int>(std::floor(v > -1e9 ? std::min(v, 1e9) : -1e9));
}
int pixel_ceil(double v) { return static_cast<int>(std::ceil(v > -1e9 ? std::min(v, 1e9) : -1e9)); }

// A splat as the raster reads it: one cache line.
struct alignas(64) Splat {
    float sx, sy;         // the projected centre, pixel units
    double depth;         // orthographic: the ray parameter of the centre; perspective: its
                          // distance from the eye (the per-splat order)
    float kappa_h;        // its extinction times h
    float h;              // the kernel's scale: the spacing, or the point's radius
    Vec3f color;          // the transfer function's colour at the point's value
    int x0, y0, x1, y1;   // pixels whose centres may lie in its footprint, inclusive
    std::uint32_t point;  // its point
    std::int32_t sheet;   // the sheet buffer: its sheet's place in the order (else 0)
};
static_assert(sizeof(Splat) == 64);

// A tile's picture, planar (loaded from the picture before its splats, stored after), and its
// sheet buffer: the current sheet's summed optical depth and depth-weighted colour. Row-major,
// kTile rows of kStride (tile_index).
struct TileBuffers {
    static constexpr int kArea = kStride * kTile;
    float r[kArea] = {}, g[kArea] = {}, b[kArea] = {};
    float tau[kArea] = {}, tau_r[kArea] = {}, tau_g[kArea] = {}, tau_b[kArea] = {};
    int rows_from = kTile, rows_to = 0;  // the rows the current sheet touched: [from, to)

    void touch(int local) {
        rows_from = std::min(rows_from, local / kStride);
        rows_to = std::max(rows_to, local / kStride + 1);
    }
};

// Where a splat's fragments go: its pixels' rectangle in the tile, the tile's corner and
// buffers, and the opaque depths.
struct TileTarget {
    int xa, xb, ya, yb;  // inclusive, inside the tile and the picture
    int x0, y0;          // the tile's corner
    TileBuffers* buffers;
    int width;                   // the picture's
    const double* opaque_depth;  // or null (then unused)
};

// The tile-local pixel `local`'s row of the tile's picture and sheet buffer.
splat_rows::ColorRow color_row(TileBuffers& t, int local) {
    return {t.r + local, t.g + local, t.b + local};
}
splat_rows::SheetRow sheet_row(TileBuffers& t, int local) {
    t.touch(local);
    return {t.tau + local, t.tau_r + local, t.tau_g + local, t.tau_b + local};
}

// `count` fragments of one splat on a row from the tile-local pixel `local` on: optical depth
// tau[i] (0 where the opaque surface hides it: then the pixel is unchanged, exactly), colour
// `colour`, summed into the sheet or composited over the picture.
template <bool kSheets>
void composite_row(TileBuffers& t, int local, const float* tau, int count, const Vec3f& colour) {
    if constexpr (kSheets) {
        splat_rows::add_to_sheet(sheet_row(t, local), tau, count, colour);
    } else {
        splat_rows::composite(color_row(t, local), tau, count, colour);
    }
}

// One splat of an orthographic view at the stamps' scale: per row, the four stamps around its
// centre's sub-pixel position blended (weights times kappa h) into the row's optical depths,
// hidden ones zeroed, then composited. Returns the fragments drawn.
template <bool kSheets, bool kOpaque>
std::size_t raster_stamped(const Splat& s, const SplatStamps& stamps, const TileTarget& t) {
    const SplatStamps::Placement p = stamps.place(s.sx, s.sy);
    const float kappa_h = s.kappa_h;
    const Vec3f colour = s.color;
    const int width = stamps.width();
    splat_rows::StampBlock block{{{p.stamp[0], p.stamp[1], p.stamp[2], p.stamp[3]},
                                  {kappa_h * p.weight[0], kappa_h * p.weight[1],
                                   kappa_h * p.weight[2], kappa_h * p.weight[3]}},
                                 width,
                                 std::max(0, t.ya - p.y0),
                                 std::min(width - 1, t.yb - p.y0),
                                 t.xa - p.x0,
                                 t.xb - p.x0 + 1,
                                 t.x0 - kApron - p.x0,
                                 t.x0 + kTile + kApron - p.x0,
                                 p.span_from,
                                 p.span_to,
                                 tile_index(p.x0 - t.x0, p.y0 - t.y0),
                                 kStride};
    if (block.v_from > block.v_to) return 0;
    TileBuffers& buffers = *t.buffers;
    if constexpr (!kOpaque) {
        if constexpr (kSheets) {
            buffers.touch(tile_index(0, p.y0 + block.v_from - t.y0));
            buffers.touch(tile_index(0, p.y0 + block.v_to - t.y0));
            return static_cast<std::size_t>(splat_rows::add_stamp_block_to_sheet(
                {buffers.tau, buffers.tau_r, buffers.tau_g, buffers.tau_b}, block, colour));
        } else {
            const bool small = kappa_h * stamps.peak() <= splat_rows::kSmallDepth;
            return static_cast<std::size_t>(splat_rows::composite_stamp_block(
                {buffers.r, buffers.g, buffers.b}, block, colour, small));
        }
    }
    // Opaque geometry: row by row, the hidden pixels' depths zeroed.
    float tau[SplatStamps::kMaxWidth];
    std::size_t count = 0;
    splat_rows::StampRows rows = block.stamps;
    for (int v = block.v_from; v <= block.v_to; ++v) {
        const int u_from = std::max<int>(p.span_from[v], block.u_lo);
        const int u_to = std::min<int>(p.span_to[v], block.u_hi);
        const int n = u_to - u_from;
        if (n <= 0) continue;
        const std::size_t offset = static_cast<std::size_t>(v) * width + u_from;
        for (int k = 0; k < 4; ++k) rows.stamp[k] = p.stamp[k] + offset;
        const int y = p.y0 + v, x = p.x0 + u_from;
        splat_rows::blend_stamps(tau, rows, n);
        const double* depth =
            t.opaque_depth + static_cast<std::size_t>(y) * t.width + static_cast<std::size_t>(x);
        for (int i = 0; i < n; ++i) {
            if (!(s.depth < depth[i])) tau[i] = 0.0f;
        }
        composite_row<kSheets>(buffers, tile_index(x - t.x0, y - t.y0), tau, n, colour);
        count += static_cast<std::size_t>(n);
    }
    return count;
}

// One splat of an orthographic view without stamps (a per-point radius, or a footprint wider
// than the stamps): rays are parallel, so the distance to each pixel's ray is that on the image
// (in kernel units). Per row, the pixels whose centres lie strictly inside the support's circle;
// f read by rho^2. Returns the fragments drawn.
template <bool kSheets, bool kOpaque>
std::size_t raster_orthographic(const Splat& s, double per_unit, const SplatFootprint& footprint,
                                const TileTarget& t) {
    const auto support_sq = static_cast<float>(footprint.support() * footprint.support());
    const auto to_kernel = static_cast<float>(1.0 / (per_unit * s.h));
    const float kappa_h = s.kappa_h;
    const float sx = s.sx, sy = s.sy;
    const Vec3f colour = s.color;
    std::size_t count = 0;
    float tau[kTile];
    for (int y = t.ya; y <= t.yb; ++y) {
        const float dy = (static_cast<float>(y) + 0.5f - sy) * to_kernel;
        const float dy_sq = dy * dy;
        if (!(dy_sq < support_sq)) continue;
        const float half = std::sqrt(support_sq - dy_sq) / to_kernel;  // pixels
        const int from = std::max(t.xa, pixel_floor(sx - half - 0.5f) + 1);
        const int to = std::min(t.xb, pixel_ceil(sx + half - 0.5f) - 1);
        if (from > to) continue;
        const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(t.width);
        for (int x = from; x <= to; ++x) {
            const float dx = (static_cast<float>(x) + 0.5f - sx) * to_kernel;
            float& f = tau[x - from];
            f = kappa_h * footprint.of_squared_inside(dx * dx + dy_sq);
            if constexpr (kOpaque) {
                if (!(s.depth < t.opaque_depth[row + static_cast<std::size_t>(x)])) f = 0.0f;
            }
        }
        composite_row<kSheets>(*t.buffers, tile_index(from - t.x0, y - t.y0), tau, to - from + 1,
                               colour);
        count += static_cast<std::size_t>(to - from + 1);
    }
    return count;
}

// One orthographic splat: from the stamps when there are (a lattice's splats), else by the
// footprint's table.
template <bool kSheets, bool kOpaque>
std::size_t raster_splat(const Splat& s, const TileTarget& t, const SplatStamps* stamps,
                         double per_unit, const SplatFootprint& footprint) {
    return stamps ? raster_stamped<kSheets, kOpaque>(s, *stamps, t)
                  : raster_orthographic<kSheets, kOpaque>(s, per_unit, footprint, t);
}

// A splat to draw and its depth: a tile's per-splat order.
struct DepthEntry {
    double depth;
    std::uint32_t index;
};

// Back to front: decreasing depth, ties by increasing index (the points' order).
bool further_back(const DepthEntry& a, const DepthEntry& b) {
    return a.depth != b.depth ? a.depth > b.depth : a.index < b.index;
}

// The indices of `sheet` (each >= 0) grouped by sheet, the sheets in the order `further`
// (a strict weak order on sheet indices: true when the first is composited first), each sheet's
// in increasing index. Counting when the sheets' indices are few against the splats (a lattice:
// O(n)), else a stable sort. Stores the number of distinct sheets.
template <class Further>
std::vector<std::uint32_t> order_by_sheet(const std::vector<std::int64_t>& sheet, Further further,
                                          std::size_t* distinct) {
    const std::int64_t largest = *std::max_element(sheet.begin(), sheet.end());
    std::vector<std::uint32_t> order(sheet.size());
    if (largest > static_cast<std::int64_t>(4 * sheet.size() + 1024)) {
        std::iota(order.begin(), order.end(), 0u);
        std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
            return sheet[a] != sheet[b] && further(sheet[a], sheet[b]);
        });
        std::size_t count = 0;
        for (std::size_t i = 0; i < order.size(); ++i) {
            count += i == 0 || sheet[order[i]] != sheet[order[i - 1]];
        }
        *distinct = count;
        return order;
    }
    std::vector<std::size_t> start(static_cast<std::size_t>(largest) + 1, 0);
    for (std::int64_t s : sheet) ++start[static_cast<std::size_t>(s)];
    std::vector<std::int64_t> used;
    for (std::size_t s = 0; s < start.size(); ++s) {
        if (start[s] > 0) used.push_back(static_cast<std::int64_t>(s));
    }
    *distinct = used.size();
    std::sort(used.begin(), used.end(), further);
    std::size_t next = 0;
    for (std::int64_t s : used) {
        const std::size_t count = start[static_cast<std::size_t>(s)];
        start[static_cast<std::size_t>(s)] = next;
        next += count;
    }
    for (std::size_t i = 0; i < sheet.size(); ++i) {
        order[start[static_cast<std::size_t>(sheet[i])]++] = static_cast<std::uint32_t>(i);
    }
    return order;
}

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

namespace {

// Every point's splat: `splats[i]` is point i's where `drawn` lists i (a non-zero extinction, in
// view), in the points' order.
struct SplatSet {
    std::unique_ptr<Splat[]> splats;
    std::vector<std::uint32_t> drawn;
};

SplatSet make_splats(const SplatInputs& in, double support, double per_unit) {
    const CameraFrame& camera = *in.camera;
    const int w = camera.width(), h = camera.height();
    const bool orthographic = camera.orthographic();
    // Point i as a splat of extinction kappa (> 0), but its colour; false when it is not in view.
    auto make_splat = [&](std::size_t i, double kappa, Splat& splat) {
        const Vec3& p = in.points[i];
        const Vec3 s = camera.project(p);
        const double kernel_h = in.radius.empty() ? in.spacing : static_cast<double>(in.radius[i]);
        const double radius = support * kernel_h;  // world units
        double r_px;
        if (orthographic) {
            r_px = radius * per_unit;
        } else {
            if (!(s.z > radius)) return false;  // its support reaches behind the eye
            // A sphere of the support's radius projects within this (its nearest depth, and the
            // stretch off the axis, distance over depth).
            const double distance = glm::length(p - camera.eye());
            r_px = radius * per_unit / (s.z - radius) * (distance / s.z);
        }
        splat = Splat{static_cast<float>(s.x),
                      static_cast<float>(s.y),
                      orthographic ? s.z : glm::length(p - camera.eye()),
                      static_cast<float>(kappa * kernel_h),
                      static_cast<float>(kernel_h),
                      Vec3f(0.0f),
                      std::max(pixel_floor(s.x - r_px - 0.5), 0),
                      std::max(pixel_floor(s.y - r_px - 0.5), 0),
                      std::min(pixel_ceil(s.x + r_px - 0.5), w - 1),
                      std::min(pixel_ceil(s.y + r_px - 0.5), h - 1),
                      static_cast<std::uint32_t>(i),
                      0};
        return splat.x0 <= splat.x1 && splat.y0 <= splat.y1;
    };
    // Concurrently, in blocks. Uninitialised (default-initialised): only the drawn points' are
    // written and read, and the pages are first touched by the threads that fill them.
    constexpr std::size_t kBlock = 16384;
    const std::size_t n = in.points.size();
    SplatSet set;
    set.splats.reset(new Splat[n]);
    Splat* const splats = set.splats.get();
    std::vector<std::vector<std::uint32_t>> drawn_blocks((n + kBlock - 1) / kBlock);
    parallel_for(0, drawn_blocks.size(), 1, [&](std::size_t block) {
        for (std::size_t i = block * kBlock; i < std::min(n, (block + 1) * kBlock); ++i) {
            const double kappa = in.tf->extinction(in.scalar[i]);
            if (!(kappa > 0) || !make_splat(i, kappa, splats[i])) continue;
            splats[i].color = Vec3f(in.tf->color(in.scalar[i]));
            drawn_blocks[block].push_back(static_cast<std::uint32_t>(i));
        }
    });
    for (const auto& block : drawn_blocks) {
        set.drawn.insert(set.drawn.end(), block.begin(), block.end());
    }
    return set;
}

// The order the drawn points are drawn in: with the sheet buffer back to front, each splat's
// sheet numbered by its place among the sheets; per splat, the points' order (each tile sorts
// its own by depth).
struct DrawOrder {
    std::vector<std::uint32_t> sequence;
    int axis = -1;                // the sheets' axis (sheet buffer)
    std::size_t sheet_count = 0;  // sheets holding a splat
};

DrawOrder draw_order(const SplatInputs& in, SplatSet& set, bool sheets) {
    const CameraFrame& camera = *in.camera;
    const bool orthographic = camera.orthographic();
    const std::vector<std::uint32_t>& drawn = set.drawn;
    DrawOrder out;
    out.sequence = drawn;
    if (!sheets || drawn.empty()) return out;
    // The axis most parallel to the view, and the sheets of thickness `spacing` across it.
    Vec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (std::uint32_t i : drawn) lo = glm::min(lo, in.points[i]), hi = glm::max(hi, in.points[i]);
    const Vec3 view = orthographic ? camera.forward() : 0.5 * (lo + hi) - camera.eye();
    int axis = 0;
    for (int k = 1; k < 3; ++k) {
        if (std::abs(view[k]) > std::abs(view[axis])) axis = k;
    }
    std::vector<std::int64_t> sheet(drawn.size());  // each drawn point's sheet
    for (std::size_t k = 0; k < drawn.size(); ++k) {
        sheet[k] = std::llround((in.points[drawn[k]][axis] - lo[axis]) / in.spacing);
    }
    // Back to front: orthographic, further along the view; perspective, further from the eye
    // across the sheets (ties, sheets either side of the eye, by index). Within a sheet the
    // order does not matter (its splats are summed): the points' order.
    const double sign = view[axis] < 0 ? -1.0 : 1.0;
    auto key = [&](std::int64_t index) {
        const double plane = lo[axis] + static_cast<double>(index) * in.spacing;
        return orthographic ? sign * plane : std::abs(plane - camera.eye()[axis]);
    };
    auto further = [&](std::int64_t a, std::int64_t b) {
        const double ka = key(a), kb = key(b);
        return ka != kb ? ka > kb : a > b;
    };
    const std::vector<std::uint32_t> order = order_by_sheet(sheet, further, &out.sheet_count);
    out.axis = axis;
    for (std::size_t k = 0; k < drawn.size(); ++k) out.sequence[k] = drawn[order[k]];
    for (std::size_t k = 1; k < out.sequence.size(); ++k) {
        set.splats[out.sequence[k]].sheet = set.splats[out.sequence[k - 1]].sheet +
                                            (sheet[order[k]] != sheet[order[k - 1]] ? 1 : 0);
    }
    return out;
}

// The splats binned into screen tiles in drawing order: tile t's are
// binned[start[t], start[t + 1]).
struct TileBins {
    int tiles_x = 0;
    std::size_t tiles = 0;
    std::vector<std::size_t> start;
    std::vector<std::uint32_t> binned;
};

TileBins bin_into_tiles(const SplatSet& set, const std::vector<std::uint32_t>& sequence, int w,
                        int h, std::size_t num_points) {
    TileBins bins;
    bins.tiles_x = (w + kTile - 1) / kTile;
    const int tiles_y = (h + kTile - 1) / kTile;
    bins.tiles = static_cast<std::size_t>(bins.tiles_x) * tiles_y;
    // Each drawn splat's tiles, inclusive (read in the order above: a small array).
    struct TileSpan {
        int x0, y0, x1, y1;
    };
    const std::unique_ptr<TileSpan[]> tile_span(new TileSpan[num_points]);
    for (std::uint32_t i : set.drawn) {
        const Splat& s = set.splats[i];
        tile_span[i] = {s.x0 / kTile, s.y0 / kTile, s.x1 / kTile, s.y1 / kTile};
    }
    auto for_each_tile = [&](std::uint32_t i, auto&& body) {
        const TileSpan& span = tile_span[i];
        for (int ty = span.y0; ty <= span.y1; ++ty) {
            for (int tx = span.x0; tx <= span.x1; ++tx) {
                body(static_cast<std::size_t>(ty) * bins.tiles_x + tx);
            }
        }
    };
    bins.start.assign(bins.tiles + 1, 0);
    for (std::uint32_t i : set.drawn) {
        for_each_tile(i, [&](std::size_t t) { ++bins.start[t + 1]; });
    }
    std::partial_sum(bins.start.begin(), bins.start.end(), bins.start.begin());
    bins.binned.resize(bins.start.back());
    std::vector<std::size_t> next(bins.start.begin(), bins.start.end() - 1);
    for (std::uint32_t i : sequence) {
        for_each_tile(i, [&](std::size_t t) { bins.binned[next[t]++] = i; });
    }
    return bins;
}

// What every tile's raster reads.
struct TileRasterInputs {
    const SplatInputs* in = nullptr;
    const Splat* splats = nullptr;
    TileBins* bins = nullptr;
    Image* image = nullptr;
    bool sheets = false;
    double per_unit = 0;
    double support_sq = 0;
    const SplatStamps* stamps = nullptr;  // orthographic splats of one scale, or null
    decltype(&raster_splat<false, false>) raster_ortho = nullptr;
    splat_rows::FootprintTable table{};
};

// Draws the splats of one tile over its pixels of the image; returns the fragments drawn.
std::size_t raster_tile(const TileRasterInputs& r, std::size_t tile) {
    const SplatInputs& in = *r.in;
    const CameraFrame& camera = *in.camera;
    const bool orthographic = camera.orthographic();
    const int w = camera.width(), h = camera.height();
    const Splat* const splats = r.splats;
    const SplatFootprint& fp = *in.footprint;
    const double* const opaque = in.opaque_depth ? in.opaque_depth->data() : nullptr;
    const int x0 = static_cast<int>(tile % r.bins->tiles_x) * kTile;
    const int y0 = static_cast<int>(tile / r.bins->tiles_x) * kTile;
    const int x1 = std::min(x0 + kTile, w) - 1, y1 = std::min(y0 + kTile, h) - 1;
    if (r.bins->start[tile] == r.bins->start[tile + 1]) return 0;
    // Perspective: the pixels' rays from the eye, their unit directions planar.
    double dir_x[kTile * kTile], dir_y[kTile * kTile], dir_z[kTile * kTile];
    for (int y = y0; !orthographic && y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
            const Vec3 d = camera.pixel_ray(x, y).direction;
            const int k = (y - y0) * kTile + (x - x0);
            dir_x[k] = d.x, dir_y[k] = d.y, dir_z[k] = d.z;
        }
    }
    TileBuffers buffers;
    auto pixel = [&](int x, int y) -> Vec3f& {
        return r.image->pixels[static_cast<std::size_t>(y) * w + x];
    };
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
            const int local = tile_index(x - x0, y - y0);
            const Vec3f& p = pixel(x, y);
            buffers.r[local] = p.r, buffers.g[local] = p.g, buffers.b[local] = p.b;
        }
    }
    std::size_t count = 0;
    std::int64_t current = 0;
    bool open = false;
    // The sheet composited over the tile: alpha = 1 - e^-tau, colour sum(c tau) / tau alpha.
    auto flush = [&] {
        const int from = buffers.rows_from * kStride, to = buffers.rows_to * kStride;
        if (from < to) {
            splat_rows::composite_sheet(color_row(buffers, from),
                                        {buffers.tau + from, buffers.tau_r + from,
                                         buffers.tau_g + from, buffers.tau_b + from},
                                        to - from);
        }
        buffers.rows_from = kTile, buffers.rows_to = 0;
    };
    // The tile's splats in order: per splat, sorted here by depth (their data now cached).
    const std::span<std::uint32_t> bin(r.bins->binned.data() + r.bins->start[tile],
                                       r.bins->start[tile + 1] - r.bins->start[tile]);
    if (!r.sheets) {
        std::vector<DepthEntry> entries(bin.size());
        for (std::size_t k = 0; k < bin.size(); ++k) {
            if (k + kPrefetch < bin.size()) __builtin_prefetch(&splats[bin[k + kPrefetch]]);
            entries[k] = {splats[bin[k]].depth, bin[k]};
        }
        std::sort(entries.begin(), entries.end(), further_back);
        for (std::size_t k = 0; k < bin.size(); ++k) bin[k] = entries[k].index;
    }
    for (std::size_t k = 0; k < bin.size(); ++k) {
        // The tile's splats lie scattered through the array: fetched a few ahead.
        if (k + kPrefetch < bin.size()) __builtin_prefetch(&splats[bin[k + kPrefetch]]);
        const std::uint32_t i = bin[k];
        const Splat& s = splats[i];
        if (r.sheets) {
            if (open && s.sheet != current) flush();
            current = s.sheet, open = true;
        }
        const int ya = std::max(s.y0, y0), yb = std::min(s.y1, y1);
        const int xa = std::max(s.x0, x0), xb = std::min(s.x1, x1);
        const TileTarget target{xa, xb, ya, yb, x0, y0, &buffers, w, opaque};
        if (orthographic) {
            if (!(s.depth > 0)) continue;
            count += r.raster_ortho(s, target, r.stamps, r.per_unit, fp);
            continue;
        }
        const double kernel_h = s.h, reach_sq = r.support_sq * kernel_h * kernel_h;
        const Vec3 v = in.points[s.point] - camera.eye();
        if (!opaque) {
            // Row by row, vectorised (project/splat/splat_rows.h).
            float tau[kTile];
            for (int y = ya; y <= yb; ++y) {
                const int k = (y - y0) * kTile + (xa - x0), n = xb - xa + 1;
                splat_rows::perspective_depths(tau, dir_x + k, dir_y + k, dir_z + k, n, v,
                                               1.0 / (kernel_h * kernel_h), s.kappa_h, r.table);
                if (r.sheets) {
                    composite_row<true>(buffers, tile_index(xa - x0, y - y0), tau, n, s.color);
                } else {
                    composite_row<false>(buffers, tile_index(xa - x0, y - y0), tau, n, s.color);
                }
                count += static_cast<std::size_t>(n);
            }
            continue;
        }
        for (int y = ya; y <= yb; ++y) {
            for (int x = xa; x <= xb; ++x) {
                const int local = tile_index(x - x0, y - y0);
                const int k = (y - y0) * kTile + (x - x0);
                const Vec3 d(dir_x[k], dir_y[k], dir_z[k]);
                const double t = glm::dot(v, d);  // the centre's ray parameter
                const double rho_sq = glm::dot(v, v) - t * t;
                if (!(rho_sq < reach_sq) || !(t > 0)) continue;
                if (!(t < opaque[static_cast<std::size_t>(y) * w + x])) continue;
                const double rho = std::sqrt(std::max(rho_sq, 0.0)) / kernel_h;
                const auto tau = s.kappa_h * static_cast<float>(fp(rho));
                ++count;
                if (r.sheets) {
                    composite_row<true>(buffers, local, &tau, 1, s.color);
                } else {
                    composite_row<false>(buffers, local, &tau, 1, s.color);
                }
            }
        }
    }
    if (open) flush();
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
            const int local = tile_index(x - x0, y - y0);
            pixel(x, y) = Vec3f(buffers.r[local], buffers.g[local], buffers.b[local]);
        }
    }
    return count;
}

}  // namespace

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
    // Each point's splat; the drawing order; the tiles' bins.
    SplatSet set = make_splats(in, support, per_unit);
    const bool sheets = in.compositing == SplatCompositing::kSheetBuffer;
    const DrawOrder order = draw_order(in, set, sheets);
    TileBins bins = bin_into_tiles(set, order.sequence, w, h, in.points.size());

    // The tiles, each over its pixels of the background or the opaque surfaces.
    Image image(w, h, Vec3f(in.background));
    if (in.opaque_color) image = *in.opaque_color;
    const SplatFootprint& fp = *in.footprint;
    TileRasterInputs raster;
    raster.in = &in;
    raster.splats = set.splats.get();
    raster.bins = &bins;
    raster.image = &image;
    raster.sheets = sheets;
    raster.per_unit = per_unit;
    raster.support_sq = support * support;
    // Orthographic splats of one scale (a lattice's) are drawn from stamps.
    std::optional<SplatStamps> stamps;
    if (orthographic && in.radius.empty() && SplatStamps::fits(fp, per_unit * in.spacing)) {
        stamps.emplace(fp, per_unit * in.spacing);
        raster.stamps = &*stamps;
    }
    const bool opaque = in.opaque_depth != nullptr;
    raster.raster_ortho = sheets
                              ? (opaque ? raster_splat<true, true> : raster_splat<true, false>)
                              : (opaque ? raster_splat<false, true> : raster_splat<false, false>);
    raster.table = {fp.squared_table(), fp.squared_scale(), fp.squared_last(),
                    static_cast<float>(raster.support_sq)};
    std::atomic<std::size_t> fragments{0};
    parallel_for(0, bins.tiles, 1,
                 [&](std::size_t tile) { fragments += raster_tile(raster, tile); });
    if (stats) {
        stats->splats_drawn = set.drawn.size();
        stats->fragments = fragments.load();
        stats->sheet_axis = order.axis;
        stats->sheets = order.sheet_count;
        stats->raster_ms = ms_since(start);
    }
    return image;
}

}  // namespace tr
