#pragma once
// The `splat` method (texture-mapping paper, 3.1; project/splat/splat_renderer.h): the points of
// the scene's mesh — a regular grid's lattice, or any mesh's points — each spread by a
// reconstruction kernel and composited back to front, over the opaque geometry. One volume.
//
// Method keys (docs/scene-file.md): kernel ("crawfis-max", the paper's cubic, default;
// "gaussian"), spacing (the lattice spacing h the kernel is scaled to, > 0; default: that of a
// lattice filling the points' bounds, project/splat/splat_renderer.h lattice_spacing, exact for a
// regular grid with the same spacing on every axis), compositing ("per-splat", default;
// "sheet-buffer": Westover's sheet buffer, project/splat/splat_renderer.h). Textured vector splats
// (the paper's 4.2, project/splat/vector_splat.h): vectors (the name of a 3-component point array:
// each splat a streak-textured rectangle along its projected vector), cycle (N textures in the
// animation's cycle, 1 to kMaxSplatCycle, default 8), frame (which of them, taken modulo N;
// default 0); cycle and frame need vectors, vectors refuses the sheet buffer.

#include <core/camera.h>
#include <core/image.h>
#include <core/result.h>
#include <mesh/tet_mesh.h>
#include <pipeline/methods/method.h>
#include <pipeline/pipeline.h>
#include <project/opaque_geometry.h>
#include <project/splat/splat_renderer.h>
#include <project/transfer_function.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace tr {

std::unique_ptr<RenderMethod> make_splat_method();

// The method keys as the picture takes them (after Pipeline::check accepted them).
struct SplatSettings {
    SplatKernel kernel = SplatKernel::kCrawfisMax;
    bool kernel_given = false;  // vector splats ignore it (a note says so)
    SplatCompositing compositing = SplatCompositing::kPerSplat;
    std::optional<double> spacing;  // else the lattice's, or each point's local spacing
    std::string radius;             // a 1-component point array, or empty
    std::string vectors;            // a 3-component point array, or empty
    int cycle = 8;
    std::int64_t frame = 0;  // taken modulo cycle
};

// The scene's splat keys (a scene without them: the defaults).
SplatSettings splat_settings(const Scene& scene);

// What one splat picture is made of: the first `points` points of `mesh` (0: all; the points
// real tets use come first, convexification appends its own), their scalar (one per point of
// `mesh` at least), the transfer function, camera, background and the opaque layer drawn.
// `where` names the mesh in errors.
struct SplatPicture {
    const TetMesh* mesh = nullptr;
    std::size_t points = 0;
    std::span<const float> scalar;
    const TransferFunction* tf = nullptr;
    View view;  // camera, background, opaque layer (project/view.h)
    std::string where;
};

// The picture the `splat` method draws (its render() is this after loading): scalar splats
// scaled as `settings` says, or, with `vectors`, textured vector splats at frame `frame` of
// their cycle. Errors (one line, naming `where`): no spacing, a missing or malformed radius or
// vector array. Stats (raster time, points, fragments, ...) go to `stats`, notes to `notes`.
Result<Image> render_splat_picture(const SplatPicture& picture, const SplatSettings& settings,
                                   NamedStats* stats = nullptr,
                                   std::vector<std::string>* notes = nullptr);

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
