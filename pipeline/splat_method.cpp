#include <core/parallel.h>
#include <mesh/field.h>
#include <project/point_spacing.h>
#include <project/splat_renderer.h>
#include <project/vector_splat.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <pipeline/scene_volumes.h>
#include <pipeline/splat_method.h>

namespace tr {
namespace {

// Processor time of this process (every thread) since `start`, ms: the raster's cost, which the
// wall time hides on a machine shared with other jobs.
double cpu_ms_since(std::clock_t start) {
    return 1000.0 * static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
}

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

// The point array `name` of the loaded mesh as one vector per point. Errors: no such array,
// or one without 3 components (a scalar: naming its components).
Result<std::vector<Vec3>> point_vectors(const LoadedMesh& mesh, const std::string& name,
                                        const std::string& where) {
    const Field* field = find_field(mesh.tets.point_fields(), name);
    if (!field) {
        return make_error(ErrorCode::kInvalidArgument,
                          "splat: no point array '" + name + "' for the vectors", where);
    }
    if (field->num_components != 3) {
        return make_error(
            ErrorCode::kInvalidArgument,
            "splat: the point array '" + name + "' has " + std::to_string(field->num_components) +
                (field->num_components == 1 ? " component (a scalar)" : " components") +
                "; vectors need 3",
            where);
    }
    std::vector<Vec3> vectors(field->num_tuples());
    for (std::size_t i = 0; i < vectors.size(); ++i) {
        vectors[i] = {field->get(i, 0), field->get(i, 1), field->get(i, 2)};
    }
    return vectors;
}

// The point array `name` as one radius per point. Errors: no such array, not 1 component, a
// radius that is not > 0 and finite (the first, by point index).
Result<std::vector<float>> point_radii(const LoadedMesh& mesh, const std::string& name,
                                       const std::string& where) {
    const Field* field = find_field(mesh.tets.point_fields(), name);
    if (!field) {
        return make_error(ErrorCode::kInvalidArgument,
                          "splat: no point array '" + name + "' for the radius", where);
    }
    if (field->num_components != 1) {
        return make_error(ErrorCode::kInvalidArgument,
                          "splat: the radius array '" + name + "' has " +
                              std::to_string(field->num_components) + " components; a radius is 1",
                          where);
    }
    std::vector<float> radii(field->num_tuples());
    for (std::size_t i = 0; i < radii.size(); ++i) {
        const double r = field->get(i);
        const auto f = static_cast<float>(r);
        if (!(f > 0) || !std::isfinite(f)) {
            char value[32];
            std::snprintf(value, sizeof value, "%g", r);
            return make_error(ErrorCode::kInvalidArgument,
                              "splat: the radius array '" + name + "' has " + value + " at point " +
                                  std::to_string(i) + " (each radius must be > 0 and finite)",
                              where);
        }
        radii[i] = f;
    }
    return radii;
}

class Splat final : public RenderMethod {
  public:
    std::string_view name() const override { return "splat"; }

