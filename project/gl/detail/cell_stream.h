#pragma once
// The CPU half of a GL frame: each cell of a back-to-front order classified (Shirley-Tuchman)
// into its slot of the vertex stream, or sent to the exact per-pixel path (the cells around a
// perspective eye) with what the exact fragment stage needs of it. No GL here.

#include <core/camera.h>
#include <mesh/tet_mesh.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace tr::gl::detail {

constexpr int kFloatsPerVertex = 6;  // x, y (pixels), thickness, s_front, s_back, t_front
constexpr int kVerticesPerCell = 5;  // the thick vertex, then the hull (4th repeated if 3)
constexpr int kIndicesPerCell = 12;  // four triangles around the thick vertex
// A perspective corner projected farther than this many times (width + height) pixels from the
// image centre sends its cell to the exact path: seen from the eye, it lies within about 1-3
// degrees of the eye's plane (90-30 degree views), where single-precision screen positions and
// attributes of the projected triangles stop being trustworthy.
constexpr double kExactGuard = 16.0;

// What the exact fragment shader needs of one cell (its place in the order, its rectangle on
// screen, its planes and scalar relative to the eye), in single precision as GL takes it.
struct ExactCell {
    std::size_t index;  // in the order
    float rect[4];      // x0, y0, x1, y1 in normalized device coordinates
    float planes[16];   // per face: unit outward normal, offset - normal . eye
    float scalar[4];    // gradient, scalar at the eye
};

// One frame's cells as GL draws them; buffers reused from frame to frame.
struct CellStream {
    // kVerticesPerCell x kFloatsPerVertex floats per index of the order; zeros (an empty
    // triangle fan) where the cell is not projected.
    std::vector<float> vertices;
    std::vector<std::uint8_t> exact_flags;  // per index of the order: takes the exact path
    std::vector<ExactCell> exact_cells;     // those with something on screen, in order
    std::size_t projected = 0;              // cells projected with area on screen
};

// Whether cell `t` takes the exact path: a corner at or behind a perspective eye (the CPU
// renderer's test), or projected so far outside the image (a corner just in front of the eye)
// that single-precision screen positions and attributes would not hold it.
bool needs_exact(const TetMesh& mesh, CellId t, const CameraFrame& camera);

// The exact cell of order index `index` (tet `t`): its screen rectangle, planes and scalar.
// False when nothing of it in front of the eye reaches the image (or the tet is degenerate).
bool exact_cell(const TetMesh& mesh, std::span<const float> scalar, CellId t, std::size_t index,
                const CameraFrame& camera, ExactCell& out);

// Fills `stream` for `order` (real cells of `mesh`, back to front; `scalar` one per point).
// Orthographic cameras send no cell to the exact path. Cost: O(cells), parallel over cells
// (core/parallel.h), then a serial pass over the exact ones.
void classify_cells(const TetMesh& mesh, std::span<const float> scalar,
                    std::span<const CellId> order, const CameraFrame& camera, CellStream& stream);

}  // namespace tr::gl::detail
