// tetrender spotnoise MESH --scalar S --iso V --vectors NAME --frames DIR: spot noise near a
// contour surface, advected by the mesh's vector field, one PNG per frame (flowtex/,
// docs/flowtex.md).
#include <apps/cli_checks.h>
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <flowtex/spot_noise_frames.h>
#include <io/read_surface.h>
#include <io/write_image.h>
#include <pipeline/flow_volume_scene.h>
#include <pipeline/movie.h>
#include <pipeline/pipeline.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

namespace tr::apps {
namespace {

struct SpotNoiseArgs {
    std::string mesh;
    std::string scalar;
    std::optional<double> iso;
    std::string vectors;
    std::string frames;
    std::string movie;
    std::size_t count = 20000;
    int steps = 100;
    double dt = 0;
    double band = 0;
    int lifetime = 60;
    std::string size = "512x512";
    std::vector<std::string> surfaces;
    int time_step = 0;
    bool unsteady = false;
    std::optional<double> start_time;
};

int run_spotnoise(const SpotNoiseArgs& args) {
    SpotNoiseFramesOptions options;
    if (!parse_image_size(args.size, options.width, options.height)) {
        std::fprintf(stderr, "tetrender: --size must be WxH, not '%s'\n", args.size.c_str());
        return kExitUsage;
    }
    options.scalar = args.scalar;
    options.spots.iso = args.iso.value_or(0.0);
    options.spots.count = args.count;
    options.spots.dt = args.dt;
    options.spots.band = args.band;
    options.spots.lifetime_frames = args.lifetime;
    options.steps = args.steps;
    if (args.start_time) {
        options.spots.start_time = *args.start_time;
        options.start_time_set = true;
    }
    std::vector<SurfaceMesh> surfaces;
    for (const std::string& path : args.surfaces) {
        auto surface = read_surface(path);
        if (!surface.ok()) return report_error(surface.error());
        surfaces.push_back(std::move(surface).value());
    }
    for (const SurfaceMesh& surface : surfaces) options.opaque.push_back({&surface});

    // The frames folder must take files, and the movie be possible, before any work.
    const std::filesystem::path dir(args.frames);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir)) {
        std::fprintf(stderr, "tetrender: %s: error: cannot create the frames folder\n",
                     args.frames.c_str());
        return kExitError;
    }
    if (const Status ok = check_output_path(frame_path(dir, 0).string(), {".png"}); !ok.ok()) {
        return report_usage(ok.error());
    }
    if (!args.movie.empty()) {
        if (const Status ok = check_output_path(args.movie, {".mp4", ".webm", ".gif"}); !ok.ok()) {
            return report_usage(ok.error());
        }
        if (!movie_encoder_available()) {
            std::fprintf(stderr, "tetrender: --movie needs the ffmpeg program (Debian: ffmpeg)\n");
            return kExitError;
        }
    }

    PipelineOptions pipeline_options;
    pipeline_options.progress = terminal_progress();
    Pipeline pipeline(pipeline_options);
    SceneVolume volume;
    volume.mesh = args.mesh;
    volume.time_step = args.time_step;
    auto domain = pipeline.flow_domain(volume);
    if (!domain.ok()) return report_error(domain.error());
    if (!domain->planar && (args.scalar.empty() || !args.iso)) {
        std::fprintf(stderr,
                     "tetrender: spotnoise needs --scalar and --iso on a 3D mesh (the contour the "
                     "spots lie near); on a planar 2D mesh they cover the mesh\n");
        return kExitUsage;
    }
    options.planar = domain->planar;
    if (domain->planar) std::printf("%s\n", planar_flow_note(*domain->planar).c_str());
    auto velocity = load_velocity(*domain, args.vectors, args.unsteady);
    if (!velocity.ok()) return report_error(velocity.error());