    Status check(const Scene& scene, const RenderOptions& options) const override {
        TR_TRY_STATUS(
            only_keys(scene, name(),
                      {"kernel", "spacing", "compositing", "radius", "vectors", "cycle", "frame"}));
        if (const MethodOption* o = option(scene, "radius")) {
            const auto* v = std::get_if<std::string>(o);
            if (!v || v->empty()) {
                return method_option_error(scene, "radius", "expected the name of a point array");
            }
            if (option(scene, "vectors")) {
                return method_option_error(scene, "radius",
                                           "applies to scalar splats, not with 'vectors'");
            }
        }
        if (const MethodOption* o = option(scene, "vectors")) {
            const auto* v = std::get_if<std::string>(o);
            if (!v || v->empty()) {
                return method_option_error(scene, "vectors", "expected the name of a point array");
            }
            const MethodOption* c = option(scene, "compositing");
            if (c && std::get_if<std::string>(c) &&
                *std::get_if<std::string>(c) == "sheet-buffer") {
                return method_option_error(scene, "compositing",
                                           "the sheet buffer is for scalar splats; vector splats "
                                           "are composited per splat");
            }
        }
        if (const MethodOption* o = option(scene, "cycle")) {
            const std::int64_t* i = std::get_if<std::int64_t>(o);
            if (!i || *i < 1 || *i > kMaxSplatCycle) {
                return method_option_error(
                    scene, "cycle",
                    "expected an integer from 1 to " + std::to_string(kMaxSplatCycle));
            }
        }
        if (const MethodOption* o = option(scene, "frame")) {
            if (!std::get_if<std::int64_t>(o)) {
                return method_option_error(scene, "frame", "expected an integer");
            }
        }
        for (const char* key : {"cycle", "frame"}) {
            if (option(scene, key) && !option(scene, "vectors")) {
                return method_option_error(scene, key,
                                           "applies to vector splats: give the key 'vectors'");
            }
        }
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
        if (const MethodOption* o = option(scene, "vectors")) {
            TR_TRY(const std::vector<Vec3> vectors,
                   point_vectors(*loaded->meshes[0], std::get<std::string>(*o),
                                 scene.volumes[0].mesh.string()));
            StreakTextureOptions texture_options;
            if (const MethodOption* c = option(scene, "cycle")) {
                texture_options.cycle = static_cast<int>(std::get<std::int64_t>(*c));
            }
            int k = 0;
            if (const MethodOption* f = option(scene, "frame")) {
                const std::int64_t n = texture_options.cycle;
                k = static_cast<int>(((std::get<std::int64_t>(*f) % n) + n) % n);
            }
            const StreakTexture texture(texture_options);
            VectorSplatInputs in;
            in.points = points;
            in.scalar = loaded->scalars[0];
            in.vectors = vectors;
            in.spacing = spacing;
            in.tf = &scene.volumes[0].transfer_function;
            in.texture = &texture;
            in.camera = &frame;
            in.frame = k;
            in.background = scene.background;
            if (!layer.depth.empty()) {
                in.opaque_color = &layer.color;
                in.opaque_depth = &layer.depth;
            }
            VectorSplatStats stats;
            const std::clock_t cpu = std::clock();
            result.image = render_vector_splats(in, &stats);
            NamedStats& s = result.stats;
            s.set("raster_ms", stats.raster_ms);
            s.set("raster_cpu_ms", cpu_ms_since(cpu));
            s.set("points", points.size());
            s.set("splats_drawn", stats.splats_drawn);
            s.set("fragments", stats.fragments);
            s.set("method", std::string(name()));
            s.set("vectors", std::get<std::string>(*o));
            s.set("cycle", texture_options.cycle);
            s.set("frame", k);
            s.set("fastest", stats.fastest);
            s.set("spacing", spacing);
            s.set("threads", thread_count());
            s.set("width", scene.width);
            s.set("height", scene.height);
            if (option(scene, "kernel")) {
                result.notes.push_back("vector splats are textured with streaks: kernel ignored");
            }
            return result;
        }
        // Each splat's scale: the radius array named; else, for points that are not a lattice
        // (a cloud, a mesh's nodes) and no `spacing` given, each point's local spacing, so that
        // dense and sparse regions get the optical depth of their own density; else the
        // lattice spacing.
        std::vector<float> radii;
        std::string scaled_by = "spacing";
        if (const MethodOption* o = option(scene, "radius")) {
            TR_TRY(radii, point_radii(*loaded->meshes[0], std::get<std::string>(*o),
                                      scene.volumes[0].mesh.string()));
            scaled_by = "radius array";
        } else if (!option(scene, "spacing") && compositing == SplatCompositing::kPerSplat &&
                   !is_axis_aligned_lattice(points)) {
            const auto spacing_start = std::chrono::steady_clock::now();
            radii = local_spacing(points);
            result.stats.set("local_spacing_ms", ms_since(spacing_start));
            scaled_by = "local spacing";
        }
        const SplatFootprint footprint(kernel);
        SplatInputs in;
        in.radius = radii;
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
        const std::clock_t cpu = std::clock();
        result.image = render_splats(in, &stats);
        NamedStats& s = result.stats;
        s.set("scaled_by", scaled_by);
        s.set("raster_ms", stats.raster_ms);
        s.set("raster_cpu_ms", cpu_ms_since(cpu));
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

Result<SplatCycle> render_splat_cycle(Pipeline& pipeline, const Scene& scene,
                                      const std::string& vectors, int cycle,
                                      const RenderOptions& options) {
    if (cycle < 1 || cycle > kMaxSplatCycle) {
        return make_error(ErrorCode::kInvalidArgument,
                          "splat: the cycle must have 1 to " + std::to_string(kMaxSplatCycle) +
                              " frames (got " + std::to_string(cycle) + ")",
                          scene.source);
    }
    Scene s = scene;
    if (!s.method) s.method = MethodSpec{};
    s.method->name = "splat";
    s.method->options["vectors"] = vectors;
    s.method->options["cycle"] = std::int64_t{cycle};
    SplatCycle out;
    for (int k = 0; k < cycle; ++k) {
        s.method->options["frame"] = std::int64_t{k};
        TR_TRY(RenderResult r, pipeline.render(s, options));
        if (k == 0) out.stats = r.stats, out.notes = r.notes;
        out.frames.push_back(std::move(r.image));
    }
    return out;
}

}  // namespace tr
