// tetrender flowvol MESH --vectors NAME [--seed-center x,y,z] [--seed-size w,h] [--dt T]: dye
// released through a polygon, grown layer by layer through the flow, rendered without sorting;
// what is not given is chosen from the flow (pipeline/flow_volume_scene.h choose_flow_spec) and
// said, and a small dye is framed alone.
#include <apps/cli_checks.h>
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <io/write_image.h>
#include <io/write_vtu.h>
#include <pipeline/pipeline.h>
#include <pipeline/quick_scene.h>
#include <pipeline/scene.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

namespace tr::apps {
namespace {

struct FlowvolArgs {
    std::string mesh;
    FlowVolumeSpec spec;
    std::vector<double> seed_center;
    std::vector<double> seed_size;
    std::vector<double> seed_normal;
    double start_time = 0;
    int time_step = 0;
    std::string output;
    std::string frames;
    std::string mesh_out;
    std::string size = "800x600";
    FlowSpecChoices choose;  // what the command line left out
};

int run_flowvol(FlowvolArgs args) {
    int width = 0, height = 0;
    if (!parse_image_size(args.size, width, height)) {
        std::fprintf(stderr, "tetrender: --size must be WxH, not '%s'\n", args.size.c_str());
        return kExitUsage;
    }
    FlowVolumeSpec& spec = args.spec;
    if (!args.choose.seed_center)
        spec.seed_center = Vec3(args.seed_center[0], args.seed_center[1], args.seed_center[2]);
    if (!args.choose.seed_size) {
        spec.seed_width = args.seed_size[0];
        spec.seed_height = args.seed_size[1];
    }
    if (!args.seed_normal.empty()) {
        const auto& n = args.seed_normal;
        if (!std::isfinite(n[0]) || !std::isfinite(n[1]) || !std::isfinite(n[2]) ||
            (n[0] == 0 && n[1] == 0 && n[2] == 0)) {
            std::ostringstream given;
            given << n[0] << "," << n[1] << "," << n[2];
            return report_usage(make_error(ErrorCode::kInvalidArgument,
                                           "--seed-normal must be a finite non-zero vector x,y,z, "
                                           "not " +
                                               given.str(),
                                           ""));
        }
        spec.seed_normal = Vec3(args.seed_normal[0], args.seed_normal[1], args.seed_normal[2]);
    }
    if (const Status ok = check_output_path(args.output, {".png", ".pfm"}); !ok.ok()) {
        return report_usage(ok.error());
    }
    if (!args.mesh_out.empty()) {
        if (const Status ok = check_output_path(args.mesh_out, {".vtu"}); !ok.ok()) {
            return report_usage(
                make_error(ok.error().code, "--mesh-out: " + ok.error().message, args.mesh_out));
        }
    }
    PipelineOptions pipeline_options;
    pipeline_options.progress = terminal_progress();
    Pipeline pipeline(pipeline_options);
    Scene scene;
    SceneVolume volume;
    volume.mesh = args.mesh;
    volume.time_step = args.time_step;
    auto loaded = pipeline.mesh(volume);
    if (!loaded.ok()) return report_error(loaded.error());
    scene.volumes.push_back(volume);
    std::vector<std::string> chosen;  // said with the picture: a failure is one line
    {
        auto domain = pipeline.flow_domain(volume);
        if (!domain.ok()) return report_error(domain.error());
        auto completed = choose_flow_spec(*domain, spec, args.choose, &chosen);
        if (!completed.ok()) return report_error(completed.error());
        spec = std::move(completed).value();
    }
    spec.fit_camera_to_dye = true;
    scene.camera = framing_camera((*loaded)->tets.bounds(), kDefaultViewDirection);
    scene.width = width;
    scene.height = height;
    scene.background = Vec3(0.02, 0.02, 0.05);
    scene.flow_volume = spec;

    RenderOptions options;
    std::size_t frames = 0;
    if (!args.frames.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(args.frames, ec);
        options.on_flow_volume_layer = [&](std::size_t layer, const Image& picture) {
            char name[64];
            std::snprintf(name, sizeof(name), "/frame_%04zu.png", layer + 1);
            ++frames;
            return write_image(picture, args.frames + name);
        };
    }
    auto result = pipeline.render(scene, options);
    if (!result.ok()) return report_error(result.error());
    const FlowVolume& fv = *result->flow_volume;
    const NamedStats& stats = result->stats;
    std::printf(
        "flow volume: %d layers, %zu tets in %.0f ms; %zu particles inserted where the front "
        "stretched, %zu stopped\n",
        spec.steps, fv.mesh.num_tets(), stats.number("grow_ms"), fv.particles_inserted,
        fv.particles_stopped);
    print_notes(chosen);
    print_notes(result->notes);
    if (!args.mesh_out.empty()) {
        const Status written = write_vtu(fv.mesh, args.mesh_out);
        if (!written.ok()) return report_error(written.error());
        std::printf("wrote %s\n", args.mesh_out.c_str());
    }
    if (frames > 0) std::printf("wrote %zu frames to %s\n", frames, args.frames.c_str());
    std::printf("rendered in %.0f ms (no sort: one dye colour)\n", stats.number("render_ms"));
    const Status written = write_image(result->image, args.output);
    if (!written.ok()) return report_error(written.error());
    std::printf("wrote %s\n", args.output.c_str());
    return kExitOk;
}

}  // namespace

std::function<int()> add_flowvol_command(CLI::App& app) {
    auto args = std::make_shared<FlowvolArgs>();
    CLI::App* cmd = app.add_subcommand(
        "flowvol", "Grow a flow volume from a dye polygon through a vector field and render it");
    cmd->add_option("mesh", args->mesh, "Mesh with a 3-component point array")->required();
    cmd->add_option("--vectors", args->spec.vectors, "The velocity array")->required();
    auto* seed_center =
        cmd->add_option("--seed-center", args->seed_center,
                        "Dye polygon centre x,y,z (default: where the flow is fastest)")
            ->expected(3)
            ->delimiter(',');
    auto* seed_size = cmd->add_option("--seed-size", args->seed_size,
                                      "Dye polygon width,height (default: an eighth of the "
                                      "domain's diagonal each)")
                          ->expected(2)
                          ->delimiter(',')
                          ->check(kPositive);
    cmd->add_option("--seed-normal", args->seed_normal,
                    "Dye polygon normal x,y,z (default: the flow direction at its centre)")
        ->expected(3)
        ->delimiter(',');
    cmd->add_option("--seed-res", args->spec.seed_resolution,
                    "Quads per side of the polygon (default 32)")
        ->check(in_range(1, 4096));
    cmd->add_option("--steps", args->spec.steps, "Layers (default 50)")->check(in_range(1, 100000));
    auto* dt = cmd->add_option("--dt", args->spec.dt,
                               "Time per layer (default: the front travels 40% of the domain's "
                               "diagonal in --steps layers at the seed's speed)")
                   ->check(kPositive);
    cmd->add_option("--split-threshold", args->spec.split_threshold,
                    "Split front edges longer than this many seed spacings (default 2; 0: off)")
        ->check(CLI::Number);
    cmd->add_flag("--compressible", args->spec.compressible,
                  "Scale each tet's dye concentration by its volume change (mass conserved)");
    cmd->add_flag("--unsteady", args->spec.unsteady,
                  "Interpolate the velocity linearly in time over all the file's time steps "
                  "(.pvd, Exodus)");
    auto* start_time = cmd->add_option("--start-time", args->start_time,
                                       "Unsteady: when the dye is released (default: the time "
                                       "of --time-step)");
    cmd->add_option("--time-step", args->time_step,
                    "The time step to read (steady), or to start from (unsteady); default 0")
        ->check(kNonNegativeInteger);
    args->spec.context = true;  // a first picture shows where the dye is in the domain
    cmd->add_flag("--context,!--no-context", args->spec.context,
                  "The domain's boundary as a faint veil over the dye, for context (default on; "
                  "--no-context: the dye alone)");
    cmd->add_option("-o,--output", args->output, "Output image (.png or .pfm)")->required();
    cmd->add_option("--frames", args->frames, "Also write one picture per layer into DIR");
    cmd->add_option("--mesh-out", args->mesh_out,
                    "Write the flow volume (tets, concentration, age) as .vtu");
    cmd->add_option("--size", args->size, "Image size WxH (default 800x600)");
    return [args, start_time, seed_center, seed_size, dt] {
        FlowvolArgs a = *args;
        if (start_time->count() > 0) a.spec.start_time = a.start_time;
        a.choose.seed_center = seed_center->count() == 0;
        a.choose.seed_size = seed_size->count() == 0;
        a.choose.dt = dt->count() == 0;
        return run_flowvol(std::move(a));
    };
}

}  // namespace tr::apps