    const auto report = spot_noise_frames(domain->mesh(), *domain->adjacency, *velocity, options,
                                          [&](int frame, const Image& picture) -> Status {
                                              return write_png(picture, frame_path(dir, frame));
                                          });
    if (!report.ok()) {
        Error error = report.error();
        if (error.where.empty()) error.where = args.mesh;
        return report_error(error);
    }
    if (domain->planar) {
        std::printf("sheet: %zu spots, mean speed %.4g, dt %.4g%s\n", report->spots,
                    report->mean_speed, report->dt,
                    report->mean_speed > 0 ? "" : " (zero velocity: still frames)");
    } else {
        std::printf(
            "band: %zu tets within %.4g of '%s' = %.6g; %zu spots, mean speed %.4g, dt %.4g%s\n",
            report->band_tets, report->band, args.scalar.c_str(), *args.iso, report->spots,
            report->mean_speed, report->dt,
            report->mean_speed > 0 ? "" : " (zero velocity: still frames)");
    }
    std::printf("wrote %d frames to %s (advection %.0f ms, raster %.0f ms, %zu reseeded)\n",
                report->frames, args.frames.c_str(), report->advect_ms, report->raster_ms,
                report->reseeded);
    if (!args.movie.empty()) {
        if (const Status ok = encode_movie(dir, 25.0, args.movie); !ok.ok()) {
            return report_error(ok.error());
        }
        std::printf("wrote %s\n", args.movie.c_str());
    }
    return kExitOk;
}

}  // namespace

std::function<int()> add_spotnoise_command(CLI::App& app) {
    auto args = std::make_shared<SpotNoiseArgs>();
    CLI::App* cmd = app.add_subcommand(
        "spotnoise",
        "Spot noise near a contour surface (or over a 2D mesh), advected by a vector field "
        "(frames)");
    cmd->add_option("mesh", args->mesh,
                    "Mesh with a scalar and a 3-component point array, or a planar 2D mesh "
                    "(triangles, quads, polygons) with a 2- or 3-component one")
        ->required();
    cmd->add_option("--scalar", args->scalar,
                    "The scalar point array of the contour surface (3D meshes)");
    cmd->add_option("--iso", args->iso, "The contour value (3D meshes)");
    cmd->add_option("--vectors", args->vectors, "The velocity array")->required();
    cmd->add_option("--frames", args->frames, "Folder for frame_NNNN.png (created)")->required();
    cmd->add_option("--count", args->count, "Spots (default 20000)")
        ->check(in_range(std::size_t{1}, kMaxSpots));
    cmd->add_option("--steps", args->steps, "Frames after the first (default 100)")
        ->check(in_range(0, 100000));
    cmd->add_option("--dt", args->dt,
                    "Flow time per frame (default: the mean speed over the spots carries a spot "
                    "1/400 of the mesh's diagonal per frame; unsteady, the file's time span over "
                    "the steps)")
        ->check(kPositive);
    cmd->add_option("--band", args->band,
                    "Half-width of the band around the surface, world units (default: the "
                    "diagonal / 100)")
        ->check(kPositive);
    cmd->add_option("--lifetime", args->lifetime,
                    "Frames a spot lives before it is reseeded (default 60; 0: until it leaves)")
        ->check(in_range(0, 1000000));
    cmd->add_option("--surface", args->surfaces,
                    "Opaque surface file(s) drawn under the spots, which are depth-tested "
                    "against them");
    cmd->add_option("--time-step", args->time_step, "The time step to read (steady; default 0)")
        ->check(kNonNegativeInteger);
    cmd->add_flag("--unsteady", args->unsteady,
                  "Velocity linear in time over all the file's time steps (.pvd, Exodus); the "
                  "default dt spans them over the steps");
    cmd->add_option("--start-time", args->start_time,
                    "Unsteady: the time of frame 0 (default: the first step's)");
    cmd->add_option("--size", args->size, "Image size WxH (default 512x512)");
    cmd->add_option("--movie", args->movie,
                    "Also encode the frames into out.mp4|webm|gif at 25 fps (needs ffmpeg)");
    return [args] { return run_spotnoise(*args); };
}

}  // namespace tr::apps
