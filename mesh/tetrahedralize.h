#pragma once
// Splits a mixed UnstructuredMesh into a conforming TetMesh: merges coincident points, splits
// hexahedra, voxels, wedges, pyramids (and the corners of quadratic cells, and pentagonal and
// hexagonal prisms) so that every quad face shared by two cells is cut along the same diagonal.
//
// The split is the "pulling" triangulation over the lexicographic order of the (merged)
// points' coordinates: x first, then y, then z. Each polygonal face is fanned from its
// lexicographically smallest vertex, and each cell is the cone from its smallest corner over
// the faces that do not contain it. A face's triangulation thus depends only on its own
// vertices' coordinates, so neighbours agree: no cracks, no T-junctions. For a quad this is the
// diagonal through its smallest vertex. A non-convex cell (twisted or crushed) whose cone from
// that corner would mix orientations is coned from its next corner in the same order that sees
// all its faces' triangles, those of the faces through that corner included (a corner on a
// planar face fanned from another vertex would give a flat tet, leave a crack, and is passed
// over); the faces' triangles never change with the apex. A cell no corner sees whole is coned
// from its smallest corner anyway: its tets overlap, it is counted as tangled, and it stays
// conforming.
//
// What this guarantees: the set of tets, each as its four corners' coordinates with the input
// cell it came from (hence its cell fields), does not depend on how points or cells are
// numbered, nor on how the cells are cut into pieces: a .pvtu's pieces (or MPI ranks' parts)
// split one by one, each with its own numbering, give exactly the whole file's tets, and the
// faces across each cut match. Exceptions: exactly coincident points left distinct
// (merge_points off) tie in the order, and the tie is broken by point index, so there the
// split depends on the numbering; with a merge tolerance, a merged group takes the coordinates
// of its lowest-index point, which depends on the numbering when the group is not one point.

#include <core/progress.h>
#include <core/result.h>
#include <mesh/cell_type.h>
#include <mesh/tet_mesh.h>
#include <mesh/unstructured_mesh.h>

#include <cstddef>
#include <map>

namespace tr {

struct TetrahedralizeOptions {
    // Merge points with identical coordinates before splitting (Exodus block and .pvtu piece
    // interfaces, O-grid seams). Off only to inspect a file as written: coincident points then
    // tie in the split's coordinate order and are ordered by index (see above).
    bool merge_points = true;
    // 0: merge exactly equal points only. > 0: also merge points closer than this fraction
    // of the shortest edge at either point (e.g. 1e-6).
    double merge_tolerance = 0.0;
    // Cells of unsupported types (polygons, polyhedra, lines) are an error unless true: then
    // they are skipped and counted.
    bool skip_unsupported = false;
    TetMeshCreateOptions tet_options;
    ProgressFn progress;
};

struct TetrahedralizeReport {
    std::map<CellType, std::size_t> input_cells;  // input cells by type
    std::size_t num_quadratic_cells = 0;          // of which higher order: corners used
    std::size_t num_merged_points = 0;            // points merged into another
    std::size_t num_inverted_cells = 0;           // input cells with negative volume, fixed
    std::size_t num_degenerate_cells = 0;         // input cells of zero volume, dropped
    std::size_t num_degenerate_tets = 0;          // zero-volume tets dropped from kept cells
    // Non-convex cells that no corner sees whole: their tets overlap (counted, kept).
    std::size_t num_tangled_cells = 0;
    std::size_t num_skipped_cells = 0;  // unsupported cells skipped (see options)
    std::size_t num_tets = 0;           // tets in the result
};

// Converts `input` to tets. Point fields are kept (merged points keep the first point's
// values); cell fields are copied to every tet of their cell. Errors: point cloud (no cells:
// use delaunay_tetrahedralize), index out of range, non-finite point, unsupported cell type
// (names the cell), a cell with the wrong node count. Cost: O(cells + points log points).
Result<TetMesh> tetrahedralize(const UnstructuredMesh& input,
                               const TetrahedralizeOptions& options = {},
                               TetrahedralizeReport* report = nullptr);

// Merges coincident points of `points` (exactly, or within tolerance as in
// TetrahedralizeOptions). Returns for each point the index of its representative (the lowest
// index among those merged; representatives map to themselves).
std::vector<PointId> find_coincident_points(const std::vector<Vec3>& points,
                                            double tolerance_fraction,
                                            const std::vector<double>& local_length);

}  // namespace tr
