#include <overlay/scene_marks.h>
#include <pipeline/annotations.h>

namespace tr {

Status annotate(Image& image, const Scene& scene, Pipeline& pipeline,
                const AnnotationOptions& options) {
    if (image.width != scene.width || image.height != scene.height) {
        return make_error(ErrorCode::kInvalidArgument,
                          "annotations: the picture is " + std::to_string(image.width) + "x" +
                              std::to_string(image.height) + ", the scene's " +
                              std::to_string(scene.width) + "x" + std::to_string(scene.height));
    }
    if (scene.volumes.empty()) return {};
    if (options.bounding_box) {
        Bounds3 bounds;
        for (const SceneVolume& volume : scene.volumes) {
            auto mesh = pipeline.mesh(volume);
            if (!mesh) return mesh.error();
            const Bounds3 b = (*mesh)->tets.bounds();
            if (!b.empty()) {
                bounds.extend(b.lo);
                bounds.extend(b.hi);
            }
        }
        draw_bounding_box(image, scene.camera, bounds, options.box_color);
    }
    if (options.axes) {
        auto font = Font::shared_default();
        if (!font) return font.error();
        draw_axes_triad(image, scene.camera, *font);
    }
    if (options.legend) {
        const std::size_t count = options.every_volume ? scene.volumes.size() : 1;
        for (std::size_t v = 0; v < count; ++v) {
            const SceneVolume& volume = scene.volumes[v];
            LegendSpec spec = options.legend_spec;
            if (v > 0) spec.lo = spec.hi = std::nullopt;  // the overrides are volume 0's
            if (spec.title.empty() || v > 0) {
                spec.title = volume.scalar;
                if (volume.component >= 0) {
                    spec.title.append("[").append(std::to_string(volume.component)).append("]");
                }
            }
            if (!spec.background) spec.background = Vec3f(scene.background);
            if (volume.log_scale) spec.log_scale = true;
            // Each legend avoids what is drawn already, the earlier legends included.
            auto layout = draw_legend(image, volume.transfer_function, spec);
            if (!layout) {
                Error e = layout.error();
                if (count > 1) e.message = "volume " + std::to_string(v) + ": " + e.message;
                return e;
            }
        }
    }
    return {};
}

}  // namespace tr
