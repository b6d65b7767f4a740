#include <core/parallel.h>
#include <project/tet_fragments.h>

#include <algorithm>
#include <cmath>

namespace tr {
namespace {

// Pixels whose centres may lie in the tet's projection; the whole image when the tet reaches
// behind a perspective eye; empty when it is wholly behind.
ScreenBox screen_box(const TetMesh& mesh, CellId t, const CameraFrame& camera, bool& behind) {
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    bool front = false;
    behind = false;
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
    // The pixels whose centres may lie in the projection (padded a little: the exact ray test
    // decides, the box only has to be conservative).
    constexpr double kPad = 1e-6;
    return pixels_centred_in(x0, y0, x1, y1, kPad)
        .clipped_to({0, 0, camera.width() - 1, camera.height() - 1});
}

using Double4 = double __attribute__((vector_size(32)));
using Mask4 = long long __attribute__((vector_size(32)));

}  // namespace

TileBins bin_cells(const TetMesh& mesh, std::span<const CellId> cells, const CameraFrame& camera) {
    TileBins bins;
    const int w = camera.width(), h = camera.height();
    bins.tiles_x = (w + kFragmentTile - 1) / kFragmentTile;
    bins.tiles_y = (h + kFragmentTile - 1) / kFragmentTile;
    bins.boxes.resize(cells.size());
    bins.behind_eye.assign(cells.size(), 0);
    parallel_for(0, cells.size(), 4096, [&](std::size_t i) {
        bool behind = false;
        bins.boxes[i] = screen_box(mesh, cells[i], camera, behind);
        bins.behind_eye[i] = behind;
    });
    bins.bins.resize(static_cast<std::size_t>(bins.tiles_x) * bins.tiles_y);
    for (std::uint32_t i = 0; i < cells.size(); ++i) {
        const ScreenBox& b = bins.boxes[i];
        if (b.empty()) continue;
        ++bins.cells_drawn;
        for (int ty = b.y0 / kFragmentTile; ty <= b.y1 / kFragmentTile; ++ty) {
            for (int tx = b.x0 / kFragmentTile; tx <= b.x1 / kFragmentTile; ++tx) {
                bins.bins[static_cast<std::size_t>(ty) * bins.tiles_x + tx].push_back(i);
            }
        }
    }
    return bins;
}

void tile_rays(const TileBins& bins, std::size_t tile, const CameraFrame& camera, TileRays& rays) {
    const int tx = static_cast<int>(tile % static_cast<std::size_t>(bins.tiles_x));
    const int ty = static_cast<int>(tile / static_cast<std::size_t>(bins.tiles_x));
    rays.x0 = tx * kFragmentTile;
    rays.y0 = ty * kFragmentTile;
    rays.x1 = std::min(rays.x0 + kFragmentTile, camera.width()) - 1;
    rays.y1 = std::min(rays.y0 + kFragmentTile, camera.height()) - 1;
    for (int y = rays.y0; y <= rays.y1; ++y) {
        for (int x = rays.x0; x <= rays.x1; ++x) {
            rays.rays[(y - rays.y0) * kFragmentTile + (x - rays.x0)] = camera.pixel_ray(x, y);
        }
    }
    if (camera.orthographic()) return;
    const CameraFrame::PixelDirections d = camera.pixel_directions();
    rays.direction_origin =
        d.at_origin + double(rays.x0) * d.per_column + double(rays.y0) * d.per_row;
    rays.direction_per_column = d.per_column;
    rays.direction_per_row = d.per_row;
    std::fill(std::begin(rays.direction_length), std::end(rays.direction_length), 1.0);
    for (int j = 0; j <= rays.y1 - rays.y0; ++j) {
        for (int i = 0; i <= rays.x1 - rays.x0; ++i) {
            rays.direction_length[j * kFragmentTile + i] = glm::length(
                rays.direction_origin + double(i) * d.per_column + double(j) * d.per_row);
        }
    }
}

CellFragments::CellFragments(const TetMesh& mesh, std::span<const float> scalar, CellId t,
                             const CameraFrame& camera)
    : planes_(tet_planes(mesh, scalar, t)), orthographic_(camera.orthographic()) {
    if (!orthographic_) {
        for (int k = 0; k < 4; ++k) {
            eye_num_[k] = planes_.offsets[k] - glm::dot(planes_.normals[k], camera.eye());
        }
        s_eye_ = planes_.s0 + glm::dot(planes_.gradient, camera.eye() - planes_.p0);
    }
}

CellFragments::TileSetup CellFragments::tile_setup(const TileRays& rays) const {
    TileSetup setup;
    for (int k = 0; k < 4; ++k) {
        const Vec3& n = planes_.normals[k];
        setup.numerator[k] = eye_num_[k];
        setup.den_a[k] = glm::dot(n, rays.direction_origin);
        setup.den_b[k] = glm::dot(n, rays.direction_per_column);
        setup.den_c[k] = glm::dot(n, rays.direction_per_row);
        setup.parallel_misses[k] = eye_num_[k] < 0 || (eye_num_[k] == 0 && !owns_plane(n));
    }
    setup.s_eye = s_eye_;
    setup.slope_a = glm::dot(planes_.gradient, rays.direction_origin);
    setup.slope_b = glm::dot(planes_.gradient, rays.direction_per_column);
    setup.slope_c = glm::dot(planes_.gradient, rays.direction_per_row);
    return setup;
}

__attribute__((target_clones("avx2", "default"))) void find_perspective_fragments(
    const CellFragments& cell, int x0, int y0, int x1, int y1, const TileRays& rays, int width,
    std::span<const double> max_depth, TileFragments& out) {
    const CellFragments::TileSetup setup = cell.tile_setup(rays);
    constexpr double kInf = std::numeric_limits<double>::infinity();
    int count = 0;
    for (int y = y0; y <= y1; ++y) {
        const int j = y - rays.y0;
        double den_row[4];
        for (int k = 0; k < 4; ++k) den_row[k] = setup.den_a[k] + setup.den_c[k] * j;
        const double slope_row = setup.slope_a + setup.slope_c * j;
        const double* lengths = rays.direction_length + j * kFragmentTile;
        const double* limits =
            max_depth.empty() ? nullptr : max_depth.data() + static_cast<std::size_t>(y) * width;
        for (int x = x0; x <= x1; x += 4) {
            const int i = x - rays.x0;
            const double di = i;
            const Double4 column = {di, di + 1, di + 2, di + 3};
            Double4 lo = {0, 0, 0, 0};
            Double4 hi = {kInf, kInf, kInf, kInf};
            Mask4 missed = {0, 0, 0, 0};
            for (int k = 0; k < 4; ++k) {
                const Double4 den = den_row[k] + setup.den_b[k] * column;
                const Double4 u = setup.numerator[k] / den;
                lo = ((den < 0) & (u > lo)) ? u : lo;
                hi = ((den > 0) & (u < hi)) ? u : hi;
                if (setup.parallel_misses[k]) missed |= den == 0;
            }
            Double4 length;
            __builtin_memcpy(&length, lengths + i, sizeof length);
            // World distances along the normalized ray, clipped at the opaque depth.
            const Double4 t_in = lo * length;
            Double4 t_out = hi * length;
            if (limits) {
                Double4 limit = {kInf, kInf, kInf, kInf};
                for (int l = 0; l < 4 && x + l <= x1; ++l) limit[l] = limits[x + l];
                t_out = limit < t_out ? limit : t_out;
            }
            const Mask4 found = (t_out > t_in) & ~missed;
            if (!(found[0] | found[1] | found[2] | found[3])) continue;
            const Double4 slope = (slope_row + setup.slope_b * column) / length;
            const Double4 s_in = setup.s_eye + t_in * slope;
            const Double4 s_out = setup.s_eye + t_out * slope;
            alignas(32) double lanes[4][4];
            __builtin_memcpy(lanes[0], &t_in, sizeof t_in);
            __builtin_memcpy(lanes[1], &t_out, sizeof t_out);
            __builtin_memcpy(lanes[2], &s_in, sizeof s_in);
            __builtin_memcpy(lanes[3], &s_out, sizeof s_out);
            alignas(32) long long hit[4];
            __builtin_memcpy(hit, &found, sizeof found);
            const int last = std::min(3, x1 - x);
            for (int l = 0; l <= last; ++l) {
                out.x[count] = static_cast<std::uint8_t>(i + l);
                out.y[count] = static_cast<std::uint8_t>(j);
                out.t_in[count] = lanes[0][l];
                out.t_out[count] = lanes[1][l];
                out.s_in[count] = lanes[2][l];
                out.s_out[count] = lanes[3][l];
                count += hit[l] != 0;
            }
        }
    }
    out.count = count;
}

}  // namespace tr
