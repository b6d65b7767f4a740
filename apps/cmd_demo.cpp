// tetrender demo: the built-in scene, flow around a cylinder standing in a box.
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <core/config.h>
#include <io/write_vtu.h>
#include <mesh/face_adjacency.h>

#if TETRENDER_HAS_TETGEN
#include <mesh/copyleft/cylinder_demo.h>
#endif

#include <chrono>
#include <cstdio>
#include <memory>

namespace tr::apps {
namespace {

struct DemoArgs {
    std::string mesh_out;
    std::size_t tets = 200000;
};

int run_demo(const DemoArgs& args) {
#if TETRENDER_HAS_TETGEN
    const auto start = std::chrono::steady_clock::now();
    CylinderDemoOptions options;
    options.target_tets = args.tets;
    auto mesh = make_cylinder_demo(options);
    if (!mesh.ok()) return report_error(mesh.error());
    const double generate_ms = ms_since(start);
    auto adjacency = build_face_adjacency(*mesh);
    if (!adjacency.ok()) return report_error(adjacency.error());
    const ConvexityReport convexity = check_convexity(*mesh, *adjacency);
    const Bounds3 b = mesh->bounds();
    std::printf("demo: flow past a cylinder standing in a box, meshed by TetGen in %.0f ms\n",
                generate_ms);
    std::printf("  %zu tets, %zu points, volume %.6g, bounds x [%g, %g] y [%g, %g] z [%g, %g]\n",
                mesh->num_tets(), mesh->num_points(), mesh->real_volume(), b.lo.x, b.hi.x, b.lo.y,
                b.hi.y, b.lo.z, b.hi.z);
    std::printf("  boundary: %zu faces, %s\n", adjacency->boundary_faces.size(),
                convexity.convex ? "convex" : "not convex (the cylinder is a hole)");
    for (const Field& f : mesh->point_fields()) {
        const auto [lo, hi] = field_range(f, f.num_components > 1 ? -1 : 0);
        std::printf("  point array %-10s %d component%s, %s [%g, %g]\n", f.name.c_str(),
                    f.num_components, f.num_components > 1 ? "s" : " ",
                    f.num_components > 1 ? "magnitude" : "range", lo, hi);
    }
    if (!args.mesh_out.empty()) {
        const Status written = write_vtu(*mesh, args.mesh_out);
        if (!written.ok()) return report_error(written.error());
        std::printf("  wrote %s\n", args.mesh_out.c_str());
    }
    std::printf("(rendering lands with the renderer; open the .vtu in ParaView meanwhile)\n");
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
        "demo", "Build the built-in demo: potential flow with swirl past a cylinder in a box");
    cmd->add_option("--mesh-out", args->mesh_out, "Write the demo mesh and its fields as .vtu");
    cmd->add_option("--tets", args->tets, "About how many tets (default 200000)")
        ->check(CLI::Range(1000, 20000000));
    return [args] { return run_demo(*args); };
}

}  // namespace tr::apps
