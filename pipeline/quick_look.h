#pragma once
// The choices a quick look makes from the data, so that a first picture of any mesh shows it:
// a robust scalar range, a unit distance that lets a typical ray through the object reach a
// stated opacity, and a camera that fits the object's projected extent. Used by
// make_quick_scene (pipeline/quick_scene.h) and the viewer; each is a pure function of the mesh.

#include <core/camera.h>
#include <core/result.h>
#include <mesh/tet_mesh.h>

#include <array>
#include <cmath>
#include <span>

namespace tr {

// The [p, 100 - p] percentiles of the finite values (p in [0, 50); p = 0: min and max), by
// selection (O(n)). Error kInvalidArgument when no value is finite. A range whose ends are
// equal is returned as is (the caller decides what a constant field shows).
Result<std::array<double, 2>> robust_range(std::span<const float> values, double percent);

// Cauchy's mean chord length 4 V / S of the real tets (V their volume, S the area of their
// boundary surface): the mean length inside the object of a straight line through it, over
// uniformly random lines. 0 for a mesh with no volume. Cost: one face adjacency, O(tets).
double mean_chord_length(const TetMesh& mesh);

// The unit distance that gives a ray of length `chord`, along which the scalar is distributed as
// `values`, the opacity `target` (in (0, 1)) under opacities a(s): the mean over the finite
// values of -ln(1 - a(s)), times chord / -ln(1 - target). 0 when every value has zero opacity.
template <class Opacity>
double unit_distance_for_opacity(std::span<const float> values, const Opacity& opacity,
                                 double chord, double target);

// A perspective camera looking from direction `from` (rotated by `azimuth` degrees about the
// up axis and then `elevation` degrees towards it, as ParaView's Azimuth and Elevation do) at
// the centre of the points' projected extent, as close as lets every point lie inside a
// width x height picture with `margin` (a fraction of each side) left free; view_up +z unless
// the view is nearly along z (+y), as is (not made square to the view: an orbit about it does
// not roll); `zoom` > 1 narrows the view angle by that factor (VTK's
// Zoom). Points: every point of the meshes, strided beyond a million a mesh.
struct CameraFit {
    Vec3 from{1.0, -1.2, 0.8};
    int width = 800, height = 600;
    double view_angle = 30.0;
    double azimuth = 0.0, elevation = 0.0, zoom = 1.0;
    double margin = 0.04;
};
Camera fitting_camera(std::span<const TetMesh* const> meshes, const CameraFit& fit);

// ---------------------------------------------------------------------------------------------

template <class Opacity>
double unit_distance_for_opacity(std::span<const float> values, const Opacity& opacity,
                                 double chord, double target) {
    double sum = 0.0;
    std::size_t n = 0;
    for (float v : values) {
        if (!std::isfinite(v)) continue;
        sum += -std::log1p(-opacity(static_cast<double>(v)));
        ++n;
    }
    if (n == 0 || !(sum > 0.0) || !(chord > 0.0)) return 0.0;
    return chord * (sum / static_cast<double>(n)) / -std::log1p(-target);
}

}  // namespace tr
