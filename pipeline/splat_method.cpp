#include <core/parallel.h>
#include <project/splat_renderer.h>

#include <cmath>
#include <pipeline/scene_volumes.h>
#include <pipeline/splat_method.h>

namespace tr {
namespace {

std::optional<SplatKernel> parse_kernel(std::string_view name) {
    for (SplatKernel k : {SplatKernel::kCrawfisMax, SplatKernel::kGaussian}) {
        if (splat_kernel_name(k) == name) return k;
    }
    return std::nullopt;
}

std::optional<SplatCompositing> parse_compositing(std::string_view name) {
    if (name == "per-splat") return SplatCompositing::kPerSplat;
    if (name == "sheet-buffer") return SplatCompositing::kSheetBuffer;
    return std::nullopt;
}

class Splat final : public RenderMethod {
  public:
    std::string_view name() const override { return "splat"; }

    Status check(const Scene& scene, const RenderOptions& options) const override {
        TR_TRY_STATUS(only_keys(scene, name(), {"kernel", "spacing", "compositing"}));
        if (const MethodOption* o = option(scene, "compositing")) {
            const auto* v = std::get_if<std::string>(o);
            if (!v || !parse_compositing(*v)) {
                return method_option_error(scene, "compositing",
                                           "expected \"per-splat\" or \"sheet-buffer\"");
            }
        }
        if (const MethodOption* o = option(scene, "kernel")) {
            const auto* v = std::get_if<std::string>(o);
            if (!v || !parse_kernel(*v)) {
                return method_option_error(scene, "kernel",
                                           "expected \"crawfis-max\" or \"gaussian\"");
            }
        }
        if (const MethodOption* o = option(scene, "spacing")) {
            const double* d = std::get_if<double>(o);
            const std::int64_t* i = std::get_if<std::int64_t>(o);
            const double v = d ? *d : i ? static_cast<double>(*i) : 0.0;
            if (!(v > 0) || !std::isfinite(v)) {
                return method_option_error(scene, "spacing", "expected a number > 0");
            }
        }
        auto refuse = [&](const std::string& what) {
            return make_error(ErrorCode::kUnsupported, "splat: " + what, scene.source);
        };
        if (scene.volumes.size() > 1) {
            return refuse(
                "draws one volume (several overlapping volumes: projected-tetrahedra, the "
                "default, or pbvr-image)");
        }
        if (scene.flow_volume) return refuse("does not draw flow volumes");
        if (options.reference) {
            return refuse(
                "the reference ray caster is an integrator of projected-tetrahedra, not of "
                "splat");
        }
        return {};
    }

    Result<RenderResult> render(Pipeline& pipeline, const Scene& scene,
                                const RenderOptions&) const override {
        RenderResult result;
        if (scene.method && (scene.method->repetitions || scene.method->seed)) {
            result.notes.push_back(
                "repetitions and seed apply to the stochastic methods: splat ignores them");
        }
        TR_TRY(const std::unique_ptr<SceneVolumes> loaded,
               load_scene_volumes(pipeline, scene, result.stats));
        const CameraFrame frame(scene.camera, scene.width, scene.height);
        TR_TRY(const OpaqueLayer layer, opaque_layer(pipeline, scene, frame, result.stats));
        SplatKernel kernel = SplatKernel::kCrawfisMax;
        if (const MethodOption* o = option(scene, "kernel")) {
            kernel = *parse_kernel(std::get<std::string>(*o));
        }
        SplatCompositing compositing = SplatCompositing::kPerSplat;
        if (const MethodOption* o = option(scene, "compositing")) {
            compositing = *parse_compositing(std::get<std::string>(*o));
        }
        const std::vector<Vec3>& points = loaded->meshes[0]->tets.points();
        double spacing = lattice_spacing(points);
        if (const MethodOption* o = option(scene, "spacing")) {
            const double* d = std::get_if<double>(o);
            spacing = d ? *d : static_cast<double>(std::get<std::int64_t>(*o));
        }
        if (!(spacing > 0)) {
            return make_error(ErrorCode::kInvalidArgument,
                              "splat: the mesh's points have no spacing (fewer than two, or all "
                              "at one place); give the method key 'spacing'",
                              scene.volumes[0].mesh.string());
        }
        const SplatFootprint footprint(kernel);
        SplatInputs in;
        in.points = points;
        in.scalar = loaded->scalars[0];
        in.spacing = spacing;
        in.tf = &scene.volumes[0].transfer_function;
        in.footprint = &footprint;
        in.camera = &frame;
        in.background = scene.background;
        in.compositing = compositing;
        if (!layer.depth.empty()) {
            in.opaque_color = &layer.color;
            in.opaque_depth = &layer.depth;
        }
        SplatStats stats;
        result.image = render_splats(in, &stats);
        NamedStats& s = result.stats;
        s.set("raster_ms", stats.raster_ms);
        s.set("points", points.size());
        s.set("splats_drawn", stats.splats_drawn);
        s.set("fragments", stats.fragments);
        s.set("method", std::string(name()));
        s.set("kernel", std::string(splat_kernel_name(kernel)));
        s.set("spacing", spacing);
        s.set("compositing",
              std::string(compositing == SplatCompositing::kSheetBuffer ? "sheet-buffer"
                                                                        : "per-splat"));
        if (compositing == SplatCompositing::kSheetBuffer) {
            s.set("sheets", stats.sheets);
            s.set("sheet_axis", stats.sheet_axis);
        }
        s.set("threads", thread_count());
        s.set("width", scene.width);
        s.set("height", scene.height);
        return result;
    }
};

}  // namespace

std::unique_ptr<RenderMethod> make_splat_method() { return std::make_unique<Splat>(); }

}  // namespace tr
