#include <flowtex/sheet.h>
#include <flowvol/point_locator.h>

#include <algorithm>
#include <cmath>
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

Result<Sheet> sheet_from_triangles(const std::vector<Vec3>& points,
                                   const std::vector<std::array<std::uint32_t, 3>>& triangles) {
    if (triangles.empty() || points.empty()) {
        return make_error(ErrorCode::kInvalidMesh, "the sheet has no triangles");
    }
    Bounds3 bounds;
    for (const Vec3& p : points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            return make_error(ErrorCode::kInvalidMesh, "the sheet has a non-finite point");
        }
        bounds.extend(p);
    }
    Vec3 area_normal(0.0);
    for (const auto& t : triangles) {
        if (t[0] >= points.size() || t[1] >= points.size() || t[2] >= points.size()) {
            return make_error(ErrorCode::kInvalidMesh, "a sheet triangle indexes past the points");
        }
        area_normal += glm::cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]);
    }
    const double diagonal = bounds.diagonal();
    const double length = glm::length(area_normal);
    if (!(length > 1e-12 * diagonal * diagonal)) {
        return make_error(ErrorCode::kInvalidMesh, "the sheet has zero area");
    }
    const Vec3 n = area_normal / length;
    const Vec3 o = points[triangles[0][0]];
    double farthest = 0;
    for (const Vec3& p : points) farthest = std::max(farthest, std::abs(glm::dot(p - o, n)));
    if (farthest > 1e-6 * diagonal) {
        std::ostringstream message;
        message << "the sheet is not planar: a point lies " << farthest
                << " from the plane of its triangles (tolerance 1e-6 of the diagonal " << diagonal
                << ")";
        return make_error(ErrorCode::kInvalidMesh, message.str());
    }
    const Vec3 a = glm::abs(n);
    const Vec3 least = a.x <= a.y && a.x <= a.z ? Vec3(1, 0, 0)
                       : a.y <= a.z             ? Vec3(0, 1, 0)
                                                : Vec3(0, 0, 1);
    Sheet sheet;
    sheet.normal = n;
    sheet.axis_u = glm::normalize(glm::cross(n, least));
    sheet.axis_v = glm::cross(n, sheet.axis_u);
    // Points projected onto the plane exactly (within the tolerance above).
    sheet.points.reserve(points.size());
    glm::dvec2 lo(1e300), hi(-1e300);
    for (const Vec3& p : points) {
        const Vec3 q = p - glm::dot(p - o, n) * n;
        sheet.points.push_back(q);
        const glm::dvec2 st(glm::dot(q - o, sheet.axis_u), glm::dot(q - o, sheet.axis_v));
        lo = glm::min(lo, st);
        hi = glm::max(hi, st);
    }
    sheet.triangles = triangles;
    // Buckets: about one triangle per square.
    const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
    const int side =
        std::clamp(static_cast<int>(std::sqrt(static_cast<double>(triangles.size()))), 1, 4096);
    sheet.spacing = extent / side;
    sheet.nu = std::max(1, static_cast<int>(std::ceil((hi.x - lo.x) / sheet.spacing)));
    sheet.nv = std::max(1, static_cast<int>(std::ceil((hi.y - lo.y) / sheet.spacing)));
    sheet.origin = o + lo.x * sheet.axis_u + lo.y * sheet.axis_v;
    const auto cells_of = [&](const std::array<std::uint32_t, 3>& t) {
        glm::dvec2 tlo(1e300), thi(-1e300);
        for (const std::uint32_t k : t) {
            const glm::dvec2 st = sheet.plane_coordinates(sheet.points[k]) / sheet.spacing;
            tlo = glm::min(tlo, st);
            thi = glm::max(thi, st);
        }
        return std::array<int, 4>{std::clamp(static_cast<int>(std::floor(tlo.x)), 0, sheet.nu - 1),
                                  std::clamp(static_cast<int>(std::floor(tlo.y)), 0, sheet.nv - 1),
                                  std::clamp(static_cast<int>(std::floor(thi.x)), 0, sheet.nu - 1),
                                  std::clamp(static_cast<int>(std::floor(thi.y)), 0, sheet.nv - 1)};
    };
    const std::size_t num_cells = static_cast<std::size_t>(sheet.nu) * sheet.nv;
    sheet.bucket_start.assign(num_cells + 1, 0);
    for (const auto& t : triangles) {
        const auto c = cells_of(t);
        for (int j = c[1]; j <= c[3]; ++j)
            for (int i = c[0]; i <= c[2]; ++i) ++sheet.bucket_start[j * sheet.nu + i + 1];
    }
    for (std::size_t k = 0; k < num_cells; ++k) sheet.bucket_start[k + 1] += sheet.bucket_start[k];
    sheet.bucket_triangles.resize(sheet.bucket_start.back());
    std::vector<std::uint32_t> fill(sheet.bucket_start.begin(), sheet.bucket_start.end() - 1);
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        const auto c = cells_of(triangles[t]);
        for (int j = c[1]; j <= c[3]; ++j)
            for (int i = c[0]; i <= c[2]; ++i)
                sheet.bucket_triangles[fill[j * sheet.nu + i]++] = static_cast<std::uint32_t>(t);
    }
    return sheet;
}

namespace {

std::optional<SheetLocation> locate_in_buckets(const Sheet& sheet, const glm::dvec2& st) {
    const double x = st.x / sheet.spacing, y = st.y / sheet.spacing;
    constexpr double kSlack = 1e-9;
    if (!(x >= -kSlack && y >= -kSlack && x <= sheet.nu + kSlack && y <= sheet.nv + kSlack)) {
        return std::nullopt;
    }
    const int i = std::clamp(static_cast<int>(std::floor(x)), 0, sheet.nu - 1);
    const int j = std::clamp(static_cast<int>(std::floor(y)), 0, sheet.nv - 1);
    const std::size_t cell = static_cast<std::size_t>(j) * sheet.nu + i;
    for (std::uint32_t k = sheet.bucket_start[cell]; k < sheet.bucket_start[cell + 1]; ++k) {
        const auto& t = sheet.triangles[sheet.bucket_triangles[k]];
        const glm::dvec2 a = sheet.plane_coordinates(sheet.points[t[0]]);
        const glm::dvec2 b = sheet.plane_coordinates(sheet.points[t[1]]);
        const glm::dvec2 c = sheet.plane_coordinates(sheet.points[t[2]]);
        const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
        if (area == 0) continue;
        const double wb = ((st.x - a.x) * (c.y - a.y) - (c.x - a.x) * (st.y - a.y)) / area;
        const double wc = ((b.x - a.x) * (st.y - a.y) - (st.x - a.x) * (b.y - a.y)) / area;
        const double wa = 1.0 - wb - wc;
        if (wa >= -kSlack && wb >= -kSlack && wc >= -kSlack) {
            return SheetLocation{t, {wa, wb, wc}};
        }
    }
    return std::nullopt;
}

}  // namespace

std::optional<SheetLocation> locate_on_sheet(const Sheet& sheet, const glm::dvec2& st) {
    if (sheet.grid_point.empty()) return locate_in_buckets(sheet, st);
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
