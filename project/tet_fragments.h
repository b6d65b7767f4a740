#pragma once
// The exact segments of pixel rays through tets — fragments — tile by tile: what projected
// tetrahedra composite, what image-space particle rendering draws particles from and what fused
// rendering merges. One copy of the screen-tile binning and of the ray-tet clipping for all of
// them.
//
// A fragment of cell t at pixel (x, y) is the part of the pixel's ray (through the pixel centre,
// core/camera.h) inside t, clipped at the eye (t >= 0) and at the pixel's opaque depth: the ray
// parameters t_in < t_out and the scalar there (linear in the tet). A ray in the plane of a
// face shared by two cells belongs to exactly one of them (the one whose outward normal is
// "positive"), so shared faces are neither skipped nor counted twice.

#include <core/camera.h>
#include <core/screen_box.h>
#include <mesh/tet_mesh.h>
#include <project/tet_projection.h>

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace tr {

inline constexpr int kFragmentTile = 32;  // tiles are kFragmentTile x kFragmentTile pixels
static_assert(kFragmentTile <= 256, "TileFragments keeps a pixel's place in the tile in a byte");

// Cells binned into screen tiles: each tile's list holds indices into the `cells` given, in
// their order (so compositing in a visibility order stays in order within a tile).
struct TileBins {
    int tiles_x = 0, tiles_y = 0;
    std::vector<ScreenBox> boxes;                  // per entry of `cells`: its pixels (below)
    std::vector<std::uint8_t> behind_eye;          // per entry: reaches behind a perspective eye
    std::vector<std::vector<std::uint32_t>> bins;  // per tile, row-major
    std::size_t cells_drawn = 0;                   // entries whose box is not empty

    std::size_t num_tiles() const { return bins.size(); }
};

// Bins `cells` of `mesh` for `camera`: screen boxes in parallel, tiles filled in order. A cell
// reaching behind a perspective eye gets the whole picture as its box; one wholly behind, none.
// Cost: O(cells + tiles covered).
TileBins bin_cells(const TetMesh& mesh, std::span<const CellId> cells, const CameraFrame& camera);

// The pixel rays of one tile (computed once per tile) and its pixel range. Under perspective
// also the rays' directions before normalization, affine in the pixel (direction_origin, the
// tile's first pixel, plus column and row steps), and their lengths: what for_each_fragment
// steps along a row.
struct TileRays {
    static constexpr int kPadding = 4;     // a row's last block of 4 pixels may read past its end
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // inclusive
    Ray rays[kFragmentTile * kFragmentTile];
    Vec3 direction_origin{0.0}, direction_per_column{0.0}, direction_per_row{0.0};
    double direction_length[kFragmentTile * kFragmentTile + kPadding];

    const Ray& at(int x, int y) const { return rays[(y - y0) * kFragmentTile + (x - x0)]; }
};

// Fills `rays` for tile `tile` of `bins` (row-major tile index).
void tile_rays(const TileBins& bins, std::size_t tile, const CameraFrame& camera, TileRays& rays);

// One cell set up for its fragments: face planes and the scalar's gradient, and under
// perspective the per-cell numerators (every ray starts at the eye).
class CellFragments {
  public:
    CellFragments(const TetMesh& mesh, std::span<const float> scalar, CellId t,
                  const CameraFrame& camera);

    const TetPlanes& planes() const { return planes_; }
    bool orthographic() const { return orthographic_; }

    // Perspective: the cell's planes and scalar over one tile's pixels, each affine in the
    // pixel (i, j) of the tile: a + b i + c j. The ray through the pixel, eye + u D with D its
    // direction before normalization (TileRays), meets plane k at u = numerator[k] /
    // denominator_k(i, j); the scalar along it is s_eye + u slope(i, j).
    struct TileSetup {
        double numerator[4];
        double den_a[4], den_b[4], den_c[4];
        bool parallel_misses[4];  // a ray parallel to plane k (denominator 0) misses the cell
        double s_eye, slope_a, slope_b, slope_c;
    };
    TileSetup tile_setup(const TileRays& rays) const;

    // The fragment of `ray` (a pixel ray of the camera) through the cell clipped to
    // [0, max_t]: false when there is none of positive length. Cost: O(1).
    bool segment(const Ray& ray, double max_t, double& t_in, double& t_out, double& s_in,
                 double& s_out) const {
        double lo = 0.0;  // clipped at the eye (near plane)
        double hi = std::numeric_limits<double>::infinity();
        for (int k = 0; k < 4; ++k) {
            const double denom = glm::dot(planes_.normals[k], ray.direction);
            const double num = orthographic_
                                   ? planes_.offsets[k] - glm::dot(planes_.normals[k], ray.origin)
                                   : eye_num_[k];
            if (denom < 0) {
                lo = std::max(lo, num / denom);
            } else if (denom > 0) {
                hi = std::min(hi, num / denom);
            } else if (num < 0 || (num == 0 && !owns_plane(planes_.normals[k]))) {
                return false;
            }
        }
        hi = std::min(hi, max_t);
        if (!(hi > lo)) return false;
        const double s_origin =
            orthographic_ ? planes_.s0 + glm::dot(planes_.gradient, ray.origin - planes_.p0)
                          : s_eye_;
        const double slope = glm::dot(planes_.gradient, ray.direction);
        t_in = lo;
        t_out = hi;
        s_in = s_origin + lo * slope;
        s_out = s_origin + hi * slope;
        return true;
    }

    // Of two tets sharing a face whose plane holds a pixel's ray, the one with the "positive"
    // outward normal takes it.
    static bool owns_plane(const Vec3& n) {
        if (n.x != 0) return n.x > 0;
        if (n.y != 0) return n.y > 0;
        return n.z > 0;
    }

  private:
    TetPlanes planes_;
    bool orthographic_;
    double eye_num_[4] = {0, 0, 0, 0};
    double s_eye_ = 0;
};

// The fragments of one cell in one tile, in the order for_each_fragment gives them; x, y are
// within the tile (the picture's pixel is the tile's x0 + x, y0 + y).
struct TileFragments {
    int count = 0;
    std::uint8_t x[kFragmentTile * kFragmentTile], y[kFragmentTile * kFragmentTile];
    double t_in[kFragmentTile * kFragmentTile], t_out[kFragmentTile * kFragmentTile];
    double s_in[kFragmentTile * kFragmentTile], s_out[kFragmentTile * kFragmentTile];
};

// Perspective only: fills `out` with the fragments for_each_fragment would give (the pixels of
// the box x0..x1, y0..y1 within the tile). Four pixels of a row at once, the denominators
// stepped along the row (affine in the pixel), in AVX2 where the processor has it (the same
// bits either way: no fused multiply-add).
void find_perspective_fragments(const CellFragments& cell, int x0, int y0, int x1, int y1,
                                const TileRays& rays, int width, std::span<const double> max_depth,
                                TileFragments& out);

// Calls fn(x, y, t_in, t_out, s_in, s_out) for every pixel of `box` inside the tile whose ray
// has a fragment through the cell, clipped at `max_depth` (per pixel of the camera's picture,
// or empty for no limit), row by row, left to right.
template <class Fn>
void for_each_fragment(const CellFragments& cell, const ScreenBox& box, const TileRays& rays,
                       int width, std::span<const double> max_depth, Fn&& fn) {
    const int x0 = std::max(box.x0, rays.x0), x1 = std::min(box.x1, rays.x1);
    const int y0 = std::max(box.y0, rays.y0), y1 = std::min(box.y1, rays.y1);
    if (!cell.orthographic()) {
        TileFragments found;
        find_perspective_fragments(cell, x0, y0, x1, y1, rays, width, max_depth, found);
        for (int f = 0; f < found.count; ++f) {
            fn(rays.x0 + found.x[f], rays.y0 + found.y[f], found.t_in[f], found.t_out[f],
               found.s_in[f], found.s_out[f]);
        }
        return;
    }
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
            const double limit =
                max_depth.empty()
                    ? std::numeric_limits<double>::infinity()
                    : max_depth[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + x];
            double t_in, t_out, s_in, s_out;
            if (cell.segment(rays.at(x, y), limit, t_in, t_out, s_in, s_out)) {
                fn(x, y, t_in, t_out, s_in, s_out);
            }
        }
    }
}

}  // namespace tr
