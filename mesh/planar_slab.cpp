#include <mesh/planar_slab.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <variant>
#include <vector>

namespace tr {
namespace {

constexpr int kPolygonId = 7;  // VTK_POLYGON: any number of nodes
constexpr int kPixelId = 8;    // VTK_PIXEL: a quad with nodes 2 and 3 swapped

bool is_surface_cell(CellType type) {
    const int id = static_cast<int>(type);
    return type == CellType::kTriangle || type == CellType::kQuad || id == kPolygonId ||
           id == kPixelId;
}

// Vertices, poly-vertices, lines and polylines (VTK 1 to 4): a 2D result's boundary edges or
// probe points, which carry no flow and are passed over.
bool is_point_or_line_cell(CellType type) {
    const int id = static_cast<int>(type);
    return id >= 1 && id <= 4;
}

using Triangle = std::array<std::int64_t, 3>;

// Every cell fanned into triangles from its first node, with the cell each came from; node ids
// checked against the points.
Result<std::vector<std::pair<Triangle, std::size_t>>> fan_triangles(const UnstructuredMesh& mesh) {
    std::vector<std::pair<Triangle, std::size_t>> out;
    out.reserve(mesh.num_cells() * 2);
    const auto n_points = static_cast<std::int64_t>(mesh.points.size());
    std::vector<std::int64_t> nodes;
    for (std::size_t c = 0; c < mesh.num_cells(); ++c) {
        if (!is_surface_cell(mesh.types[c])) continue;  // a point or a line
        const std::int64_t begin = mesh.offsets[c], end = mesh.offsets[c + 1];
        nodes.assign(mesh.connectivity.begin() + begin, mesh.connectivity.begin() + end);
        for (const std::int64_t n : nodes) {
            if (n < 0 || n >= n_points) {
                return make_error(ErrorCode::kInvalidMesh, "cell " + std::to_string(c) +
                                                               " names point " + std::to_string(n) +
                                                               " of " + std::to_string(n_points));
            }
        }
        if (static_cast<int>(mesh.types[c]) == kPixelId && nodes.size() == 4) {
            std::swap(nodes[2], nodes[3]);
        }
        for (std::size_t k = 1; k + 1 < nodes.size(); ++k) {
            out.push_back({{nodes[0], nodes[k], nodes[k + 1]}, c});
        }
    }
    return out;
}

Vec3 triangle_normal(const UnstructuredMesh& mesh, const Triangle& t) {
    const Vec3& a = mesh.points[t[0]];
    return glm::cross(mesh.points[t[1]] - a, mesh.points[t[2]] - a);
}

// A point field on the slab's two layers; 2- and 3-component fields as tangent vectors.
template <typename T>
std::vector<T> slab_values(const std::vector<T>& values, int components, const Vec3& normal) {
    const std::size_t n = values.size() / components;
    const int out_components = components == 2 ? 3 : components;
    std::vector<T> out(2 * n * out_components);
    for (std::size_t i = 0; i < n; ++i) {
        T* bottom = &out[i * out_components];
        if (components == 2 || components == 3) {
            Vec3 v(values[i * components], values[i * components + 1],
                   components == 3 ? static_cast<double>(values[i * components + 2]) : 0.0);
            v -= glm::dot(v, normal) * normal;
            bottom[0] = static_cast<T>(v.x);
            bottom[1] = static_cast<T>(v.y);
            bottom[2] = static_cast<T>(v.z);
        } else {
            std::copy_n(&values[i * components], components, bottom);
        }
        std::copy_n(bottom, out_components, &out[(n + i) * out_components]);
    }
    return out;
}

}  // namespace

bool is_surface_mesh(const UnstructuredMesh& mesh) {
    return std::any_of(mesh.types.begin(), mesh.types.end(), is_surface_cell) &&
           std::all_of(mesh.types.begin(), mesh.types.end(), [](CellType type) {
               return is_surface_cell(type) || is_point_or_line_cell(type);
           });
}

Result<PlanarSheet> planar_sheet(const UnstructuredMesh& mesh) {
    if (!is_surface_mesh(mesh)) {
        return make_error(ErrorCode::kInvalidMesh,
                          "not a 2D mesh: a planar mesh of triangles, quads or polygons only");
    }
    TR_TRY(const auto triangles, fan_triangles(mesh));
    // The normal: the triangles' area vectors, each turned to agree with the first non-zero one
    // (a file's cells need not wind the same way).
    Vec3 sum(0.0), reference(0.0);
    Bounds3 bounds;
    Vec3 centroid(0.0);
    std::size_t counted = 0;
    std::vector<double> sizes;
    sizes.reserve(triangles.size());
    for (const auto& [t, cell] : triangles) {
        for (const std::int64_t n : t) {
            const Vec3& p = mesh.points[n];
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
                return make_error(ErrorCode::kInvalidMesh,
                                  "point " + std::to_string(n) + " is not finite");
            }
            bounds.extend(p);
            centroid += p;
            ++counted;
        }
        const Vec3 area = triangle_normal(mesh, t);
        const double length = glm::length(area);
        if (!(length > 0)) continue;
        if (reference == Vec3(0.0)) reference = area;
        sum += glm::dot(area, reference) < 0 ? -area : area;
        sizes.push_back(std::sqrt(length));  // sqrt(2 x the triangle's area)
    }
    if (sizes.empty() || !(glm::length(sum) > 0)) {
        return make_error(
            ErrorCode::kInvalidMesh,
            "the 2D mesh's " + std::to_string(mesh.num_cells()) + " cells have no area");
    }
    PlanarSheet sheet;
    sheet.normal = glm::normalize(sum);
    const Vec3 a = glm::abs(sheet.normal);
    const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    if (sheet.normal[axis] < 0) sheet.normal = -sheet.normal;
    centroid /= static_cast<double>(counted);
    const Vec3 centre = 0.5 * (bounds.lo + bounds.hi);
    sheet.point = centre - glm::dot(centre - centroid, sheet.normal) * sheet.normal;

