#include <core/parallel.h>
#include <core/stopwatch.h>
#include <flowtex/advected_sheets.h>
#include <flowtex/frame_loop.h>
#include <flowtex/sheet_raster.h>
#include <pipeline/layered_volume.h>
#include <pipeline/methods/animated_flow.h>
#include <pipeline/methods/texture_advection_method.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace tr {
namespace {

using Clock = std::chrono::steady_clock;

const MethodKeys kTextureAdvectionKeys{
    .keys = {vectors_key(),
             {.key = "slices",
              .type = KeyType::kLists,
              .default_value = "one",
              .doc = "`[[px, py, pz, nx, ny, nz], ...]`, 1 to 16 planes, each cut by the mesh into "
                     "a sheet; default one through the bounds' centre normal to their thinnest "
                     "axis",
              .expected = "a list of slices [[px, py, pz, nx, ny, nz], ...]"},
             steps_key(),
             frame_key(),
             dt_key("flow time per frame; default as `tetrender advect`: 1/200 of the longest "
                    "sheet side per frame at the mean in-plane speed over all sheets, or the "
                    "series' span over the steps when unsteady"),
             unsteady_key(),
             start_time_key(),
             {.key = "advection",
              .type = KeyType::kChoice,
              .default_value = "`\"backward\"`",
              .doc = "`backward`, the seed's method, or `forward`",
              .choices = {"backward", "forward"}},
             {.key = "reinject",
              .type = KeyType::kInteger,
              .default_value = "40",
              .doc = "frames between re-injections of fresh noise (even; 0: off)",
              .lo = 0,
              .hi = 1e6,
              .expected = "an even integer >= 0"},
             {.key = "resolution",
              .type = KeyType::kInteger,
              .default_value = "256",
              .doc = "grid squares along each sheet's longer side",
              .lo = 1,
              .hi = 8192},
             {.key = "sheet_opacity",
              .type = KeyType::kNumber,
              .default_value = "0.6",
              .doc = "each sheet a thin layer of this opacity, its colour the advected noise's",
              .lo = 0,
              .hi = 1,
              .open_lo = true}}};

// Each sheet's fragments at this frame: the advected noise in grey, `opacity` where drawn.
void sheet_fragments(const CameraFrame& frame, const AdvectedSheets& sheets, float opacity,
                     std::vector<SurfaceFragments>& fragments) {
    const SheetRasterOptions colours;
    for (std::size_t s = 0; s < sheets.size(); ++s) {
        const std::vector<TexturedMeshView> views = sheets.views(s);
        const std::vector<float> values = rasterize_sheet_values(frame, views, sheets.texture());
        SurfaceFragments& f = fragments[s];
        f.color.resize(values.size());
        f.alpha.resize(values.size());
        parallel_for(0, values.size(), 4096, [&](std::size_t p) {
            const float v = values[p];
            const bool drawn = !std::isnan(v);
            f.alpha[p] = drawn ? opacity : 0.0f;
            f.color[p] = drawn ? colours.dark + v * (colours.light - colours.dark) : Vec3f(0.0f);
        });
    }
}

class TextureAdvectionMethod final : public RenderMethod {
  public:
    std::string_view name() const override { return "texture-advection"; }

    const MethodKeys& keys() const override { return kTextureAdvectionKeys; }

    Status check(const Scene& scene, const RenderOptions& options) const override {
        TR_TRY_STATUS(check_method_keys(scene, name(), keys()));
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
        return check_animated_scene(scene, options, name());
    }

    Result<RenderResult> render(Pipeline& pipeline, const Scene& scene,
                                const RenderOptions& options) const override {
        RenderResult result;
        NamedStats& stats = result.stats;
        TR_TRY(const SceneFlow flow, scene_flow(pipeline, scene));
        AdvectedSheetsOptions sheet_options;
        if (const MethodOption* o = option(scene, "slices")) {
            for (const std::vector<double>& s : *std::get_if<NumberLists>(o)) {
                sheet_options.slices.push_back({Vec3(s[0], s[1], s[2]), Vec3(s[3], s[4], s[5])});
            }
        } else if (flow.domain.planar) {  // a 2D flow: the sheet is its plane
            sheet_options.slices.push_back({flow.domain.planar->point, flow.domain.planar->normal});
        }
        TR_TRY_STATUS(
            check_layers_memory(scene, std::max<std::size_t>(1, sheet_options.slices.size())));
        sheet_options.sheet_resolution = static_cast<int>(integer_key(scene, "resolution", 256));
        const int steps = steps_of(scene);
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
        if (!made.ok()) return method_key_error(scene, made.error(), "slices");
        const std::unique_ptr<AdvectedSheets> sheets = std::move(made).value();
        stats.set("sheets_ms", ms_since(start));

        const CameraFrame frame(scene.camera, scene.width, scene.height);
        std::vector<std::vector<double>> depths;
        for (std::size_t s = 0; s < sheets->size(); ++s) {
            const Sheet& sheet = sheets->sheet(s);
            depths.push_back(plane_depths(frame, sheet.origin, sheet.normal));
        }
        const bool volume_drawn = !flow.domain.planar;
        if (!volume_drawn) result.notes.push_back(planar_scene_note(*flow.domain.planar));
        TR_TRY(const LayeredVolume volume,
               LayeredVolume::create(pipeline, scene, options, depths, stats, result.notes,
                                     volume_drawn));

        const float opacity = static_cast<float>(number_key(scene, "sheet_opacity", 0.6));
        const int last = last_frame(scene, options);
        std::vector<SurfaceFragments> fragments(sheets->size());
        double raster_ms = 0;
        TR_TRY(const FrameLoopTimes times,
               run_frame_loop(
                   last, static_cast<bool>(options.on_frame), [&] { sheets->advance(); },
                   [&](int k) -> Status {
                       const auto drawing = Clock::now();
                       sheet_fragments(frame, *sheets, opacity, fragments);
                       result.image = volume.composite(fragments);
                       raster_ms += ms_since(drawing);
                       return options.on_frame ? options.on_frame(k, result.image) : Status{};
                   }));
        stats.set("sheets", sheets->size());
        stats.set("sheet_points", sheets->points());
        stats.set("sheet_triangles", sheets->triangles());
        stats.set("mean_speed", sheets->mean_speed());
        stats.set("dt", sheets->dt());
        stats.set("frame", last);
        stats.set("advect_ms", times.advance_ms);
        stats.set("sheet_raster_ms", raster_ms);
        if (!(sheets->mean_speed() > 0)) {
            result.notes.push_back("zero velocity on every sheet: the frames are still");
        }
        return result;
    }
};

}  // namespace

std::unique_ptr<RenderMethod> make_texture_advection_method() {
    return std::make_unique<TextureAdvectionMethod>();
}

}  // namespace tr
