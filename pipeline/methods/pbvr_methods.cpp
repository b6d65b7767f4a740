#include <core/stopwatch.h>
#include <pipeline/methods/pbvr_methods.h>
#include <pipeline/scene_volumes.h>
#include <project/cpu_renderer.h>
#include <project/opaque_geometry.h>
#include <project/pbvr/pbvr_image.h>
#include <project/pbvr/pbvr_object.h>

#include <chrono>

namespace tr {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kDefaultRepetitions = 64;

// What both methods refuse, and the keys they share.
Status check_common(const Scene& scene, const RenderOptions& options, std::string_view name,
                    double samples_per_pixel) {
    if (scene.flow_volume) {
        return make_error(ErrorCode::kUnsupported,
                          "$.flow_volume: flow volumes are drawn by projected-tetrahedra, not " +
                              std::string(name),
                          scene.source);
    }
    if (options.reference) {
        return make_error(ErrorCode::kUnsupported,
                          "the reference ray caster is an integrator of projected-tetrahedra, not "
                          "of " +
                              std::string(name),
                          scene.source);
    }
    const double work = samples_per_pixel * scene.width * scene.height;
    if (work > kMaxParticleSamples) {
        return make_error(ErrorCode::kInvalidArgument,
                          "$.method: " + std::to_string(static_cast<long long>(samples_per_pixel)) +
                              " samples per pixel of a " + std::to_string(scene.width) + "x" +
                              std::to_string(scene.height) + " picture is " + std::to_string(work) +
                              " samples, more than the " + std::to_string(kMaxParticleSamples) +
                              " allowed",
                          scene.source);
    }
    return {};
}

int repetitions_of(const Scene& scene) { return repetitions_of(scene, kDefaultRepetitions); }

std::uint64_t seed_of(const Scene& scene) { return seed_of(scene, 1); }

const MethodKeys kObjectKeys{
    .keys =
        {{.key = "subpixel_level",
          .type = KeyType::kInteger,
          .default_value = "1",
          .doc = "L x L sub-pixels a pixel; the work repetitions x L^2 x pixels is capped (2^38)",
          .lo = 1,
          .hi = 16},
         {.key = "sampling",
          .type = KeyType::kChoice,
          .default_value = "`\"exact\"`",
          .doc =
              "`exact`: Poisson thinning of the true density; `uniform`: the paper's cell-constant "
              "density; `metropolis`: the paper's Metropolis placement",
          .choices = {"exact", "uniform", "metropolis"}}},
    .uses_repetitions = true,
    .uses_seed = true};

const MethodKeys kImageKeys{
    .keys =
        {{.key = "depth",
          .type = KeyType::kChoice,
          .default_value = "`\"inverse-cdf\"`",
          .doc = "where in its segment a particle lies: `inverse-cdf` (exact); `entry`, `middle`, "
                 "`exit`, `random` for the paper's comparison",
          .choices = {"inverse-cdf", "entry", "middle", "exit", "random"}},
         {.key = "stratified",
          .type = KeyType::kBool,
          .default_value = "true",
          .doc =
              "true: each segment's repetitions on a randomly rotated lattice; false: the paper's "
              "independent repetitions"},
         {.key = "control_variate",
          .type = KeyType::kBool,
          .default_value = "true",
          .doc = "true: the known probability that a pixel has any particle takes out most of the "
                 "noise, unbiased; false: the plain mean"}},
    .uses_repetitions = true,
    .uses_seed = true};

class PbvrObject final : public RenderMethod {
  public:
    std::string_view name() const override { return "pbvr-object"; }
    bool draws_transparent() const override { return true; }
    const MethodKeys& keys() const override { return kObjectKeys; }

    Status check(const Scene& scene, const RenderOptions& options) const override {
        TR_TRY_STATUS(check_method_keys(scene, name(), keys()));
        const auto level = static_cast<int>(integer_key(scene, "subpixel_level", 1));
        return check_common(scene, options, name(),
                            static_cast<double>(repetitions_of(scene)) * level * level);
    }

