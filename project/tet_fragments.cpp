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

}  // namespace tr
