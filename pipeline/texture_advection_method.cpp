#include <core/parallel.h>
#include <core/stopwatch.h>
#include <flowtex/advected_sheets.h>
#include <flowtex/sheet_raster.h>
#include <flowtex/spot_noise_frames.h>
#include <flowtex/spot_raster.h>
#include <pipeline/flow_volume_scene.h>
#include <pipeline/layered_volume.h>
#include <pipeline/scene_volumes.h>
#include <pipeline/texture_advection_method.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace tr {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::int64_t kMaxSteps = 100000;

// The kind of value a method key takes, for check().
enum class Kind { kString, kInteger, kNumber, kBool, kLists };

struct KeyRule {
    const char* key;
    Kind kind;
    double lo = -std::numeric_limits<double>::infinity();  // inclusive bounds for numbers
    double hi = std::numeric_limits<double>::infinity();
    bool open_lo = false;  // lo excluded
    const char* expected = "";
};

std::optional<double> as_number(const MethodOption& o) {
    if (const double* d = std::get_if<double>(&o)) return *d;
    if (const std::int64_t* i = std::get_if<std::int64_t>(&o)) return static_cast<double>(*i);
    return std::nullopt;
}

// Each given key has its kind and range; `required` keys are given.
Status check_keys(const Scene& scene, std::string_view name, std::initializer_list<KeyRule> rules,
                  std::initializer_list<const char*> required) {
    for (const auto& [key, value] :
         scene.method ? scene.method->options : std::map<std::string, MethodOption>{}) {
        const KeyRule* rule = nullptr;
        for (const KeyRule& r : rules) {
            if (key == r.key) rule = &r;
        }
        if (!rule) {
            std::string list = "name";
            for (const KeyRule& r : rules) list += ", " + std::string(r.key);
            return method_option_error(
                scene, key, "unknown key for " + std::string(name) + " (it takes " + list + ")");
        }
        bool ok = false;
        switch (rule->kind) {
            case Kind::kString: {
                const auto* s = std::get_if<std::string>(&value);
                ok = s && !s->empty();
                break;
            }
            case Kind::kBool:
                ok = std::holds_alternative<bool>(value);
                break;
            case Kind::kLists:
                ok = std::holds_alternative<NumberLists>(value);
                break;
            case Kind::kInteger:
            case Kind::kNumber: {
                const std::int64_t* i = std::get_if<std::int64_t>(&value);
                const std::optional<double> v = as_number(value);
                ok = (rule->kind == Kind::kNumber ? v.has_value() : i != nullptr) &&
                     std::isfinite(*v) && (rule->open_lo ? *v > rule->lo : *v >= rule->lo) &&
                     *v <= rule->hi;
                break;
            }
        }
        if (!ok) return method_option_error(scene, key, std::string("expected ") + rule->expected);
    }
    for (const char* key : required) {
        if (!option(scene, key)) {
            return method_option_error(scene, key, "missing (" + std::string(name) + " needs it)");
        }
    }
    return {};
}

// What both methods refuse of a scene.
Status check_scene(const Scene& scene, const RenderOptions& options, std::string_view name) {
    auto refuse = [&](const std::string& what) {
        return make_error(ErrorCode::kUnsupported, std::string(name) + ": " + what, scene.source);
    };
    if (scene.flow_volume) return refuse("does not draw flow volumes");
    if (options.reference) {
        return refuse(
            "the reference ray caster draws no opaque stops (the sheets split the "
            "volume's integral); use preintegrated or exact");
    }
    return {};
}

std::string string_key(const Scene& scene, const char* key, std::string fallback = {}) {
    const MethodOption* o = option(scene, key);
    const auto* s = o ? std::get_if<std::string>(o) : nullptr;
    return s ? *s : fallback;
}

double number_key(const Scene& scene, const char* key, double fallback) {
    const MethodOption* o = option(scene, key);
    return o ? as_number(*o).value_or(fallback) : fallback;
}

std::int64_t integer_key(const Scene& scene, const char* key, std::int64_t fallback) {
    const MethodOption* o = option(scene, key);
    const auto* i = o ? std::get_if<std::int64_t>(o) : nullptr;
    return i ? *i : fallback;
}

