#pragma once
// A scene's volumes loaded through a Pipeline's cache, each with its scalar, as the renderers of
// several volumes take them (project/volume_scene.h), and its opaque surfaces drawn: one path
// for the segment merge, the particle renderers, splatting and the reference ray caster.

#include <core/result.h>
#include <pipeline/loaded_mesh.h>
#include <pipeline/pipeline.h>
#include <pipeline/render_stats.h>
#include <project/opaque_geometry.h>
#include <project/volume_scene.h>

#include <memory>
#include <vector>

namespace tr {

struct SceneVolumes {
    std::vector<std::shared_ptr<const LoadedMesh>> meshes;  // per scene volume
    std::vector<std::vector<float>> scalars;                // per scene volume, per point
    // Each volume's mesh, scalar and transfer function (no shader, camera or opaque layer yet):
    // pointers into this object and into the scene, valid while both live unmoved.
    VolumeScene scene;
};

// Loads every volume of `scene` and its scalar. Errors are the pipeline's, prefixed with
// "volume N: " when the scene has several. Sets `stats`' load_ms, tetrahedralize_ms (summed),
// cells (real tets, summed) and volumes.
Result<std::unique_ptr<SceneVolumes>> load_scene_volumes(Pipeline& pipeline, const Scene& scene,
                                                         NamedStats& stats);

// The scene's opaque surfaces drawn for `frame` over the background (empty when it has none);
// sets `stats`' opaque_ms.
Result<OpaqueLayer> opaque_layer(Pipeline& pipeline, const Scene& scene, const CameraFrame& frame,
                                 NamedStats& stats);

// The view a scene's volumes are drawn in (project/view.h): `frame`, over `layer` (the opaque
// surfaces drawn, or stops standing in for them; no depth: none) or the scene's background; for
// a transparent picture (RenderOptions::transparent), over black with the layer's depth only.
// Points into `frame` and `layer`.
View scene_view(const Scene& scene, const RenderOptions& options, const CameraFrame& frame,
                const OpaqueLayer& layer);

}  // namespace tr
