// tetrender flowvol MESH --vectors NAME --seed-center x,y,z --seed-size w,h: dye released
// through a polygon, grown layer by layer through the flow, rendered without sorting.
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <apps/flowvol_render.h>
#include <apps/flowvol_setup.h>
#include <io/write_image.h>
#include <io/write_vtu.h>
#include <mesh/face_adjacency.h>
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
};

int run_flowvol(FlowvolArgs args) {
    int width = 0, height = 0;
    if (!parse_image_size(args.size, width, height)) {
        std::fprintf(stderr, "tetrender: --size must be WxH, not '%s'\n", args.size.c_str());
        return kExitUsage;
    }
    FlowVolumeSpec& spec = args.spec;
    spec.seed_center = Vec3(args.seed_center[0], args.seed_center[1], args.seed_center[2]);
    spec.seed_width = args.seed_size[0];
    spec.seed_height = args.seed_size[1];
    if (!args.seed_normal.empty()) {
        spec.seed_normal = Vec3(args.seed_normal[0], args.seed_normal[1], args.seed_normal[2]);
    }
    LoadOptions load;
    load.time_step = args.time_step;
    auto loaded = load_tet_mesh(args.mesh, load);
    if (!loaded.ok()) return report_error(loaded.error());
    const TetMesh& domain = loaded->tets;
    if (spec.unsteady && loaded->input.time_values.size() > 1 && !spec.start_time) {
        spec.start_time = loaded->input.time_values[static_cast<std::size_t>(args.time_step)];
    }
    auto velocity = load_velocity(args.mesh, *loaded, spec.vectors, spec.unsteady);
    if (!velocity.ok()) return report_error(velocity.error());
    auto adjacency = build_face_adjacency(domain);
    if (!adjacency.ok()) return report_error(with_where(adjacency.error(), args.mesh));
    const auto start = std::chrono::steady_clock::now();
    auto fv = grow_flow_volume(domain, *adjacency, *velocity, dye_seed(spec),
                               flow_volume_options(spec), terminal_progress());
    if (!fv.ok()) return report_error(with_where(fv.error(), args.mesh));
    const double grow_ms = ms_since(start);
    std::printf(
        "flow volume: %d layers, %zu tets in %.0f ms; %zu particles inserted where the front "
        "stretched, %zu stopped\n",
        spec.steps, fv->mesh.num_tets(), grow_ms, fv->particles_inserted, fv->particles_stopped);
    if (fv->unresolved_edges > 0) {
        std::fprintf(stderr,
                     "tetrender: note: %zu stretched front edges were left unsplit (at the "
                     "refinement limit, e.g. at a stagnation point, or their new particle left "
                     "the domain)\n",
                     fv->unresolved_edges);
    }
    if (!args.mesh_out.empty()) {
        const Status written = write_vtu(fv->mesh, args.mesh_out);
        if (!written.ok()) return report_error(written.error());
        std::printf("wrote %s\n", args.mesh_out.c_str());
    }
    const Camera camera = framing_camera(domain.bounds(), Vec3(1.0, -1.2, 0.8));
    FlowVolumeView view{camera, width, height, Vec3(0.02, 0.02, 0.05), {}};
    SurfaceMesh boundary;
    if (spec.context) {
        boundary = boundary_surface(domain, *adjacency);
        view.context = &boundary;
    }
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
    const Image image = renderer.render_up_to(fv->mesh.num_tets());
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
    cmd->add_option("--vectors", args->spec.vectors, "The velocity array")->required();
    cmd->add_option("--seed-center", args->seed_center, "Dye polygon centre x,y,z")
        ->required()
        ->expected(3)
        ->delimiter(',');
    cmd->add_option("--seed-size", args->seed_size, "Dye polygon width,height")
        ->required()
        ->expected(2)
        ->delimiter(',')
        ->check(CLI::PositiveNumber);
    cmd->add_option("--seed-normal", args->seed_normal,
                    "Dye polygon normal x,y,z (default: the flow direction at its centre)")
        ->expected(3)
        ->delimiter(',');
    cmd->add_option("--seed-res", args->spec.seed_resolution,
                    "Quads per side of the polygon (default 32)")
        ->check(CLI::Range(1, 4096));
    cmd->add_option("--steps", args->spec.steps, "Layers (default 50)")
        ->check(CLI::Range(1, 100000));
    cmd->add_option("--dt", args->spec.dt, "Time per layer (default 0.05)")
        ->check(CLI::PositiveNumber);
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
        ->check(CLI::NonNegativeNumber);
    cmd->add_flag("--context", args->spec.context,
                  "Draw the domain's boundary as a faint veil, for context");
    cmd->add_option("-o,--output", args->output, "Output image (.png or .pfm)")->required();
    cmd->add_option("--frames", args->frames, "Also write one picture per layer into DIR");
    cmd->add_option("--mesh-out", args->mesh_out,
                    "Write the flow volume (tets, concentration, age) as .vtu");
    cmd->add_option("--size", args->size, "Image size WxH (default 800x600)");
    return [args, start_time] {
        FlowvolArgs a = *args;
        if (start_time->count() > 0) a.spec.start_time = a.start_time;
        return run_flowvol(std::move(a));
    };
}

}  // namespace tr::apps
