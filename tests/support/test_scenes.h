#pragma once
// Scenes the rendering tests share (particles, splats, fused volumes, the pipeline): a box of
// tets with a constant scalar (the uniform slab whose picture is known in closed form), cameras
// looking at it, and the expected picture supersampled over each pixel.

#include <core/camera.h>
#include <core/image.h>
#include <mesh/tet_mesh.h>
#include <project/transfer_function.h>

#include <vector>

namespace tr::testing {

// The cube [0, side]^3 split into 6 n^3 tets, and a scalar of 1 everywhere.
TetMesh uniform_box(int n, double side);

// A camera at `eye` looking at `focal` (view_up +z, or +y when looking along z).
Camera camera_at(const Vec3& eye, const Vec3& focal, bool parallel, double scale_or_angle);

// The picture of a box [0, side]^3 of constant extinction kappa and colour `color` over
// `background`: per pixel the mean over rays_per_side^2 rays spread over the pixel of
// color a + background (1 - a), a = 1 - exp(-kappa chord): the expected value of a stochastic
// picture whose samples cover the pixel (8), or of one that samples the pixel centre's ray (1).
Image uniform_box_picture(const CameraFrame& frame, double side, double kappa, const Vec3& color,
                          const Vec3& background, int rays_per_side = 8);

// The chance that one sample of the pixel sees a particle, for the same box: the mean of a over
// the rays (for the per-pixel standard error).
std::vector<double> uniform_box_coverage(const CameraFrame& frame, double side, double kappa,
                                         int rays_per_side = 8);

}  // namespace tr::testing
