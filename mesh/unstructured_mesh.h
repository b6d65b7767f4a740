#pragma once
// The mesh as a file or a simulation gives it: points, mixed cells in VTK's layout, fields.
// This is the hand-over API for simulations (no file needed); tetrahedralize() turns it into a
// TetMesh.

#include <core/math.h>
#include <mesh/cell_type.h>
#include <mesh/field.h>
#include <mesh/surface_mesh.h>

#include <cstdint>
#include <string>
#include <vector>

namespace tr {

struct UnstructuredMesh {
    std::vector<Vec3> points;
    // Cell c has nodes connectivity[offsets[c] .. offsets[c + 1]) and type types[c].
    // offsets has types.size() + 1 entries and starts at 0 (empty for a point cloud).
    std::vector<std::int64_t> offsets;
    std::vector<std::int64_t> connectivity;
    std::vector<CellType> types;

    std::vector<Field> point_fields;  // one tuple per point
    std::vector<Field> cell_fields;   // one tuple per cell

    std::vector<SurfaceMesh> surfaces;  // e.g. Exodus side sets, for opaque geometry

    // Where it came from (for `info`): "VTK XML unstructured grid", "Exodus II", ...
    std::string format;
    // Time values of all steps in the source (empty: not a time series) and the one read.
    std::vector<double> time_values;
    int time_step = 0;

    std::size_t num_cells() const { return types.size(); }
    std::size_t num_points() const { return points.size(); }
    bool is_point_cloud() const { return types.empty(); }

    // Appends one cell. Node ids index `points`.
    void add_cell(CellType type, const std::vector<std::int64_t>& nodes);
};

// Builds a mesh from arrays a simulation already has (copies them). Checks sizes only; the
// full validation happens in tetrahedralize(). `cell_types` holds VTK ids, `offsets` has one
// more entry than cell_types (or is empty when every cell has the node count of its type:
// then offsets are computed).
Result<UnstructuredMesh> make_unstructured_mesh(const std::vector<double>& xyz,
                                                const std::vector<std::int64_t>& connectivity,
                                                const std::vector<std::int64_t>& offsets,
                                                const std::vector<std::uint8_t>& cell_types);

}  // namespace tr
