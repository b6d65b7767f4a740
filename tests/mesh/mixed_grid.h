#pragma once
// Random conforming mixed meshes for tests and benchmarks: an nx * ny * nz grid of boxes, each
// column or box a hexahedron, two wedges, six pyramids around a centre point, or twelve tets,
// with points numbered in random order and an affine map applied.

#include <core/math.h>
#include <mesh/unstructured_mesh.h>

#include <cstdint>

namespace tr::testing {

struct MixedGridOptions {
    int nx = 4, ny = 4, nz = 4;
    std::uint32_t seed = 1;
    bool shuffle_points = true;     // random global numbering
    bool duplicate_points = false;  // every cell gets its own copies of its points
    double p_wedge_column = 0.25;   // fraction of (i, j) columns split into two wedge columns
    double p_pyramids = 0.2;        // fraction of the other boxes split into 6 pyramids
    double p_tets = 0.2;            // fraction split into 12 tets (pyramids, then min-id diagonal)
    glm::dmat3 linear = glm::dmat3(1.0);  // the affine map's linear part
    Vec3 offset = Vec3(0.0);
    // Boxes (i, j, k) to leave out, as a predicate on the box index; none by default.
    bool (*skip_box)(int i, int j, int k) = nullptr;
};

// Returns the mesh; `expected_volume` (optional) gets det(linear) * number of boxes kept.
UnstructuredMesh make_mixed_grid(const MixedGridOptions& options,
                                 double* expected_volume = nullptr);

}  // namespace tr::testing
