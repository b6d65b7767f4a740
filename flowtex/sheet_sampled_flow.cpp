#include <core/parallel.h>
#include <flowtex/sheet_sampled_flow.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace tr {

SheetSampledFlow::SheetSampledFlow(const Sheet& sheet, const Flow& base)
    : sheet_(&sheet), base_(&base), inv_spacing_(1.0 / sheet.spacing) {
    const std::size_t stride = static_cast<std::size_t>(sheet.nu) + 1;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    velocity_.assign(stride * (static_cast<std::size_t>(sheet.nv) + 1), Vec3(nan));
    // Row by row, each lookup starting from the cell of the one before.
    parallel_for(0, static_cast<std::size_t>(sheet.nv) + 1, 1, [&](std::size_t row) {
        CellId hint = kNoCell;
        for (std::size_t col = 0; col < stride; ++col) {
            const std::int32_t i = sheet.grid_point[row * stride + col];
            if (i < 0) continue;
            if (const auto v = base.at(sheet.points[static_cast<std::size_t>(i)], 0.0, hint)) {
                velocity_[row * stride + col] = *v;
            }
        }
    });
    in_plane_.resize(velocity_.size());
    for (std::size_t k = 0; k < velocity_.size(); ++k) {
        in_plane_[k] =
            glm::dvec2(glm::dot(velocity_[k], sheet.axis_u), glm::dot(velocity_[k], sheet.axis_v)) *
            inv_spacing_;
    }
}

glm::dvec2 SheetSampledFlow::grid_velocity(const glm::dvec2& grid) const {
    const Sheet& sheet = *sheet_;
    const double x = grid.x, y = grid.y;
    const bool inside = x >= 0 && y >= 0 && x <= sheet.nu && y <= sheet.nv;
    // Off the sheet (or NaN) the look-up goes to square (0, 0) and its answer is replaced.
    const int i = inside ? std::min(static_cast<int>(x), sheet.nu - 1) : 0;
    const int j = inside ? std::min(static_cast<int>(y), sheet.nv - 1) : 0;
    const double fx = x - i, fy = y - j;
    const std::size_t stride = static_cast<std::size_t>(sheet.nu) + 1;
    const std::size_t at = static_cast<std::size_t>(j) * stride + i;
    // The triangle below the diagonal, (i, j), (i + 1, j), (i + 1, j + 1), or the one above,
    // (i, j), (i + 1, j + 1), (i, j + 1): the same weights by max and min, without a branch (a
    // trace crosses the diagonal at random).
    const std::size_t lower = fx >= fy ? 1 : 0;
    const double l = static_cast<double>(lower);
    const double hi = l * fx + (1.0 - l) * fy, lo = l * fy + (1.0 - l) * fx;
    const std::size_t side = at + stride - lower * (stride - 1);
    const glm::dvec2 v =
        (1.0 - hi) * in_plane_[at] + (hi - lo) * in_plane_[side] + lo * in_plane_[at + stride + 1];
    return inside ? v : glm::dvec2(std::numeric_limits<double>::quiet_NaN());
}

std::optional<glm::dvec2> SheetSampledFlow::grid_step(const glm::dvec2& grid, double dt) const {
    glm::dvec2 out;
    grid_steps(std::span<const glm::dvec2>(&grid, 1), dt, std::span<glm::dvec2>(&out, 1));
    if (std::isnan(out.x)) return std::nullopt;
    return out;
}

void SheetSampledFlow::grid_steps(std::span<const glm::dvec2> from, double dt,
                                  std::span<glm::dvec2> to) const {
    constexpr std::size_t kWidth = 4;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t first = 0; first < from.size(); first += kWidth) {
        const std::size_t count = std::min(kWidth, from.size() - first);
        std::array<glm::dvec2, kWidth> x{}, k1{}, k2{}, k3{}, k4{};
        for (std::size_t k = 0; k < count; ++k) x[k] = from[first + k];
        // NaN (off the sheet) flows through the stages into the result.
        for (std::size_t k = 0; k < kWidth; ++k) k1[k] = grid_velocity(x[k]);
        for (std::size_t k = 0; k < kWidth; ++k) k2[k] = grid_velocity(x[k] + 0.5 * dt * k1[k]);
        for (std::size_t k = 0; k < kWidth; ++k) k3[k] = grid_velocity(x[k] + 0.5 * dt * k2[k]);
        for (std::size_t k = 0; k < kWidth; ++k) k4[k] = grid_velocity(x[k] + dt * k3[k]);
        for (std::size_t k = 0; k < count; ++k) {
            const glm::dvec2 next = x[k] + dt / 6.0 * (k1[k] + 2.0 * k2[k] + 2.0 * k3[k] + k4[k]);
            to[first + k] = std::isfinite(next.x) && std::isfinite(next.y) ? next : glm::dvec2(nan);
        }
    }
}

std::optional<Vec3> SheetSampledFlow::at(const Vec3& p, double time, CellId& hint) const {
    const Sheet& sheet = *sheet_;
    const Vec3 d = p - sheet.origin;
    // Only points in the sheet's plane lie on its triangles (a trace projected into the plane
    // stays there); anything else goes to the flow itself.
    if (std::abs(glm::dot(d, sheet.normal)) <= 1e-6 * sheet.spacing) {
        const double x = glm::dot(d, sheet.axis_u) * inv_spacing_;
        const double y = glm::dot(d, sheet.axis_v) * inv_spacing_;
        if (x >= 0 && y >= 0 && x <= sheet.nu && y <= sheet.nv) {
            const int i = std::min(static_cast<int>(x), sheet.nu - 1);
            const int j = std::min(static_cast<int>(y), sheet.nv - 1);
            const double fx = x - i, fy = y - j;
            const std::size_t stride = static_cast<std::size_t>(sheet.nu) + 1;
            const std::size_t at = static_cast<std::size_t>(j) * stride + i;
            const Vec3& a = velocity_[at];
            const Vec3& c = velocity_[at + stride + 1];
            // The sheet's triangles: (i, j), (i + 1, j), (i + 1, j + 1) below the diagonal,
            // (i, j), (i + 1, j + 1), (i, j + 1) above; an unknown corner's NaN falls through.
            const Vec3 v = fx >= fy ? (1.0 - fx) * a + (fx - fy) * velocity_[at + 1] + fy * c
                                    : (1.0 - fy) * a + (fy - fx) * velocity_[at + stride] + fx * c;
            if (!std::isnan(v.x) && !std::isnan(v.y) && !std::isnan(v.z)) return v;
        }
    }
    return base_->at(p, time, hint);
}

}  // namespace tr
