// tetrender render: a scene file, or a mesh with --scalar for a quick look, to PNG or PFM.
// Argument parsing and printing only: the pipeline (pipeline/pipeline.h) renders.
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <core/parallel.h>
#include <io/write_image.h>
#include <project/scene.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <pipeline/pipeline.h>
#include <pipeline/quick_scene.h>

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
    std::string component = "magnitude";
    std::string size = "800x600";
    std::string view = "iso";
    std::string colormap = "viridis";
    std::string write_scene_path;
    std::vector<std::string> volumes;  // quick mode: more volumes, MESH:ARRAY each
};

bool is_scene_file(const std::string& path) {
    return path.size() > 5 && path.compare(path.size() - 5, 5, ".json") == 0;
}

// The quick-look scene of the mesh at `args.input` (loaded through the pipeline, which keeps it).
Result<Scene> quick_scene(Pipeline& pipeline, const RenderArgs& args) {
    QuickSceneOptions options;
    options.scalar = args.scalar;
    if (args.component != "magnitude") {
        try {
            options.component = std::stoi(args.component);
        } catch (...) {
            return make_error(ErrorCode::kInvalidArgument,
                              "--component must be 'magnitude' or an index");
        }
    }
    if (!parse_image_size(args.size, options.width, options.height)) {
        return make_error(ErrorCode::kInvalidArgument, "--size must be WxH with sides in [1, " +
                                                           std::to_string(kMaxImageSide) +
                                                           "], not " + args.size);
    }
    options.view = args.view;
    options.colormap = args.colormap;
    SceneVolume volume;
    volume.mesh = std::filesystem::absolute(args.input);
    TR_TRY(const std::shared_ptr<const LoadedMesh> loaded, pipeline.mesh(volume));
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
        TR_TRY(std::shared_ptr<const LoadedMesh> mesh, pipeline.mesh(other));
        more.push_back({other.mesh, &mesh->tets, spec.substr(colon + 1), -1, ""});
        others.push_back(std::move(mesh));
    }
    auto scene = make_quick_scene(volume.mesh, loaded->tets, options, more);
    if (!scene.ok()) return with_where(scene.error(), args.input);
    return scene;
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
    if (!scene_mode && args.scalar.empty()) {
        std::fprintf(stderr,
                     "tetrender: rendering a mesh file needs --scalar NAME (or give a "
                     "scene .json)\n");
        return kExitUsage;
    }
    if (const Status ok = check_output_path(args.output, {".png", ".pfm"}); !ok.ok()) {
        return report_usage(ok.error());
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
    } else {
        auto quick = quick_scene(pipeline, args);
        if (!quick.ok()) return report_error(quick.error());
        scene = std::move(quick).value();
    }
    if (!args.method.empty() || args.repetitions || args.seed) {
        MethodSpec method = scene.method.value_or(MethodSpec{});
        if (!args.method.empty()) method.name = args.method;
        if (args.repetitions) method.repetitions = args.repetitions;
        if (args.seed) method.seed = args.seed;
        scene.method = method;
    }
    if (!scene_mode && !args.write_scene_path.empty()) {
        const Status written = write_scene(scene, args.write_scene_path);
        if (!written.ok()) return report_error(written.error());
    }
    auto result = pipeline.render(scene, options);
    if (!result.ok()) return report_error(result.error());
    print_notes(result->notes);
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
    cmd->add_option("-o,--output", args->output, "Output image (.png, or .pfm for floats)")
        ->required();
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
    cmd->add_option("--scalar", args->scalar, "Quick mode: the array to render");
    cmd->add_option("--component", args->component,
                    "Quick mode: 'magnitude' (default) or a component index");
    cmd->add_option("--size", args->size, "Quick mode: image size WxH (default 800x600)");
    cmd->add_option("--view", args->view, "Quick mode: iso (default), +x, -x, +y, -y, +z, -z");
    cmd->add_option("--colormap", args->colormap,
                    "Quick mode: viridis (default), coolwarm, inferno, gray");
    cmd->add_option("--write-scene", args->write_scene_path,
                    "Quick mode: save the scene used, to edit and re-render");
    cmd->add_option("--volume", args->volumes,
                    "Quick mode: one more volume in the same space, MESH:ARRAY (repeatable; each "
                    "with its own colour map over its own range, drawn fused)");
    return [args] { return run_render(*args); };
}

}  // namespace tr::apps
