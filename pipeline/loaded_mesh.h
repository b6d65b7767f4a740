#pragma once
// A mesh ready for the renderers: read from a file (io/, when built with VTK) or handed over,
// and made tetrahedral (the conforming split, or Delaunay for a point cloud when built with
// CGAL).

#include <core/progress.h>
#include <core/result.h>
#include <mesh/planar_slab.h>
#include <mesh/tet_mesh.h>
#include <mesh/tetrahedralize.h>
#include <mesh/unstructured_mesh.h>

#include <filesystem>
#include <optional>

namespace tr {

// How a file becomes tets.
struct LoadOptions {
    int time_step = 0;
    double merge_tolerance = 0.0;  // 0: exact merging (TetrahedralizeOptions)
    bool no_merge = false;
    bool delaunay = false;         // Delaunay of the points even when the file has cells
    bool whole_exodus_set = true;  // io/read_mesh.h ReadOptions::whole_exodus_set
    // A planar 2D mesh (triangles, quads, polygons) becomes a thin slab of wedges
    // (mesh/planar_slab.h) instead of an error: what the flow tools take a 2D flow from.
    bool planar_as_slab = false;
    ProgressFn progress;  // stages "reading", "tetrahedralizing"
};

struct LoadedMesh {
    UnstructuredMesh input;  // as read (its fields are also on `tets`)
    TetMesh tets;
    TetrahedralizeReport report;
    bool used_delaunay = false;
    // Set when a planar 2D mesh was made a slab (LoadOptions::planar_as_slab): its plane, its
    // thickness; `input` is then the slab.
    std::optional<PlanarSheet> planar;
    double read_ms = 0;
    double tetrahedralize_ms = 0;
};

// Reads `path` (io/read_mesh.h lists the formats) and tetrahedralizes it. Errors: those of
// read_mesh and tetrahedralize, with the path in `where`; kInvalidMesh when no tetrahedron of
// non-zero volume is left (coplanar cells, all points coincident, coordinates whose volumes
// overflow), saying how many cells or points gave nothing; kUnsupported for a point cloud in a
// build without CGAL, or for any file in a build without VTK; with planar_as_slab, a 2D mesh
// that is not planar (planar_sheet's errors). Cost: the reader's and the
// split's, O(file size + cells log cells).
Result<LoadedMesh> load_tet_mesh(const std::filesystem::path& path, const LoadOptions& options);

// The same for a mesh handed over in memory (`name` is used in messages).
Result<LoadedMesh> load_tet_mesh(UnstructuredMesh input, const std::string& name,
                                 const LoadOptions& options);

// The coordinates the renderers hold: their opacity tables are single precision, and the
// extinction of a quick look's unit distance (about the mesh's size) underflows float past
// about 1e45 (measured: a tet of side 1e45 draws, one of 1e50 draws nothing).
inline constexpr double kMaxCoordinate = 1e30;
inline constexpr double kMinExtent = 1e-30;

// An error (kInvalidMesh, naming `name`) when a coordinate's magnitude exceeds kMaxCoordinate
// or the bounds' diagonal is below kMinExtent, saying to rescale the mesh: such a mesh would be
// drawn as an empty picture. load_tet_mesh checks it.
Status check_coordinate_scale(const Bounds3& bounds, const std::string& name);

// `error` with `path` in front of its where ("path: where" or "path").
Error with_where(Error error, const std::string& path);

}  // namespace tr
