// tetrender demo: the built-in scene, flow past a cylinder standing in a box, rendered with the
// cylinder opaque.
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <apps/flowvol_render.h>
#include <apps/sort_setup.h>
#include <core/config.h>
#include <io/write_image.h>
#include <io/write_vtu.h>
#include <mesh/point_data.h>
#include <project/colormap.h>
#include <project/cpu_renderer.h>
#include <project/opaque_geometry.h>

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
    const auto integrator = parse_integrator(args.integrator);
    if (!integrator) {
        std::fprintf(stderr, "tetrender: unknown --integrator '%s'\n", args.integrator.c_str());
        return kExitUsage;
    }
    auto start = std::chrono::steady_clock::now();
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
    Camera camera;
    camera.position = Vec3(-4.2, -6.5, 4.4);
    camera.focal_point = Vec3(1.0, 0.0, -0.1);
    camera.view_up = Vec3(0, 0, 1);
    camera.view_angle = 38;
    const Vec3 background(0.02, 0.02, 0.05);
    const SurfaceMesh cylinder =
        make_cylinder_surface(0.999 * options.cylinder_radius, -1, 1, cylinder_demo_sides(options));
    if (args.flowvol) {
        // Dye released upstream of the cylinder, grown through the velocity field.
        const Field* velocity = find_field(mesh->point_fields(), "velocity");
        auto adjacency = build_face_adjacency(*mesh);
        if (!velocity || !adjacency.ok()) {
            return report_error(make_error(ErrorCode::kInternal, "demo mesh without velocity"));
        }
        DyeSeed seed;
        seed.center = Vec3(-2.0, 0.0, 0.0);
        seed.width = 1.6;
        seed.height = 1.2;
        seed.resolution = 32;
        FlowVolumeOptions fv_options;
        fv_options.steps = 60;
        fv_options.dt = 0.08;
        start = std::chrono::steady_clock::now();
        auto fv = grow_flow_volume(*mesh, *adjacency, *velocity, seed, fv_options);
        if (!fv.ok()) return report_error(fv.error());
        const double grow_ms = ms_since(start);
        start = std::chrono::steady_clock::now();
        const FlowVolumeView view{
            camera, args.width, args.height, background, {{&cylinder, Vec3(0.75, 0.75, 0.8)}}};
        FlowVolumeRenderer renderer(*fv, *mesh, view);
        const Image& image = renderer.render_up_to(fv->mesh.num_tets());
        const double render_ms = ms_since(start);
        const Status written = write_image(image, args.output);
        if (!written.ok()) return report_error(written.error());
        std::printf(
            "  flow volume: dye through a 1.6 x 1.2 polygon upstream, %d layers, %zu tets "
            "grown in %.0f ms, rendered without sorting in %.0f ms\n  wrote %s\n",
            fv_options.steps, fv->mesh.num_tets(), grow_ms, render_ms, args.output.c_str());
        return kExitOk;
    }
    auto scalar = point_scalar(*mesh, args.scalar, -1);
    if (!scalar.ok()) return report_error(scalar.error());
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (float v : *scalar) lo = std::min(lo, v), hi = std::max(hi, v);
    const Bounds3 bounds = mesh->bounds();
    auto tf = make_quick_transfer_function("inferno", lo, hi, 0.5, bounds.diagonal() / 12.0);
    if (!tf.ok()) return report_error(tf.error());

    start = std::chrono::steady_clock::now();
    auto setup = prepare_sort(std::move(mesh).value(), SortMethod::kAuto);
    if (!setup.ok()) return report_error(setup.error());
    scalar->resize(setup->mesh.num_points(), 0.0f);
    const double prepare_ms = ms_since(start);

    const CameraFrame frame(camera, args.width, args.height);
    const OpaqueLayer layer =
        render_opaque({{&cylinder, Vec3(0.75, 0.75, 0.8)}}, frame, background);

    VisibilitySorter sorter;
    std::vector<CellId> order;
    const SortStats sort_stats = sorter.sort(setup->mesh, setup->adjacency,
                                             SortView::from_camera(frame), setup->method, order);
    const SegmentShader shader(*tf, *integrator, longest_edge(setup->mesh));
    RenderInputs in;
    in.mesh = &setup->mesh;
    in.scalar = *scalar;
    in.order = order;
    in.shader = &shader;
    in.camera = &frame;
    in.opaque_color = &layer.color;
    in.opaque_depth = &layer.depth;
    RenderStats render_stats;
    const Image image = render_projected_tetrahedra(in, &render_stats);
    const Status written = write_image(image, args.output);
    if (!written.ok()) return report_error(written.error());
    std::printf("  rendered '%s' (%s, sort %s%s) at %dx%d: sort %.0f ms, raster %.0f ms\n",
                args.scalar.c_str(), std::string(integrator_name(*integrator)).c_str(),
                setup->convexified ? "MPVO on the convexified mesh" : "MPVO",
                setup->exact ? ", exact" : "", args.width, args.height, sort_stats.milliseconds,
                render_stats.raster_ms);
    std::printf("  wrote %s\n", args.output.c_str());
    if (args.stats) {
        nlohmann::json j = {{"generate_ms", generate_ms},
                            {"prepare_ms", prepare_ms},
                            {"sort_ms", sort_stats.milliseconds},
                            {"raster_ms", render_stats.raster_ms},
                            {"cells_drawn", render_stats.cells_drawn},
                            {"fragments", render_stats.fragments}};
        std::printf("%s\n", j.dump().c_str());
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
