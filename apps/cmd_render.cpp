// tetrender render: a scene file, or a mesh with --scalar for a quick look, to PNG or PFM.
// Argument parsing and printing only: the pipeline (pipeline/pipeline.h) renders.
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <apps/quick_look_args.h>
#include <core/parallel.h>
#include <io/write_image.h>
#include <pipeline/annotations.h>
#include <pipeline/movie.h>
#include <pipeline/paraview_camera.h>
#include <pipeline/pipeline.h>
#include <pipeline/quick_scene.h>
#include <pipeline/scene.h>
#include <project/colormap_preset.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
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
    QuickLookArgs quick;
    std::string size = "800x600";
    std::string write_scene_path;
    std::vector<std::string> volumes;  // quick mode: more volumes, MESH:ARRAY each
    std::string time_step = "0";       // a step, or "all" (frames)
    std::string write_camera_file;     // the camera used, as a .pvcc
    // Quick-mode options given (filled when the command line is parsed): refused with a scene.
    std::vector<std::string> quick_given;
    // Annotations and colour maps.
    std::string legend = "auto";  // auto: on in quick mode, off for scene files
    bool bounding_box = false, axes = false;
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

// The quick-look scene of the mesh at `args.input` (loaded through the pipeline, which keeps it);
// `notes` receives what was chosen (printed after the picture: an error stays one line).
Result<Scene> quick_scene(Pipeline& pipeline, const RenderArgs& args,
                          std::vector<std::string>& notes) {
    TR_TRY(QuickSceneOptions options, quick_scene_options(args.quick));
    if (!parse_image_size(args.size, options.width, options.height)) {
        return make_error(ErrorCode::kInvalidArgument, "--size must be WxH with sides in [1, " +
                                                           std::to_string(kMaxImageSide) +
                                                           "], not " + args.size);
    }
    TR_TRY(options.time_step, first_time_step(args.time_step));
    TR_TRY_STATUS(check_picture_memory(options.width, options.height));  // before the loading
    QuickFileOptions file = quick_file_options(args.quick);
    file.every_time_step = args.time_step == "all";
    // More volumes in the same space: MESH:ARRAY each (the array after the last colon).
    for (const std::string& spec : args.volumes) {
        const auto colon = spec.rfind(':');
        if (colon == std::string::npos || colon == 0 || colon + 1 == spec.size()) {
            return make_error(ErrorCode::kInvalidArgument,
                              "--volume takes MESH:ARRAY, not '" + spec + "'");
        }
        file.more.emplace_back(spec.substr(0, colon), spec.substr(colon + 1));
    }
    return quick_scene_of_file(pipeline, args.input, options, file, &notes);
}

// Whether the scene's method animates by itself (its frames 0 .. steps: texture-advection,
// spot-noise).
bool animated_method(const Scene& scene) {
    return scene.method_name() == "texture-advection" || scene.method_name() == "spot-noise";
}

// The frames of an orbit (--orbit), of every time step (--time-step all) or of an animated
// method, each written as frame_NNNN.png into --frames DIR (or a temporary folder) and, with
// --movie, encoded.

