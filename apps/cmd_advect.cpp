// tetrender advect MESH --vectors NAME --frames DIR: a noise texture advected over a slice of
// the mesh by its vector field, one PNG per frame (flowtex/, docs/flowtex.md).
#include <apps/cli_checks.h>
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <flowtex/advect_frames.h>
#include <io/read_surface.h>
#include <io/write_image.h>
#include <pipeline/flow_volume_scene.h>
#include <pipeline/movie.h>
#include <pipeline/pipeline.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <unistd.h>

namespace tr::apps {
namespace {

struct AdvectArgs {
    std::string mesh;
    std::string vectors;
    std::vector<double> slice;
    std::string sheet;
    std::string frames;
    int steps = 100;
    double dt = 0;
    bool unsteady = false;
    std::string method = "backward";
    std::string size = "512x512";
    int resolution = 256;
    int reinject = 40;
    int time_step = 0;
    std::string movie;
    double fps = 24;
};

int advect_into(const AdvectArgs& args, const AdvectFramesOptions& options,
                const std::filesystem::path& dir);

int run_advect(const AdvectArgs& args) {
    AdvectFramesOptions options;
    if (!parse_image_size(args.size, options.width, options.height)) {
        std::fprintf(stderr, "tetrender: --size must be WxH, not '%s'\n", args.size.c_str());
        return kExitUsage;
    }
    if (args.method == "backward") {
        options.method = AdvectionMethod::kBackward;
    } else if (args.method == "forward") {
        options.method = AdvectionMethod::kForward;
    } else {
        std::fprintf(stderr, "tetrender: --method must be backward or forward, not '%s'\n",
                     args.method.c_str());
        return kExitUsage;
    }
    if (args.reinject % 2 != 0) {
        std::fprintf(stderr, "tetrender: --reinject must be even (or 0), not %d\n", args.reinject);
        return kExitUsage;
    }
    if (!args.slice.empty()) {
        options.slice_point = Vec3(args.slice[0], args.slice[1], args.slice[2]);
        options.slice_normal = Vec3(args.slice[3], args.slice[4], args.slice[5]);
    }
    if (!args.sheet.empty()) {
        auto surface = read_surface(args.sheet);
        if (!surface.ok()) return report_error(surface.error());
        options.sheet = std::move(surface).value();
    }
    options.steps = args.steps;
    options.dt = args.dt;
    options.sheet_resolution = args.resolution;
    options.reinject_frames = args.reinject;

    // The frames folder (a temporary one for a movie alone) must take files before any work.
    if (args.frames.empty() && args.movie.empty()) {
        std::fprintf(stderr, "tetrender: advect writes --frames DIR or --movie FILE\n");
        return kExitUsage;
    }
    if (!args.movie.empty()) {
        if (const Status ok = check_output_path(args.movie, {".mp4", ".webm", ".gif"}); !ok.ok()) {
            return report_usage(ok.error());
        }
        if (!movie_encoder_available()) {
            std::fprintf(stderr,
                         "tetrender: --movie needs the ffmpeg program (Debian: apt-get "
                         "install ffmpeg); --frames DIR writes the frames\n");
            return kExitError;
        }
    }
    const std::filesystem::path dir = args.frames.empty()
                                          ? std::filesystem::temp_directory_path() /
                                                ("tetrender_advect_" + std::to_string(::getpid()))
                                          : std::filesystem::path(args.frames);
    const auto cleanup = [&] {
        std::error_code ignored;
        if (args.frames.empty()) std::filesystem::remove_all(dir, ignored);
    };
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir)) {
        std::fprintf(stderr, "tetrender: %s: error: cannot create the frames folder\n",
                     dir.c_str());
        return kExitError;
    }
    if (const Status ok = check_output_path(frame_path(dir, 0).string(), {".png"}); !ok.ok()) {
        cleanup();
        return report_usage(ok.error());
    }
    const int status = advect_into(args, options, dir);
    if (status == kExitOk && !args.movie.empty()) {
        const Status encoded = encode_movie(dir, args.fps, args.movie);
        cleanup();
        if (!encoded.ok()) return report_error(encoded.error());
        std::printf("movie %s\n", args.movie.c_str());
    }
    cleanup();
    return status;
}

