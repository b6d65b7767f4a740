#pragma once
// Opaque geometry drawn before the volume (Figures 1 and 2 of the texture-mapping paper):
// triangle surfaces with a z-buffer and simple headlight shading. The depth kept per pixel is
// the ray parameter of the nearest surface along that pixel's ray (the same rays the volume
// renderer casts), so each volume segment is cut exactly where the surface is.

#include <core/camera.h>
#include <core/image.h>
#include <mesh/surface_mesh.h>
#include <project/view.h>

#include <limits>
#include <vector>

namespace tr {

struct OpaqueSurface {
    const SurfaceMesh* surface = nullptr;
    Vec3 color{0.8, 0.8, 0.8};
};

struct OpaqueLayer {
    Image color;                // shaded surfaces over the background
    std::vector<double> depth;  // per pixel, ray parameter of the nearest surface, or +inf
    std::size_t pixels_covered = 0;
};

// Draws the surfaces (two-sided Lambert with a light at the eye: 0.2 + 0.8 |cos|) over
// `background`. Deterministic whatever the thread count: the nearest hit wins, ties to the
// earlier surface and triangle. Cost: O(triangles + covered pixels x triangles per tile).
OpaqueLayer render_opaque(const std::vector<OpaqueSurface>& surfaces, const CameraFrame& camera,
                          const Vec3& background);

// The view `camera` over `layer` (its colour and depth; nothing when it has no depth: no surfaces
// were drawn) or `background` (project/view.h). Points into `camera` and `layer`.
View view_over(const CameraFrame& camera, const Vec3& background, const OpaqueLayer& layer);

// A closed polygonal cylinder (sides and caps) around the z axis: the demo's body.
SurfaceMesh make_cylinder_surface(double radius, double z0, double z1, int sides);

}  // namespace tr
