#include <core/parallel.h>
#include <core/stopwatch.h>
#include <flowtex/frame_loop.h>
#include <flowtex/spot_noise_frames.h>
#include <flowtex/spot_raster.h>
#include <pipeline/layered_volume.h>
#include <pipeline/methods/animated_flow.h>
#include <pipeline/methods/spot_noise_method.h>
#include <pipeline/scene_volumes.h>

#include <chrono>
#include <limits>

namespace tr {
namespace {

using Clock = std::chrono::steady_clock;

const MethodKeys kSpotNoiseKeys{
    .keys = {vectors_key(),
             {.key = "scalar",
              .type = KeyType::kString,
              .default_value = "the scene's `scalar`",
              .doc = "a 1-component point array whose contour the spots follow",
              .expected = "the name of a 1-component point array"},
             {.key = "iso",
              .type = KeyType::kNumber,
              .default_value = "required on a 3D mesh",
              .doc = "the contour `scalar` = `iso`, inside the scalar's range (a planar 2D "
                     "mesh needs none: the spots cover it)"},
             {.key = "band",
              .type = KeyType::kNumber,
              .default_value = "diagonal / 100",
              .doc = "the half-width of the band around the contour the spots live in",
              .lo = 0,
              .open_lo = true},
             {.key = "count",
              .type = KeyType::kInteger,
              .default_value = "20000",
              .doc = "spots",
              .lo = 1,
              .hi = static_cast<double>(kMaxSpots)},
             dt_key("default: the mean speed over the spots carries them 1/400 of the diagonal "
                    "per frame"),
             steps_key(),
             frame_key(),
             {.key = "lifetime",
              .type = KeyType::kInteger,
              .default_value = "60",
              .doc = "frames a spot lives (0: reseeded only when it leaves)",
              .lo = 0,
              .hi = 1e6},
             unsteady_key(),
             start_time_key(),
             {.key = "spot_opacity",
              .type = KeyType::kNumber,
              .default_value = "1.5",
              .doc = "opacity 1 - exp(-spot_opacity W) for summed weight W",
              .lo = 0,
              .hi = 1e3,
              .open_lo = true}},
    .uses_seed = true};

// The spots of this frame as one layer of fragments, each pixel at its weighted mean spot depth.
void spot_fragments(const View& view, const SpotNoise& spots, const SpotRasterOptions& raster,
                    SpotBuffers& buffers, SurfaceFragments& f, std::vector<double>& depths) {
    splat_spots(view, spots, raster, buffers);
    const std::size_t num_pixels =
        static_cast<std::size_t>(view.camera->width()) * view.camera->height();
    f.color.assign(num_pixels, Vec3f(0.0f));
    f.alpha.assign(num_pixels, 0.0f);
    depths.assign(num_pixels, std::numeric_limits<double>::infinity());
    parallel_for(0, num_pixels, 4096, [&](std::size_t p) {
        const float w = buffers.coverage[p];
        if (!(w > 0)) return;
        spot_color(raster, buffers.intensity[p], w, f.color[p], f.alpha[p]);
        depths[p] = buffers.depth[p] / w;
    });
}

class SpotNoiseMethod final : public RenderMethod {
  public:
    std::string_view name() const override { return "spot-noise"; }

    const MethodKeys& keys() const override { return kSpotNoiseKeys; }

    Status check(const Scene& scene, const RenderOptions& options) const override {
        TR_TRY_STATUS(check_method_keys(scene, name(), keys()));
        return check_animated_scene(scene, options, name());
    }

