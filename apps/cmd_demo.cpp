// tetrender demo: the built-in scenes (pipeline/demo_scene.h), flow past a cylinder standing in
// a box rendered with the cylinder opaque; --flowvol grows dye through it, --fused adds a heat
// plume on its own hexahedral grid in the same space.
#include <apps/cli_checks.h>
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <io/write_image.h>
#include <io/write_vtu.h>
#include <pipeline/demo_scene.h>
#include <pipeline/pipeline.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

namespace tr::apps {
namespace {

struct DemoArgs {
    std::string output = "demo.png";
    std::string mesh_out;
    std::size_t tets = 200000;
    std::size_t plume_tets = 0;
    int width = 960;
    int height = 540;
    std::string scalar = "vorticity";
    std::string integrator = "preintegrated";
    std::string method;
    std::optional<int> repetitions;
    std::optional<std::int64_t> seed;
    std::string depth;
    bool stats = false;
    bool flowvol = false;
    bool fused = false;
};

// Where --mesh-out puts the plume's tets: demo.vtu -> demo_plume.vtu.
std::filesystem::path plume_mesh_path(const std::filesystem::path& mesh_out) {
    std::filesystem::path path = mesh_out;
    path.replace_filename(mesh_out.stem().string() + "_plume" + mesh_out.extension().string());
    return path;
}

int run_demo(const DemoArgs& args) {
    if (args.flowvol && args.fused) {
        return report_usage(make_error(ErrorCode::kInvalidArgument,
                                       "--flowvol and --fused are two different demos: pick one"));
    }
    const auto integrator = integrator_named(args.integrator);
    if (!integrator.ok()) return report_usage(integrator.error());
    RenderOptions render;
    render.integrator = *integrator;
    if (const Status ok = check_output_path(args.output, {".png", ".pfm"}); !ok.ok()) {
        return report_usage(ok.error());
    }
    DemoOptions options;
    options.kind = args.fused     ? DemoKind::kFused
                   : args.flowvol ? DemoKind::kFlowVolume
                                  : DemoKind::kVolume;
    options.tets = args.tets;
    options.plume_tets = args.plume_tets;
    options.width = args.width;
    options.height = args.height;
    options.scalar = args.scalar;
    auto made = make_demo_scene(options);
    if (!made.ok()) return report_error(made.error());
    DemoScene& demo = *made;
    Scene& scene = demo.scene;
    if (!args.method.empty() || args.repetitions || args.seed || !args.depth.empty()) {
        MethodSpec method;
        if (!args.method.empty()) method.name = args.method;
        method.repetitions = args.repetitions;
        method.seed = args.seed;
        if (!args.depth.empty()) method.options["depth"] = args.depth;
        scene.method = method;
    }
    PipelineOptions pipeline_options;
    pipeline_options.progress = terminal_progress();
    Pipeline pipeline(pipeline_options);
    if (const Status ok = pipeline.check(scene, render); !ok.ok()) {
        return report_usage(ok.error());
    }
    std::printf(
        "demo: flow past a cylinder standing in a box, meshed by TetGen, and its fields in %.0f "
        "ms:\n  %zu tets, %zu points; point arrays",
        demo.generate_ms, demo.flow->num_tets(), demo.flow->num_points());
    for (const Field& f : demo.flow->point_fields()) std::printf(" %s", f.name.c_str());
    std::printf("\n");
    if (demo.plume) {
        std::printf(
            "  a heat plume in the same space, on its own grid: %zu hexahedra behind the "
            "cylinder (%zu tets), point array temperature\n",
            demo.plume_grid->num_cells(), demo.plume->num_tets());
    }
    if (!args.mesh_out.empty()) {
        const Status written = write_vtu(*demo.flow, args.mesh_out);
        if (!written.ok()) return report_error(written.error());
        std::printf("  wrote %s\n", args.mesh_out.c_str());
        if (demo.plume) {
            const std::filesystem::path plume_path = plume_mesh_path(args.mesh_out);
            const Status plume_written = write_vtu(*demo.plume, plume_path);
            if (!plume_written.ok()) return report_error(plume_written.error());
            std::printf("  wrote %s (the plume's tets; source_cell numbers its hexahedra)\n",
                        plume_path.string().c_str());
        }
    }

    auto result = pipeline.render(scene, render);
    if (!result.ok()) return report_error(result.error());
    print_notes(result->notes);
    const Status written = write_image(result->image, args.output);
    if (!written.ok()) return report_error(written.error());
    const NamedStats& stats = result->stats;
    const std::string& method = scene.method_name();
    if (args.flowvol) {
        std::printf(
            "  flow volume: dye through a 1.6 x 1.2 polygon upstream, %d layers, %zu tets "
            "grown in %.0f ms, rendered without sorting in %.0f ms\n",
            scene.flow_volume->steps, result->flow_volume->mesh.num_tets(), stats.number("grow_ms"),
            stats.number("render_ms"));
    } else if (method != kDefaultMethod) {
        const std::string what =
            args.fused ? "the flow's '" + args.scalar + "' and the plume's temperature"
                       : "'" + args.scalar + "'";
        std::printf("  rendered %s by %s at %dx%d: %s %.0f ms\n", what.c_str(), method.c_str(),
                    args.width, args.height, method == "pbvr-object" ? "particles" : "raster",
                    stats.number(method == "pbvr-object" ? "generate_ms" : "raster_ms"));
    } else if (args.fused) {
        std::printf(
            "  rendered the flow's '%s' (blue) and the plume's temperature (red) as one medium, "
            "each pixel's segments of both meshes merged by depth (%s) at %dx%d: raster %.0f "
            "ms\n",
            args.scalar.c_str(), std::string(integrator_name(render.integrator)).c_str(),
            args.width, args.height, stats.number("raster_ms"));
    } else {
        std::printf("  rendered '%s' (%s, sort %s%s) at %dx%d: sort %.0f ms, raster %.0f ms\n",
                    args.scalar.c_str(), std::string(integrator_name(render.integrator)).c_str(),
                    stats.number("convexified") ? "MPVO on the convexified mesh" : "MPVO",
                    std::get<bool>(*stats.find("sort_exact")) ? ", exact" : "", args.width,
                    args.height, stats.number("sort_ms"), stats.number("raster_ms"));
    }
    std::printf("  wrote %s\n", args.output.c_str());
    if (args.stats) {
        NamedStats all;
        all.set("generate_ms", demo.generate_ms);
        for (const auto& [key, value] : stats.entries()) all.set_value(key, value);
        print_stats(all);
    }
    return kExitOk;
}

}  // namespace

std::function<int()> add_demo_command(CLI::App& app) {
    auto args = std::make_shared<DemoArgs>();
    CLI::App* cmd = app.add_subcommand(
        "demo", "Render the built-in demo: flow with swirl past an opaque cylinder in a box");
    cmd->add_option("-o,--output", args->output, "Output image (default demo.png)");
    cmd->add_option("--mesh-out", args->mesh_out,
                    "Also write the demo mesh and fields (.vtu); with --fused the plume's tets "
                    "too, next to it as NAME_plume.vtu");
    cmd->add_option("--tets", args->tets, "About how many tets (default 200000)")
        ->check(in_range(1000, 20000000));
    cmd->add_option("--plume-tets", args->plume_tets,
                    "--fused: about how many tets the plume's grid splits into (default: --tets)")
        ->check(in_range(100, 20000000));
    cmd->add_option("--width", args->width, "Image width (default 960)")->check(in_range(1, 16384));
    cmd->add_option("--height", args->height, "Image height (default 540)")
        ->check(in_range(1, 16384));
    cmd->add_option("--scalar", args->scalar, "vorticity (default), velocity, pressure");
    cmd->add_option("--integrator", args->integrator,
                    "preintegrated (default), exact, exp-texture");
    cmd->add_option("--method", args->method,
                    "projected-tetrahedra (default; --fused: the exact segment merge), "
                    "pbvr-image, pbvr-object");
    cmd->add_option("--repetitions", args->repetitions, "Stochastic methods: ensemble size")
        ->check(in_range(1, 1 << 20));
    cmd->add_option("--seed", args->seed, "Stochastic methods: random seed");
    cmd->add_option("--depth", args->depth,
                    "pbvr-image: where a particle lies on its segment: inverse-cdf (default), "
                    "entry, middle, exit, random");
    cmd->add_flag("--stats", args->stats, "Print one JSON line of timings");
    cmd->add_flag("--flowvol", args->flowvol,
                  "Render a flow volume instead: dye released upstream of the cylinder");
    cmd->add_flag("--fused", args->fused,
                  "Two meshes in one space: the flow (blue) and a heat plume on its own "
                  "hexahedral grid (red), drawn as one medium");
    return [args] { return run_demo(*args); };
}

}  // namespace tr::apps
