// The only translation unit that includes CGAL (slow to compile: keep it alone).
#include <core/stopwatch.h>
#include <mesh/copyleft/delaunay.h>
#include <mesh/tetrahedralize.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace tr {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<PointId, Kernel>;
using DataStructure =
    CGAL::Triangulation_data_structure_3<VertexBase,
                                         CGAL::Delaunay_triangulation_cell_base_3<Kernel>>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, DataStructure>;

bool is_finite(const Vec3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// The tuples `keep` of `field`, in that order.
Field select_tuples(const Field& field, const std::vector<PointId>& keep) {
    Field out;
    out.name = field.name;
    out.num_components = field.num_components;
    const std::size_t nc = static_cast<std::size_t>(field.num_components);
    std::visit(
        [&](const auto& values) {
            std::decay_t<decltype(values)> selected;
            selected.reserve(keep.size() * nc);
            for (PointId p : keep) {
                for (std::size_t c = 0; c < nc; ++c) selected.push_back(values[p * nc + c]);
            }
            out.values = std::move(selected);
        },
        field.values);
    return out;
}

Result<TetMesh> triangulate(const UnstructuredMesh& cloud, DelaunayReport& report) {
    const std::vector<Vec3>& points = cloud.points;
    const std::size_t n = points.size();
    report.num_input_points = n;
    if (n >= kNoCell) {
        return make_error(ErrorCode::kInvalidArgument,
                          "too many points for a TetMesh: " + std::to_string(n));
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (!is_finite(points[i])) {
            return make_error(ErrorCode::kInvalidMesh,
                              "point " + std::to_string(i) + " has a non-finite coordinate",
                              "point " + std::to_string(i));
        }
    }
    for (const Field& f : cloud.point_fields) {
        const std::size_t size = std::visit([](const auto& v) { return v.size(); }, f.values);
        if (f.num_components < 1 || size != n * static_cast<std::size_t>(f.num_components)) {
            return make_error(ErrorCode::kInvalidArgument,
                              "point field '" + f.name + "' has " + std::to_string(size) +
                                  " values for " + std::to_string(n) + " points",
                              "point field '" + f.name + "'");
        }
    }

    // Merge identical points into the first of them (the split's exact merging).
    const std::vector<PointId> representative = find_coincident_points(points, 0.0, {});
    std::vector<PointId> kept;  // input index of each distinct point, in input order
    std::vector<PointId> new_index(n);
    for (std::size_t i = 0; i < n; ++i) {
        if (representative[i] == i) {
            new_index[i] = static_cast<PointId>(kept.size());
            kept.push_back(static_cast<PointId>(i));
        }
    }
    report.num_duplicate_points = n - kept.size();
    if (kept.size() < 4) {
        return make_error(ErrorCode::kInvalidMesh,
                          "Delaunay tetrahedralization needs at least 4 distinct points, got " +
                              std::to_string(kept.size()));
    }

    std::vector<std::pair<Kernel::Point_3, PointId>> input;
    input.reserve(kept.size());
    for (PointId i : kept) {
        const Vec3& p = points[i];
        input.emplace_back(Kernel::Point_3(p.x, p.y, p.z), new_index[i]);
    }
    Delaunay dt(input.begin(), input.end());
    if (dt.dimension() < 3) {
        return make_error(
            ErrorCode::kInvalidMesh,
            std::string("all ") + std::to_string(kept.size()) + " distinct points are " +
                (dt.dimension() == 2 ? "coplanar" : "collinear") + ": no tetrahedra to make");
    }

    std::vector<Vec3> mesh_points;
    mesh_points.reserve(kept.size());
    for (PointId i : kept) mesh_points.push_back(points[i]);
    std::vector<Tet> tets;
    tets.reserve(dt.number_of_finite_cells());
    for (auto cell = dt.finite_cells_begin(); cell != dt.finite_cells_end(); ++cell) {
        // CGAL's finite cells are positively oriented in the same sense as orient3d.
        tets.push_back({cell->vertex(0)->info(), cell->vertex(1)->info(), cell->vertex(2)->info(),
                        cell->vertex(3)->info()});
    }
    const std::size_t num_cells = tets.size();
    TetMeshCreateOptions options;
    options.degenerate_tolerance = 0.0;  // every Delaunay cell is a real tet: keep slivers
    TR_TRY(TetMesh mesh, TetMesh::create(std::move(mesh_points), std::move(tets), {}, options));
    report.num_dropped_tets = num_cells - mesh.num_tets();
    report.num_tets = mesh.num_tets();
    for (const Field& f : cloud.point_fields) {
        TR_TRY_STATUS(mesh.add_point_field(select_tuples(f, kept)));
    }
    return mesh;
}

}  // namespace

Result<TetMesh> delaunay_tetrahedralize(const UnstructuredMesh& cloud, DelaunayReport* report) {
    const auto start = std::chrono::steady_clock::now();
    DelaunayReport local;
    Result<TetMesh> result = make_error(ErrorCode::kInternal, "not run");
    try {
        result = triangulate(cloud, local);
    } catch (const std::bad_alloc&) {
        result = make_error(ErrorCode::kInternal,
                            "out of memory in the Delaunay tetrahedralization of " +
                                std::to_string(cloud.points.size()) + " points");
    } catch (const std::exception& e) {
        result =
            make_error(ErrorCode::kInternal,
                       std::string("CGAL failed in the Delaunay tetrahedralization: ") + e.what());
    } catch (...) {
        result = make_error(ErrorCode::kInternal,
                            "CGAL failed in the Delaunay tetrahedralization (unknown exception)");
    }
    local.seconds = seconds_since(start);
    if (report) *report = local;
    return result;
}

}  // namespace tr