    Result<RenderResult> render(Pipeline& pipeline, const Scene& scene,
                                const RenderOptions& render_options) const override {
        RenderResult result;
        TR_TRY(const std::unique_ptr<SceneVolumes> loaded,
               load_scene_volumes(pipeline, scene, result.stats));
        const CameraFrame frame(scene.camera, scene.width, scene.height);
        TR_TRY(const OpaqueLayer layer, opaque_layer(pipeline, scene, frame, result.stats));
        ObjectPbvrOptions options;
        options.repetitions = repetitions_of(scene);
        options.seed = seed_of(scene);
        options.subpixel_level =
            static_cast<int>(integer_key(scene, "subpixel_level", options.subpixel_level));
        if (option(scene, "sampling")) {
            options.sampling = *parse_particle_sampling(string_key(scene, "sampling"));
        }
        VolumeScene& ps = loaded->scene;
        static_cast<View&>(ps) = scene_view(scene, render_options, frame, layer);
        const ObjectPbvrPlan plan = plan_object_pbvr(ps, options);
        const double candidates = plan.candidates;
        if (candidates > kMaxObjectCandidates) {
            return make_error(
                ErrorCode::kInvalidArgument,
                "pbvr-object: " + std::to_string(static_cast<long long>(candidates)) +
                    " candidate particles a repetition, more than the " +
                    std::to_string(static_cast<long long>(kMaxObjectCandidates)) +
                    " allowed: the camera is inside or very near the volume, where the particle "
                    "density grows as 1 / depth^2; move it out, or use pbvr-image",
                scene.source);
        }
        ObjectPbvrStats stats;
        result.image = render_object_pbvr(ps, options, &stats, &plan,
                                          render_options.transparent ? &result.alpha : nullptr);
        NamedStats& s = result.stats;
        s.set("generate_ms", stats.generate_ms);
        s.set("resolve_ms", stats.resolve_ms);
        s.set("particles", stats.particles);
        s.set("candidates", stats.candidates);
        s.set("repetitions", options.repetitions);
        s.set("subpixel_level", options.subpixel_level);
        s.set("sampling", std::string(particle_sampling_name(options.sampling)));
        s.set("seed", options.seed);
        return result;
    }
};

class PbvrImage final : public RenderMethod {
  public:
    std::string_view name() const override { return "pbvr-image"; }
    bool draws_transparent() const override { return true; }
    const MethodKeys& keys() const override { return kImageKeys; }

    Status check(const Scene& scene, const RenderOptions& options) const override {
        TR_TRY_STATUS(check_method_keys(scene, name(), keys()));
        return check_common(scene, options, name(), repetitions_of(scene));
    }

    Result<RenderResult> render(Pipeline& pipeline, const Scene& scene,
                                const RenderOptions& render_options) const override {
        RenderResult result;
        TR_TRY(const std::unique_ptr<SceneVolumes> loaded,
               load_scene_volumes(pipeline, scene, result.stats));
        const CameraFrame frame(scene.camera, scene.width, scene.height);
        TR_TRY(const OpaqueLayer layer, opaque_layer(pipeline, scene, frame, result.stats));
        ImagePbvrOptions options;
        options.repetitions = repetitions_of(scene);
        options.seed = seed_of(scene);
        if (option(scene, "depth"))
            options.depth = *parse_particle_depth(string_key(scene, "depth"));
        options.stratified = bool_key(scene, "stratified", options.stratified);
        options.control_variate = bool_key(scene, "control_variate", options.control_variate);
        VolumeScene& ps = loaded->scene;
        static_cast<View&>(ps) = scene_view(scene, render_options, frame, layer);
        if (ps.volumes.size() == 1) {  // the segments' mean colours (pbvr_image.h)
            const auto start = Clock::now();
            ps.volumes[0].shader =
                &pipeline.shader(scene.volumes[0].transfer_function, Integrator::kPreintegrated,
                                 longest_edge(loaded->meshes[0]->tets));
            result.stats.set("shader_ms", ms_since(start));
        }
        ImagePbvrStats stats;
        result.image = render_image_pbvr(ps, options, &stats,
                                         render_options.transparent ? &result.alpha : nullptr);
        NamedStats& s = result.stats;
        s.set("raster_ms", stats.raster_ms);
        s.set("fragments", stats.fragments);
        s.set("particles", stats.particles);
        s.set("repetitions", options.repetitions);
        s.set("depth", std::string(particle_depth_name(options.depth)));
        s.set("stratified", options.stratified);
        s.set("control_variate", options.control_variate);
        s.set("seed", options.seed);
        return result;
    }
};

}  // namespace

std::unique_ptr<RenderMethod> make_pbvr_object_method() { return std::make_unique<PbvrObject>(); }
std::unique_ptr<RenderMethod> make_pbvr_image_method() { return std::make_unique<PbvrImage>(); }

}  // namespace tr
