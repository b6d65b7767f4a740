#pragma once
// Random conforming mixed meshes for tests and benchmarks: an nx * ny * nz grid of boxes, each
// column or box a hexahedron, two wedges, six pyramids around a centre point, or twelve tets,
// with points numbered in random order and an affine map applied; a twisted stack of hexagonal
// and pentagonal prisms, hexahedra and wedges; renumbering and cutting any mesh; and a small
// wavy field on a grid of tets.

#include <core/math.h>
#include <mesh/tet_mesh.h>
#include <mesh/unstructured_mesh.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

namespace tr::testing {

struct MixedGridOptions {
    int nx = 4, ny = 4, nz = 4;
    std::uint32_t seed = 1;
    bool shuffle_points = true;     // random global numbering
    bool duplicate_points = false;  // every cell gets its own copies of its points
    double p_wedge_column = 0.25;   // fraction of (i, j) columns split into two wedge columns
    double p_pyramids = 0.2;        // fraction of the other boxes split into 6 pyramids
    double p_tets = 0.2;  // fraction split into 12 tets (pyramids, then the diagonal through
                          // each quad's lexicographically smallest point, as tetrahedralize)
    glm::dmat3 linear = glm::dmat3(1.0);  // the affine map's linear part
    Vec3 offset = Vec3(0.0);
    // Boxes (i, j, k) to leave out, as a predicate on the box index; none by default.
    bool (*skip_box)(int i, int j, int k) = nullptr;
    // Each point moved by up to this much along each axis (in box units, before the map), at
    // random: cells become non-convex and, at 0.45, some tangled.
    double jitter = 0.0;
    bool voxels = false;     // hexahedral boxes written as voxels (VTK's other node order)
    bool quadratic = false;  // every cell written as its quadratic type (mid nodes appended)
};

// Returns the mesh; `expected_volume` (optional) gets det(linear) * number of boxes kept.
UnstructuredMesh make_mixed_grid(const MixedGridOptions& options,
                                 double* expected_volume = nullptr);

// Boundary triangles of the whole nx * ny * nz grid split conformingly: two per boundary quad.
std::size_t box_boundary_triangles(const MixedGridOptions& options);

// A random linear map near 1.5 * identity with determinant at least 0.2 (for
// MixedGridOptions::linear).
glm::dmat3 random_rotation_scale(std::mt19937& rng);

struct PrismStackOptions {
    int layers = 3;
    double twist = 0.0;  // radians each layer is turned about z from the one below
    std::uint32_t seed = 1;
    bool shuffle_points = true;  // random global numbering
};

// A disc of polygons extruded through `layers` unit layers: a hexagon in the middle, 6
// pentagons, 12 quads and 24 triangles around it (radius 4), giving hexagonal and pentagonal
// prisms, hexahedra and wedges in VTK order, each layer turned by `twist`. A twist of 0.8
// tangles about one cell in seven. `boundary_triangles` (optional) gets the number of boundary
// triangles a conforming split has: 140 on the two caps plus 24 per layer on the side.
UnstructuredMesh make_prism_stack(const PrismStackOptions& options,
                                  std::size_t* boundary_triangles = nullptr);

// The cells `cells` of `mesh`, in that order, as a mesh of their own: only the points they use,
// numbered at random (seeded), with their point and cell fields. With every cell in a shuffled
// order it renumbers the whole mesh; with a subset it cuts out a piece as a .pvtu holds it.
UnstructuredMesh extract_cells(const UnstructuredMesh& mesh, const std::vector<std::size_t>& cells,
                               std::uint32_t seed);

// `mesh` with its points and cells numbered at random (seeded); unused points are dropped.
UnstructuredMesh shuffle_mesh(const UnstructuredMesh& mesh, std::uint32_t seed);

// A 3 x 3 x 3 mixed grid (seed 1) moved by `offset` and split into tets, with the point field
// "wave" = 0.5 + 0.45 sin(1.3 x) cos(0.9 y + 0.4 z), in [0.05, 0.95]: a small volume with
// structure for the rendering tests.
std::shared_ptr<const TetMesh> wavy_grid(const Vec3& offset = Vec3(0.0));

}  // namespace tr::testing
