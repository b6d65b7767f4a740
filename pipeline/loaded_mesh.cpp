#include <core/config.h>
#include <core/stopwatch.h>
#include <pipeline/loaded_mesh.h>

#if TETRENDER_HAS_VTK
#include <io/read_mesh.h>
#endif
#if TETRENDER_HAS_CGAL
#include <mesh/copyleft/delaunay.h>
#endif

#include <core/memory_budget.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace tr {

Error with_where(Error error, const std::string& path) {
    error.where = error.where.empty() ? path : path + ": " + error.where;
    return error;
}

namespace {

// Why a mesh ended with no tetrahedron, from what the split or Delaunay reported.
std::string why_no_tets(const LoadedMesh& loaded) {
    if (loaded.used_delaunay) {
        return std::to_string(loaded.input.points.size()) +
               " points span no volume (coincident or coplanar): Delaunay made no tetrahedron";
    }
    const TetrahedralizeReport& r = loaded.report;
    return std::to_string(loaded.input.num_cells()) +
           " cells left no tetrahedron of non-zero volume (" +
           std::to_string(r.num_degenerate_cells) + " cells of zero volume, " +
           std::to_string(r.num_degenerate_tets) + " zero-volume tets, " +
           std::to_string(r.num_skipped_cells) +
           " unsupported cells dropped; coplanar, coincident or overflowing coordinates)";
}

// The peak memory of tetrahedralizing `input`, before it starts: the tets its cells split into
// (1 a tet, 2 a pyramid, 3 a wedge, 6 a hexahedron, twice the corners of other cells) at 110
// bytes each. Measured: `tetrender info` of a 200^3 image (47.3M tets) peaked at 5.05 GB
// resident, 107 bytes a tet with the input, its points and the adjacency included.
double tetrahedralize_bytes(const UnstructuredMesh& input) {
    double tets = 0;
    for (CellType type : input.types) {
        const int corners = cell_corner_count(type);
        tets += corners == 4   ? 1
                : corners == 5 ? 2
                : corners == 6 ? 3
                : corners == 8 ? 6
                               : 2.0 * corners;
    }
    return tets * 110.0;
}

}  // namespace

Status check_coordinate_scale(const Bounds3& bounds, const std::string& name) {
    const Vec3 far = glm::max(glm::abs(bounds.lo), glm::abs(bounds.hi));
    const double largest = std::max({far.x, far.y, far.z});
    const double diagonal = bounds.diagonal();
    char message[240];
    if (largest > kMaxCoordinate) {
        std::snprintf(message, sizeof message,
                      "coordinates reach %.3g, beyond %.0e: the renderers' single-precision "
                      "opacities would vanish and draw nothing; rescale the mesh",
                      largest, kMaxCoordinate);
        return make_error(ErrorCode::kInvalidMesh, message, name);
    }
    if (diagonal < kMinExtent) {
        std::snprintf(message, sizeof message,
                      "the mesh spans only %.3g, below %.0e: the renderers' single-precision "
                      "opacities would overflow; rescale the mesh",
                      diagonal, kMinExtent);
        return make_error(ErrorCode::kInvalidMesh, message, name);
    }
    return {};
}

Result<LoadedMesh> load_tet_mesh(UnstructuredMesh input, const std::string& name,
                                 const LoadOptions& options) {
    LoadedMesh loaded;
    if (options.planar_as_slab && is_surface_mesh(input)) {
        auto sheet = planar_sheet(input);
        if (!sheet.ok()) return with_where(sheet.error(), name);
        auto slab = planar_slab(input, *sheet);
        if (!slab.ok()) return with_where(slab.error(), name);
        loaded.planar = *sheet;
        input = std::move(slab).value();
    }
    loaded.input = std::move(input);
    const auto start = std::chrono::steady_clock::now();
    if (loaded.input.is_point_cloud() || options.delaunay) {
#if TETRENDER_HAS_CGAL
        UnstructuredMesh cloud;
        cloud.points = loaded.input.points;
        cloud.point_fields = loaded.input.point_fields;
        auto tets = delaunay_tetrahedralize(cloud);
        if (!tets.ok()) {
            Error e = tets.error();
            if (e.where.empty()) e.where = name;
            return e;
        }
        loaded.tets = std::move(tets).value();
        loaded.used_delaunay = true;
        loaded.report.num_tets = loaded.tets.num_tets();
#else
        return make_error(ErrorCode::kUnsupported,
                          "a point cloud needs Delaunay tetrahedralization: this build has no "
                          "CGAL (TETRENDER_WITH_CGAL=OFF)",
                          name);
#endif
    } else {
        const Status fits =
            check_memory(tetrahedralize_bytes(loaded.input),
                         "tetrahedralizing " + std::to_string(loaded.input.num_cells()) + " cells");
        if (!fits.ok()) return with_where(fits.error(), name);
        TetrahedralizeOptions tet_options;
        tet_options.merge_points = !options.no_merge;
        tet_options.merge_tolerance = options.merge_tolerance;
        tet_options.progress = options.progress;
        auto tets = tetrahedralize(loaded.input, tet_options, &loaded.report);
        if (!tets.ok()) return with_where(tets.error(), name);
        loaded.tets = std::move(tets).value();
    }
    if (loaded.tets.num_tets() == 0) {
        // Nothing to draw: a black picture with exit 0 would look like a rendering.
        return make_error(ErrorCode::kInvalidMesh, "empty volume: " + why_no_tets(loaded), name);
    }
    TR_TRY_STATUS(check_coordinate_scale(loaded.tets.bounds(), name));
    loaded.tetrahedralize_ms = ms_since(start);
    return loaded;
}

Result<LoadedMesh> load_tet_mesh(const std::filesystem::path& path, const LoadOptions& options) {
#if TETRENDER_HAS_VTK
    const auto start = std::chrono::steady_clock::now();
    ReadOptions read_options;
    read_options.time_step = options.time_step;
    read_options.progress = options.progress;
    read_options.whole_exodus_set = options.whole_exodus_set;
    TR_TRY(UnstructuredMesh input, read_mesh(path, read_options));
    const double read_ms = ms_since(start);
    TR_TRY(LoadedMesh loaded, load_tet_mesh(std::move(input), path.string(), options));
    loaded.read_ms = read_ms;
    return loaded;
#else
    (void)options;
    return make_error(ErrorCode::kUnsupported,
                      "this build reads no mesh files (TETRENDER_WITH_VTK=OFF): hand the mesh "
                      "over in memory",
                      path.string());
#endif
}

}  // namespace tr
