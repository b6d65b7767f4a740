#include <flowvol/point_locator.h>

#include <algorithm>
#include <cmath>
#include <flowtex/sheet.h>
#include <sstream>

namespace tr {
namespace {

std::string format_vec(const Vec3& v) {
    std::ostringstream out;
    out << "(" << v.x << ", " << v.y << ", " << v.z << ")";
    return out.str();
}

// Fills triangles from grid_point: both triangles of each square whose three points are kept.
void triangulate(Sheet& sheet) {
    const int stride = sheet.nu + 1;
    auto id = [&](int i, int j) {
        return sheet.grid_point[static_cast<std::size_t>(j) * stride + i];
    };
    for (int j = 0; j < sheet.nv; ++j) {
        for (int i = 0; i < sheet.nu; ++i) {
            const std::int32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1),
                               d = id(i, j + 1);
            if (a >= 0 && b >= 0 && c >= 0) {
                sheet.triangles.push_back({static_cast<std::uint32_t>(a),
                                           static_cast<std::uint32_t>(b),
                                           static_cast<std::uint32_t>(c)});
            }
            if (a >= 0 && c >= 0 && d >= 0) {
                sheet.triangles.push_back({static_cast<std::uint32_t>(a),
                                           static_cast<std::uint32_t>(c),
                                           static_cast<std::uint32_t>(d)});
            }
        }
    }
}

}  // namespace

Result<Sheet> grid_sheet(const Vec3& origin, const Vec3& axis_u, const Vec3& axis_v, int nu, int nv,
                         double spacing) {
    if (nu < 1 || nv < 1 || nu > 65535 || nv > 65535 || !(spacing > 0) || !std::isfinite(spacing)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "a sheet needs 1..65535 squares a side and a positive spacing");
    }
    const double lu = glm::length(axis_u);
    if (!(lu > 0) || !std::isfinite(lu)) {
        return make_error(ErrorCode::kInvalidArgument, "sheet axis_u is zero or not finite");
    }
    Sheet sheet;
    sheet.origin = origin;
    sheet.axis_u = axis_u / lu;
    const Vec3 v = axis_v - glm::dot(axis_v, sheet.axis_u) * sheet.axis_u;
    const double lv = glm::length(v);
    if (!(lv > 1e-12 * glm::length(axis_v)) || !std::isfinite(lv)) {
        return make_error(ErrorCode::kInvalidArgument, "sheet axes are parallel or not finite");
    }
    sheet.axis_v = v / lv;
    sheet.normal = glm::cross(sheet.axis_u, sheet.axis_v);
    sheet.spacing = spacing;
    sheet.nu = nu;
    sheet.nv = nv;
    const std::size_t n = static_cast<std::size_t>(nu + 1) * (nv + 1);
    sheet.points.reserve(n);
    sheet.grid_point.resize(n);
    for (int j = 0; j <= nv; ++j) {
        for (int i = 0; i <= nu; ++i) {
            sheet.grid_point[sheet.points.size()] = static_cast<std::int32_t>(sheet.points.size());
            sheet.points.push_back(origin + (i * spacing) * sheet.axis_u +
                                   (j * spacing) * sheet.axis_v);
        }
    }
    triangulate(sheet);
    return sheet;
}

