#pragma once
// The exact renderer that needs no visibility order: every pixel's ray segments through the
// tets of every volume (project/tet_fragments.h), merged by depth, and the ray integral of the
// spec's optical model taken over them front to back. Where one segment covers an interval
// alone, its colour and opacity are the volume's shader's (project/segment_shader.h: the
// default integrator, within half an 8-bit level of the exact integral); where segments of
// several volumes overlap, their extinctions and emissions add (scene.md, "Several volumes in
// one space") and the interval is integrated directly: split where any of the scalars crosses
// a control point of its transfer function, then midpoint steps of optical depth at most 0.02.
//
// It draws several meshes in one space (fused rendering, beyond the particle-based paper:
// deterministic and noise-free, the picture stochastic methods are measured against), and any
// single mesh whose cells cannot be put in a proven order (tangled cells, a boundary TetGen
// cannot convexify): for one volume it is the projected-tetrahedra picture, composited per
// pixel in depth order instead of per cell in visibility order. Tiles of 32 x 32 pixels keep
// their segments in memory (an A-buffer per tile); threads work on tiles, so the picture is
// bit-identical whatever the thread count.

#include <project/volume_scene.h>

#include <cstddef>
#include <vector>

namespace tr {

struct SegmentMergeStats {
    std::size_t fragments = 0;          // (cell, pixel) segments of positive length
    std::size_t overlap_intervals = 0;  // intervals where segments of several volumes overlap
    double raster_ms = 0;
};

// The picture. Preconditions: the scene's sizes agree (scalar per point, opaque buffers of the
// camera's size); every volume has a shader (VolumeData::shader) of its transfer function.
// Cost: O(fragments log fragments per pixel) plus the overlap intervals' integration; memory
// per worker: one tile's segments (about 24 bytes each).
//
// `alpha`, when given, is resized to width x height (row-major, row 0 at the top, as Image) and
// receives per pixel the opacity of the volumes there, 1 - the transparency left after the
// pixel's pieces (0 where there are none): the returned picture is then, up to float rounding,
// the picture the same call returns over black with no opaque colour plus (1 - alpha) times the
// background or opaque colour (premultiplied RGBA for a compositor). An opaque depth without an
// opaque colour stops the segments there. Asking for alpha changes no bit of the picture.
Image render_segment_merge(const VolumeScene& scene, SegmentMergeStats* stats = nullptr,
                           std::vector<float>* alpha = nullptr);

}  // namespace tr
