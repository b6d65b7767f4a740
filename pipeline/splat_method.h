#pragma once
// The `splat` method (texture-mapping paper, 3.1; project/splat_renderer.h): the points of the
// scene's mesh — a regular grid's lattice, or any mesh's points — each spread by a
// reconstruction kernel and composited back to front, over the opaque geometry. One volume.
//
// Method keys (docs/scene-file.md): kernel ("crawfis-max", the paper's cubic, default;
// "gaussian"), spacing (the lattice spacing h the kernel is scaled to, > 0; default: that of a
// lattice filling the points' bounds, project/splat_renderer.h lattice_spacing, exact for a
// regular grid with the same spacing on every axis), compositing ("per-splat", default;
// "sheet-buffer": Westover's sheet buffer, project/splat_renderer.h). Textured vector splats
// (the paper's 4.2, project/vector_splat.h): vectors (the name of a 3-component point array:
// each splat a streak-textured rectangle along its projected vector), cycle (N textures in the
// animation's cycle, 1 to kMaxSplatCycle, default 8), frame (which of them, taken modulo N;
// default 0); cycle and frame need vectors, vectors refuses the sheet buffer.

#include <core/image.h>
#include <core/result.h>

#include <memory>
#include <pipeline/method.h>
#include <pipeline/pipeline.h>
#include <string>
#include <vector>

namespace tr {

std::unique_ptr<RenderMethod> make_splat_method();

inline constexpr int kMaxSplatCycle = 1024;

struct SplatCycle {
    std::vector<Image> frames;       // frame k of the cycle at index k, k = 0 .. N - 1
    NamedStats stats;                // frame 0's (each frame's raster_ms is about the same)
    std::vector<std::string> notes;  // frame 0's
};

// The N frames of the animated textured vector splats of `scene` (its volume 0's points, its
// scalar for colour, the point array `vectors` for direction and length; the scene's own
// method keys kernel, spacing are kept, method set to splat): frame k is
// pipeline.render(scene with method keys vectors, cycle = N, frame = k). Playing frames 0 .. N-1
// in a loop shows the flow moving (frame N would be frame 0 again). Errors: cycle outside 1 ..
// kMaxSplatCycle; the scene's or pipeline's (a missing mesh or scalar; no point array
// `vectors`, or one that is not 3 components: "splat: the point array 'NAME' has 1 component
// (a scalar); vectors need 3"). Cost: N renders; the mesh is loaded once (the pipeline's cache).
Result<SplatCycle> render_splat_cycle(Pipeline& pipeline, const Scene& scene,
                                      const std::string& vectors, int cycle,
                                      const RenderOptions& options = {});

}  // namespace tr