Result<Sheet> slice_sheet(const PointLocator& locator, const Bounds3& mesh_bounds,
                          const Vec3& point, const Vec3& normal, int resolution) {
    const double ln = glm::length(normal);
    if (!(ln > 0) || !std::isfinite(ln) || !std::isfinite(point.x) || !std::isfinite(point.y) ||
        !std::isfinite(point.z)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "slice normal is zero or the slice is not finite");
    }
    if (resolution < 1 || resolution > 8192) {
        return make_error(ErrorCode::kInvalidArgument, "slice resolution must be 1..8192");
    }
    if (mesh_bounds.empty()) return make_error(ErrorCode::kInvalidMesh, "empty mesh");
    const Vec3 n = normal / ln;
    const Vec3 a = glm::abs(n);
    const Vec3 least = a.x <= a.y && a.x <= a.z ? Vec3(1, 0, 0)
                       : a.y <= a.z             ? Vec3(0, 1, 0)
                                                : Vec3(0, 0, 1);
    const Vec3 u = glm::normalize(glm::cross(n, least));
    const Vec3 v = glm::cross(n, u);
    // The bounds' footprint in the plane.
    glm::dvec2 lo(1e300), hi(-1e300);
    for (int c = 0; c < 8; ++c) {
        const Vec3 corner((c & 1) ? mesh_bounds.hi.x : mesh_bounds.lo.x,
                          (c & 2) ? mesh_bounds.hi.y : mesh_bounds.lo.y,
                          (c & 4) ? mesh_bounds.hi.z : mesh_bounds.lo.z);
        const glm::dvec2 st(glm::dot(corner - point, u), glm::dot(corner - point, v));
        lo = glm::min(lo, st);
        hi = glm::max(hi, st);
    }
    const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
    Sheet sheet;
    sheet.axis_u = u;
    sheet.axis_v = v;
    sheet.normal = n;
    sheet.spacing = extent / resolution;
    sheet.nu = std::max(1, static_cast<int>(std::ceil((hi.x - lo.x) / sheet.spacing - 1e-9)));
    sheet.nv = std::max(1, static_cast<int>(std::ceil((hi.y - lo.y) / sheet.spacing - 1e-9)));
    sheet.origin = point + lo.x * u + lo.y * v;
    sheet.grid_point.assign(static_cast<std::size_t>(sheet.nu + 1) * (sheet.nv + 1), -1);
    CellId hint = kNoCell;
    for (int j = 0; j <= sheet.nv; ++j) {
        for (int i = 0; i <= sheet.nu; ++i) {
            const Vec3 p = sheet.origin + (i * sheet.spacing) * u + (j * sheet.spacing) * v;
            if (const auto where = locator.locate(p, hint)) {
                hint = where->tet;
                sheet.grid_point[static_cast<std::size_t>(j) * (sheet.nu + 1) + i] =
                    static_cast<std::int32_t>(sheet.points.size());
                sheet.points.push_back(p);
            }
        }
    }
    triangulate(sheet);
    if (sheet.triangles.empty()) {
        return make_error(ErrorCode::kInvalidArgument, "the slice through " + format_vec(point) +
                                                           " with normal " + format_vec(n) +
                                                           " misses the mesh (bounds " +
                                                           format_vec(mesh_bounds.lo) + " to " +
                                                           format_vec(mesh_bounds.hi) + ")");
    }
    return sheet;
}

std::optional<SheetLocation> locate_on_sheet(const Sheet& sheet, const glm::dvec2& st) {
    const double x = st.x / sheet.spacing, y = st.y / sheet.spacing;
    constexpr double kSlack = 1e-9;
    if (!(x >= -kSlack && y >= -kSlack && x <= sheet.nu + kSlack && y <= sheet.nv + kSlack)) {
        return std::nullopt;
    }
    const int i = std::clamp(static_cast<int>(std::floor(x)), 0, sheet.nu - 1);
    const int j = std::clamp(static_cast<int>(std::floor(y)), 0, sheet.nv - 1);
    const double fx = std::clamp(x - i, 0.0, 1.0), fy = std::clamp(y - j, 0.0, 1.0);
    const int stride = sheet.nu + 1;
    auto id = [&](int a, int b) {
        return sheet.grid_point[static_cast<std::size_t>(b) * stride + a];
    };
    const std::int32_t a = id(i, j), c = id(i + 1, j + 1);
    SheetLocation out;
    if (fx >= fy) {  // triangle (i, j), (i + 1, j), (i + 1, j + 1)
        const std::int32_t b = id(i + 1, j);
        if (a < 0 || b < 0 || c < 0) return std::nullopt;
        out.points = {static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b),
                      static_cast<std::uint32_t>(c)};
        out.weights = {1.0 - fx, fx - fy, fy};
    } else {  // triangle (i, j), (i + 1, j + 1), (i, j + 1)
        const std::int32_t d = id(i, j + 1);
        if (a < 0 || c < 0 || d < 0) return std::nullopt;
        out.points = {static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(c),
                      static_cast<std::uint32_t>(d)};
        out.weights = {1.0 - fy, fx, fy - fx};
    }
    return out;
}

}  // namespace tr
