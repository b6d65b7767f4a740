// tetrender flowvol MESH --vectors NAME --seed-center x,y,z --seed-size w,h: dye released
// through a polygon, grown layer by layer through the flow, rendered without sorting.
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <apps/flowvol_render.h>
#include <io/write_image.h>
#include <io/write_vtu.h>
#include <project/scene.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

namespace tr::apps {
namespace {

struct FlowvolArgs {
    std::string mesh;
    std::string vectors;
    std::vector<double> seed_center;
    std::vector<double> seed_size;
    int seed_res = 32;
    int steps = 50;
    double dt = 0.05;
    bool compressible = false;
    std::string output;
    std::string frames;
    std::string mesh_out;
    std::string size = "800x600";
};

int run_flowvol(const FlowvolArgs& args) {
    int width = 0, height = 0;
    if (!parse_image_size(args.size, width, height)) {
        std::fprintf(stderr, "tetrender: --size must be WxH, not '%s'\n", args.size.c_str());
        return kExitUsage;
    }
    auto loaded = load_tet_mesh(args.mesh, {});
    if (!loaded.ok()) return report_error(loaded.error());
    const TetMesh& domain = loaded->tets;
    const Field* velocity = find_field(domain.point_fields(), args.vectors);
    if (!velocity || velocity->num_components != 3) {
        std::string names;
        for (const Field& f : domain.point_fields()) {
            if (f.num_components == 3) names += (names.empty() ? "" : ", ") + f.name;
        }
        return report_error(make_error(
            ErrorCode::kNotFound,
            "no 3-component point array '" + args.vectors +
                "' (vector arrays: " + (names.empty() ? std::string("none") : names) + ")",
            args.mesh));
    }
    auto adjacency = build_face_adjacency(domain);
    if (!adjacency.ok()) return report_error(with_where(adjacency.error(), args.mesh));
    DyeSeed seed;
    seed.center = Vec3(args.seed_center[0], args.seed_center[1], args.seed_center[2]);
    seed.width = args.seed_size[0];
    seed.height = args.seed_size[1];
    seed.resolution = args.seed_res;
    FlowVolumeOptions options;
    options.steps = args.steps;
    options.dt = args.dt;
    options.compressible = args.compressible;
    const auto start = std::chrono::steady_clock::now();
    auto fv = grow_flow_volume(domain, *adjacency, *velocity, seed, options, terminal_progress());
    if (!fv.ok()) return report_error(with_where(fv.error(), args.mesh));
    const double grow_ms = ms_since(start);
    std::printf("flow volume: %d layers, %zu tets in %.0f ms; %zu particles stopped\n", args.steps,
                fv->mesh.num_tets(), grow_ms, fv->particles_stopped);
    if (!args.mesh_out.empty()) {
        const Status written = write_vtu(fv->mesh, args.mesh_out);
        if (!written.ok()) return report_error(written.error());
        std::printf("wrote %s\n", args.mesh_out.c_str());
    }
    const Camera camera = framing_camera(domain.bounds(), Vec3(1.0, -1.2, 0.8));
    const FlowVolumeView view{camera, width, height, Vec3(0.02, 0.02, 0.05), {}};
    FlowVolumeRenderer renderer(*fv, domain, view);
    const auto render_start = std::chrono::steady_clock::now();
    if (!args.frames.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(args.frames, ec);
        for (std::size_t k = 0; k < fv->layer_tets.size(); ++k) {
            char name[64];
            std::snprintf(name, sizeof(name), "/frame_%04zu.png", k + 1);
            const Status written =
                write_image(renderer.render_up_to(fv->layer_tets[k]), args.frames + name);
            if (!written.ok()) return report_error(written.error());
        }
        std::printf("wrote %zu frames to %s\n", fv->layer_tets.size(), args.frames.c_str());
    }
    const Image& image = renderer.render_up_to(fv->mesh.num_tets());
    std::printf("rendered in %.0f ms (no sort: one dye colour)\n", ms_since(render_start));
    const Status written = write_image(image, args.output);
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
    cmd->add_option("--vectors", args->vectors, "The velocity array")->required();
    cmd->add_option("--seed-center", args->seed_center, "Dye polygon centre x,y,z")
        ->required()
        ->expected(3)
        ->delimiter(',');
    cmd->add_option("--seed-size", args->seed_size, "Dye polygon width,height")
        ->required()
        ->expected(2)
        ->delimiter(',')
        ->check(CLI::PositiveNumber);
    cmd->add_option("--seed-res", args->seed_res, "Quads per side of the polygon (default 32)")
        ->check(CLI::Range(1, 4096));
    cmd->add_option("--steps", args->steps, "Layers (default 50)")->check(CLI::Range(1, 100000));
    cmd->add_option("--dt", args->dt, "Time per layer (default 0.05)")->check(CLI::PositiveNumber);
    cmd->add_flag("--compressible", args->compressible,
                  "Scale each tet's dye concentration by its volume change (mass conserved)");
    cmd->add_option("-o,--output", args->output, "Output image (.png or .pfm)")->required();
    cmd->add_option("--frames", args->frames, "Also write one picture per layer into DIR");
    cmd->add_option("--mesh-out", args->mesh_out,
                    "Write the flow volume (tets, concentration, age) as .vtu");
    cmd->add_option("--size", args->size, "Image size WxH (default 800x600)");
    return [args] { return run_flowvol(*args); };
}

}  // namespace tr::apps