bool bool_key(const Scene& scene, const char* key, bool fallback) {
    const MethodOption* o = option(scene, key);
    const auto* b = o ? std::get_if<bool>(o) : nullptr;
    return b ? *b : fallback;
}

// The frame a single render shows, and the last frame it advances to.
Status check_frame(const Scene& scene) {
    const std::int64_t steps = integer_key(scene, "steps", 100);
    if (const MethodOption* o = option(scene, "frame")) {
        const std::int64_t frame = *std::get_if<std::int64_t>(o);
        if (frame > steps) {
            return method_option_error(scene, "frame",
                                       "frame " + std::to_string(frame) + " is past steps (" +
                                           std::to_string(steps) + ")");
        }
    }
    return {};
}

// An error of the flow's libraries as the scene's: the scene file, the method key it is about.
Error scene_key_error(const Scene& scene, const std::string& key, const Error& error) {
    Error out = error;
    out.message = "$.method." + key + ": " + error.message;
    if (!error.where.empty() && error.where != scene.source)
        out.message += " (" + error.where + ")";
    out.where = scene.source;
    return out;
}

// The domain and velocity of the scene's volume 0.
struct SceneFlow {
    FlowDomain domain;
    VelocityField velocity;
};

Result<SceneFlow> scene_flow(Pipeline& pipeline, const Scene& scene) {
    TR_TRY(FlowDomain domain, pipeline.flow_domain(scene.volumes[0]));
    auto velocity = load_velocity(domain, string_key(scene, "vectors"),
                                  bool_key(scene, "unsteady", false), pipeline.options().load);
    if (!velocity.ok()) {
        // "--unsteady" is the command line's word; a scene says it with the key.
        return scene_key_error(scene, option(scene, "unsteady") ? "unsteady" : "vectors",
                               velocity.error());
    }
    return SceneFlow{std::move(domain), std::move(velocity).value()};
}

// The keys both animated methods take, with the same rules.
const KeyRule kVectorsRule{"vectors", Kind::kString, 0,
                           0,         false,         "the name of a 3-component point array"};
const KeyRule kDtRule{"dt", Kind::kNumber, 0, 1e300, true, "a number > 0"};
const KeyRule kStepsRule{"steps",   Kind::kInteger, 0,
                         kMaxSteps, false,          "an integer from 0 to 100000"};
const KeyRule kFrameRule{"frame",   Kind::kInteger, 0,
                         kMaxSteps, false,          "an integer from 0 to steps"};
const KeyRule kUnsteadyRule{"unsteady", Kind::kBool, 0, 0, false, "true or false"};
const KeyRule kStartTimeRule{"start_time", Kind::kNumber, -1e300, 1e300, false, "a number"};

class TextureAdvectionMethod final : public RenderMethod {
  public:
    std::string_view name() const override { return "texture-advection"; }

    Status check(const Scene& scene, const RenderOptions& options) const override {
        TR_TRY_STATUS(
            check_keys(scene, name(),
                       {kVectorsRule,
                        {"slices", Kind::kLists, 0, 0, false,
                         "a list of slices [[px, py, pz, nx, ny, nz], ...]"},
                        kStepsRule,
                        kFrameRule,
                        kDtRule,
                        kUnsteadyRule,
                        kStartTimeRule,
                        {"advection", Kind::kString, 0, 0, false, "\"backward\" or \"forward\""},
                        {"reinject", Kind::kInteger, 0, 1e6, false, "an even integer >= 0"},
                        {"resolution", Kind::kInteger, 1, 8192, false, "an integer from 1 to 8192"},
                        {"sheet_opacity", Kind::kNumber, 0, 1, true, "a number in (0, 1]"}},
                       {"vectors"}));
        const std::string advection = string_key(scene, "advection", "backward");
        if (advection != "backward" && advection != "forward") {
            return method_option_error(scene, "advection", "expected \"backward\" or \"forward\"");
        }
        if (integer_key(scene, "reinject", 40) % 2 != 0) {
            return method_option_error(scene, "reinject", "expected an even integer >= 0");
        }
        if (const MethodOption* o = option(scene, "slices")) {
            const NumberLists& slices = *std::get_if<NumberLists>(o);
            if (slices.size() > kMaxSheets) {
                return method_option_error(scene, "slices",
                                           std::to_string(slices.size()) + " slices: at most " +
                                               std::to_string(kMaxSheets));
            }
            for (std::size_t i = 0; i < slices.size(); ++i) {
                const std::string at = "slices[" + std::to_string(i) + "]";
                if (slices[i].size() != 6) {
                    return method_option_error(scene, at,
                                               "expected 6 numbers: a point and a normal");
                }
                if (slices[i][3] == 0 && slices[i][4] == 0 && slices[i][5] == 0) {
                    return method_option_error(scene, at, "the normal is zero");
                }
            }
        }
        TR_TRY_STATUS(check_frame(scene));
        return check_scene(scene, options, name());
    }

