#pragma once
// The brute-force check of a visibility order, independent of the sorter: a ray through every
// pixel centre, the real cells it crosses found by ray-triangle tests on their faces (binned on
// the screen, no adjacency, none of the sort's code), and every pair of consecutive cells along
// the ray that the order puts the wrong way round counted.

#include <core/camera.h>
#include <mesh/tet_mesh.h>

#include <cstddef>
#include <span>

namespace tr {

struct OrderCheck {
    std::size_t rays = 0;           // pixels whose ray crosses at least one cell
    std::size_t pairs = 0;          // consecutive pairs checked
    std::size_t violations = 0;     // pairs in the wrong order
    std::size_t missing_cells = 0;  // crossed cells absent from the order
    double milliseconds = 0;
};

// Checks `order` (back to front, real cells only, each at most once) for the camera's view at
// its image size. Segments shorter than `min_segment` times the bounds' diagonal are ignored
// (rays grazing an edge or vertex). Precondition (TR_CHECK aborts): every id in `order` is
// below mesh.num_tets(). Cost: O(pixels x cells per pixel) after an O(cells) binning.
OrderCheck check_order(const TetMesh& mesh, std::span<const CellId> order,
                       const CameraFrame& camera, double min_segment = 1e-9);

}  // namespace tr
