#pragma once
// The built-in demo mesh: flow past a cylinder standing in a box, meshed by TetGen (AGPL-3:
// target tetrender::tetgen).

#include <core/math.h>
#include <core/result.h>
#include <mesh/tet_mesh.h>

#include <cstddef>

namespace tr {

struct CylinderDemoOptions {
    // Tets wanted; the result has this many within about +-30% (at least 1,000).
    std::size_t target_tets = 200000;
    // Radius of the cylinder (a prism) standing along z through the origin in the box
    // [-2.5, 5] x [-2, 2] x [-1, 1]; in (0, 1.5].
    double cylinder_radius = 0.5;
    // Sides of the prism, 8 to 256; 0: 64, fewer below 20,000 target tets (the sides' width
    // sets the mesh size at the cylinder, so 64 sides need about 10,000 tets): see
    // cylinder_demo_sides().
    int cylinder_sides = 0;
};

// The number of sides make_cylinder_demo uses for `options` (resolves cylinder_sides == 0:
// 64 at 20,000 target tets and more, 64 sqrt(target / 20,000) rounded to a multiple of 4 below,
// at least 12).
int cylinder_demo_sides(const CylinderDemoOptions& options);

// A box with a vertical polygonal cylinder cut out through its whole height: a non-convex
// domain whose boundary is one connected surface with a through hole. TetGen meshes it as a
// PLC (the top and bottom faces are rectangles with a polygonal hole, the polygon's vertices at
// angles 2 pi k / sides on the circle) with quality meshing (radius-edge ratio 2) and a volume
// bound chosen for target_tets (TetGen runs once more, with a corrected bound, when the count
// is more than 15% off). Deterministic: the same options give the same mesh, bit for bit.
//
// Point fields (float32), from the analytic flow below: "velocity" (3 components),
// "vorticity" (|curl velocity|), "pressure" (Bernoulli, 0.5 (U^2 - |u|^2), U = 1).
// Errors: options out of range (kInvalidArgument); TetGen failing (kInternal).
// Cost: about 1 s per 200k tets, single-threaded.
Result<TetMesh> make_cylinder_demo(const CylinderDemoOptions& options = {});

// The demo's velocity at p: 2-D potential flow past a cylinder of radius `cylinder_radius` on
// the z axis (uniform stream U = 1 along +x: u_r = U (1 - R^2/r^2) cos t, u_t = -U (1 + R^2/r^2)
// sin t) plus a swirl, a Lamb-Oseen vortex about the x axis centred at y = z = 0 with core
// radius 0.6 and circulation 2: u_phi(rho) = 2 / (2 pi rho) (1 - exp(-rho^2 / 0.36)).
// Defined for p off the z axis (r > 0).
Vec3 cylinder_demo_velocity(const Vec3& p, double cylinder_radius = 0.5);

// |curl velocity| at p: the potential flow is irrotational, so this is the vortex's axial
// vorticity 2 / (pi 0.36) exp(-rho^2 / 0.36), rho = sqrt(y^2 + z^2).
double cylinder_demo_vorticity(const Vec3& p);

}  // namespace tr