    Result<RenderResult> render(Pipeline& pipeline, const Scene& scene,
                                const RenderOptions& options) const override {
        RenderResult result;
        NamedStats& stats = result.stats;
        if (scene.method && (scene.method->repetitions || scene.method->seed)) {
            result.notes.push_back(
                "repetitions and seed apply to the stochastic methods: texture-advection ignores "
                "them");
        }
        TR_TRY(const SceneFlow flow, scene_flow(pipeline, scene));
        AdvectedSheetsOptions sheet_options;
        if (const MethodOption* o = option(scene, "slices")) {
            for (const std::vector<double>& s : *std::get_if<NumberLists>(o)) {
                sheet_options.slices.push_back({Vec3(s[0], s[1], s[2]), Vec3(s[3], s[4], s[5])});
            }
        }
        sheet_options.index_slice_errors = true;
        TR_TRY_STATUS(
            check_layers_memory(scene, std::max<std::size_t>(1, sheet_options.slices.size())));
        sheet_options.sheet_resolution = static_cast<int>(integer_key(scene, "resolution", 256));
        const int steps = static_cast<int>(integer_key(scene, "steps", 100));
        sheet_options.steps = steps;
        sheet_options.dt = number_key(scene, "dt", 0.0);
        if (option(scene, "start_time")) {
            sheet_options.start_time = number_key(scene, "start_time", 0.0);
            sheet_options.start_time_set = true;
        }
        sheet_options.method = string_key(scene, "advection", "backward") == "forward"
                                   ? AdvectionMethod::kForward
                                   : AdvectionMethod::kBackward;
        sheet_options.reinject_frames = static_cast<int>(integer_key(scene, "reinject", 40));
        auto start = Clock::now();
        auto made = AdvectedSheets::create(flow.domain.mesh(), *flow.domain.adjacency,
                                           flow.velocity, sheet_options);
        if (!made.ok()) {
            const std::string& m = made.error().message;
            if (m.rfind("slices[", 0) == 0) {
                Error e = made.error();
                e.message = "$.method." + m;
                e.where = scene.source;
                return e;
            }
            return scene_key_error(scene, "slices", made.error());
        }
        const std::unique_ptr<AdvectedSheets> sheets = std::move(made).value();
        stats.set("sheets_ms", ms_since(start));

        const CameraFrame frame(scene.camera, scene.width, scene.height);
        std::vector<std::vector<double>> depths;
        for (std::size_t s = 0; s < sheets->size(); ++s) {
            const Sheet& sheet = sheets->sheet(s);
            depths.push_back(plane_depths(frame, sheet.origin, sheet.normal));
        }
        TR_TRY(const LayeredVolume volume,
               LayeredVolume::create(pipeline, scene, options, depths, stats, result.notes));

        const SheetRasterOptions colours;
        const float opacity = static_cast<float>(number_key(scene, "sheet_opacity", 0.6));
        const int last =
            options.on_frame ? steps : static_cast<int>(integer_key(scene, "frame", steps));
        std::vector<SurfaceFragments> fragments(sheets->size());
        double advect_ms = 0, raster_ms = 0;
        for (int k = 0; k <= last; ++k) {
            if (k > 0) {
                start = Clock::now();
                sheets->advance();
                advect_ms += ms_since(start);
            }
            if (!options.on_frame && k < last) continue;
            start = Clock::now();
            for (std::size_t s = 0; s < sheets->size(); ++s) {
                const std::vector<TexturedMeshView> views = sheets->views(s);
                const std::vector<float> values =
                    rasterize_sheet_values(frame, views, sheets->texture());
                SurfaceFragments& f = fragments[s];
                f.color.resize(values.size());
                f.alpha.resize(values.size());
                parallel_for(0, values.size(), 4096, [&](std::size_t p) {
                    const float v = values[p];
                    const bool drawn = !std::isnan(v);
                    f.alpha[p] = drawn ? opacity : 0.0f;
                    f.color[p] =
                        drawn ? colours.dark + v * (colours.light - colours.dark) : Vec3f(0.0f);
                });
            }
            result.image = volume.composite(fragments);
            raster_ms += ms_since(start);
            if (options.on_frame) TR_TRY_STATUS(options.on_frame(k, result.image));
        }
        stats.set("method", std::string(name()));
        stats.set("sheets", sheets->size());
        stats.set("sheet_points", sheets->points());
        stats.set("sheet_triangles", sheets->triangles());
        stats.set("mean_speed", sheets->mean_speed());
        stats.set("dt", sheets->dt());
        stats.set("frame", last);
        stats.set("advect_ms", advect_ms);
        stats.set("sheet_raster_ms", raster_ms);
        stats.set("width", scene.width);
        stats.set("height", scene.height);
        if (!(sheets->mean_speed() > 0)) {
            result.notes.push_back("zero velocity on every sheet: the frames are still");
        }
        return result;
    }
};

