// tetrender demo: the built-in scene, flow past a cylinder standing in a box, rendered with the
// cylinder opaque.
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <core/config.h>
#include <io/write_image.h>
#include <io/write_vtu.h>
#include <project/opaque_geometry.h>

#include <pipeline/pipeline.h>
#include <pipeline/quick_scene.h>

#if TETRENDER_HAS_TETGEN
#include <mesh/copyleft/cylinder_demo.h>
#endif

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <memory>

namespace tr::apps {
namespace {

struct DemoArgs {
    std::string output = "demo.png";
    std::string mesh_out;
    std::size_t tets = 200000;
    int width = 960;
    int height = 540;
    std::string scalar = "vorticity";
    std::string integrator = "preintegrated";
    bool stats = false;
    bool flowvol = false;
};

int run_demo(const DemoArgs& args) {
#if TETRENDER_HAS_TETGEN
    const auto integrator = integrator_named(args.integrator);
    if (!integrator.ok()) return report_usage(integrator.error());
    if (const Status ok = check_output_path(args.output, {".png", ".pfm"}); !ok.ok()) {
        return report_usage(ok.error());
    }
    const auto start = std::chrono::steady_clock::now();
    CylinderDemoOptions options;
    options.target_tets = args.tets;
    auto mesh = make_cylinder_demo(options);
    if (!mesh.ok()) return report_error(mesh.error());
    const double generate_ms = ms_since(start);
    std::printf(
        "demo: flow past a cylinder standing in a box, meshed by TetGen in %.0f ms:\n"
        "  %zu tets, %zu points; point arrays",
        generate_ms, mesh->num_tets(), mesh->num_points());
    for (const Field& f : mesh->point_fields()) std::printf(" %s", f.name.c_str());
    std::printf("\n");
    if (!args.mesh_out.empty()) {
        const Status written = write_vtu(*mesh, args.mesh_out);
        if (!written.ok()) return report_error(written.error());
        std::printf("  wrote %s\n", args.mesh_out.c_str());
    }
    // The scene: the demo mesh handed over in memory, the cylinder opaque.
    Scene scene;
    SceneVolume volume;
    volume.mesh = "demo";
    volume.tets = std::make_shared<const TetMesh>(std::move(mesh).value());
    volume.scalar = args.scalar;
    scene.camera.position = Vec3(-4.2, -6.5, 4.4);
    scene.camera.focal_point = Vec3(1.0, 0.0, -0.1);
    scene.camera.view_up = Vec3(0, 0, 1);
    scene.camera.view_angle = 38;
    scene.width = args.width;
    scene.height = args.height;
    scene.background = Vec3(0.02, 0.02, 0.05);
    OpaqueSpec cylinder;
    cylinder.surface = std::make_shared<const SurfaceMesh>(make_cylinder_surface(
        0.999 * options.cylinder_radius, -1, 1, cylinder_demo_sides(options)));
    cylinder.color = Vec3(0.75, 0.75, 0.8);
    scene.opaque.push_back(cylinder);
    if (args.flowvol) {
        // Dye released upstream of the cylinder, grown through the velocity field.
        FlowVolumeSpec dye;
        dye.vectors = "velocity";
        dye.seed_center = Vec3(-2.0, 0.0, 0.0);
        dye.seed_width = 1.6;
        dye.seed_height = 1.2;
        dye.seed_resolution = 32;
        dye.steps = 60;
        dye.dt = 0.08;
        scene.flow_volume = dye;
        volume.scalar = "vorticity";  // checked, not drawn
    }
    // The scalar's range under the inferno map, opacity up to 0.5 per twelfth of the diagonal.
    QuickSceneOptions quick;
    quick.scalar = volume.scalar;
    quick.colormap = "inferno";
    quick.max_opacity = 0.5;
    quick.unit_distance = volume.tets->bounds().diagonal() / 12.0;
    auto tf = make_quick_scene(volume.mesh, *volume.tets, quick);
    if (!tf.ok()) return report_error(tf.error());
    volume.transfer_function = tf->volumes[0].transfer_function;
    scene.volumes.push_back(std::move(volume));

    PipelineOptions pipeline_options;
    pipeline_options.progress = terminal_progress();
    Pipeline pipeline(pipeline_options);
    RenderOptions render;
    render.integrator = *integrator;
    auto result = pipeline.render(scene, render);
    if (!result.ok()) return report_error(result.error());
    print_notes(result->notes);
    const Status written = write_image(result->image, args.output);
    if (!written.ok()) return report_error(written.error());
    const NamedStats& stats = result->stats;
    if (args.flowvol) {
        std::printf(
            "  flow volume: dye through a 1.6 x 1.2 polygon upstream, %d layers, %zu tets "
            "grown in %.0f ms, rendered without sorting in %.0f ms\n",
            scene.flow_volume->steps, result->flow_volume->mesh.num_tets(), stats.number("grow_ms"),
            stats.number("render_ms"));
    } else {
        std::printf("  rendered '%s' (%s, sort %s%s) at %dx%d: sort %.0f ms, raster %.0f ms\n",
                    args.scalar.c_str(), std::string(integrator_name(*integrator)).c_str(),
                    stats.number("convexified") ? "MPVO on the convexified mesh" : "MPVO",
                    std::get<bool>(*stats.find("sort_exact")) ? ", exact" : "", args.width,
                    args.height, stats.number("sort_ms"), stats.number("raster_ms"));
    }
    std::printf("  wrote %s\n", args.output.c_str());
    if (args.stats) {
        NamedStats all;
        all.set("generate_ms", generate_ms);
        for (const auto& [key, value] : stats.entries()) all.set_value(key, value);
        print_stats(all);
    }
    return kExitOk;
#else
    (void)args;
    return report_error(make_error(ErrorCode::kUnsupported,
                                   "the demo mesh is made by TetGen: this build has none "
                                   "(TETRENDER_WITH_TETGEN=OFF)"));
#endif
}

}  // namespace

std::function<int()> add_demo_command(CLI::App& app) {
    auto args = std::make_shared<DemoArgs>();
    CLI::App* cmd = app.add_subcommand(
        "demo", "Render the built-in demo: flow with swirl past an opaque cylinder in a box");
    cmd->add_option("-o,--output", args->output, "Output image (default demo.png)");
    cmd->add_option("--mesh-out", args->mesh_out, "Also write the demo mesh and fields (.vtu)");
    cmd->add_option("--tets", args->tets, "About how many tets (default 200000)")
        ->check(CLI::Range(1000, 20000000));
    cmd->add_option("--width", args->width, "Image width (default 960)")
        ->check(CLI::Range(1, 16384));
    cmd->add_option("--height", args->height, "Image height (default 540)")
        ->check(CLI::Range(1, 16384));
    cmd->add_option("--scalar", args->scalar, "vorticity (default), velocity, pressure");
    cmd->add_option("--integrator", args->integrator,
                    "preintegrated (default), exact, exp-texture");
    cmd->add_flag("--stats", args->stats, "Print one JSON line of timings");
    cmd->add_flag("--flowvol", args->flowvol,
                  "Render a flow volume instead: dye released upstream of the cylinder");
    return [args] { return run_demo(*args); };
}

}  // namespace tr::apps