    const double tolerance = 1e-6 * bounds.diagonal();
    for (const auto& [t, cell] : triangles) {
        for (const std::int64_t n : t) {
            const double distance = std::abs(glm::dot(mesh.points[n] - centroid, sheet.normal));
            if (distance > tolerance) {
                char message[200];
                std::snprintf(message, sizeof message,
                              "not planar: point %lld is %.3g from the cells' plane (more than "
                              "1e-6 of the diagonal): a curved surface is not a 2D flow",
                              static_cast<long long>(n), distance);
                return make_error(ErrorCode::kInvalidMesh, message);
            }
        }
    }
    std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
    sheet.thickness = sizes[sizes.size() / 2];
    return sheet;
}

Result<UnstructuredMesh> planar_slab(const UnstructuredMesh& mesh, const PlanarSheet& sheet) {
    for (const Field& f : mesh.point_fields) {
        if (f.num_tuples() != mesh.num_points()) {
            return make_error(ErrorCode::kInvalidMesh,
                              "point array '" + f.name + "' has " + std::to_string(f.num_tuples()) +
                                  " tuples for " + std::to_string(mesh.num_points()) + " points");
        }
    }
    for (const Field& f : mesh.cell_fields) {
        if (f.num_tuples() != mesh.num_cells()) {
            return make_error(ErrorCode::kInvalidMesh,
                              "cell array '" + f.name + "' has " + std::to_string(f.num_tuples()) +
                                  " tuples for " + std::to_string(mesh.num_cells()) + " cells");
        }
    }
    TR_TRY(const auto triangles, fan_triangles(mesh));
    UnstructuredMesh slab;
    const std::size_t n = mesh.points.size();
    const Vec3 half = 0.5 * sheet.thickness * sheet.normal;
    slab.points.resize(2 * n);
    for (std::size_t i = 0; i < n; ++i) {
        slab.points[i] = mesh.points[i] - half;
        slab.points[n + i] = mesh.points[i] + half;
    }
    // VTK's wedge: its base (0, 1, 2) winds so that its normal points away from the top
    // (3, 4, 5), hence clockwise seen from the top side.
    slab.offsets.reserve(triangles.size() + 1);
    slab.connectivity.reserve(6 * triangles.size());
    slab.types.reserve(triangles.size());
    slab.offsets.push_back(0);
    std::vector<std::size_t> source_cell;
    source_cell.reserve(triangles.size());
    for (auto [t, cell] : triangles) {
        if (glm::dot(triangle_normal(mesh, t), sheet.normal) > 0) std::swap(t[1], t[2]);
        for (const std::int64_t v : t) slab.connectivity.push_back(v);
        for (const std::int64_t v : t)
            slab.connectivity.push_back(v + static_cast<std::int64_t>(n));
        slab.types.push_back(CellType::kWedge);
        slab.offsets.push_back(static_cast<std::int64_t>(slab.connectivity.size()));
        source_cell.push_back(cell);
    }
    for (const Field& f : mesh.point_fields) {
        Field out;
        out.name = f.name;
        out.num_components = f.num_components == 2 ? 3 : f.num_components;
        std::visit(
            [&](const auto& values) {
                out.values = slab_values(values, f.num_components, sheet.normal);
            },
            f.values);
        slab.point_fields.push_back(std::move(out));
    }
    for (const Field& f : mesh.cell_fields) {
        Field out;
        out.name = f.name;
        out.num_components = f.num_components;
        std::visit(
            [&](const auto& values) {
                std::decay_t<decltype(values)> copied;
                copied.reserve(source_cell.size() * f.num_components);
                for (const std::size_t c : source_cell) {
                    const auto* tuple = &values[c * f.num_components];
                    copied.insert(copied.end(), tuple, tuple + f.num_components);
                }
                out.values = std::move(copied);
            },
            f.values);
        slab.cell_fields.push_back(std::move(out));
    }
    slab.surfaces = mesh.surfaces;
    slab.format = mesh.format + " (2D, made a slab)";
    slab.time_values = mesh.time_values;
    slab.time_step = mesh.time_step;
    return slab;
}

}  // namespace tr
