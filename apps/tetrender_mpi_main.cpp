// tetrender-mpi: `tetrender render` across MPI ranks (mpirun -np K tetrender-mpi render SCENE -o
// out.png). Starts MPI and parses the command line; the library (distributed/) renders. Rank 0
// prints and writes; every rank exits with the same code.
#include <apps/cli_checks.h>
#include <apps/cli_common.h>
#include <core/config.h>
#include <core/parallel.h>
#include <distributed/distributed_render.h>
#include <distributed/mpi_world.h>
#include <io/write_image.h>
#include <pipeline/movie.h>
#include <pipeline/scene.h>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>

namespace {

using namespace tr;
using namespace tr::apps;

struct MpiRenderArgs {
    std::string scene;
    std::string output;
    std::string sort = "auto";
    std::string integrator = "preintegrated";
    std::string method;
    std::optional<int> repetitions;
    std::optional<std::int64_t> seed;
    int threads = 0;
    bool stats = false;
    double orbit = 0;      // degrees in all
    int frame_count = 36;  // orbit frames
    std::string frames_dir;
};

// Renders on every rank; rank 0 prints and writes. The exit code, the same on every rank.
int run(const MpiWorld& world, const MpiRenderArgs& args) {
    const bool root = world.rank() == 0;
    const auto fail = [&](const Error& error, int code) {
        if (root) std::fprintf(stderr, "tetrender-mpi: %s\n", error.to_string().c_str());
        return code;
    };
    RenderOptions options;
    if (auto sort = sort_method_named(args.sort); sort.ok()) {
        options.sort = *sort;
    } else {
        return fail(sort.error(), kExitUsage);
    }
    if (const Status set = set_integrator_option(options, args.integrator); !set.ok()) {
        return fail(set.error(), kExitUsage);
    }
    if (args.output.empty() && args.frames_dir.empty()) {
        return fail(make_error(ErrorCode::kInvalidArgument,
                               "render needs -o FILE (or --orbit DEG --frames DIR)"),
                    kExitUsage);
    }
    if ((args.orbit != 0) != !args.frames_dir.empty()) {
        return fail(
            make_error(ErrorCode::kInvalidArgument, "--orbit DEG and --frames DIR go together"),
            kExitUsage);
    }
    if (!args.output.empty()) {
        if (const Status ok = check_output_path(args.output, {".png", ".pfm"}); !ok.ok()) {
            return fail(ok.error(), kExitUsage);
        }
    }
    if (!args.frames_dir.empty() && root) {
        std::error_code made;
        std::filesystem::create_directories(args.frames_dir, made);
    }
    if (!args.frames_dir.empty()) {
        // Every rank learns whether rank 0 could make the folder.
        const Status folder =
            world.agree(!root || std::filesystem::is_directory(args.frames_dir)
                            ? Status()
                            : Status(make_error(ErrorCode::kIo, "cannot make the frames folder",
                                                args.frames_dir)));
        if (!folder.ok()) return fail(folder.error(), kExitError);
    }
    if (!is_scene_file(args.scene)) {
        return fail(make_error(ErrorCode::kUnsupported,
                               "tetrender-mpi draws scene files (.json); for a mesh, write one "
                               "with `tetrender render MESH --write-scene S.json`",
                               args.scene),
                    kExitUsage);
    }
    if (args.threads > 0) set_thread_count(args.threads);
    auto read = read_scene(args.scene);
    const Status scene_read = world.agree(read.ok() ? Status() : Status(read.error()));
    if (!scene_read.ok()) return fail(scene_read.error(), kExitError);
    Scene scene = std::move(read).value();
    if (!args.method.empty() || args.repetitions || args.seed) {
        MethodSpec method = scene.method.value_or(MethodSpec{});
        if (!args.method.empty()) method.name = args.method;
        if (args.repetitions) method.repetitions = args.repetitions;
        if (args.seed) method.seed = args.seed;
        scene.method = method;
    }
    PipelineOptions pipeline_options;
    if (root) pipeline_options.progress = terminal_progress();
    DistributedRenderer renderer(world, pipeline_options);
    // One picture, or an orbit's frames (the volumes read and redistributed once).
    const std::vector<Camera> cameras =
        args.orbit != 0 ? orbit_cameras(scene.camera, args.orbit, args.frame_count)
                        : std::vector<Camera>{scene.camera};
    for (std::size_t k = 0; k < cameras.size(); ++k) {
        scene.camera = cameras[k];
        auto result = renderer.render(scene, options);
        if (!result.ok()) return fail(result.error(), kExitError);
        Status written;
        if (root) {
            if (k == 0) print_notes(result->notes);
            if (!args.frames_dir.empty()) {
                written = write_image(result->image,
                                      frame_path(args.frames_dir, static_cast<int>(k)).string());
            }
            if (written.ok() && k == 0 && !args.output.empty()) {
                written = write_image(result->image, args.output);
            }
        }
        written = world.agree(written);
        if (!written.ok()) return fail(written.error(), kExitError);
        if (root && args.stats) print_stats(result->stats);
    }
    return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
    auto world = tr::MpiWorld::start(&argc, &argv);
    if (!world.ok()) {
        std::fprintf(stderr, "tetrender-mpi: %s\n", world.error().to_string().c_str());
        return tr::apps::kExitError;
    }
    const bool root = (*world)->rank() == 0;
    tr::apps::set_program_name("tetrender-mpi");
    CLI::App app{"tetrender-mpi " TETRENDER_VERSION
                 ": tetrender render across MPI ranks, composited by IceT (docs/distributed.md)"};
    app.set_version_flag("--version", std::string("tetrender-mpi ") + TETRENDER_VERSION);
    app.require_subcommand(1);
    MpiRenderArgs args;
    CLI::App* render = app.add_subcommand(
        "render",
        "Render a scene file across the ranks: mpirun -np K tetrender-mpi render "
        "SCENE.json -o out.png");
    render->add_option("scene", args.scene, "Scene file (.json)")->required();
    render->add_option("-o,--output", args.output, "Output image (.png, or .pfm for floats)");
    render->add_option("--method", args.method,
                       "Override the scene's method: projected-tetrahedra, pbvr-image, "
                       "pbvr-object");
    render->add_option("--repetitions", args.repetitions, "PBVR: pictures averaged per rank")
        ->check(CLI::PositiveNumber);
    render->add_option("--seed", args.seed, "PBVR: random seed (each rank derives its own)");
    render->add_option("--sort", args.sort, "auto (default), mpvo, mpvonc, exact, centroid");
    render->add_option("--integrator", args.integrator,
                       "preintegrated (default), exact, exp-texture");
    render->add_option("--threads", args.threads, "Worker threads per rank (default: all cores)")
        ->check(CLI::NonNegativeNumber);
    render
        ->add_option("--orbit", args.orbit,
                     "Frames turning DEG degrees in all about the focal point, written as "
                     "DIR/frame_NNNN.png (--frames); the volumes are read and redistributed "
                     "once")
        ->check(CLI::Range(-3600.0, 3600.0));
    render->add_option("--frame-count", args.frame_count, "Frames of an orbit (default 36)")
        ->check(CLI::Range(1, 100000));
    render->add_option("--frames", args.frames_dir, "Folder for an orbit's frames");
    render->add_flag("--stats", args.stats,
                     "Print one JSON line a picture (rank 0): ranks, and per rank read, "
                     "redistribute, sort, raster and composite times, cells and bytes sent");
    int code = tr::apps::kExitUsage;
    try {
        app.parse(argc, argv);
        code = run(**world, args);
    } catch (const CLI::ParseError& e) {
        // Help and errors from rank 0 only; every rank exits the same way: 0 for --help and
        // --version, 2 (kExitUsage) for a bad command line, as tetrender does.
        const bool asked = dynamic_cast<const CLI::CallForHelp*>(&e) ||
                           dynamic_cast<const CLI::CallForAllHelp*>(&e) ||
                           dynamic_cast<const CLI::CallForVersion*>(&e);
        if (asked) {
            std::ostringstream out, err;
            app.exit(e, out, err);
            if (root) std::fputs(out.str().c_str(), stdout);
            code = tr::apps::kExitOk;
        } else {
            if (root) std::fprintf(stderr, "tetrender-mpi: %s\n", e.what());
            code = tr::apps::kExitUsage;
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tetrender-mpi: internal error (rank %d): %s\n", (*world)->rank(),
                     e.what());
        code = tr::apps::kExitError;
    }
    return code;
}
