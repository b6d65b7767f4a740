#pragma once
// How the viewer makes its picture: projected tetrahedra in OpenGL (the default), or by the
// library on the CPU: particle-based volume rendering (pbvr-image, pbvr-object) or splatting of
// the mesh's points (splat, with textured vector splats whose cycle plays live), or the animated
// flow-texture methods (texture-advection, spot-noise: their frames play in a loop); and the CPU
// modes' settings, from the command line or a scene file's `method` key.

#include <core/result.h>
#include <pipeline/methods/splat_method.h>
#include <pipeline/pipeline.h>
#include <pipeline/scene.h>
#include <project/pbvr/pbvr_image.h>
#include <project/pbvr/pbvr_object.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace tr::viewer {

enum class ViewMethod {
    kProjectedTetrahedra,
    kPbvrImage,
    kPbvrObject,
    kSplat,
    kTextureAdvection,
    kSpotNoise
};
inline constexpr int kViewMethods = 6;

// "projected-tetrahedra", "pbvr-image", "pbvr-object", "splat", "texture-advection",
// "spot-noise": the scene file's method names.
std::string_view view_method_name(ViewMethod method);
std::optional<ViewMethod> view_method_named(std::string_view name);

// texture-advection and spot-noise: drawn by the library's render of the scene (its method keys
// live there), frames 0 .. steps (apps/viewer/animation_worker.h). The viewer shows them only
// when the scene (or --method) names them: the panel cannot switch to them from another method.
inline bool animated_method(ViewMethod method) {
    return method == ViewMethod::kTextureAdvection || method == ViewMethod::kSpotNoise;
}

// Repetitions accumulated when neither the command line nor the scene gives a number: headless
// as `tetrender render` draws the scene (the pipeline's default), interactively until the view
// is good (accumulation stops there).
inline constexpr int kDefaultHeadlessRepetitions = 64;
inline constexpr int kDefaultInteractiveRepetitions = 1024;
inline constexpr int kMaxRepetitions = 1 << 20;
inline constexpr int kMaxBatch = 1024;

// The particle-based modes' settings (both kept, so that the panel can switch between them).
struct PbvrSettings {
    int repetitions = kDefaultInteractiveRepetitions;  // accumulation stops here (>= 1)
    int batch = 0;             // repetitions per batch (0: the method's default, below)
    std::uint64_t seed = 1;    // batch b of a view renders with seed + b
    ImagePbvrOptions image;    // depth, stratified (repetitions and seed: per batch)
    ObjectPbvrOptions object;  // subpixel_level, sampling (repetitions and seed: per batch)
    // O-PBVR: the particles of the first batches of a view are kept (ObjectParticleSet) up to
    // this many bytes, to re-render after a transfer-function edit or an orthographic rotation.
    std::size_t max_kept_bytes = std::size_t{512} << 20;
    // splat: the scene's splat keys and --vectors / --cycle (pipeline/methods/splat_method.h; its
    // frame comes with each request), and how many of the mesh's points are the file's (0: all; the
    // convexification's come after them and are not drawn).
    SplatSettings splat;
    std::size_t splat_points = 0;
    // texture-advection, spot-noise: the method as checked (its keys, repetitions, seed), and
    // its `steps` (frames 0 .. steps; the methods' default 100).
    MethodSpec animation;
    int animation_steps = 100;

    // The batch size for `method`: `batch`, else 16 for pbvr-image (a batch's cost is mostly
    // the segments on the pixel rays, the same for 1 or 16 repetitions) and 4 for pbvr-object
    // (its cost is per repetition: 4 keeps a batch short).
    int batch_for(ViewMethod method) const;
};

// What the command line says (each overrides the scene's `method` key).
struct MethodArgs {
    std::string method;   // empty: the scene's method, else projected-tetrahedra
    int repetitions = 0;  // 0: the scene's, else the default for `headless`
    std::optional<std::int64_t> seed;
    int batch = 0;  // 0: the method's default
    bool headless = false;
    std::string vectors;  // splat: textured vector splats of this point array (method splat)
    int cycle = 0;        // splat: textures in their cycle (0: the scene's, else 8)
};

struct ResolvedMethod {
    ViewMethod method = ViewMethod::kProjectedTetrahedra;
    PbvrSettings pbvr;
};

// The method and settings for `scene` (its `method` key, if any) and the command line. The
// scene's own method keys (pbvr-image's depth and stratified, pbvr-object's subpixel_level and
// sampling) are checked as `tetrender render` checks them (Pipeline::check) and kept; a
// command-line method other than the scene's drops them. `pipeline` only checks. Errors:
// kInvalidArgument for an unknown --method, a method the viewer does not draw (naming the six it
// does), --vectors or --cycle for another method than splat, the pipeline's errors for the
// scene's method keys (texture-advection and spot-noise need theirs: `vectors`, and spot-noise's
// `iso`).
Result<ResolvedMethod> resolve_method(const Pipeline& pipeline, const Scene& scene,
                                      const MethodArgs& args);

}  // namespace tr::viewer
