#pragma once
// A steady flow's velocity looked up once at a grid sheet's points and interpolated linearly on
// the sheet's triangles (Max and Becker's textures move with velocities given at the polygons'
// vertices): a lookup is a grid square and three points, not a point location in the flow's
// mesh. Off the sheet's triangles (or where a triangle has a point the flow does not cover),
// the flow itself answers.
//
// Error: where the flow is linear over a sheet triangle (everywhere for uniform flow and rigid
// rotation), none; on a tet mesh, only in the sheet triangles a tet face crosses, of the order
// of the sheet's spacing times the jump of the velocity's gradient there.

#include <flowtex/flow.h>
#include <flowtex/sheet.h>

#include <cstdint>
#include <span>
#include <vector>

namespace tr {

class SheetSampledFlow final : public Flow {
  public:
    // Preconditions: base.steady(); sheet is a grid sheet (grid_point not empty). `sheet` and
    // `base` must outlive it. Cost: one lookup of `base` per sheet point (parallel).
    SheetSampledFlow(const Sheet& sheet, const Flow& base);

    std::optional<Vec3> at(const Vec3& p, double time, CellId& hint) const override;
    bool steady() const override { return true; }

    // One classical RK4 step of the velocity projected into the sheet's plane, in grid
    // coordinates (plane coordinates / spacing) from `grid` over dt: what rk4_step(*this, ...)
    // with the sheet's normal computes for a point of the plane, without leaving the grid.
    // Nothing when a stage is off the sheet's triangles (the caller falls back to rk4_step).
    // Cost: four lookups of three grid points each.
    std::optional<glm::dvec2> grid_step(const glm::dvec2& grid, double dt) const;
    // grid_step for many points: to[k] = the step from from[k], or NaN where grid_step gives
    // nothing. Points are stepped four at a time (their lookups overlap in the processor).
    // Precondition: from.size() == to.size().
    void grid_steps(std::span<const glm::dvec2> from, double dt, std::span<glm::dvec2> to) const;

  private:
    const Sheet* sheet_;
    const Flow* base_;
    double inv_spacing_;
    // The in-plane velocity at grid coordinates, NaN off the sheet's triangles.
    glm::dvec2 grid_velocity(const glm::dvec2& grid) const;

    std::vector<Vec3> velocity_;        // per grid point (i, j) at j * (nu + 1) + i; NaN: unknown
    std::vector<glm::dvec2> in_plane_;  // the same, along axis_u and axis_v / spacing
};

}  // namespace tr
