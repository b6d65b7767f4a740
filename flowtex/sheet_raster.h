#pragma once
// A CPU rasteriser for advected sheets: textured triangles through the core camera with
// perspective-correct texture coordinates and mip-mapped lookups, the layers blended.

#include <core/camera.h>
#include <core/image.h>
#include <flowtex/advection.h>
#include <flowtex/periodic_texture.h>

#include <optional>
#include <span>

namespace tr {

struct SheetRasterOptions {
    Vec3f dark{0.04f, 0.07f, 0.20f};  // the colour of texture value 0
    Vec3f light{1.0f, 0.92f, 0.70f};  // the colour of texture value 1
    Vec3f background{0.0f};           // where no triangle is drawn
};

// Draws `layers` into `image` (resized to the frame's size; every pixel written). Each layer is
// rasterised on its own (pixel centres inside or on a triangle's edges; where a layer's
// triangles overlap, the later one wins); a pixel's texture value over the layers covering it
// is 0.5 + sum w_k (v_k - 0.5) / sqrt(sum w_k^2), which keeps the noise's contrast through a
// cross-fade (when all covering weights are 0: their plain mean). Texture lookups use the
// triangle's screen-space derivatives of the texture coordinates (constant per triangle) for
// the mip level. Points behind a perspective eye drop their triangles. Bit-identical for any
// thread count (bands of rows, triangles in order within a band). Layers on a grid sheet
// (TexturedMeshView::grid) find each pixel's triangle on the grid instead: the same texture
// coordinates, the mip level from each pixel's own footprint (the same as the triangle's for an
// orthographic camera).
// Cost: O(points + triangles + covered pixels x layers x 8 texel reads); on a grid sheet
// O(pixels x layers x 8 texel reads) whatever the number of triangles.
void rasterize_sheet(const CameraFrame& frame, std::span<const TexturedMeshView> layers,
                     const PeriodicTexture& texture, const SheetRasterOptions& options,
                     Image& image);

// The grey value (0..1, before colouring) each pixel got, NaN where nothing was drawn:
// rasterize_sheet's blend without the colours (tests, phase correlation).
std::vector<float> rasterize_sheet_values(const CameraFrame& frame,
                                          std::span<const TexturedMeshView> layers,
                                          const PeriodicTexture& texture);

// An orthographic camera looking at the sheet's kept points along -normal, framing them with a
// 2% margin at the aspect width / height; view up axis_v, or `view_up` made tangent to the
// sheet (precondition: not along its normal).
Camera sheet_camera(const Sheet& sheet, int width, int height,
                    const std::optional<Vec3>& view_up = std::nullopt);

// The same over `points` for the plane through `origin` with unit `normal`, the picture's
// right and up the orthonormal in-plane `right` and `up` (right x up = normal).
Camera plane_camera(std::span<const Vec3> points, const Vec3& origin, const Vec3& right,
                    const Vec3& up, const Vec3& normal, int width, int height);

// An upright view of a plane with unit `normal`: +y up for a plane facing mostly along z (a 2D
// mesh in z = c shows x to the right, y up), +z otherwise; returned tangent to the plane.
Vec3 upright_view_up(const Vec3& normal);

}  // namespace tr