    Result<RenderResult> render(Pipeline& pipeline, const Scene& scene,
                                const RenderOptions& options) const override {
        RenderResult result;
        NamedStats& stats = result.stats;
        TR_TRY(const SceneFlow flow, scene_flow(pipeline, scene));
        SpotNoiseFramesOptions spot_options;
        spot_options.scalar = string_key(scene, "scalar", scene.volumes[0].scalar);
        spot_options.spots.iso = number_key(scene, "iso", 0.0);
        spot_options.planar = flow.domain.planar;
        if (!flow.domain.planar && !option(scene, "iso")) {
            return method_option_error(scene, "iso",
                                       "missing: spot noise on a 3D mesh follows the contour "
                                       "`scalar` = `iso`");
        }
        spot_options.spots.band = number_key(scene, "band", 0.0);
        spot_options.spots.count = static_cast<std::size_t>(integer_key(scene, "count", 20000));
        spot_options.spots.dt = number_key(scene, "dt", 0.0);
        spot_options.spots.lifetime_frames = static_cast<int>(integer_key(scene, "lifetime", 60));
        // The method's seed places the spots (repetitions: none).
        spot_options.spots.seed = seed_of(scene, spot_options.spots.seed);
        if (option(scene, "start_time")) {
            spot_options.spots.start_time = number_key(scene, "start_time", 0.0);
            spot_options.start_time_set = true;
        }
        const int steps = steps_of(scene);
        spot_options.steps = steps;
        spot_options.width = scene.width;
        spot_options.height = scene.height;
        auto start = Clock::now();
        auto started = start_spot_noise(flow.domain.mesh(), *flow.domain.adjacency, flow.velocity,
                                        spot_options);
        if (!started.ok()) return method_key_error(scene, started.error(), "scalar");
        const std::unique_ptr<SpotNoiseRun> run = std::move(started).value();
        SpotNoise& spots = *run->spots;
        stats.set("seed_ms", ms_since(start));

        const CameraFrame frame(scene.camera, scene.width, scene.height);
        NamedStats discard;
        TR_TRY(const OpaqueLayer opaque, opaque_layer(pipeline, scene, frame, discard));
        SpotRasterOptions raster;
        raster.dt = run->report.dt;
        raster.opacity = number_key(scene, "spot_opacity", raster.opacity);
        // The spots are depth-tested against the opaque surfaces; their colours are composited
        // over them with the volume's layers (layered_volume.h).
        View view{.camera = &frame};
        if (!opaque.depth.empty()) view.opaque_depth = &opaque.depth;
        const int last = last_frame(scene, options);
        TR_TRY_STATUS(check_layers_memory(scene, 1));
        SpotBuffers buffers;
        std::vector<SurfaceFragments> fragments(1);
        std::vector<std::vector<double>> depths(1);
        double raster_ms = 0;
        std::size_t reseeded = 0;
        auto advance = [&] {
            spots.advance();
            reseeded += spots.reseeded();
        };
        auto draw = [&](int k) -> Status {
            const auto drawing = Clock::now();
            spot_fragments(view, spots, raster, buffers, fragments[0], depths[0]);
            raster_ms += ms_since(drawing);
            // The spots move: the volume is split at their new depths every frame.
            NamedStats volume_stats;
            std::vector<std::string> volume_notes;
            const bool volume_drawn = !flow.domain.planar;
            if (!volume_drawn) volume_notes.push_back(planar_scene_note(*flow.domain.planar));
            TR_TRY(const LayeredVolume volume,
                   LayeredVolume::create(pipeline, scene, options, depths, volume_stats,
                                         volume_notes, volume_drawn));
            result.image = volume.composite(fragments);
            if (k == last) {
                for (const auto& [key, value] : volume_stats.entries()) stats.set_value(key, value);
                result.notes = std::move(volume_notes);
            }
            return options.on_frame ? options.on_frame(k, result.image) : Status{};
        };
        TR_TRY(const FrameLoopTimes times,
               run_frame_loop(last, static_cast<bool>(options.on_frame), advance, draw));
        stats.set("spots", run->report.spots);
        stats.set("band_tets", run->report.band_tets);
        stats.set("band", run->report.band);
        stats.set("dt", run->report.dt);
        stats.set("mean_speed", run->report.mean_speed);
        stats.set("reseeded", reseeded);
        stats.set("frame", last);
        stats.set("advect_ms", times.advance_ms);
        stats.set("spot_raster_ms", raster_ms);
        return result;
    }
};

}  // namespace

std::unique_ptr<RenderMethod> make_spot_noise_method() {
    return std::make_unique<SpotNoiseMethod>();
}

}  // namespace tr
