#include <core/parallel.h>
#include <core/stopwatch.h>
#include <mesh/field.h>
#include <pipeline/methods/splat_method.h>
#include <pipeline/scene_volumes.h>
#include <project/splat/point_spacing.h>
#include <project/splat/splat_renderer.h>
#include <project/splat/vector_splat.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>

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
Result<std::vector<Vec3>> point_vectors(const TetMesh& mesh, const std::string& name,
                                        const std::string& where) {
    const Field* field = find_field(mesh.point_fields(), name);
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
Result<std::vector<float>> point_radii(const TetMesh& mesh, const std::string& name,
                                       const std::string& where) {
    const Field* field = find_field(mesh.point_fields(), name);
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

// What scalar and vector splats' inputs share, from the picture.
template <class Inputs>
void fill_common(Inputs& in, std::span<const Vec3> points, std::span<const float> scalar,
                 double spacing, const SplatPicture& picture) {
    in.points = points;
    in.scalar = scalar;
    in.spacing = spacing;
    in.tf = picture.tf;
    static_cast<View&>(in) = picture.view;
}

// The stats both kinds of splats report.
template <class Stats>
void set_raster_stats(NamedStats& s, const Stats& stats, std::clock_t cpu, std::size_t points,
                      double spacing) {
    s.set("raster_ms", stats.raster_ms);
    s.set("raster_cpu_ms", cpu_ms_since(cpu));
    s.set("points", points);
    s.set("splats_drawn", stats.splats_drawn);
    s.set("fragments", stats.fragments);
    s.set("method", std::string("splat"));
    s.set("spacing", spacing);
}

const MethodKeys kSplatKeys{
    .keys = {{.key = "kernel",
              .type = KeyType::kChoice,
              .default_value = "`\"crawfis-max\"`",
              .doc = "`crawfis-max`: the paper's cubic; `gaussian`",
              .choices = {"crawfis-max", "gaussian"}},
             {.key = "spacing",
              .type = KeyType::kNumber,
              .default_value = "from the points",
              .doc = "the lattice spacing the kernel is scaled to; default: that of a lattice "
                     "filling the points' bounds, exact for a regular grid with one spacing",
              .lo = 0,
              .open_lo = true},
             {.key = "compositing",
              .type = KeyType::kChoice,
              .default_value = "`\"per-splat\"`",
              .doc = "`per-splat`, the paper's: each splat composited whole, back to front; "
                     "`sheet-buffer`: Westover's sheet buffer, the splats summed per sheet of "
                     "thickness `spacing` across the lattice axis nearest the view (no popping "
                     "during a rotation; docs/benchmarks.md)",
              .choices = {"per-splat", "sheet-buffer"}},
             {.key = "radius",
              .type = KeyType::kString,
              .doc = "a 1-component point array: each point's own kernel scale h (SPH smoothing "
                     "lengths); each > 0 and finite, the first that is not is an error naming "
                     "its point; not with `vectors`",
              .expected = "the name of a point array"},
             {.key = "vectors",
              .type = KeyType::kString,
              .doc = "a 3-component point array: textured vector splats (the paper's 4.2), each "
                     "point a streak-textured rectangle along its projected vector, coloured by "
                     "the scalar; per-splat compositing only",
              .expected = "the name of a point array"},
             {.key = "cycle",
              .type = KeyType::kInteger,
              .default_value = "8",
              .doc = "with `vectors`: N textures in the animation's cycle",
              .lo = 1,
              .hi = kMaxSplatCycle},
             {.key = "frame",
              .type = KeyType::kInteger,
              .default_value = "0",
              .doc = "with `vectors`: which texture of the cycle, modulo N (`render_splat_cycle` "
                     "in pipeline/methods/splat_method.h renders all N)"}}};

class Splat final : public RenderMethod {
  public:
    std::string_view name() const override { return "splat"; }

    const MethodKeys& keys() const override { return kSplatKeys; }

    Status check(const Scene& scene, const RenderOptions& options) const override {
        TR_TRY_STATUS(check_method_keys(scene, name(), keys()));
        // The rules between keys.
        if (option(scene, "radius") && option(scene, "vectors")) {
            return method_option_error(scene, "radius",
                                       "applies to scalar splats, not with 'vectors'");
        }
        if (option(scene, "vectors") && string_key(scene, "compositing") == "sheet-buffer") {
            return method_option_error(scene, "compositing",
                                       "the sheet buffer is for scalar splats; vector splats "
                                       "are composited per splat");
        }
        for (const char* key : {"cycle", "frame"}) {
            if (option(scene, key) && !option(scene, "vectors")) {
                return method_option_error(scene, key,
                                           "applies to vector splats: give the key 'vectors'");
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
                                const RenderOptions& options) const override {
        RenderResult result;
        TR_TRY(const std::unique_ptr<SceneVolumes> loaded,
               load_scene_volumes(pipeline, scene, result.stats));
        const CameraFrame frame(scene.camera, scene.width, scene.height);
        TR_TRY(const OpaqueLayer layer, opaque_layer(pipeline, scene, frame, result.stats));
        SplatPicture picture;
        picture.mesh = &loaded->meshes[0]->tets;
        picture.scalar = loaded->scalars[0];
        picture.tf = &scene.volumes[0].transfer_function;
        picture.view = scene_view(scene, options, frame, layer);
        picture.where = scene.volumes[0].mesh.string();
        TR_TRY(result.image,
               render_splat_picture(picture, splat_settings(scene), &result.stats, &result.notes));
        return result;
    }
};

}  // namespace

std::unique_ptr<RenderMethod> make_splat_method() { return std::make_unique<Splat>(); }

SplatSettings splat_settings(const Scene& scene) {
    SplatSettings settings;
    if (option(scene, "kernel")) {
        settings.kernel = parse_kernel(string_key(scene, "kernel")).value_or(settings.kernel);
        settings.kernel_given = true;
    }
    settings.compositing =
        parse_compositing(string_key(scene, "compositing")).value_or(settings.compositing);
    if (option(scene, "spacing")) settings.spacing = number_key(scene, "spacing", 0.0);
    settings.radius = string_key(scene, "radius");
    settings.vectors = string_key(scene, "vectors");
    settings.cycle = static_cast<int>(integer_key(scene, "cycle", settings.cycle));
    settings.frame = integer_key(scene, "frame", settings.frame);
    return settings;
}

Result<Image> render_splat_picture(const SplatPicture& picture, const SplatSettings& settings,
                                   NamedStats* stats_out, std::vector<std::string>* notes) {
    const TetMesh& mesh = *picture.mesh;
    const std::size_t count =
        picture.points > 0 ? std::min(picture.points, mesh.num_points()) : mesh.num_points();
    const std::span<const Vec3> points(mesh.points().data(), count);
    const std::span<const float> scalar = picture.scalar.subspan(0, count);
    NamedStats discard;
    NamedStats& s = stats_out ? *stats_out : discard;
    double spacing = settings.spacing.value_or(lattice_spacing(points));
    if (!(spacing > 0)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "splat: the mesh's points have no spacing (fewer than two, or all at "
                          "one place); give the method key 'spacing'",
                          picture.where);
    }
    if (!settings.vectors.empty()) {
        TR_TRY(std::vector<Vec3> vectors, point_vectors(mesh, settings.vectors, picture.where));
        vectors.resize(count);
        StreakTextureOptions texture_options;
        texture_options.cycle = settings.cycle;
        const std::int64_t n = texture_options.cycle;
        const int k = static_cast<int>(((settings.frame % n) + n) % n);
        const StreakTexture texture(texture_options);
        VectorSplatInputs in;
        fill_common(in, points, scalar, spacing, picture);
        in.vectors = vectors;
        in.texture = &texture;
        in.frame = k;
        VectorSplatStats stats;
        const std::clock_t cpu = std::clock();
        Image image = render_vector_splats(in, &stats);
        set_raster_stats(s, stats, cpu, points.size(), spacing);
        s.set("vectors", settings.vectors);
        s.set("cycle", texture_options.cycle);
        s.set("frame", k);
        s.set("fastest", stats.fastest);
        s.set("threads", thread_count());
        if (settings.kernel_given && notes) {
            notes->push_back("vector splats are textured with streaks: kernel ignored");
        }
        return image;
    }
    // Each splat's scale: the radius array named; else, for points that are not a lattice (a
    // cloud, a mesh's nodes) and no `spacing` given, each point's local spacing, so that dense
    // and sparse regions get the optical depth of their own density; else the lattice spacing.
    std::vector<float> radii;
    std::string scaled_by = "spacing";
    if (!settings.radius.empty()) {
        TR_TRY(radii, point_radii(mesh, settings.radius, picture.where));
        radii.resize(count);
        scaled_by = "radius array";
    } else if (!settings.spacing && settings.compositing == SplatCompositing::kPerSplat &&
               !is_axis_aligned_lattice(points)) {
        const auto spacing_start = std::chrono::steady_clock::now();
        radii = local_spacing(points);
        s.set("local_spacing_ms", ms_since(spacing_start));
        scaled_by = "local spacing";
    }
    const SplatFootprint footprint(settings.kernel);
    SplatInputs in;
    fill_common(in, points, scalar, spacing, picture);
    in.radius = radii;
    in.footprint = &footprint;
    in.compositing = settings.compositing;
    SplatStats stats;
    const std::clock_t cpu = std::clock();
    Image image = render_splats(in, &stats);
    s.set("scaled_by", scaled_by);
    set_raster_stats(s, stats, cpu, points.size(), spacing);
    s.set("kernel", std::string(splat_kernel_name(settings.kernel)));
    s.set("compositing",
          std::string(settings.compositing == SplatCompositing::kSheetBuffer ? "sheet-buffer"
                                                                             : "per-splat"));
    if (settings.compositing == SplatCompositing::kSheetBuffer) {
        s.set("sheets", stats.sheets);
        s.set("sheet_axis", stats.sheet_axis);
    }
    s.set("threads", thread_count());
    return image;
}

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
