// tetrender render: a scene file, or a mesh with --scalar for a quick look, to PNG or PFM.
// Argument parsing and printing only: the pipeline (pipeline/pipeline.h) renders.
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <core/parallel.h>
#include <io/write_image.h>
#include <project/colormap_preset.h>
#include <project/scene.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <pipeline/annotations.h>
#include <pipeline/movie.h>
#include <pipeline/paraview_camera.h>
#include <pipeline/pipeline.h>
#include <pipeline/quick_scene.h>
#include <unistd.h>

namespace tr::apps {
namespace {

struct RenderArgs {
    std::string input;
    std::string output;
    std::string sort = "auto";
    std::string integrator = "preintegrated";
    std::string method;  // overrides the scene's
    std::optional<int> repetitions;
    std::optional<std::int64_t> seed;
    int threads = 0;
    bool stats = false;
    // Quick mode (input is a mesh).
    std::string scalar;
    bool point_data = false, cell_data = false;  // which of the two a name both has
    std::string component = "magnitude";
    std::string size = "800x600";
    std::string view = "iso";
    std::string colormap = "viridis";
    std::string write_scene_path;
    std::vector<std::string> volumes;  // quick mode: more volumes, MESH:ARRAY each
    std::vector<double> range;         // lo, hi
    std::string look = "fitted";
    std::optional<double> range_percent;
    bool log_scale = false;
    std::optional<double> opacity;
    std::vector<std::string> opacity_curve;  // t:a each
    std::optional<double> unit_distance;
    std::vector<double> background;  // r, g, b
    std::string time_step = "0";     // a step, or "all" (frames)
    double azimuth = 0, elevation = 0, zoom = 1;
    std::vector<double> camera_position, camera_focal_point, camera_view_up;
    std::optional<double> camera_view_angle;
    std::string camera_file;        // a ParaView .pvcc camera to render from
    std::string write_camera_file;  // the camera used, as a .pvcc
    bool fit_bounds = false;
    // Annotations and colour maps.
    std::string legend = "auto";  // auto: on in quick mode, off for scene files
    bool bounding_box = false, axes = false;
    std::string colormap_file;
    std::string write_colormap;
    // Animations.
    double orbit = 0;      // degrees in all
    int frame_count = 36;  // orbit frames
    std::string frames_dir;
    std::string movie;
    double fps = 24;
    // Splatting.
    std::string vectors;  // textured vector splats of this point array
    int cycle = 8;        // textures in their animation's cycle
    bool sheet_buffer = false;
};

// The time step of quick mode's mesh: a number, or 0 for "all" (the frames start there).
Result<int> first_time_step(const std::string& text) {
    if (text == "all") return 0;
    try {
        std::size_t used = 0;
        const int step = std::stoi(text, &used);
        if (used == text.size() && step >= 0) return step;
    } catch (const std::exception&) {
    }
    return make_error(ErrorCode::kInvalidArgument,
                      "--time-step takes a step (0, 1, ...) or all, not '" + text + "'");
}

bool is_scene_file(const std::string& path) {
    return path.size() > 5 && path.compare(path.size() - 5, 5, ".json") == 0;
}

// The quick-look scene of the mesh at `args.input` (loaded through the pipeline, which keeps it).
Result<Scene> quick_scene(Pipeline& pipeline, const RenderArgs& args) {
    if (args.look != "fitted" && args.look != "classic") {
        return make_error(ErrorCode::kInvalidArgument,
                          "--look takes fitted or classic, not '" + args.look + "'");
    }
    QuickSceneOptions options = args.look == "classic" ? classic_quick_look() : QuickSceneOptions{};
    options.scalar = args.scalar;
    if (args.component != "magnitude") {
        // A whole number >= 0: "-1" and "1.5" are not components (they used to mean the
        // magnitude and component 1).
        std::size_t used = 0;
        int component = -1;
        try {
            component = std::stoi(args.component, &used);
        } catch (...) {
            used = 0;
        }
        if (used != args.component.size() || component < 0) {
            return make_error(ErrorCode::kInvalidArgument,
                              "--component must be 'magnitude' or an index 0, 1, 2, ..., not '" +
                                  args.component + "'");
        }
        options.component = component;
    }
    if (!parse_image_size(args.size, options.width, options.height)) {
        return make_error(ErrorCode::kInvalidArgument, "--size must be WxH with sides in [1, " +
                                                           std::to_string(kMaxImageSide) +
                                                           "], not " + args.size);
    }
    options.view = args.view;
    options.colormap = args.colormap;
    if (!args.colormap_file.empty()) {
        // --colormap names the preset in the file (the first when it is the default).
        const std::string name = args.colormap == "viridis" ? "" : args.colormap;
        TR_TRY(options.colormap_preset, read_colormap_preset(args.colormap_file, name));
    }
    if (!args.range.empty()) options.range = std::array<double, 2>{args.range[0], args.range[1]};
    if (args.range_percent) options.range_percent = *args.range_percent;
    options.log_scale = args.log_scale;
    if (args.opacity) {
        options.max_opacity = *args.opacity;
        if (!options.opacity_curve.empty())
            options.opacity_curve = {{0.0, 0.0}, {1.0, *args.opacity}};
    }
    if (!args.opacity_curve.empty()) options.opacity_curve.clear();
    for (const std::string& point : args.opacity_curve) {
        const auto colon = point.find(':');
        try {
            if (colon == std::string::npos) throw std::invalid_argument(point);
            std::size_t used_t = 0, used_a = 0;
            const double t = std::stod(point.substr(0, colon), &used_t);
            const double a = std::stod(point.substr(colon + 1), &used_a);
            if (used_t != colon || used_a != point.size() - colon - 1) {
                throw std::invalid_argument(point);
            }
            options.opacity_curve.push_back({t, a});
        } catch (const std::exception&) {
            return make_error(ErrorCode::kInvalidArgument,
                              "--opacity-curve takes t:a points (t in [0, 1] across the range), "
                              "not '" +
                                  point + "'");
        }
    }
    if (args.unit_distance) options.unit_distance = *args.unit_distance;
    if (!args.background.empty()) {
        options.background = Vec3(args.background[0], args.background[1], args.background[2]);
    }
    TR_TRY(options.time_step, first_time_step(args.time_step));
    options.azimuth = args.azimuth, options.elevation = args.elevation, options.zoom = args.zoom;
    if (args.fit_bounds) options.fit_extent = false;
    if (!args.camera_position.empty() || !args.camera_focal_point.empty()) {
        if (args.camera_position.empty() || args.camera_focal_point.empty()) {
            return make_error(ErrorCode::kInvalidArgument,
                              "--camera-position and --camera-focal-point go together");
        }
        Camera camera;
        camera.position =
            Vec3(args.camera_position[0], args.camera_position[1], args.camera_position[2]);
        camera.focal_point = Vec3(args.camera_focal_point[0], args.camera_focal_point[1],
                                  args.camera_focal_point[2]);
        if (!args.camera_view_up.empty()) {
            camera.view_up =
                Vec3(args.camera_view_up[0], args.camera_view_up[1], args.camera_view_up[2]);
        } else {
            camera.view_up = Vec3(0, 0, 1);
        }
        if (args.camera_view_angle) camera.view_angle = *args.camera_view_angle;
        TR_TRY_STATUS(check_camera(camera));
        options.camera = camera;
    }
    if (!args.camera_file.empty()) {
        TR_TRY(options.camera, read_paraview_camera(args.camera_file));
    }
    SceneVolume volume;
    volume.mesh = std::filesystem::absolute(args.input);
    volume.time_step = options.time_step;
    TR_TRY(const std::shared_ptr<const LoadedMesh> loaded, pipeline.mesh(volume));
    // No --scalar: the first array, or where the mesh is when it has none.
    std::shared_ptr<const TetMesh> constant;
    std::vector<std::string> notes;
    if (options.scalar.empty()) {
        options.scalar = default_quick_scalar(loaded->tets);
        if (options.scalar.empty()) {
            options.scalar = "constant";
            constant = with_constant_field(loaded->tets, options.scalar);
            notes.push_back(
                "the mesh has no arrays: showing where it is (give --scalar NAME "
                "for a mesh with arrays)");
        } else {
            notes.push_back("no --scalar: showing '" + options.scalar + "', the mesh's first " +
                            (loaded->tets.point_fields().empty() ? "cell" : "point") + " array");
        }
    }
    // A name that is both point and cell data: the point data unless --cell-data says.
    const auto has = [&](const std::vector<Field>& fields) {
        return std::any_of(fields.begin(), fields.end(),
                           [&](const Field& f) { return f.name == options.scalar; });
    };
    const bool as_point = has(loaded->tets.point_fields());
    const bool as_cell = has(loaded->tets.cell_fields());
    if ((args.point_data && !as_point) || (args.cell_data && !as_cell)) {
        return make_error(ErrorCode::kNotFound,
                          "no " + std::string(args.point_data ? "point" : "cell") + " array '" +
                              options.scalar + "'",
                          args.input);
    }
    if (args.cell_data && as_point) {
        constant = without_point_field(loaded->tets, options.scalar);
        notes.push_back("--cell-data: '" + options.scalar +
                        "' from the cell data (a scene written now would read the point data)");
    } else if (as_point && as_cell && !args.point_data) {
        notes.push_back("'" + options.scalar +
                        "' is both point and cell data: showing the point data (--cell-data for "
                        "the other)");
    }
    const TetMesh& shown = constant ? *constant : loaded->tets;
    // More volumes in the same space: MESH:ARRAY each (the array after the last colon).
    std::vector<std::shared_ptr<const LoadedMesh>> others;
    std::vector<QuickVolume> more;
    for (const std::string& spec : args.volumes) {
        const auto colon = spec.rfind(':');
        if (colon == std::string::npos || colon == 0 || colon + 1 == spec.size()) {
            return make_error(ErrorCode::kInvalidArgument,
                              "--volume takes MESH:ARRAY, not '" + spec + "'");
        }
        SceneVolume other;
        other.mesh = std::filesystem::absolute(spec.substr(0, colon));
        other.time_step = options.time_step;
        TR_TRY(std::shared_ptr<const LoadedMesh> mesh, pipeline.mesh(other));
        more.push_back({other.mesh, &mesh->tets, spec.substr(colon + 1), -1, ""});
        others.push_back(std::move(mesh));
    }
    // Of a field of ones, the note that it is constant says nothing new.
    std::vector<std::string> scene_notes;
    auto scene = make_quick_scene(volume.mesh, shown, options, more, &scene_notes);
    if (!constant) notes.insert(notes.end(), scene_notes.begin(), scene_notes.end());
    if (!scene.ok()) return with_where(scene.error(), args.input);
    if (constant) scene->volumes[0].tets = constant;  // handed over: the file has no such array
    print_notes(notes);
    return scene;
}

// The frames of an orbit (--orbit) or of every time step (--time-step all), each written as
// frame_NNNN.png into --frames DIR (or a temporary folder) and, with --movie, encoded.
template <class Picture>
int render_frames(const RenderArgs& args, const Scene& scene, const Picture& picture,
                  Pipeline& pipeline) {
    std::filesystem::path dir = args.frames_dir;
    std::filesystem::path temporary;
    if (dir.empty()) {
        temporary = std::filesystem::temp_directory_path() /
                    ("tetrender_frames_" + std::to_string(::getpid()));
        std::filesystem::create_directories(temporary);
        dir = temporary;
    }
    const auto cleanup = [&] {
        std::error_code ignored;
        if (!temporary.empty()) std::filesystem::remove_all(temporary, ignored);
    };
    AnimationSpec spec;
    spec.orbit_degrees = args.orbit;
    spec.orbit_frames = args.frame_count;
    spec.every_time_step = args.time_step == "all";
    spec.splat_cycle = args.vectors.empty() ? 0 : args.cycle;
    const auto written =
        for_each_animation_frame(pipeline, scene, spec, [&](int k, const Scene& view) -> Status {
            TR_TRY(const RenderResult result, picture(view));
            TR_TRY_STATUS(write_image(result.image, frame_path(dir, k).string()));
            if (!args.output.empty() && k == 0) {
                TR_TRY_STATUS(write_image(result.image, args.output));
            }
            if (::isatty(STDERR_FILENO)) std::fprintf(stderr, "\rframe %d", k + 1);
            return Status{};
        });
    if (!written.ok()) {
        cleanup();
        return report_error(written.error());
    }
    if (::isatty(STDERR_FILENO)) std::fprintf(stderr, "\n");
    if (!args.movie.empty()) {
        const Status encoded = encode_movie(dir, args.fps, args.movie);
        cleanup();
        if (!encoded.ok()) return report_error(encoded.error());
    }
    cleanup();
    std::fprintf(stderr, "tetrender: %d frames%s%s\n", *written,
                 args.frames_dir.empty() ? "" : (" in " + args.frames_dir).c_str(),
                 args.movie.empty() ? "" : (", movie " + args.movie).c_str());
    return kExitOk;
}

int run_render(const RenderArgs& args) {
    RenderOptions options;
    if (auto sort = sort_method_named(args.sort); sort.ok()) {
        options.sort = *sort;
    } else {
        return report_usage(sort.error());
    }
    if (const Status set = set_integrator_option(options, args.integrator); !set.ok()) {
        return report_usage(set.error());
    }
    const bool scene_mode = is_scene_file(args.input);
    if (scene_mode && !args.volumes.empty()) {
        std::fprintf(stderr, "tetrender: --volume is for quick mode; a scene lists `volumes`\n");
        return kExitUsage;
    }
    if (scene_mode && args.log_scale) {
        std::fprintf(stderr,
                     "tetrender: --log is for quick mode; a scene's transfer function is its own "
                     "(quick mode's --log --write-scene writes one)\n");
        return kExitUsage;
    }
    const bool animated = args.orbit != 0 || args.time_step == "all" || !args.frames_dir.empty() ||
                          !args.movie.empty();
    if (!args.vectors.empty() && args.orbit != 0) {
        std::fprintf(stderr,
                     "tetrender: --vectors animates the splats' textures; it does not "
                     "take --orbit\n");
        return kExitUsage;
    }
    if (!args.vectors.empty() && args.sheet_buffer) {
        std::fprintf(stderr,
                     "tetrender: --vectors draws each splat whole; it does not take "
                     "--sheet-buffer\n");
        return kExitUsage;
    }
    if (args.output.empty() && !animated) {
        std::fprintf(stderr, "tetrender: render needs -o FILE (or --frames DIR / --movie FILE)\n");
        return kExitUsage;
    }
    if (!args.output.empty()) {
        if (const Status ok = check_output_path(args.output, {".png", ".pfm"}); !ok.ok()) {
            return report_usage(ok.error());
        }
    }
    if (animated) {
        if (args.frames_dir.empty() && args.movie.empty()) {
            std::fprintf(stderr,
                         "tetrender: --orbit and --time-step all write --frames DIR or "
                         "--movie FILE\n");
            return kExitUsage;
        }
        if (!args.movie.empty()) {
            if (const Status ok = check_output_path(args.movie, {".mp4", ".webm", ".gif"});
                !ok.ok()) {
                return report_usage(ok.error());
            }
            if (!movie_encoder_available()) {
                std::fprintf(stderr,
                             "tetrender: --movie needs the ffmpeg program (Debian: "
                             "apt-get install ffmpeg); --frames DIR writes the frames\n");
                return kExitError;
            }
        }
        if (!args.frames_dir.empty()) {
            std::error_code made;
            std::filesystem::create_directories(args.frames_dir, made);
            if (made || !std::filesystem::is_directory(args.frames_dir)) {
                std::fprintf(stderr, "tetrender: %s: cannot make the frames folder\n",
                             args.frames_dir.c_str());
                return kExitError;
            }
        }
    }
    if (args.legend != "auto" && args.legend != "on" && args.legend != "off") {
        std::fprintf(stderr, "tetrender: --legend takes on or off, not '%s'\n",
                     args.legend.c_str());
        return kExitUsage;
    }
    if (!args.write_colormap.empty()) {
        if (const Status ok = check_output_path(args.write_colormap, {".json"}); !ok.ok()) {
            return report_usage(ok.error());
        }
    }
    if (!args.write_camera_file.empty()) {
        if (const Status ok = check_output_path(args.write_camera_file, {".pvcc"}); !ok.ok()) {
            return report_usage(ok.error());
        }
    }
    if (!args.camera_file.empty() && !args.camera_position.empty()) {
        std::fprintf(stderr,
                     "tetrender: --camera takes a .pvcc file; give it or the "
                     "--camera-* values, not both\n");
        return kExitUsage;
    }
    if (args.threads > 0) set_thread_count(args.threads);

    PipelineOptions pipeline_options;
    pipeline_options.progress = terminal_progress();
    Pipeline pipeline(pipeline_options);
    Scene scene;
    if (scene_mode) {
        auto read = read_scene(args.input);
        if (!read.ok()) return report_error(read.error());
        scene = std::move(read).value();
        if (!args.colormap_file.empty()) {
            const auto preset = read_colormap_preset(args.colormap_file, "");
            if (!preset.ok()) return report_error(preset.error());
            for (SceneVolume& v : scene.volumes) {
                const TransferFunction& tf = v.transfer_function;
                auto recoloured = preset_transfer_function(*preset, tf.color_points().front().s,
                                                           tf.color_points().back().s,
                                                           tf.opacity_points(), tf.unit_distance());
                if (!recoloured.ok()) return report_error(recoloured.error());
                v.transfer_function = std::move(recoloured).value();
            }
        }
    } else {
        auto quick = quick_scene(pipeline, args);
        if (!quick.ok()) return report_error(quick.error());
        scene = std::move(quick).value();
    }
    const bool splat_keys = !args.vectors.empty() || args.sheet_buffer;
    if (!args.method.empty() || args.repetitions || args.seed || splat_keys) {
        MethodSpec method = scene.method.value_or(MethodSpec{});
        if (!args.method.empty()) method.name = args.method;
        if (args.repetitions) method.repetitions = args.repetitions;
        if (args.seed) method.seed = args.seed;
        if (splat_keys) {
            if (!args.method.empty() && args.method != "splat") {
                std::fprintf(stderr,
                             "tetrender: --vectors and --sheet-buffer are for --method "
                             "splat\n");
                return kExitUsage;
            }
            method.name = "splat";
        }
        if (!args.vectors.empty()) {
            method.options["vectors"] = args.vectors;
            method.options["cycle"] = static_cast<std::int64_t>(args.cycle);
        }
        if (args.sheet_buffer) method.options["compositing"] = std::string("sheet-buffer");
        scene.method = method;
    }
    if (scene_mode && !args.camera_file.empty()) {
        auto camera = read_paraview_camera(args.camera_file);
        if (!camera.ok()) return report_error(camera.error());
        scene.camera = *camera;
    }
    if (!args.write_camera_file.empty()) {
        const Status written = write_paraview_camera(scene.camera, args.write_camera_file);
        if (!written.ok()) return report_error(written.error());
    }
    if (!scene_mode && !args.write_scene_path.empty()) {
        const Status written = write_scene(scene, args.write_scene_path);
        if (!written.ok()) return report_error(written.error());
    }
    if (!args.write_colormap.empty()) {
        const Status written = write_colormap_presets(
            {preset_from_transfer_function(scene.volumes[0].transfer_function,
                                           scene.volumes[0].scalar)},
            args.write_colormap);
        if (!written.ok()) return report_error(written.error());
    }
    // One picture of `view`: rendered, notes printed, annotated.
    const bool legend =
        args.legend == "on" || (args.legend == "auto" && !scene_mode && args.look != "classic");
    const auto picture = [&](const Scene& view) -> Result<RenderResult> {
        TR_TRY(RenderResult result, pipeline.render(view, options));
        print_notes(result.notes);
        // The classic look had no legend: its pictures stay comparable.
        if (legend || args.bounding_box || args.axes) {
            AnnotationOptions annotations;
            annotations.legend = legend;
            annotations.bounding_box = args.bounding_box;
            annotations.axes = args.axes;
            const Status drawn = annotate(result.image, view, pipeline, annotations);
            // A picture too small for its legend is still a picture: say so and go on.
            if (!drawn.ok()) print_notes({"no annotations: " + drawn.error().message});
        }
        return result;
    };
    if (animated) return render_frames(args, scene, picture, pipeline);
    auto result = picture(scene);
    if (!result.ok()) return report_error(result.error());
    const Status written = write_image(result->image, args.output);
    if (!written.ok()) return report_error(written.error());
    if (args.stats) print_stats(result->stats);
    return kExitOk;
}

}  // namespace

std::function<int()> add_render_command(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand(
        "render", "Render a scene file, or a mesh with --scalar for a quick look, to PNG/PFM");
    cmd->add_option("input", args->input, "Scene file (.json) or mesh file")->required();
    cmd->add_option("-o,--output", args->output,
                    "Output image (.png, or .pfm for floats); with frames, the first frame");
    cmd->add_option("--method", args->method,
                    "Rendering method, overriding the scene's: projected-tetrahedra (default; "
                    "several volumes by the exact segment merge), pbvr-image, pbvr-object "
                    "(particles: --repetitions, --seed), splat (the mesh's points, a kernel each)");
    cmd->add_option("--repetitions", args->repetitions,
                    "Stochastic methods: ensemble size (>= 1), overriding the scene's")
        ->check(CLI::Range(1, 1 << 20));
    cmd->add_option("--seed", args->seed,
                    "Stochastic methods: random seed (the same seed gives the same picture)");
    cmd->add_option("--sort", args->sort, "auto (default), mpvo, mpvonc, exact, centroid");
    cmd->add_option("--integrator", args->integrator,
                    "preintegrated (default), exact, exp-texture, or reference (the slow "
                    "brute-force ray caster the others are tested against)");
    cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 1024));
    cmd->add_flag("--stats", args->stats,
                  "Print one JSON line: time of each phase (ms), cells drawn, fragments");
    cmd->add_option("--scalar", args->scalar,
                    "Quick mode: the array to render (default: the first point array, else the "
                    "first cell array, else where the mesh is)");
    cmd->add_flag("--point-data", args->point_data,
                  "Quick mode: the point array of that name, when it is cell data too (default)");
    cmd->add_flag("--cell-data", args->cell_data,
                  "Quick mode: the cell array of that name, when it is point data too")
        ->excludes("--point-data");
    cmd->add_option("--component", args->component,
                    "Quick mode: 'magnitude' (default) or a component index");
    cmd->add_option("--size", args->size, "Quick mode: image size WxH (default 800x600)");
    cmd->add_option("--view", args->view, "Quick mode: iso (default), +x, -x, +y, -y, +z, -z");
    cmd->add_option("--colormap", args->colormap,
                    "Quick mode: viridis (default), coolwarm, inferno, gray, or a ParaView preset "
                    "name (Cool to Warm, Jet, Rainbow Uniform, Black-Body Radiation, ...)");
    cmd->add_option(
        "--look", args->look,
        "Quick mode: fitted (default: robust range, every value visible, the object "
        "framed) or classic (tetrender's look before 2026-11, for comparable pictures)");
    cmd->add_option("--range", args->range,
                    "Quick mode: the scalar range under the colour map and opacity, lo,hi "
                    "(default: the 1st to 99th percentile of the point values)")
        ->expected(2)
        ->delimiter(',');
    cmd->add_option("--range-percentile", args->range_percent,
                    "Quick mode: the range from the P-th to the (100-P)-th percentile (default 1; "
                    "0: the whole range)")
        ->check(CLI::Range(0.0, 49.0));
    cmd->add_flag("--log", args->log_scale,
                  "Quick mode: a log colour scale: colours and opacity spread over log10 of the "
                  "range (of the positive values; those <= 0 take the low end's colour), the "
                  "legend's ticks at powers of ten");
    cmd->add_option("--opacity", args->opacity,
                    "Quick mode: the opacity at the range's top (default 0.5), a fifth of it at "
                    "the bottom")
        ->check(CLI::Range(0.001, 0.999));
    cmd->add_option("--opacity-curve", args->opacity_curve,
                    "Quick mode: opacity points t:a,... with t in [0, 1] across the range")
        ->delimiter(',');
    cmd->add_option("--unit-distance", args->unit_distance,
                    "Quick mode: the thickness a slab of the stated opacity has (default: chosen "
                    "so that a typical ray through the object reaches opacity 0.8)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--background", args->background, "Quick mode: background r,g,b in [0, 1]")
        ->expected(3)
        ->delimiter(',')
        ->check(CLI::Range(0.0, 1.0));
    cmd->add_option("--time-step", args->time_step,
                    "Quick mode: the time step to read (default 0); all (scene files too): a "
                    "frame of each step (--frames, --movie), with step 0's range and camera");
    cmd->add_option("--orbit", args->orbit,
                    "Frames turning this many degrees about the camera's up axis (--frame-count, "
                    "--frames, --movie)")
        ->check(CLI::Range(-3600.0, 3600.0));
    cmd->add_option("--frame-count", args->frame_count, "Frames of an orbit (default 36)")
        ->check(CLI::Range(1, 100000));
    cmd->add_option("--frames", args->frames_dir,
                    "Write the frames as DIR/frame_0000.png, ... (made if missing)");
    cmd->add_option("--movie", args->movie,
                    "Encode the frames into a movie (.mp4, .webm, .gif) with the ffmpeg program");
    cmd->add_option("--vectors", args->vectors,
                    "Splat: textured vector splats along this 3-component point array (method "
                    "splat); with --frames or --movie, the frames of their texture cycle")
        ->check(CLI::TypeValidator<std::string>());
    cmd->add_option(
           "--cycle", args->cycle,
           "Splat: textures in the vector splats' cycle (default 8; frame k + N is frame k)")
        ->check(CLI::Range(1, 1024));
    cmd->add_flag("--sheet-buffer", args->sheet_buffer,
                  "Splat: Westover's sheet buffer (splats summed per sheet of lattice planes, "
                  "sheets composited) instead of each splat composited whole");
    cmd->add_option("--fps", args->fps, "Movie frames per second (default 24)")
        ->check(CLI::Range(0.1, 1000.0));
    cmd->add_option("--azimuth", args->azimuth,
                    "Quick mode: turn the view about the up axis, degrees (ParaView's Azimuth)")
        ->check(CLI::Range(-360.0, 360.0));
    cmd->add_option("--elevation", args->elevation,
                    "Quick mode: raise the view towards the up axis, degrees (ParaView's "
                    "Elevation)")
        ->check(CLI::Range(-89.0, 89.0));
    cmd->add_option("--zoom", args->zoom, "Quick mode: magnify by this factor (VTK's Zoom)")
        ->check(CLI::Range(0.01, 100.0));
    cmd->add_flag("--fit-bounds", args->fit_bounds,
                  "Quick mode: frame the bounds' sphere instead of the object's projected extent");
    cmd->add_option("--camera-position", args->camera_position,
                    "Quick mode: the camera as ParaView gives it: position x,y,z (with "
                    "--camera-focal-point, --camera-view-up, --camera-view-angle)")
        ->expected(3)
        ->delimiter(',');
    cmd->add_option("--camera", args->camera_file,
                    "Render from a camera ParaView saved (.pvcc: Save Camera), in quick mode and "
                    "for a scene file");
    cmd->add_option("--write-camera", args->write_camera_file,
                    "Write the camera used as a ParaView .pvcc file (Load Camera)");
    cmd->add_option("--camera-focal-point", args->camera_focal_point, "Quick mode: x,y,z")
        ->expected(3)
        ->delimiter(',');
    cmd->add_option("--camera-view-up", args->camera_view_up, "Quick mode: x,y,z (default +z)")
        ->expected(3)
        ->delimiter(',');
    cmd->add_option("--camera-view-angle", args->camera_view_angle,
                    "Quick mode: vertical view angle, degrees (default 30)")
        ->check(CLI::Range(0.1, 179.0));
    cmd->add_option("--legend", args->legend,
                    "on or off: a colour bar with the array's name, range and ticks (default: on "
                    "in quick mode, off for scene files, which are compared pixel for pixel, and "
                    "for --look classic)");
    cmd->add_flag("--bounding-box", args->bounding_box, "Draw the meshes' bounding box");
    cmd->add_flag("--axes", args->axes, "Draw an x, y, z axes triad in a corner");
    cmd->add_option(
        "--colormap-file", args->colormap_file,
        "A ParaView colour-map preset file (JSON); --colormap names the preset in it "
        "(default: its first); for a scene file, recolours every volume over its range");
    cmd->add_option("--write-colormap", args->write_colormap,
                    "Write volume 0's transfer function as a ParaView preset (.json)");
    cmd->add_option("--write-scene", args->write_scene_path,
                    "Quick mode: save the scene used, to edit and re-render");
    cmd->add_option("--volume", args->volumes,
                    "Quick mode: one more volume in the same space, MESH:ARRAY (repeatable; each "
                    "with its own colour map over its own range, drawn fused)");
    return [args] { return run_render(*args); };
}

}  // namespace tr::apps
