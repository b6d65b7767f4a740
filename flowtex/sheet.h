#pragma once
// A planar polygon sheet to advect a texture on: a regular grid of points in a plane, each
// square cut into two triangles, clipped to where the flow is defined (a slice through a mesh),
// or any planar triangle mesh (a 2D mesh read from a file, quads split in two).
//
// Conventions: axis_u, axis_v are orthonormal and normal = axis_u x axis_v. A grid sheet's point
// (i, j) lies at origin + i * spacing * axis_u + j * spacing * axis_v (i < nu + 1, j < nv + 1),
// square (i, j) split along its diagonal (i, j)-(i + 1, j + 1). A triangle-mesh sheet has no
// grid points; its nu x nv squares of side `spacing` from `origin` bucket its triangles for
// point location instead.

#include <core/math.h>
#include <core/result.h>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace tr {

class PointLocator;

struct Sheet {
    Vec3 origin{0.0};
    Vec3 axis_u{1, 0, 0};
    Vec3 axis_v{0, 1, 0};
    Vec3 normal{0, 0, 1};
    double spacing = 1.0;
    int nu = 0, nv = 0;  // squares along each axis

    std::vector<Vec3> points;                             // the kept grid points
    std::vector<std::array<std::uint32_t, 3>> triangles;  // into points, counter-clockwise
    // Grid sheets: (nu + 1) * (nv + 1) entries, index into points or -1. Empty for a
    // triangle-mesh sheet.
    std::vector<std::int32_t> grid_point;
    // Triangle-mesh sheets: the triangles overlapping each of the nu * nv squares (CSR).
    std::vector<std::uint32_t> bucket_start;
    std::vector<std::uint32_t> bucket_triangles;

    // Plane coordinates (s, t) of p: (p - origin) . axis_u, (p - origin) . axis_v.
    glm::dvec2 plane_coordinates(const Vec3& p) const {
        return {glm::dot(p - origin, axis_u), glm::dot(p - origin, axis_v)};
    }
};

// Where a point falls on a sheet: a triangle's three points and their barycentric weights.
struct SheetLocation {
    std::array<std::uint32_t, 3> points{};
    std::array<double, 3> weights{};
};

// The whole rectangle origin + [0, nu * spacing] x [0, nv * spacing] in the plane of the two
// (orthonormalised) axes. Errors: nu or nv < 1, spacing not positive, parallel axes.
Result<Sheet> grid_sheet(const Vec3& origin, const Vec3& axis_u, const Vec3& axis_v, int nu, int nv,
                         double spacing);

// The plane through `point` with `normal` cut by the mesh behind `locator`: a grid of square
// cells (`resolution` along the longer side of the mesh bounds' footprint in the plane) whose
// points inside the mesh are kept, and the triangles whose three points are kept. The in-plane
// axes: axis_u is normal x (the coordinate axis least aligned with the normal), normalised.
// Errors: a zero or non-finite normal, resolution < 1 or > 8192, and a plane that misses the
// mesh (no triangle kept: "the slice ... misses the mesh", with the bounds).
// Cost: one point location per grid point.
Result<Sheet> slice_sheet(const PointLocator& locator, const Bounds3& mesh_bounds,
                          const Vec3& point, const Vec3& normal, int resolution);

// A sheet from a planar triangle mesh (a 2D mesh from a file: read_surface fan-splits quads).
// The plane: through the first point, normal the area-weighted sum of the triangles' normals;
// axes as slice_sheet's. Errors: no triangles, non-finite points, points farther than 1e-6 of
// the bounds' diagonal from the plane ("not planar", with the distance), degenerate (zero
// area). Cost: O(points + triangles).
Result<Sheet> sheet_from_triangles(const std::vector<Vec3>& points,
                                   const std::vector<std::array<std::uint32_t, 3>>& triangles);

// The triangle of `sheet` holding the point with plane coordinates st, or nothing when it is
// outside the sheet's kept triangles. Points within 1e-9 of a grid square (1e-9 in barycentric
// terms for a triangle-mesh sheet) of the sheet's edge count as on it. Cost: O(1) for a grid,
// the triangles of one bucket otherwise.
std::optional<SheetLocation> locate_on_sheet(const Sheet& sheet, const glm::dvec2& st);

}  // namespace tr