class SpotNoiseMethod final : public RenderMethod {
  public:
    std::string_view name() const override { return "spot-noise"; }

    Status check(const Scene& scene, const RenderOptions& options) const override {
        TR_TRY_STATUS(check_keys(
            scene, name(),
            {kVectorsRule,
             {"scalar", Kind::kString, 0, 0, false, "the name of a 1-component point array"},
             {"iso", Kind::kNumber, -1e308, 1e308, false, "a number"},
             {"band", Kind::kNumber, 0, 1e300, true, "a number > 0"},
             {"count", Kind::kInteger, 1, static_cast<double>(kMaxSpots), false,
              "an integer from 1 to 10000000"},
             kDtRule,
             kStepsRule,
             kFrameRule,
             {"lifetime", Kind::kInteger, 0, 1e6, false, "an integer >= 0"},
             kUnsteadyRule,
             kStartTimeRule,
             {"spot_opacity", Kind::kNumber, 0, 1e3, true, "a number > 0"}},
            {"vectors", "iso"}));
        TR_TRY_STATUS(check_frame(scene));
        return check_scene(scene, options, name());
    }

    Result<RenderResult> render(Pipeline& pipeline, const Scene& scene,
                                const RenderOptions& options) const override {
        RenderResult result;
        NamedStats& stats = result.stats;
        TR_TRY(const SceneFlow flow, scene_flow(pipeline, scene));
        SpotNoiseFramesOptions spot_options;
        spot_options.scalar = string_key(scene, "scalar", scene.volumes[0].scalar);
        spot_options.spots.iso = number_key(scene, "iso", 0.0);
        spot_options.spots.band = number_key(scene, "band", 0.0);
        spot_options.spots.count = static_cast<std::size_t>(integer_key(scene, "count", 20000));
        spot_options.spots.dt = number_key(scene, "dt", 0.0);
        spot_options.spots.lifetime_frames = static_cast<int>(integer_key(scene, "lifetime", 60));
        // The method's seed places the spots; repetitions: none.
        if (scene.method && scene.method->seed) {
            spot_options.spots.seed = static_cast<std::uint64_t>(*scene.method->seed);
        }
        if (scene.method && scene.method->repetitions) {
            result.notes.push_back(
                "repetitions apply to the stochastic methods: spot-noise "
                "draws one set of spots (its seed places them)");
        }
        if (option(scene, "start_time")) {
            spot_options.spots.start_time = number_key(scene, "start_time", 0.0);
            spot_options.start_time_set = true;
        }
        const int steps = static_cast<int>(integer_key(scene, "steps", 100));
        spot_options.steps = steps;
        spot_options.width = scene.width;
        spot_options.height = scene.height;
        auto start = Clock::now();
        auto started = start_spot_noise(flow.domain.mesh(), *flow.domain.adjacency, flow.velocity,
                                        spot_options);
        if (!started.ok()) {
            // Which key the library's message is about: the contour's, or the array's.
            const std::string& m = started.error().message;
            const std::string key = m.find("iso") != std::string::npos     ? "iso"
                                    : m.find("count") != std::string::npos ? "count"
                                    : m.find("band") != std::string::npos  ? "band"
                                                                           : "scalar";
            return scene_key_error(scene, key, started.error());
        }
        const std::unique_ptr<SpotNoiseRun> run = std::move(started).value();
        SpotNoise& spots = *run->spots;
        stats.set("seed_ms", ms_since(start));

        const CameraFrame frame(scene.camera, scene.width, scene.height);
        NamedStats discard;
        TR_TRY(const OpaqueLayer opaque, opaque_layer(pipeline, scene, frame, discard));
        SpotRasterOptions raster;
        raster.dt = run->report.dt;
        raster.opacity = number_key(scene, "spot_opacity", raster.opacity);
        if (!opaque.depth.empty()) raster.opaque_depth = &opaque.depth;
        const int last =
            options.on_frame ? steps : static_cast<int>(integer_key(scene, "frame", steps));
        const std::size_t num_pixels = static_cast<std::size_t>(scene.width) * scene.height;
        TR_TRY_STATUS(check_layers_memory(scene, 1));
        SpotBuffers buffers;
        std::vector<SurfaceFragments> fragments(1);
        std::vector<std::vector<double>> depths(1);
        double advect_ms = 0, raster_ms = 0;
        std::size_t reseeded = 0;
        for (int k = 0; k <= last; ++k) {
            if (k > 0) {
                start = Clock::now();
                spots.advance();
                reseeded += spots.reseeded();
                advect_ms += ms_since(start);
            }
            if (!options.on_frame && k < last) continue;
            start = Clock::now();
            splat_spots(frame, spots, raster, buffers);
            SurfaceFragments& f = fragments[0];
            f.color.assign(num_pixels, Vec3f(0.0f));
            f.alpha.assign(num_pixels, 0.0f);
            depths[0].assign(num_pixels, std::numeric_limits<double>::infinity());
            parallel_for(0, num_pixels, 4096, [&](std::size_t p) {
                const float w = buffers.coverage[p];
                if (!(w > 0)) return;
                spot_color(raster, buffers.intensity[p], w, f.color[p], f.alpha[p]);
                depths[0][p] = buffers.depth[p] / w;
            });
            raster_ms += ms_since(start);
            // The spots move: the volume is split at their new depths every frame.
            NamedStats volume_stats;
            std::vector<std::string> volume_notes;
            TR_TRY(const LayeredVolume volume,
                   LayeredVolume::create(pipeline, scene, options, depths, volume_stats,
                                         volume_notes));
            result.image = volume.composite(fragments);
            if (k == last) {
                for (const auto& [key, value] : volume_stats.entries()) stats.set_value(key, value);
                result.notes = std::move(volume_notes);
            }
            if (options.on_frame) TR_TRY_STATUS(options.on_frame(k, result.image));
        }
        stats.set("method", std::string(name()));
        stats.set("spots", run->report.spots);
        stats.set("band_tets", run->report.band_tets);
        stats.set("band", run->report.band);
        stats.set("dt", run->report.dt);
        stats.set("mean_speed", run->report.mean_speed);
        stats.set("reseeded", reseeded);
        stats.set("frame", last);
        stats.set("advect_ms", advect_ms);
        stats.set("spot_raster_ms", raster_ms);
        stats.set("width", scene.width);
        stats.set("height", scene.height);
        return result;
    }
};

}  // namespace

std::unique_ptr<RenderMethod> make_texture_advection_method() {
    return std::make_unique<TextureAdvectionMethod>();
}

std::unique_ptr<RenderMethod> make_spot_noise_method() {
    return std::make_unique<SpotNoiseMethod>();
}

}  // namespace tr