// The frames into `dir`.
int advect_into(const AdvectArgs& args, const AdvectFramesOptions& options,
                const std::filesystem::path& dir) {
    PipelineOptions pipeline_options;
    pipeline_options.progress = terminal_progress();
    Pipeline pipeline(pipeline_options);
    SceneVolume volume;
    volume.mesh = args.mesh;
    volume.time_step = args.time_step;
    auto domain = pipeline.flow_domain(volume);
    if (!domain.ok()) return report_error(domain.error());
    AdvectFramesOptions chosen = options;
    chosen.planar = domain->planar;  // a 2D mesh is the flow: its plane is the slice
    if (domain->planar) std::printf("%s\n", planar_flow_note(*domain->planar).c_str());
    auto velocity = load_velocity(*domain, args.vectors, args.unsteady);
    if (!velocity.ok()) return report_error(velocity.error());

    const std::string where = args.sheet.empty() ? args.mesh : args.sheet;
    const auto report = advect_frames(domain->mesh(), *domain->adjacency, *velocity, chosen,
                                      [&](int frame, const Image& picture) -> Status {
                                          return write_png(picture, frame_path(dir, frame));
                                      });
    if (!report.ok()) {
        Error error = report.error();
        if (error.where.empty()) error.where = where;
        return report_error(error);
    }
    std::printf("sheet: %zu points, %zu triangles; mean in-plane speed %.4g, dt %.4g%s\n",
                report->sheet_points, report->sheet_triangles, report->mean_speed, report->dt,
                report->mean_speed > 0 ? "" : " (zero velocity: still frames)");
    std::printf("wrote %d frames to %s (advection %.0f ms, raster %.0f ms)\n", report->frames,
                dir.c_str(), report->advect_ms, report->raster_ms);
    return kExitOk;
}

}  // namespace

std::function<int()> add_advect_command(CLI::App& app) {
    auto args = std::make_shared<AdvectArgs>();
    CLI::App* cmd = app.add_subcommand(
        "advect",
        "Advect a noise texture over a slice of a mesh (or over a 2D mesh) by its vector "
        "field (frames)");
    cmd->add_option("mesh", args->mesh,
                    "Mesh with a 3-component point array, or a planar 2D mesh (triangles, "
                    "quads, polygons) with a 2- or 3-component one: the flow on its plane")
        ->required();
    cmd->add_option("--vectors", args->vectors, "The velocity array")->required();
    cmd->add_option("--slice", args->slice,
                    "Slice plane px,py,pz,nx,ny,nz (default: through the centre, normal along "
                    "the bounds' thinnest axis)")
        ->expected(6)
        ->delimiter(',');
    cmd->add_option("--sheet", args->sheet,
                    "Instead of a slice: a planar 2D mesh of triangles or quads (.obj, .vtk, "
                    ".vtp, .ply, .stl, .off) in the mesh's space")
        ->excludes("--slice");
    cmd->add_option("--frames", args->frames, "Folder for frame_NNNN.png (created)");
    cmd->add_option("--movie", args->movie,
                    "Encode the frames into a movie (.mp4, .webm, .gif) with the ffmpeg program");
    cmd->add_option("--fps", args->fps, "Movie frames per second (default 24)")
        ->check(in_range(0.1, 1000.0));
    cmd->add_option("--steps", args->steps, "Frames after the first (default 100)")
        ->check(in_range(0, 100000));
    cmd->add_option("--dt", args->dt,
                    "Flow time per frame (default: steady, 1/200 of the slice per frame at the "
                    "mean speed; unsteady, the file's time span over the steps)")
        ->check(kPositive);
    cmd->add_flag("--unsteady", args->unsteady,
                  "Velocity linear in time over all the file's time steps (.pvd, Exodus)");
    cmd->add_option("--time-step", args->time_step, "The time step to read (steady; default 0)")
        ->check(kNonNegativeInteger);
    cmd->add_option("--method", args->method,
                    "backward (points fixed, texture coordinates traced back; default) or "
                    "forward (points moved along paths)");
    cmd->add_option("--resolution", args->resolution,
                    "Sheet squares along its longer side (default 256)")
        ->check(in_range(1, 8192));
    cmd->add_option("--reinject", args->reinject,
                    "Frames between re-injections of fresh texture, even (default 40; 0: off)")
        ->check(in_range(0, 100000));
    cmd->add_option("--size", args->size, "Image size WxH (default 512x512)");
    return [args] { return run_advect(*args); };
}

}  // namespace tr::apps
