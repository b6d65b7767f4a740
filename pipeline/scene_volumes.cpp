#include <core/stopwatch.h>
#include <pipeline/scene_volumes.h>
#include <project/opaque_geometry.h>

#include <chrono>
#include <string>

namespace tr {

Result<std::unique_ptr<SceneVolumes>> load_scene_volumes(Pipeline& pipeline, const Scene& scene,
                                                         NamedStats& stats) {
    auto loaded = std::make_unique<SceneVolumes>();
    double load_ms = 0, tetrahedralize_ms = 0;
    std::size_t cells = 0;
    for (std::size_t v = 0; v < scene.volumes.size(); ++v) {
        const SceneVolume& volume = scene.volumes[v];
        // With several volumes, errors say which.
        auto name = [&](Error e) {
            if (scene.volumes.size() > 1) {
                e.message = "volume " + std::to_string(v) + ": " + e.message;
            }
            return e;
        };
        auto mesh = pipeline.mesh(volume);
        if (!mesh.ok()) return name(mesh.error());
        auto values = pipeline.scalar(volume, (*mesh)->tets);
        if (!values.ok()) return name(values.error());
        load_ms += (*mesh)->read_ms;
        tetrahedralize_ms += (*mesh)->tetrahedralize_ms;
        cells += (*mesh)->tets.num_real_tets();
        loaded->meshes.push_back(std::move(mesh).value());
        loaded->scalars.push_back(std::move(values).value());
    }
    for (std::size_t v = 0; v < scene.volumes.size(); ++v) {
        loaded->scene.volumes.push_back(
            {&loaded->meshes[v]->tets, loaded->scalars[v], &scene.volumes[v].transfer_function});
    }
    stats.set("load_ms", load_ms);
    stats.set("tetrahedralize_ms", tetrahedralize_ms);
    stats.set("cells", cells);
    stats.set("volumes", scene.volumes.size());
    return loaded;
}

Result<OpaqueLayer> opaque_layer(Pipeline& pipeline, const Scene& scene, const CameraFrame& frame,
                                 NamedStats& stats) {
    TR_TRY(const OpaqueSet opaque, pipeline.opaque(scene));
    const auto start = std::chrono::steady_clock::now();
    OpaqueLayer layer;
    if (!opaque.empty()) layer = render_opaque(opaque.layers(), frame, scene.background);
    stats.set("opaque_ms", ms_since(start));
    return layer;
}

View scene_view(const Scene& scene, const RenderOptions& options, const CameraFrame& frame,
                const OpaqueLayer& layer) {
    View view = view_over(frame, scene.background, layer);
    if (options.transparent) {
        view.background = Vec3(0.0);
        view.opaque_color = nullptr;
    }
    return view;
}

}  // namespace tr
