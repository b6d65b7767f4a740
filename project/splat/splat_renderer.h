#pragma once
// Splatting (texture-mapping paper, 3.1): a field given at points — the lattice points of a
// regular grid, or the points of any mesh — rendered without cells. Each point's value is
// classified by the transfer function (extinction kappa and colour c), and spread by the
// reconstruction kernel of project/splat/splat_kernel.h scaled to the point spacing h: along a
// pixel ray passing at distance rho from the point, the point adds the optical depth
//     tau = kappa h f(rho / h)
// (f the kernel's footprint, its line integral in lattice units), so a constant field's optical
// depth along any ray is kappa times the length times the kernel's lattice sum (within 0.53% of 1
// for the Crawfis-Max cubic). The splat faces each pixel's ray (rho is the distance from the point
// to that ray: right under perspective, as the paper's "square facing the ray to its centre"),
// and is composited whole, alpha = 1 - exp(-tau), colour c alpha, back to front by the distance
// of the points along the view (the paper's order; the per-splat compositing the paper notes
// makes colours jump when that order changes during a rotation).
//
// Compositing (SplatCompositing):
// - kPerSplat (the default, the paper's): each splat composited whole, back to front.
// - kSheetBuffer (Westover's sheet buffer, which the paper describes but did not build): of the
//   three lattice axes the one most parallel to the view direction (orthographic: the camera's
//   forward; perspective: from the eye to the points' centre) is chosen; the points are binned
//   into sheets of thickness `spacing` across it (the lattice planes most perpendicular to the
//   view, exactly, for an axis-aligned lattice); within a sheet the splats' optical depths and
//   depth-weighted colours are summed per pixel (no mutual occlusion: their order does not
//   matter), and the sheets are composited back to front, alpha = 1 - exp(-sum tau), colour
//   sum(c tau) / sum(tau) alpha. So the picture changes smoothly with the view except where the
//   chosen axis changes (at 45 degrees to two axes), where it jumps; measured in
//   tests/splat/splat_popping_test.cpp and docs/benchmarks.md.
//
// Opaque geometry: a splat is drawn on a pixel only where its centre lies in front of the
// pixel's surface. Splats whose support reaches behind a perspective eye are not drawn.
//
// The raster: the picture in tiles of 32^2 pixels, drawn concurrently, each tile's splats in the
// order above. Orthographic splats of one scale (a lattice's: no per-point radius) are drawn from
// footprint stamps (project/splat/splat_stamps.h: within 2.3e-4 of the footprint's peak) by the
// vectorised row loops of project/splat/splat_rows.h; other orthographic splats read the
// footprint's table per pixel by rho^2, perspective ones too, rho the distance from each pixel's
// ray (row by row, project/splat/splat_rows.h's perspective_depths; with opaque geometry pixel by
// pixel).

#include <core/camera.h>
#include <core/image.h>
#include <project/splat/splat_kernel.h>
#include <project/transfer_function.h>
#include <project/view.h>

#include <cstddef>
#include <span>
#include <vector>

namespace tr {

enum class SplatCompositing { kPerSplat, kSheetBuffer };

// The view (camera, background, opaque layer: project/view.h) and the points splatted in it.
struct SplatInputs : View {
    std::span<const Vec3> points;
    std::span<const float> scalar;  // one per point
    double spacing = 1.0;           // h: the lattice spacing the kernel is scaled to (> 0)
    // Per-point h instead of `spacing` (SPH smoothing lengths: each > 0 and finite, checked by
    // the caller), or empty. The sheet buffer's sheets stay `spacing` thick.
    std::span<const float> radius;
    const TransferFunction* tf = nullptr;
    const SplatFootprint* footprint = nullptr;  // the kernel's table
    SplatCompositing compositing = SplatCompositing::kPerSplat;
};

struct SplatStats {
    std::size_t splats_drawn = 0;  // points with a non-zero extinction in view
    std::size_t fragments = 0;     // (splat, pixel) pairs rasterised (some hidden or 0 at the rim)
    std::size_t sheets = 0;        // sheet buffer: the sheets holding a splat in view (else 0)
    int sheet_axis = -1;           // sheet buffer: the axis across the sheets (0, 1, 2; else -1)
    double raster_ms = 0;
};

// The picture. Preconditions: scalar.size() == points.size(), spacing > 0, radius empty or one per
// point, opaque buffers of
// the camera's size (checked: a wrong call would read out of bounds). Cost: O(points log points)
// for the order plus the splats' footprints in pixels; memory O(points + pixels).
Image render_splats(const SplatInputs& in, SplatStats* stats = nullptr);

// The lattice spacing of `points`: for an axis-aligned lattice (as many points as the product of
// the distinct coordinates per axis) the geometric mean of its spacings per axis, exact when they
// are equal; otherwise that of a lattice of as many points filling their bounds. Over the axes
// of non-zero extent; 0 when fewer than 2 points or all coincide. Cost: O(n log n).
double lattice_spacing(std::span<const Vec3> points);

// Whether `points` are a full axis-aligned lattice (as many points as the product of the
// distinct coordinates per axis, at least 2 along one axis). Cost: O(n log n).
bool is_axis_aligned_lattice(std::span<const Vec3> points);

}  // namespace tr