template <class Picture>
int render_frames(const RenderArgs& args, const Scene& scene, const Picture& picture,
                  Pipeline& pipeline, RenderOptions& options) {
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
    // An animated method hands over its frames from one render.
    int method_frames = 0;
    options.on_frame = [&](int k, const Image& image) -> Status {
        TR_TRY_STATUS(write_image(image, frame_path(dir, k).string()));
        if (!args.output.empty() && k == 0) TR_TRY_STATUS(write_image(image, args.output));
        if (::isatty(STDERR_FILENO)) std::fprintf(stderr, "\rframe %d", k + 1);
        ++method_frames;
        return Status{};
    };
    if (!animated_method(scene)) options.on_frame = nullptr;
    const auto method_render = [&]() -> Result<int> {
        TR_TRY(const RenderResult result, picture(scene));
        return method_frames;
    };
    const auto written =
        options.on_frame
            ? method_render()
            : for_each_animation_frame(
                  pipeline, scene, spec, [&](int k, const Scene& view) -> Status {
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

// The command line's combinations that cannot work, refused before any work: the exit code of
// the refusal (its message printed), or none.
std::optional<int> refuse_render_args(const RenderArgs& args, bool scene_mode, bool animated) {
    if (scene_mode && !args.volumes.empty()) {
        std::fprintf(stderr, "tetrender: --volume is for quick mode; a scene lists `volumes`\n");
        return kExitUsage;
    }
    if (scene_mode && !args.quick_given.empty()) {
        // A scene's transfer function, size and array are its own: say so rather than ignore.
        std::fprintf(stderr,
                     "tetrender: %s is for quick mode (a mesh file); a scene file says it "
                     "itself (quick mode's --write-scene writes one to edit)\n",
                     args.quick_given.front().c_str());
        return kExitUsage;
    }
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
    if (!args.quick.camera_file.empty() && !args.quick.camera_position.empty()) {
        std::fprintf(stderr,
                     "tetrender: --camera takes a .pvcc file; give it or the "
                     "--camera-* values, not both\n");
        return kExitUsage;
    }
    return std::nullopt;
}

// The scene to render: the scene file (recoloured by --colormap-file), or the quick-look scene
// of a mesh file (its notes into `quick_notes`, printed with the first picture).
Result<Scene> load_render_scene(const RenderArgs& args, bool scene_mode, Pipeline& pipeline,
                                std::vector<std::string>& quick_notes) {
    Scene scene;
    if (scene_mode) {
        auto read = read_scene(args.input);
        if (!read.ok()) return read.error();
        scene = std::move(read).value();
        if (!args.quick.colormap_file.empty()) {
            const std::string name = args.quick.colormap == "viridis" ? "" : args.quick.colormap;
            const auto preset = read_colormap_preset(args.quick.colormap_file, name);
            if (!preset.ok()) return preset.error();
            for (SceneVolume& v : scene.volumes) {
                const TransferFunction& tf = v.transfer_function;
                auto recoloured = preset_transfer_function(*preset, tf.color_points().front().s,
                                                           tf.color_points().back().s,
                                                           tf.opacity_points(), tf.unit_distance());
                if (!recoloured.ok()) return recoloured.error();
                v.transfer_function = std::move(recoloured).value();
            }
        }
    } else {
        auto quick = quick_scene(pipeline, args, quick_notes);
        if (!quick.ok()) return quick.error();
        scene = std::move(quick).value();
    }
    return scene;
}

// --method, --repetitions, --seed, --vectors and --sheet-buffer over the scene's method: the
// exit code of a refusal (its message printed), or none.
std::optional<int> override_method(const RenderArgs& args, Scene& scene) {
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
    return std::nullopt;
}

// --camera in scene mode, and the files written beside the picture: --write-camera,
// --write-scene, --write-colormap.
Status apply_camera_and_write_side_files(const RenderArgs& args, bool scene_mode, Scene& scene) {
    if (scene_mode && !args.quick.camera_file.empty()) {
        auto camera = read_paraview_camera(args.quick.camera_file);
        if (!camera.ok()) return camera.error();
        scene.camera = *camera;
    }
    if (!args.write_camera_file.empty()) {
        const Status written = write_paraview_camera(scene.camera, args.write_camera_file);
        if (!written.ok()) return written.error();
    }
    if (!scene_mode && !args.write_scene_path.empty()) {
        const Status written = write_scene(scene, args.write_scene_path);
        if (!written.ok()) return written.error();
    }
    if (!args.write_colormap.empty()) {
        const Status written = write_colormap_presets(
            {preset_from_transfer_function(scene.volumes[0].transfer_function,
                                           scene.volumes[0].scalar)},
            args.write_colormap);
        if (!written.ok()) return written.error();
    }
    return Status{};
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
    const bool animated = args.orbit != 0 || args.time_step == "all" || !args.frames_dir.empty() ||
                          !args.movie.empty();
    if (const auto refused = refuse_render_args(args, scene_mode, animated)) return *refused;
    if (args.threads > 0) set_thread_count(args.threads);

    PipelineOptions pipeline_options;
    pipeline_options.progress = terminal_progress();
    Pipeline pipeline(pipeline_options);
    std::vector<std::string> quick_notes;  // printed with the first picture
    auto loaded = load_render_scene(args, scene_mode, pipeline, quick_notes);
    if (!loaded.ok()) return report_error(loaded.error());
    Scene scene = std::move(loaded).value();
    if (const auto refused = override_method(args, scene)) return *refused;
    if (const Status done = apply_camera_and_write_side_files(args, scene_mode, scene);
        !done.ok()) {
        return report_error(done.error());
    }
    // One picture of `view`: rendered, notes printed, annotated.
    const bool legend =
        args.legend == "on" ||
        (args.legend == "auto" && legend_by_default(scene_mode, args.quick.look == "classic"));
    const auto picture = [&](const Scene& view) -> Result<RenderResult> {
        TR_TRY(RenderResult result, pipeline.render(view, options));
        print_notes(quick_notes);
        quick_notes.clear();
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
    if (animated && animated_method(scene) && (args.orbit != 0 || args.time_step == "all")) {
        std::fprintf(stderr,
                     "tetrender: %s animates its own frames (--frames, --movie); it does not "
                     "take --orbit or --time-step all\n",
                     scene.method_name().c_str());
        return kExitUsage;
    }
    if (animated) return render_frames(args, scene, picture, pipeline, options);
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
                    "(particles: --repetitions, --seed), splat (the mesh's points, a kernel each); "
                    "texture-advection and spot-noise take their keys from the scene file");
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
    add_quick_look_options(*cmd, args->quick, true, "Quick mode: ");
    cmd->add_option("--size", args->size, "Quick mode: image size WxH (default 800x600)");
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
    cmd->add_option("--write-camera", args->write_camera_file,
                    "Write the camera used as a ParaView .pvcc file (Load Camera)");
    cmd->add_option("--legend", args->legend,
                    "on or off: a colour bar with the array's name, range and ticks (default: on "
                    "in quick mode, off for scene files, which are compared pixel for pixel, and "
                    "for --look classic)");
    cmd->add_flag("--bounding-box", args->bounding_box, "Draw the meshes' bounding box");
    cmd->add_flag("--axes", args->axes, "Draw an x, y, z axes triad in a corner");
    cmd->add_option("--write-colormap", args->write_colormap,
                    "Write volume 0's transfer function as a ParaView preset (.json)");
    cmd->add_option("--write-scene", args->write_scene_path,
                    "Quick mode: save the scene used, to edit and re-render");
    cmd->add_option("--volume", args->volumes,
                    "Quick mode: one more volume in the same space, MESH:ARRAY (repeatable; each "
                    "with its own colour map over its own range, drawn fused)");
    return [args, cmd] {
        // With a scene file these are refused; --camera and --colormap-file apply to it too
        // (--colormap naming the preset in the file).
        args->quick_given = quick_look_options_given(*cmd, {"--camera", "--colormap-file"});
        for (const char* name :
             {"--scalar", "--opacity", "--unit-distance", "--size", "--write-scene", "--volume"}) {
            if (cmd->count(name) > 0) args->quick_given.push_back(name);
        }
        if (cmd->count("--colormap") > 0 && args->quick.colormap_file.empty()) {
            args->quick_given.push_back("--colormap");
        }
        return run_render(*args);
    };
}

}  // namespace tr::apps
